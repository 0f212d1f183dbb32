// Per-triangle drop-cutter kernel, per cutter: random triangles and random tool positions
// within reach, so facet, edge and vertex contacts all occur.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "kernels/cutters/drop_cutter.hpp"

namespace ncpath {
namespace {

struct Case {
  std::vector<PreparedFacet> facets;
  std::vector<Vec2> points;
};

const Case& cases() {
  static const Case c = [] {
    Case k;
    std::mt19937_64 rng(1);
    std::uniform_real_distribution<double> U(-3, 3);
    while (k.facets.size() < 4096) {
      PreparedFacet f;
      if (prepare_facet({U(rng), U(rng), U(rng)}, {U(rng), U(rng), U(rng)},
                        {U(rng), U(rng), U(rng)}, f))
        k.facets.push_back(f);
    }
    for (int i = 0; i < 4096; ++i) k.points.emplace_back(U(rng) * 0.5, U(rng) * 0.5);
    return k;
  }();
  return c;
}

void drop(benchmark::State& state, Cutter cutter) {
  const Case& c = cases();
  std::size_t i = 0;
  for (auto _ : state) {
    CutterContact best;
    const std::size_t k = i++ & 4095;
    drop_facet(cutter, c.facets[k], c.points[k].x(), c.points[k].y(), 0, best);
    benchmark::DoNotOptimize(best);
  }
  state.SetItemsProcessed(state.iterations());
}

BENCHMARK_CAPTURE(drop, ball_d5, ball_cutter(5));
BENCHMARK_CAPTURE(drop, flat_d5, flat_cutter(5));
BENCHMARK_CAPTURE(drop, bullnose_d5_r1, bull_nose_cutter(5, 1));

}  // namespace
}  // namespace ncpath
