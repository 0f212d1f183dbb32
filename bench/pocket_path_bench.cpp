// Full pocket tool path (issue 4): offsets, uncut regions and clean-up curves, linking into
// one path, CL points and G-code, on the 10,000-segment wavy loop (A = 8.85) with 12
// circular islands; tool D = 1 mm, stepover 0.5 mm (the offset benchmark's levels) and
// 0.9 mm, one depth pass. Counters give the seconds of each stage of the last iteration: the issue
// asks that linking and clean-up together cost no more than the offsetting. verify_pocket
// times the job's full verification of the same path (issue 16: against the plan's time).
#include <benchmark/benchmark.h>

#include <filesystem>

#include "batch/output/gcode_writer.hpp"
#include "bench/wave_shapes.hpp"
#include "engine/pocket_path.hpp"
#include "engine/run_control.hpp"
#include "engine/verify_profile.hpp"

namespace ncpath {
namespace {

// The wavy 10,000-segment loop (A = 8.85), with the 12 islands when asked.
std::vector<Region> wave_pocket(bool islands) {
  std::vector<Region> regions(1);
  regions[0].boundary = profile_of(bench::wave_loop(10000, 8.85));
  if (islands)
    for (const std::vector<Seg2>& island : bench::twelve_islands())
      regions[0].islands.push_back(profile_of(island));
  return regions;
}

// Tool D = 1 mm, one pass 1 mm deep.
PocketPathParams wave_params(double stepover) {
  PocketPathParams p;
  p.tool_radius = 0.5;
  p.stepover = stepover;
  p.depth = 1;
  p.chordal_tolerance = 0.00125;  // a quarter of the G-code arc tolerance, as jobs use
  return p;
}

void full_pocket(benchmark::State& state, bool islands, bool gcode, double stepover) {
  const std::vector<Region> regions = wave_pocket(islands);
  const PocketPathParams p = wave_params(stepover);
  const std::filesystem::path out = std::filesystem::temp_directory_path() / "ncpath_bench.ngc";
  PocketPathStats st;
  double gcode_s = 0;
  std::size_t points = 0;
  for (auto _ : state) {
    PocketPath path = plan_pocket(regions, p);
    if (gcode) {
      Stopwatch clock;
      out::GcodeWriter w(out, {});
      w.append(path.cl);
      w.finish();
      gcode_s = clock.seconds();
    }
    st = path.stats;
    points = path.cl.point_count();
    benchmark::DoNotOptimize(path.cl.xyz.data());
  }
  std::filesystem::remove(out);
  state.counters["offset_s"] = st.offset_s;
  state.counters["uncut_s"] = st.uncut_s;
  state.counters["link_s"] = st.link_s;
  state.counters["path_s"] = st.path_s;
  state.counters["gcode_s"] = gcode_s;
  state.counters["loops"] = static_cast<double>(st.loops);
  state.counters["cleanup_curves"] = static_cast<double>(st.cleanup_curves);
  state.counters["retractions"] = static_cast<double>(st.retractions);
  state.counters["uncut_after_mm2"] = st.uncut_area_after;
  state.counters["points"] = static_cast<double>(points);
}

// The verifier on the planned wave pocket (with islands): walls indexed and every move checked,
// as a pocket job does after planning; plan_s is the planning time of the same path.
void verify_pocket(benchmark::State& state) {
  const std::vector<Region> regions = wave_pocket(true);
  const PocketPathParams p = wave_params(0.5);
  Stopwatch plan_clock;
  const PocketPath path = plan_pocket(regions, p);
  const double plan_s = plan_clock.seconds();
  ProfileVerifyParams v;
  v.cutter = flat_cutter(1);
  v.top = p.top;
  v.floor = p.top - p.depth;
  v.rapid_limit = p.top;
  VerifyReport r;
  for (auto _ : state) {
    const WallSet walls = profile_walls(regions, v);
    r = verify_profile_moves(walls, path.cl, v);
    benchmark::DoNotOptimize(r.moves);
  }
  state.counters["plan_s"] = plan_s;
  state.counters["moves"] = static_cast<double>(r.moves);
  state.counters["max_gouge"] = r.max_gouge;
  state.counters["min_clearance"] = r.min_clearance;
}

// Stepover 0.5 mm = R: nothing can be left uncut, the uncut stage is skipped (see
// engine/pocket_path.cpp); 0.9 mm: uncut regions computed between all levels.
BENCHMARK_CAPTURE(full_pocket, wave_islands12, true, false, 0.5)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(full_pocket, wave_islands12_gcode, true, true, 0.5)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(full_pocket, wave_islands12_step0_9_gcode, true, true, 0.9)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(full_pocket, wave, false, false, 0.5)->Unit(benchmark::kMillisecond);
BENCHMARK(verify_pocket)->Name("verify_pocket/wave_islands12")->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace ncpath
