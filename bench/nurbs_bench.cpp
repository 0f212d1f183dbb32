// NURBS kernels on a wavy closed cubic of 200 spans (radius 50 +- 3 mm, 12 waves, crest
// curvature radius about 5.8 mm): the biarc conversion and the chordal polyline at 0.01 mm.
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "kernels/curves/nurbs.hpp"

namespace ncpath {
namespace {

Nurbs2 wavy_closed_cubic(int spans) {
  Nurbs2 n;
  n.degree = 3;
  const int count = spans + 3;
  // Control points on the wavy circle, uniform clamped knots; the last control point is the
  // first, so the curve is closed (with a slight corner at the seam).
  for (int i = 0; i < count; ++i) {
    const double a = 2 * std::numbers::pi * i / (count - 1);
    const double r = 50 + 3 * std::sin(12 * a);
    n.ctrl.emplace_back(r * std::cos(a), r * std::sin(a));
    n.weights.push_back(1);
  }
  n.ctrl.back() = n.ctrl.front();
  n.knots.assign(4, 0.0);
  for (int i = 1; i < spans; ++i) n.knots.push_back(i);
  n.knots.insert(n.knots.end(), 4, static_cast<double>(spans));
  return n;
}

const Nurbs2& curve() {
  static const Nurbs2 c = wavy_closed_cubic(200);
  return c;
}

void to_arcs(benchmark::State& state) {
  std::size_t n = 0;
  for (auto _ : state) {
    const auto segs = nurbs_to_arcs(curve(), 0.01, 0);
    n = segs.size();
    benchmark::DoNotOptimize(segs.data());
  }
  state.counters["segments"] = static_cast<double>(n);
}

void polyline(benchmark::State& state) {
  std::size_t n = 0;
  for (auto _ : state) {
    const auto pl = nurbs_polyline(curve(), 0.01);
    n = pl.size();
    benchmark::DoNotOptimize(pl.data());
  }
  state.counters["points"] = static_cast<double>(n);
}

BENCHMARK(to_arcs)->Name("to_arcs/wavy200_tol0.01")->Unit(benchmark::kMillisecond);
BENCHMARK(polyline)->Name("polyline/wavy200_tol0.01")->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace ncpath
