// The fillet command and the fillet job end to end (issue 6): a V-groove of two 45-degree
// flanks z = |x| joined by a fillet of radius 3, cleaned up with ball:3 after ball:10. The
// reference ball (radius 5 > 3) rides on the flanks and leaves the fillet; every point of the
// clean-up passes puts the small ball's centre at distance r = 1.5 from the groove (computed
// analytically, not from the mesh), the passes sweep from one reference contact to the other,
// linked at depth; every statistic with its unit; G-code; identical datasets for 1 and 2
// threads; the problems a user can make, named. With --stock s and --direction climb the
// centres lie r + s from the groove and the passes run one way, joined by one-point rapids
// (the groove is symmetric: no material side, every pass along its pencil path).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <numbers>

#include "kernels/geom/tolerance.hpp"
#include "tests/batch/cli_job_checks.hpp"
#include "tests/batch/cli_run.hpp"
#include "tests/batch/mesh_op_cli_support.hpp"

namespace ncpath {
namespace {

namespace h5 = out::test;
using test::CmdResult;
using test::ncpath;
using namespace cli_checks;
using namespace mesh_op_cli;

constexpr double kRho = 3;        // fillet radius
constexpr double kR = 5;          // reference ball radius (ball:10)
constexpr double kr = 1.5;        // clean-up ball radius (ball:3)
constexpr int kArcFacets = 2000;  // fine: the chords stay within rho (1 - cos(pi / 4 / n)) <
                                  // 3e-7 mm of the arc, so the mesh is the analytic groove
const double kSqrt2 = std::sqrt(2.0);

// Flanks z = |x| for rho / sqrt 2 <= |x| <= 10, joined by the arc of radius rho about
// (0, rho sqrt 2) in xz from -135 to -45 degrees (tangent to both flanks), along y in
// [-8, 8]; the arc in kArcFacets chords. Written with every digit (the OFF helper of the scan
// tests keeps 6, which would move the vertices off the arc by 1e-6 mm).
void write_filleted_groove(const std::filesystem::path& path) {
  std::vector<std::array<double, 2>> prof{{-10, 10}};  // (x, z)
  for (int i = 0; i <= kArcFacets; ++i) {
    const double a = -0.75 * std::numbers::pi + 0.5 * std::numbers::pi * i / kArcFacets;
    prof.push_back({kRho * std::cos(a), kRho * kSqrt2 + kRho * std::sin(a)});
  }
  prof.push_back({10, 10});
  std::ofstream out(path);
  out << std::setprecision(17) << "OFF\n"
      << 2 * prof.size() << " " << 2 * (prof.size() - 1) << " 0\n";
  for (const auto& q : prof) out << q[0] << " -8 " << q[1] << "\n" << q[0] << " 8 " << q[1] << "\n";
  for (std::size_t i = 0; i + 1 < prof.size(); ++i) {
    const std::size_t a = 2 * i;
    out << "3 " << a << " " << a + 2 << " " << a + 3 << "\n";
    out << "3 " << a << " " << a + 3 << " " << a + 1 << "\n";
  }
}

double segment_distance(double x, double z, double ax, double az, double bx, double bz) {
  const double dx = bx - ax, dz = bz - az;
  const double t = std::clamp(((x - ax) * dx + (z - az) * dz) / (dx * dx + dz * dz), 0.0, 1.0);
  return std::hypot(x - ax - t * dx, z - az - t * dz);
}

// Distance from (x, z) to the groove's section (the analytic one, not the mesh).
double groove_distance(double x, double z) {
  const double t = kRho / kSqrt2;  // where the flanks meet the arc
  double d = std::min(segment_distance(x, z, -10, 10, -t, t), segment_distance(x, z, t, t, 10, 10));
  const double cz = kRho * kSqrt2, a = std::atan2(z - cz, x);
  if (a >= -0.75 * std::numbers::pi && a <= -0.25 * std::numbers::pi)
    d = std::min(d, std::abs(kRho - std::hypot(x, z - cz)));
  return d;
}

TEST(FilletCli, PassesTouchTheFilletedGrooveFromContactToContact) {
  // The oracle itself: a point on the arc's bisector and one above a flank.
  EXPECT_NEAR(groove_distance(0, kRho * kSqrt2 - 1), kRho - 1, 1e-12);
  EXPECT_NEAR(groove_distance(6, 6 + 2 * kSqrt2), 2, 1e-12);

  const auto dir = scan_cli::fixture_dir("fillet_groove");
  write_filleted_groove(dir / "groove.off");
  // No z-levels: the drive planes alone find the reference crease (z-levels would add the
  // groove's ends).
  const CmdResult r = ncpath("fillet --mesh " + (dir / "groove.off").string() +
                             " --tool ball:3 --reference ball:10 --interval 0.5 --step-down 0 "
                             "--quiet --out " +
                             (dir / "f.h5").string() + " --gcode " + (dir / "f.ngc").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  h5::Id f = h5::open_read(dir / "f.h5");
  ASSERT_NO_FATAL_FAILURE(
      expect_job_ok(f, "fillet", "fillet",
                    {"\"reference\":\"ball:10\"", "\"reference_diameter\":10.0", "\"stepover\":0.0",
                     "\"scallop\":0.005", "\"step_down\":0.0"}));

  // One reference pencil path: its passes, cut (0) and linked at depth (1), no rapid.
  const ClOut cl = read_cl(f, "fillet");
  ASSERT_GE(cl.cut_paths.size(), 3u);
  for (std::size_t k = 0; k < cl.kind.size(); ++k) EXPECT_EQ(cl.kind[k], k % 2 == 0 ? 0 : 1) << k;
  EXPECT_EQ(cl.kind.size() % 2, 1u);  // starts and ends with a pass
  const std::size_t n = cl.pts.size() / 3;
  for (const std::uint8_t c : cl.contact) EXPECT_EQ(c, 2);

  // Every pass point away from the groove's ends: the ball centre at distance r from the
  // groove; the passes span the region between the reference ball's contacts, whose
  // clean-up positions are x = +-(R - r) / sqrt 2 (the small ball moved from the reference
  // centre along the flank's normal).
  std::size_t checked = 0, cut_points = 0;
  double x_min = INFINITY, x_max = -INFINITY, cut_length = 0;
  for (const std::size_t p : cl.cut_paths) {
    for (auto i = std::size_t(cl.off[p]); i < std::size_t(cl.off[p + 1]); ++i) {
      const Row q = cl.point(i);
      ++cut_points;
      if (i > std::size_t(cl.off[p]))
        cut_length += std::hypot(q[0] - cl.point(i - 1)[0], q[1] - cl.point(i - 1)[1],
                                 q[2] - cl.point(i - 1)[2]);
      if (std::abs(q[1]) >= 6) continue;
      ++checked;
      const double d = groove_distance(q[0], q[2] + kr);
      ASSERT_NEAR(d, kr, 1e-6) << "pass point " << i << " at " << q[0] << " " << q[1] << " "
                               << q[2];
      x_min = std::min(x_min, q[0]);
      x_max = std::max(x_max, q[0]);
    }
  }
  ASSERT_GE(checked, 3 * 23u);  // several passes, each with a point every 0.5 mm along y
  // The pencil runs on the conditioned mesh with its stock grown by the largest vertex move
  // (kernels/mesh/condition.hpp), at most tol::kConditionMove: the passes' ends by as much.
  const double side = (kR - kr) / kSqrt2;
  EXPECT_NEAR(x_min, -side, 1e-6 + tol::kConditionMove);
  EXPECT_NEAR(x_max, side, 1e-6 + tol::kConditionMove);

  // Statistics: the reference run found the groove's crease along its whole length.
  const scan_cli::Stats st{f, "fillet"};
  EXPECT_EQ(st["passes"], double(cl.cut_paths.size()));
  EXPECT_EQ(st["pass_points"], double(cut_points));
  EXPECT_EQ(st["points"], double(n));
  EXPECT_NEAR(st["cut_length"], cut_length, 1e-6 * cut_length);
  EXPECT_GE(st["rays"], st["pass_points"]);
  EXPECT_EQ(st["misses"], 0);
  EXPECT_EQ(st["unreachable"], 0);
  EXPECT_EQ(st["reference_paths"], 1);
  EXPECT_EQ(st["reference_levels"], 0);
  // The planes reach one interval more than the reference ball's radius (5 mm) beyond the
  // part's box: x lines y = -13.5 ... 13.5, y lines x = -15.5 ... 15.5.
  EXPECT_EQ(st["reference_planes"], 55 + 63);
  EXPECT_EQ(st["reference_pencil_points"], 33);
  EXPECT_NEAR(st["reference_traced_length"], 16, 1e-6);
  for (const char* s : {"cut_length", "reference_traced_length", "reference_air_length"})
    EXPECT_EQ(st.unit(s), "mm") << s;
  for (const char* s : {"pencil_s", "rays_s", "reference_elements_s", "reference_scan_s",
                        "reference_zlevel_s", "reference_link_s", "reference_refine_s",
                        "reference_check_s", "compute_s", "write_s", "read_s"})
    EXPECT_EQ(st.unit(s), "s") << s;
  for (const char* s :
       {"passes", "pass_points", "rays", "misses", "unreachable", "lifted_points",
        "reference_planes", "reference_levels", "reference_candidates", "reference_pencil_points",
        "reference_kept_points", "reference_chains", "reference_refined_points",
        "reference_lifted_points", "reference_paths", "points"})
    EXPECT_EQ(st.unit(s), "") << s;
  EXPECT_GE(st["compute_s"], st["pencil_s"]);

  // G-code: rapids 5 mm above the groove's top (z = 10).
  expect_gcode_has(dir / "f.ngc", {"G0 Z15.0000", "M2"});
}

TEST(FilletCli, StockAndDirection) {
  const auto dir = scan_cli::fixture_dir("fillet_stock");
  write_filleted_groove(dir / "groove.off");
  const double s = 0.3;
  const CmdResult r = ncpath("fillet --mesh " + (dir / "groove.off").string() +
                             " --tool ball:3 --reference ball:10 --stepover 0.4 --interval 0.5 "
                             "--step-down 0 --stock 0.3 --direction climb --quiet --out " +
                             (dir / "s.h5").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  h5::Id f = h5::open_read(dir / "s.h5");
  ASSERT_NO_FATAL_FAILURE(
      expect_job_ok(f, "fillet", "", {"\"stock\":0.3", "\"direction\":\"climb\""}));

  // One pencil path: passes (0) joined by one-point rapids (2) to the next pass's start.
  const ClOut cl = read_cl(f, "fillet");
  ASSERT_GE(cl.cut_paths.size(), 3u);
  EXPECT_EQ(cl.kind.size() % 2, 1u);
  for (std::size_t k = 0; k < cl.kind.size(); ++k) {
    ASSERT_EQ(cl.kind[k], k % 2 == 0 ? 0 : 2) << k;
    if (k % 2 == 0) continue;
    ASSERT_EQ(cl.off[k + 1] - cl.off[k], 1);
    EXPECT_EQ(cl.point(std::size_t(cl.off[k])), cl.point(std::size_t(cl.off[k + 1])));
  }
  // Every pass: the centre r + s from the groove (away from its ends), and all running the
  // same way along y (one way, as their pencil path).
  int towards = 0;
  for (const std::size_t p : cl.cut_paths) {
    const auto a = std::size_t(cl.off[p]), b = std::size_t(cl.off[p + 1]);
    ASSERT_GE(b - a, 2u);
    const int dir_y = cl.point(b - 1)[1] > cl.point(a)[1] ? 1 : -1;
    if (towards == 0) towards = dir_y;
    EXPECT_EQ(dir_y, towards) << "pass " << p;
    for (std::size_t i = a; i < b; ++i) {
      const Row q = cl.point(i);
      if (std::abs(q[1]) >= 6) continue;
      ASSERT_NEAR(groove_distance(q[0], q[2] + kr), kr + s, 1e-6) << "point " << i;
    }
  }
  const scan_cli::Stats st{f, "fillet"};
  EXPECT_EQ(st["passes"], double(cl.cut_paths.size()));
  EXPECT_EQ(st["neutral_passes"], st["passes"]);  // symmetric groove: no material side
  EXPECT_EQ(st.unit("neutral_passes"), "");
}

TEST(FilletCli, OneAndTwoThreadsWriteIdenticalDatasets) {
  // The plate's pocket: several reference pencil paths (floor creases, corners), spread over
  // the threads.
  const auto dir = scan_cli::fixture_dir("fillet_threads");
  scan_cli::write_off(dir / "plate.off", plate_pocket());
  std::ofstream(dir / "jobs.toml") << R"(
output = "unused.h5"
[[job]]
name = "cleanup"
operation = "fillet"
input = "plate.off"
tool = "ball:1"
params = { reference = "ball:2.5", interval = 0.5, step_down = 0.3, stepover = 0.25, max_passes = 8 }
)";
  ASSERT_NO_FATAL_FAILURE(run_with_one_and_two_threads(dir));
  h5::Id a = h5::open_read(dir / "t1.h5");
  h5::Id b = h5::open_read(dir / "t2.h5");
  EXPECT_EQ((scan_cli::Stats{a, "cleanup"}["threads"]), 1);
  EXPECT_EQ((scan_cli::Stats{b, "cleanup"}["threads"]), 2);
  for (const char* d : {"cl/points", "cl/path_offsets", "cl/path_kind", "cl/contact_kind"})
    expect_same_dataset(a, b, std::string("/jobs/cleanup/") + d);
  const scan_cli::Stats st{a, "cleanup"};
  EXPECT_GE(st["reference_paths"], 2);  // work for both threads
  EXPECT_GE(st["passes"], st["reference_paths"]);
  EXPECT_LE(st["passes"], st["reference_paths"] * (8 + 1));  // passes 0 ... n, n <= max_passes
  // A rapid before every pencil path's passes but the first.
  const ClOut cl = read_cl(a, "cleanup");
  EXPECT_EQ(double(std::count(cl.kind.begin(), cl.kind.end(), 2)), st["reference_paths"] - 1);
  for (const char* s : {"passes", "pass_points", "rays", "cut_length", "reference_paths"})
    EXPECT_EQ(st[s], (scan_cli::Stats{b, "cleanup"}[s])) << s;
}

// A real CAD part with near-vertical walls (anchor_dense from libcgal-demo, fit to 100 mm),
// ball 3 after ball 8: every move passes the job's verifier. Before the reachability check
// swept the ball up from each pass point, a point 1.8e-4 mm under a steep wall's CL surface
// was taken for one touching the wall and the job failed verification (move 8542).
TEST(FilletCli, SteepWallsOfARealPartPassTheVerifier) {
  const auto dir = scan_cli::fixture_dir("fillet_anchor");
  const std::string mesh =
      (std::filesystem::path(NCPATH_SOURCE_DIR) / "datasets/cache/meshes/anchor_dense.off").string();
  const CmdResult r = ncpath("fillet --mesh " + mesh + " --tool ball:3 --reference ball:8 "
                             "--interval 1 --step-down 0 --fit-xy 100 --quiet --out " +
                             (dir / "a.h5").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  h5::Id f = h5::open_read(dir / "a.h5");
  ASSERT_NO_FATAL_FAILURE(expect_job_ok(f, "fillet", "fillet"));
  const scan_cli::Stats st{f, "fillet"};
  EXPECT_GT(st["passes"], 100);
  EXPECT_EQ(st["verify_max_gouge"], 0.0);
}

TEST(FilletCli, ProblemsAreNamed) {
  const auto dir = scan_cli::fixture_dir("fillet_problems");
  scan_cli::write_off(dir / "groove.off", scan_cli::groove(false));
  const std::string mesh = "--mesh " + (dir / "groove.off").string();
  expect_failure(dir, "fillet", mesh + " --tool flat:3 --reference ball:10",
                 "fillet-cut needs a ball-end mill");
  expect_failure(dir, "fillet", mesh + " --tool bull:3:1 --reference ball:10",
                 "fillet-cut needs a ball-end mill");
  expect_failure(dir, "fillet", mesh + " --tool ball:3 --reference flat:10",
                 "--reference must be a ball-end mill (ball:D");
  expect_failure(dir, "fillet", mesh + " --tool ball:3 --reference ball:2",
                 "--reference must be a larger ball than the tool (3 mm), got 'ball:2' (2 mm)");
  expect_failure(dir, "fillet", mesh + " --tool ball:3 --reference ball:3",
                 "--reference must be a larger ball than the tool (3 mm)");
  expect_failure(dir, "fillet", mesh + " --tool ball:3 --reference ball",
                 "--reference is not a usable ball: tool 'ball' is malformed");
  expect_failure(dir, "fillet", mesh + " --tool ball:3 --reference ball:10 --scallop 0",
                 "--scallop must be a positive number of mm when stepover is 0, got 0");
  expect_failure(dir, "fillet",
                 mesh + " --tool ball:3 --reference ball:10 --stepover 0.5 --scallop 0.01",
                 "--scallop is not used when --stepover is given (> 0)");
  expect_failure(dir, "fillet", mesh + " --tool ball:3 --reference ball:10 --stepover -1",
                 "--stepover must be >= 0 mm");
  expect_failure(dir, "fillet", mesh + " --tool ball:3 --reference ball:10 --max-passes 0",
                 "--max-passes must be >= 1");
  expect_failure(dir, "fillet", mesh + " --tool ball:3 --reference ball:10 --interval 0",
                 "--interval must be a positive number of mm, got 0");
  expect_failure(dir, "fillet", mesh + " --tool ball:3 --reference ball:10 --min-angle 200",
                 "--min-angle must be between 0 and 180 degrees, got 200");
  expect_failure(dir, "fillet", mesh + " --tool ball:3 --reference ball:10 --stock -1.5",
                 "--stock must be greater than minus the ball radius (-1.5 mm)");
  // CLI11 refuses a direction that is not one of the three before anything runs, naming it.
  expect_refused("fillet " + mesh +
                     " --tool ball:3 --reference ball:10 --direction zigzag --quiet --out " +
                     (dir / "d.h5").string(),
                 "--direction");
  // Without --reference CLI11 refuses the command line before anything runs, naming it.
  expect_refused("fillet " + mesh + " --tool ball:3 --quiet --out " + (dir / "x.h5").string(),
                 "--reference");

  // The same in a batch file: each bad job is recorded and the good one still runs.
  std::ofstream(dir / "jobs.toml") << R"(
output = "batch.h5"
[[job]]
name = "flat"
operation = "fillet"
input = "groove.off"
tool = "flat:3"
params = { reference = "ball:10" }
[[job]]
name = "small-reference"
operation = "fillet"
input = "groove.off"
tool = "ball:3"
params = { reference = "ball:2" }
[[job]]
name = "good"
operation = "fillet"
input = "groove.off"
tool = "ball:3"
params = { reference = "ball:10", interval = 1, step_down = 0, stepover = 0.5 }
)";
  expect_bad_jobs_named(
      dir, "3 job(s), 1 ok, 2 failed",
      {{"flat", "fillet-cut needs a ball-end mill"},
       {"small-reference", "'params.reference' must be a larger ball than the tool (3 mm)"}},
      {"good"});
  h5::Id f = h5::open_read(dir / "batch.h5");
  // The sharp groove (no fillet): the reference's contacts are x = +-R / sqrt 2 on the flanks
  // and the small ball's +-r / sqrt 2 at the floor, so passes 0.5 mm apart span them.
  EXPECT_GE((scan_cli::Stats{f, "good"}["passes"]), 3);
}

TEST(FilletCli, HelpDocumentsEveryOption) {
  const CmdResult h = ncpath("fillet --help");
  EXPECT_EQ(h.exit_code, 0);
  for (const char* s :
       {"--mesh",           "--tool",       "--reference", "--stepover",  "--scallop",
        "--max-passes",     "--interval",   "--step-down", "--min-angle", "--tolerance",
        "--merge-distance", "--min-length", "--margin",    "--floor-z",   "--out",
        "--name",           "--threads",    "--fit-xy",    "--quiet",     "--gcode",
        "--safe-z",         "ball",         "--stock",     "--direction", "conventional"})
    EXPECT_NE(h.output.find(s), std::string::npos) << s;
  EXPECT_NE(ncpath("--help").output.find("fillet"), std::string::npos);
}

}  // namespace
}  // namespace ncpath
