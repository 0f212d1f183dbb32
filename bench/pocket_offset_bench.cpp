// A NURBS-bounded pocket (issue 3): a closed cubic B-spline of 200 spans, offset level by
// level until empty, tolerance 0.01 mm (the NURBS as arcs, then exact arc offsets).
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>

#include "engine/parallel.hpp"
#include "engine/pocket_offset.hpp"
#include "kernels/curves/nurbs.hpp"

namespace ncpath {
namespace {

Region nurbs_pocket(int spans) {
  Nurbs2 c;
  c.degree = 3;
  const int n = spans + 2;       // control points before closing
  for (int k = 0; k < n; ++k) {  // clockwise wavy ring
    const double a = -2 * std::numbers::pi * k / n;
    const double r = 100 + 6 * std::sin(12 * a);
    c.ctrl.emplace_back(r * std::cos(a), r * std::sin(a));
  }
  c.ctrl.push_back(c.ctrl.front());
  c.weights.assign(c.ctrl.size(), 1.0);
  c.knots = clamped_uniform_knots(c.ctrl.size(), 3);
  Region r;
  r.boundary.nurbs.push_back(c);
  r.boundary.curves.push_back({make_line(c.ctrl.front(), c.ctrl.back()), 0});
  return r;
}

void nurbs_pocket_levels(benchmark::State& state) {
  const std::vector<Region> regions = {nurbs_pocket(200)};
  PocketOffsetParams p;
  p.tool_radius = 3;
  p.stepover = 1;
  p.tolerance = 0.01;
  par::ThreadLimit one(1);
  std::size_t loops = 0, levels = 0, open = 0;
  for (auto _ : state) {
    const PocketOffsetResult r = offset_pocket(regions, p);
    loops = r.loops.size();
    levels = r.levels;
    open = r.open_fragments;
  }
  state.counters["levels"] = static_cast<double>(levels);
  state.counters["loops"] = static_cast<double>(loops);
  state.counters["open_fragments"] = static_cast<double>(open);
}
BENCHMARK(nurbs_pocket_levels)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace ncpath
