// The scan command: identical datasets for 1 and 2 threads, both families in one job (a rapid
// between them), the problems a user can make (a tool that is not a ball, a bad interval, an
// unknown family) reported by key with status invalid_parameter, and the help text.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "batch/io/stl_writer.hpp"
#include "tests/batch/cli_job_checks.hpp"
#include "tests/batch/cli_run.hpp"
#include "tests/batch/output/h5_read.hpp"
#include "tests/batch/scan_cli_support.hpp"
#include "tests/support/meshes.hpp"

namespace ncpath {
namespace {

namespace h5 = out::test;
using test::CmdResult;
using test::ncpath;
using namespace cli_checks;
using namespace scan_cli;

TEST(ScanCli, OneAndTwoThreadsWriteIdenticalDatasets) {
  const auto dir = fixture_dir("threads");
  const TriangleMesh m = test::height_field(
      20, 40, [](double x, double y) { return 2 + std::sin(x / 5) * std::cos(y / 4); });
  io::write_binary_stl(dir / "part.stl", m);
  // Small chunks, so that both threads get work and chunks are handed over many times.
  std::ofstream(dir / "jobs.toml") << R"(
output = "unused.h5"
[[job]]
name = "both"
operation = "scan"
input = "part.stl"
tool = "ball:6"
params = { families = "both", interval = 1.5, tolerance = 0.002, margin = 2, chunk_planes = 3 }
)";
  ASSERT_NO_FATAL_FAILURE(run_with_one_and_two_threads(dir));
  h5::Id a = h5::open_read(dir / "t1.h5");
  h5::Id b = h5::open_read(dir / "t2.h5");
  EXPECT_EQ((Stats{a, "both"}["threads"]), 1);
  EXPECT_EQ((Stats{b, "both"}["threads"]), 2);
  for (const char* d :
       {"cl/points", "cl/path_offsets", "cl/path_kind", "cl/contact_kind", "scan/segment_path",
        "scan/segment_kind", "scan/segment_element", "scan/segment_start", "scan/segment_end",
        "scan/segment_geometry", "scan/junction_path", "scan/junction_kind",
        "scan/junction_position", "scan/junction_b1", "scan/junction_b2",
        "scan/junction_element1", "scan/junction_element2", "scan/junction_angle"})
    expect_same_dataset(a, b, std::string("/jobs/both/") + d);
  // Both families: x lines (y = -2 ... 42 every 1.5: 30), a rapid, then y lines (30).
  const ScanOut s = read_scan(a, "both");
  const Stats st{a, "both"};
  EXPECT_EQ(st["planes_x"], 30);
  EXPECT_EQ(st["planes_y"], 30);
  EXPECT_EQ(st["planes"], 60);
  ASSERT_EQ(s.cut_paths.size(), 60u);
  std::size_t rapids = 0;
  for (std::size_t p = 0; p < s.kind.size(); ++p) rapids += s.kind[p] == 2;
  EXPECT_EQ(rapids, 1u);
  EXPECT_EQ(s.kind[s.cut_paths[30] - 1], 2);  // the rapid comes right before the first y line
  // The rapid is one point; points are the cut, link and rapid points.
  EXPECT_EQ(st["cut_points"] + st["link_points"] + 1, st["points"]);
  // x lines keep y, y lines keep x, whatever their segments and junctions.
  for (std::size_t i = 0; i < s.seg_kind.size(); ++i) {
    const int fixed = s.seg_path[i] < 30 ? 1 : 0;
    ASSERT_EQ(s.seg_start[3 * i + fixed], s.seg_end[3 * i + fixed]) << "segment " << i;
  }
  check_shapes(a, "both", s);
}

TEST(ScanCli, ProblemsAreNamed) {
  const auto dir = fixture_dir("problems");
  write_off(dir / "groove.off", groove(false));
  const std::string mesh = "--mesh " + (dir / "groove.off").string();
  expect_failure(dir, "scan", mesh + " --tool flat:4", "needs a ball-end mill");
  expect_failure(dir, "scan", mesh + " --tool bull:4:1", "needs a ball-end mill");
  expect_failure(dir, "scan", mesh + " --tool ball:4 --interval 0",
                 "interval must be a positive number");
  expect_failure(dir, "scan", mesh + " --tool ball:4 --tolerance -1",
                 "tolerance must be a positive");
  expect_failure(dir, "scan", mesh + " --tool ball:4 --rect 5 0 -5 20", "rect must be");
  // CLI11 refuses an unknown family before anything runs, naming the option.
  expect_refused("scan " + mesh + " --families z --quiet --out " + (dir / "z.h5").string(),
                 "--families");

  // The same in a batch file: each bad job is recorded and the good one still runs.
  std::ofstream(dir / "jobs.toml") << R"(
output = "batch.h5"
[[job]]
name = "flat"
operation = "scan"
input = "groove.off"
tool = "flat:4"
[[job]]
name = "interval"
operation = "scan"
input = "groove.off"
tool = "ball:4"
params = { interval = 0 }
[[job]]
name = "families"
operation = "scan"
input = "groove.off"
tool = "ball:4"
params = { families = "z" }
[[job]]
name = "good"
operation = "scan"
input = "groove.off"
tool = "ball:4"
params = { interval = 5 }
)";
  expect_bad_jobs_named(
      dir, "4 job(s), 1 ok, 3 failed",
      {{"flat", "ball-end mill"},
       {"interval", "interval must be a positive number of mm, got 0"},
       {"families", "'params.families' must be \"x\", \"y\" or \"both\", got \"z\""}},
      {"good"});
}

TEST(ScanCli, HelpDocumentsEveryOption) {
  const CmdResult r = ncpath("scan --help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* s : {"--mesh", "--tool", "--families", "--interval", "--tolerance", "--margin",
                        "--rect", "--floor-z", "--out", "--name", "--threads", "--fit-xy",
                        "--scale", "--translate", "--quiet", "--gcode", "--dialect", "--feed",
                        "--safe-z", "ball"})
    EXPECT_NE(r.output.find(s), std::string::npos) << s;
  EXPECT_EQ(r.output.find("--step "), std::string::npos);
  EXPECT_NE(ncpath("--help").output.find("scan"), std::string::npos);
}

}  // namespace
}  // namespace ncpath
