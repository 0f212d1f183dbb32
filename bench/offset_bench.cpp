// Multi-level pocket offsets, the cases of issue 3: a closed loop of 10,000 segments (5,000
// arcs and 5,000 lines) through r(t) = 100 + A sin(20 t), offset inward by 0.5 mm per
// level from the previous loop until empty; and the same with 12 circular islands.
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>

#include "bench/wave_shapes.hpp"
#include "kernels/pocket/offset_levels.hpp"

namespace ncpath {
namespace {

void levels(benchmark::State& state, double amplitude, bool islands) {
  std::vector<std::vector<Seg2>> input = {bench::wave_loop(10000, amplitude)};
  if (islands)
    for (std::vector<Seg2>& island : bench::twelve_islands()) input.push_back(std::move(island));
  std::size_t n_levels = 0, loops = 0, open = 0;
  for (auto _ : state) {
    // The input is the zero-distance level: offset it by 0.5 from itself, then by 0.5 each.
    const OffsetLevels out = offset_levels(input, 0.5, 0.5);
    n_levels = out.level_start.size();
    loops = out.loops.size();
    open = out.open_fragments;
    benchmark::DoNotOptimize(out.loops.data());
  }
  state.counters["levels"] = static_cast<double>(n_levels);
  state.counters["loops"] = static_cast<double>(loops);
  state.counters["open_fragments"] = static_cast<double>(open);
}

BENCHMARK_CAPTURE(levels, wave_a8_85, 8.85, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(levels, wave_a10, 10.0, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(levels, wave_a8_85_islands12, 8.85, true)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace ncpath
