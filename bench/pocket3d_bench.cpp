// Pockets with a sculptured bottom (issue 7, engine/pocket3d.hpp), planned end to end: offset
// loops spaced by the scallop height, uncut regions, linking, CL points dropped onto the
// bottom within eps / delta with chord lifting. Two named inputs:
//  - seed000: the case study (datasets/pockets/seed000.toml over seed000_bottom.toml, read
//    from the source tree), ball R = 6, scallop 0.4, eps = delta = 0.5 (the paper's values);
//  - wave10k_nurbs32x32: the 10,000-segment wavy loop of the pocket benchmarks (A = 8.85,
//    about 218 mm across) over a bicubic NURBS bottom of 32 x 32 = 1,024 control points
//    (gentle waves, clamped uniform knots, control points at the Greville abscissae so that
//    the plan map is linear), ball R = 3, scallop 0.05, eps = delta = 0.01 mm.
// Counters: the planner's stage times of the last iteration (offset_s, uncut_s, link_s,
// cl_s), CL points, drops, levels and loops, intervals, retractions, the area left uncut,
// and the process's peak RSS so far (run one case
// per process, --benchmark_filter, for a figure of that case alone).
#include <benchmark/benchmark.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <vector>

#include "batch/io/surface_toml.hpp"
#include "batch/jobs/profile_input.hpp"
#include "bench/wave_shapes.hpp"
#include "engine/pocket3d.hpp"
#include "engine/run_control.hpp"

namespace ncpath {
namespace {

struct Case {
  std::vector<Region> regions;
  NurbsSurface bottom;
  Pocket3dParams params;
};

const Case& seed000() {
  static const Case c = [] {
    const std::filesystem::path dir = std::filesystem::path(NCPATH_SOURCE_DIR) / "datasets/pockets";
    std::vector<out::StatValue> stats;
    Case k;
    k.regions = jobs::read_profile_regions(dir / "seed000.toml", 1e-6, std::nullopt, stats).regions;
    k.bottom = io::read_surface_toml(dir / "seed000_bottom.toml");
    k.params.tool_radius = 6;
    k.params.scallop = 0.4;
    k.params.eps = 0.5;
    k.params.delta = 0.5;
    k.params.tolerance = 0.01;  // the job's default, min(0.01, eps / 4)
    return k;
  }();
  return c;
}

// Clamped uniform knots of n control points, degree p, on [0, 1].
std::vector<double> clamped_uniform(int n, int p) {
  std::vector<double> t(static_cast<std::size_t>(p), 0.0);
  const int spans = n - p;
  for (int i = 0; i <= spans; ++i) t.push_back(static_cast<double>(i) / spans);
  t.insert(t.end(), static_cast<std::size_t>(p), 1.0);
  return t;
}

// Bicubic, n x n control points over [-half, half]^2, z = -20 + waves of +-1.5 mm
// (wavelengths 60 and 80 mm: curvature radii over 35 mm, well above the ball's).
NurbsSurface wavy_bottom(int n, double half) {
  constexpr int kDegree = 3;
  NurbsSurface s;
  s.degree_u = s.degree_v = kDegree;
  s.nu = s.nv = n;
  s.knots_u = s.knots_v = clamped_uniform(n, kDegree);
  std::vector<double> greville(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    double sum = 0;
    for (int k = 1; k <= kDegree; ++k) sum += s.knots_u[static_cast<std::size_t>(i + k)];
    greville[static_cast<std::size_t>(i)] = -half + 2 * half * sum / kDegree;
  }
  const double two_pi = 2 * std::numbers::pi;
  for (double x : greville)
    for (double y : greville)
      s.ctrl.emplace_back(x, y, -20 + 1.5 * std::sin(two_pi * x / 60) * std::cos(two_pi * y / 80));
  s.weights.assign(s.ctrl.size(), 1.0);
  return s;
}

const Case& wave10k() {
  static const Case c = [] {
    Case k;
    k.regions.resize(1);
    k.regions[0].boundary = profile_of(bench::wave_loop(10000, 8.85));  // |xy| <= 108.85 mm
    k.bottom = wavy_bottom(32, 120);
    k.params.tool_radius = 3;
    k.params.scallop = 0.05;
    k.params.eps = 0.01;
    k.params.delta = 0.01;
    k.params.tolerance = 0.0025;  // the job's default, min(0.01, eps / 4)
    return k;
  }();
  return c;
}

void pocket3d(benchmark::State& state, const Case& (*input)()) {
  const Case& c = input();
  Pocket3dStats st;
  std::size_t points = 0;
  for (auto _ : state) {
    Pocket3dPath path = plan_pocket3d(c.regions, c.bottom, c.params);
    st = path.stats;
    points = path.cl.point_count();
    benchmark::DoNotOptimize(path.cl.xyz.data());
  }
  state.counters["offset_s"] = st.offset_s;
  state.counters["uncut_s"] = st.uncut_s;
  state.counters["link_s"] = st.link_s;
  state.counters["cl_s"] = st.cl_s;
  state.counters["cl_points"] = static_cast<double>(st.cl_points);
  state.counters["points"] = static_cast<double>(points);
  state.counters["drops"] = static_cast<double>(st.drops);
  state.counters["levels"] = static_cast<double>(st.levels);
  state.counters["loops"] = static_cast<double>(st.loops);
  state.counters["lifted"] = static_cast<double>(st.lifted_points);
  state.counters["min_interval"] = st.min_interval;
  state.counters["max_interval"] = st.max_interval;
  state.counters["retractions"] = static_cast<double>(st.retractions);
  state.counters["uncut_after_mm2"] = st.uncut_area_after;
  state.counters["peak_rss_MB"] = static_cast<double>(peak_rss_bytes()) / (1 << 20);
}

BENCHMARK_CAPTURE(pocket3d, seed000, &seed000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(pocket3d, wave10k_nurbs32x32, &wave10k)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

}  // namespace
}  // namespace ncpath
