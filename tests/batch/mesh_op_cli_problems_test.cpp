// The zlevel and pencil commands: identical datasets for 1 and 2 threads, the problems a user
// can make (a tool that is not a ball, levels and step-down both or neither, bad values)
// reported by key with status invalid_parameter, and the help texts.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "batch/io/stl_writer.hpp"
#include "tests/batch/cli_job_checks.hpp"
#include "tests/batch/cli_run.hpp"
#include "tests/batch/mesh_op_cli_support.hpp"
#include "tests/support/meshes.hpp"

namespace ncpath {
namespace {

namespace h5 = out::test;
using test::CmdResult;
using test::ncpath;
using namespace cli_checks;
using namespace mesh_op_cli;

TEST(MeshOpCli, OneAndTwoThreadsWriteIdenticalDatasets) {
  const auto dir = scan_cli::fixture_dir("mesh_op_threads");
  const TriangleMesh m = test::height_field(
      20, 40, [](double x, double y) { return 2 + std::sin(x / 5) * std::cos(y / 4); });
  io::write_binary_stl(dir / "part.stl", m);
  scan_cli::write_off(dir / "plate.off", plate_pocket());
  // Small chunks of levels, so that both threads get work and chunks are handed over often.
  std::ofstream(dir / "jobs.toml") << R"(
output = "unused.h5"
[[job]]
name = "contours"
operation = "zlevel"
input = "part.stl"
tool = "ball:6"
params = { step_down = 0.25, tolerance = 0.002, chunk_levels = 2 }
[[job]]
name = "creases"
operation = "pencil"
input = "plate.off"
tool = "ball:2.5"
params = { interval = 0.5, step_down = 0.3 }
)";
  ASSERT_NO_FATAL_FAILURE(run_with_one_and_two_threads(dir));
  h5::Id a = h5::open_read(dir / "t1.h5");
  h5::Id b = h5::open_read(dir / "t2.h5");
  EXPECT_EQ((scan_cli::Stats{a, "contours"}["threads"]), 1);
  EXPECT_EQ((scan_cli::Stats{b, "contours"}["threads"]), 2);
  const char* cl[] = {"cl/points", "cl/path_offsets", "cl/path_kind", "cl/contact_kind"};
  const char* zlevel[] = {"segment_path",      "segment_kind",      "segment_shadow",
                          "segment_element",   "segment_start",     "segment_end",
                          "segment_geometry",  "junction_path",     "junction_kind",
                          "junction_position", "junction_b1",       "junction_b2",
                          "junction_element1", "junction_element2", "junction_angle",
                          "contour_level",     "contour_hole"};
  const char* pencil[] = {"point_position", "point_b1",     "point_b2",
                          "point_angle",    "point_family", "point_kept"};
  auto same = [&](const std::string& path) { expect_same_dataset(a, b, path); };
  for (const char* d : cl) same(std::string("/jobs/contours/") + d);
  for (const char* d : zlevel) same(std::string("/jobs/contours/zlevel/") + d);
  for (const char* d : cl) same(std::string("/jobs/creases/") + d);
  for (const char* d : pencil) same(std::string("/jobs/creases/pencil/") + d);
  // The height field 1 ... 3 stepped down by 0.25 from its top: levels above its lowest point.
  const scan_cli::Stats st{a, "contours"};
  EXPECT_EQ(st["levels"], std::ceil((st["top_z"] - st["bottom_z"]) / 0.25) - 1);
  EXPECT_EQ(st["open_chains"], 0);
  // The pocket's creases: the floor's square and the corners, each a cut path.
  EXPECT_GE((scan_cli::Stats{a, "creases"}["paths"]), 1);
}

TEST(MeshOpCli, ProblemsAreNamed) {
  const auto dir = scan_cli::fixture_dir("mesh_op_problems");
  scan_cli::write_off(dir / "groove.off", scan_cli::groove(false));
  const std::string mesh = "--mesh " + (dir / "groove.off").string();
  expect_failure(dir, "zlevel", mesh + " --tool flat:4 --levels 1", "needs a ball-end mill");
  expect_failure(dir, "zlevel", mesh + " --tool bull:4:1 --step-down 1", "needs a ball-end mill");
  expect_failure(dir, "zlevel", mesh + " --tool ball:4 --levels 1,2 --step-down 1",
                 "--levels and --step-down are both given: give one of them");
  expect_failure(dir, "zlevel", mesh + " --tool ball:4",
                 "--levels or --step-down is required for a zlevel job");
  expect_failure(dir, "zlevel", mesh + " --tool ball:4 --step-down 0",
                 "--step-down must be a positive number of mm, got 0");
  expect_failure(dir, "zlevel", mesh + " --tool ball:4 --levels 1 --tolerance 0",
                 "--tolerance must be a positive number of mm, got 0");
  expect_failure(dir, "pencil", mesh + " --tool flat:4", "needs a ball-end mill");
  expect_failure(dir, "pencil", mesh + " --tool ball:4 --min-angle 200",
                 "--min-angle must be between 0 and 180 degrees, got 200");
  expect_failure(dir, "pencil", mesh + " --tool ball:4 --min-angle 0",
                 "--min-angle must be between 0 and 180 degrees, got 0");
  expect_failure(dir, "pencil", mesh + " --tool ball:4 --interval 0",
                 "--interval must be a positive number of mm, got 0");
  expect_failure(dir, "pencil", mesh + " --tool ball:4 --merge-distance -1",
                 "--merge-distance must be >= 0 mm");
  expect_failure(dir, "pencil", mesh + " --tool ball:4 --stock -2",
                 "--stock must be greater than minus the ball radius (-2 mm)");
  // CLI11 refuses a direction that is not one of the three before anything runs, naming it.
  expect_refused(
      "pencil " + mesh + " --tool ball:4 --direction down --quiet --out " + (dir / "d.h5").string(),
      "--direction");
  // CLI11 refuses a level that is not a number before anything runs, naming the option.
  expect_refused("zlevel " + mesh + " --levels 1,x --quiet --out " + (dir / "x.h5").string(),
                 "--levels");

  // The same in a batch file: each bad job is recorded and the good ones still run.
  std::ofstream(dir / "jobs.toml") << R"(
output = "batch.h5"
[[job]]
name = "zlevel-flat"
operation = "zlevel"
input = "groove.off"
tool = "flat:4"
params = { levels = [1] }
[[job]]
name = "zlevel-both"
operation = "zlevel"
input = "groove.off"
tool = "ball:4"
params = { levels = [1], step_down = 1 }
[[job]]
name = "pencil-flat"
operation = "pencil"
input = "groove.off"
tool = "flat:4"
[[job]]
name = "pencil-angle"
operation = "pencil"
input = "groove.off"
tool = "ball:4"
params = { min_angle = 200 }
[[job]]
name = "pencil-direction"
operation = "pencil"
input = "groove.off"
tool = "ball:4"
params = { direction = "sideways" }
[[job]]
name = "zlevel-good"
operation = "zlevel"
input = "groove.off"
tool = "ball:4"
params = { levels = [2, 5] }
[[job]]
name = "pencil-good"
operation = "pencil"
input = "groove.off"
tool = "ball:4"
params = { interval = 2, step_down = 0 }
)";
  expect_bad_jobs_named(
      dir, "7 job(s), 2 ok, 5 failed",
      {{"zlevel-flat", "z-level contouring needs a ball-end mill"},
       {"zlevel-both", "'params.levels' and 'params.step_down' are both given"},
       {"pencil-flat", "pencil-cut needs a ball-end mill"},
       {"pencil-angle", "min_angle must be between 0 and 180 degrees, got 200"},
       {"pencil-direction",
        "'params.direction' must be \"any\", \"climb\" or \"conventional\", got \"sideways\""}},
      {"zlevel-good", "pencil-good"});
  h5::Id f = h5::open_read(dir / "batch.h5");
  // The groove z = |x| at levels 2 and 5: two lines each side, no hole (its ends are open).
  const scan_cli::Stats st{f, "zlevel-good"};
  EXPECT_EQ(st["levels"], 2);
}

TEST(MeshOpCli, HelpDocumentsEveryOption) {
  const CmdResult z = ncpath("zlevel --help");
  EXPECT_EQ(z.exit_code, 0);
  for (const char* s : {"--mesh", "--tool", "--levels", "--step-down", "--tolerance", "--out",
                        "--name", "--threads", "--fit-xy", "--scale", "--translate", "--quiet",
                        "--gcode", "--dialect", "--feed", "--safe-z", "ball"})
    EXPECT_NE(z.output.find(s), std::string::npos) << s;
  const CmdResult p = ncpath("pencil --help");
  EXPECT_EQ(p.exit_code, 0);
  for (const char* s :
       {"--mesh", "--tool", "--interval", "--step-down", "--min-angle", "--tolerance",
        "--merge-distance", "--min-length", "--margin", "--floor-z", "--stock", "--direction",
        "climb", "conventional", "--out", "--name", "--threads", "--fit-xy", "--quiet", "--gcode",
        "--safe-z", "ball"})
    EXPECT_NE(p.output.find(s), std::string::npos) << s;
  const std::string top = ncpath("--help").output;
  EXPECT_NE(top.find("zlevel"), std::string::npos);
  EXPECT_NE(top.find("pencil"), std::string::npos);
}

}  // namespace
}  // namespace ncpath
