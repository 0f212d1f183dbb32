// The ncpath program end to end: batch semantics, statuses in HDF5, exit codes, thread
// determinism of the written datasets, help texts.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "batch/io/stl_writer.hpp"
#include "tests/batch/cli_run.hpp"
#include "tests/batch/output/h5_read.hpp"
#include "tests/support/meshes.hpp"

namespace ncpath {
namespace {

namespace h5 = out::test;

using test::CmdResult;
using test::ncpath;
using test::slurp;

// A folder of its own per test: ctest runs the tests of this binary in parallel processes.
std::filesystem::path fixture_dir() {
  const auto dir = test::part_dir("cli_");
  std::ofstream(dir / "xy.csv") << "# x,y\n1,1\n20,20\n\n500,500\n";
  return dir;
}

TEST(Cli, BatchRecordsEveryJobAndGoesOnAfterFailures) {
  const auto dir = fixture_dir();
  std::ofstream(dir / "jobs.toml") << R"(
output = "out.h5"
[[job]]
name = "good"
input = "part.stl"
tool = "ball:4"
params = { interval = 2, step = 0.5 }
[[job]]
name = "missing"
input = "nope.stl"
tool = "ball:4"
[[job]]
name = "bad-corner"
input = "part.stl"
tool = "bull:4:3"
[[job]]
name = "points"
operation = "drop"
input = "part.stl"
tool = "flat:3"
params = { points = "xy.csv" }
)";
  const CmdResult r = ncpath("run " + (dir / "jobs.toml").string() + " --quiet");
  EXPECT_EQ(r.exit_code, 1) << r.output;  // some job failed
  EXPECT_NE(r.output.find("4 job(s), 2 ok, 2 failed"), std::string::npos) << r.output;
  h5::Id f = h5::open_read(dir / "out.h5");
  EXPECT_EQ(h5::attr_str(f, "format"), "ncpath-cl");
  h5::Id good(H5Gopen2(f, "/jobs/good", H5P_DEFAULT));
  EXPECT_EQ(h5::attr_str(good, "status"), "ok");
  EXPECT_NE(h5::attr_str(good, "params").find("\"interval\":2.0"), std::string::npos);
  EXPECT_NE(h5::attr_str(good, "tool").find("\"diameter_mm\":4.0"), std::string::npos);
  EXPECT_EQ(h5::attr_str(good, "input_sha256").size(), 64u);
  const auto offsets =
      h5::read_all<std::int64_t>(f, "/jobs/good/cl/path_offsets", H5T_NATIVE_INT64);
  // 40 / 2 + 1 = 21 lines of 40 / 0.5 + 1 = 81 points, 20 links in between; a line that
  // climbs onto the part gets lift-overs (chord guard) instead of chords through its edges.
  EXPECT_EQ(offsets.size(), 21u + 20u + 1u);
  EXPECT_GE(offsets[1], 81);
  h5::Id missing(H5Gopen2(f, "/jobs/missing", H5P_DEFAULT));
  EXPECT_EQ(h5::attr_str(missing, "status"), "invalid_input");
  EXPECT_NE(h5::attr_str(missing, "message").find("nope.stl"), std::string::npos);
  h5::Id bad(H5Gopen2(f, "/jobs/bad-corner", H5P_DEFAULT));
  EXPECT_EQ(h5::attr_str(bad, "status"), "invalid_parameter");
  EXPECT_NE(h5::attr_str(bad, "message").find("corner radius 3"), std::string::npos);
  // Drop: input order kept, the miss flagged with NaN and contact 0.
  const auto pts = h5::read_all<double>(f, "/jobs/points/cl/points", H5T_NATIVE_DOUBLE);
  const auto kinds =
      h5::read_all<std::uint8_t>(f, "/jobs/points/cl/contact_kind", H5T_NATIVE_UINT8);
  const auto poff = h5::read_all<std::int64_t>(f, "/jobs/points/cl/path_offsets", H5T_NATIVE_INT64);
  ASSERT_EQ(pts.size(), 9u);
  EXPECT_EQ(poff, (std::vector<std::int64_t>{0, 2, 3}));  // the blank line split the paths
  EXPECT_EQ(pts[3], 20);
  EXPECT_FALSE(std::isnan(pts[5]));
  EXPECT_TRUE(std::isnan(pts[8]));
  EXPECT_EQ(kinds[2], 0);
}

// Job `job` (a path /jobs/<name>) of file f has the int64 statistic `stat` equal to value.
void expect_stat(hid_t f, const std::string& job, const std::string& stat, std::int64_t value) {
  EXPECT_EQ(h5::read_all<std::int64_t>(f, job + "/stats/" + stat, H5T_NATIVE_INT64),
            std::vector<std::int64_t>{value})
      << job << " " << stat;
}

// Runs the jobs (TOML job tables) as one batch, all.h5, and each alone, one<k>.h5.
void run_together_and_alone(const std::filesystem::path& dir,
                            const std::vector<std::string>& jobs) {
  std::ofstream all(dir / "all.toml");
  all << "output = \"all.h5\"\n";
  for (const std::string& j : jobs) all << "[[job]]\n" << j;
  all.close();
  for (std::size_t k = 0; k < jobs.size(); ++k)
    std::ofstream(dir / ("one" + std::to_string(k) + ".toml"))
        << "output = \"one" << k << ".h5\"\n[[job]]\n"
        << jobs[k];
  for (std::size_t k = 0; k <= jobs.size(); ++k) {
    const std::string name = k == jobs.size() ? "all" : "one" + std::to_string(k);
    const CmdResult r = ncpath("run " + (dir / (name + ".toml")).string() + " --quiet");
    ASSERT_EQ(r.exit_code, 0) << name << ": " << r.output;
  }
}

// Job `job` (a path /jobs/<name>, the k-th job of run_together_and_alone) wrote the same
// points in all.h5 as alone in one<k>.h5; returns one<k>.h5 for further checks.
h5::Id expect_points_as_alone(const std::filesystem::path& dir, hid_t all, std::size_t k,
                              const std::string& job) {
  h5::Id one = h5::open_read(dir / ("one" + std::to_string(k) + ".h5"));
  EXPECT_EQ(h5::read_all<double>(all, job + "/cl/points", H5T_NATIVE_DOUBLE),
            h5::read_all<double>(one, job + "/cl/points", H5T_NATIVE_DOUBLE))
      << job;
  return one;
}

// Jobs on the same file and transform share its read mesh and swept-tool index (the
// verifier's and the chord guard's): each writes the datasets it writes when run alone, and
// says whether it reused the mesh; another transform of the same file is read again.
TEST(Cli, JobsOnOneMeshShareItAndWriteWhatTheyWriteAlone) {
  const auto dir = fixture_dir();
  ASSERT_NO_FATAL_FAILURE(run_together_and_alone(
      dir, {"name = \"a\"\ninput = \"part.stl\"\ntool = \"ball:4\"\n"
            "params = { interval = 2, step = 0.5 }\n",
            "name = \"b\"\noperation = \"zlevel\"\ninput = \"part.stl\"\ntool = \"ball:4\"\n"
            "params = { levels = [2.0, 2.5] }\n",
            "name = \"c\"\ninput = \"part.stl\"\ntool = \"ball:4\"\ntransform = { scale = 1.5 }\n"
            "params = { interval = 2, step = 0.5 }\n"}));
  h5::Id all = h5::open_read(dir / "all.h5");
  const std::int64_t shared[3] = {0, 1, 0};
  for (int k = 0; k < 3; ++k) {
    const std::string job = std::string("/jobs/") + char('a' + k);
    h5::Id one = expect_points_as_alone(dir, all, std::size_t(k), job);
    expect_stat(all, job, "mesh_shared", shared[k]);
    EXPECT_GT(h5::read_all<double>(all, job + "/cl/points", H5T_NATIVE_DOUBLE).size(), 30u)
        << job;
    EXPECT_EQ(h5::read_all<std::int64_t>(all, job + "/cl/path_offsets", H5T_NATIVE_INT64),
              h5::read_all<std::int64_t>(one, job + "/cl/path_offsets", H5T_NATIVE_INT64))
        << job;
    h5::Id g(H5Gopen2(all, job.c_str(), H5P_DEFAULT));
    h5::Id g1(H5Gopen2(one, job.c_str(), H5P_DEFAULT));
    EXPECT_EQ(h5::attr_str(g, "input_sha256"), h5::attr_str(g1, "input_sha256"));
    EXPECT_EQ(h5::attr_str(g, "status"), "ok");
  }
}

// Scan jobs on one mesh with the same ball share their elements (built once, by the first):
// elements_shared 0, 1 and 0 for a job with another ball; each writes what it writes alone.
TEST(Cli, ScanJobsOnOneMeshAndBallShareTheirElements) {
  const auto dir = fixture_dir();
  const std::string scan = "operation = \"scan\"\ninput = \"part.stl\"\n";
  ASSERT_NO_FATAL_FAILURE(run_together_and_alone(
      dir,
      {"name = \"x\"\n" + scan + "tool = \"ball:4\"\nparams = { families = \"x\", interval = 1 }\n",
       "name = \"y\"\n" + scan +
           "tool = \"ball:4\"\nparams = { families = \"y\", interval = 1.5 }\n",
       "name = \"z\"\n" + scan +
           "tool = \"ball:6\"\nparams = { families = \"both\", interval = 2 }\n"}));
  h5::Id all = h5::open_read(dir / "all.h5");
  const std::int64_t shared[3] = {0, 1, 0};
  for (int k = 0; k < 3; ++k) {
    const std::string job = std::string("/jobs/") + "xyz"[k];
    h5::Id one = expect_points_as_alone(dir, all, std::size_t(k), job);
    expect_stat(all, job, "elements_shared", shared[k]);
    expect_stat(one, job, "elements_shared", 0);
    EXPECT_GT(h5::read_all<double>(all, job + "/cl/points", H5T_NATIVE_DOUBLE).size(), 30u)
        << job;
    for (const char* table : {"/scan/segment_start", "/scan/junction_position"})
      EXPECT_EQ(h5::read_all<double>(all, job + table, H5T_NATIVE_DOUBLE),
                h5::read_all<double>(one, job + table, H5T_NATIVE_DOUBLE))
          << job << table;
  }
}

// Z-level, pencil and fillet jobs on one mesh condition it once (conditioned_shared 0, 1, 1),
// and each writes what it writes alone.
TEST(Cli, SlicingJobsOnOneMeshConditionItOnce) {
  const auto dir = fixture_dir();
  const std::string part = "input = \"part.stl\"\n";
  ASSERT_NO_FATAL_FAILURE(run_together_and_alone(
      dir, {"name = \"z\"\noperation = \"zlevel\"\n" + part +
                "tool = \"ball:4\"\nparams = { step_down = 0.5 }\n",
            "name = \"p\"\noperation = \"pencil\"\n" + part +
                "tool = \"ball:6\"\nparams = { interval = 0.5 }\n",
            "name = \"f\"\noperation = \"fillet\"\n" + part +
                "tool = \"ball:2\"\nparams = { reference = \"ball:8\", interval = 0.5 }\n"}));
  h5::Id all = h5::open_read(dir / "all.h5");
  const std::int64_t shared[3] = {0, 1, 1};
  for (int k = 0; k < 3; ++k) {
    const std::string job = std::string("/jobs/") + "zpf"[k];
    expect_points_as_alone(dir, all, std::size_t(k), job);
    expect_stat(all, job, "conditioned_shared", shared[k]);
    h5::Id g(H5Gopen2(all, job.c_str(), H5P_DEFAULT));
    EXPECT_EQ(h5::attr_str(g, "status"), "ok") << job;
  }
  EXPECT_GT(h5::read_all<double>(all, "/jobs/z/cl/points", H5T_NATIVE_DOUBLE).size(), 30u);
}

TEST(Cli, OneAndTwoThreadsWriteIdenticalDatasets) {
  const auto dir = fixture_dir();
  for (const char* t : {"1", "2"}) {
    const CmdResult r =
        ncpath("raster --mesh " + (dir / "part.stl").string() +
               " --tool bull:6:1 --interval 0.7 --step 0.2 --adaptive 0.002 --threads " + t +
               " --quiet --out " + (dir / (std::string("t") + t + ".h5")).string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
  h5::Id a = h5::open_read(dir / "t1.h5");
  h5::Id b = h5::open_read(dir / "t2.h5");
  for (const char* ds : {"points", "path_offsets", "path_kind", "contact_kind"}) {
    const std::string path = std::string("/jobs/raster/cl/") + ds;
    EXPECT_GT(h5::read_all<std::uint8_t>(a, path, H5T_NATIVE_UINT8).size(), 0u) << path;
  }
  EXPECT_EQ(h5::read_all<double>(a, "/jobs/raster/cl/points", H5T_NATIVE_DOUBLE),
            h5::read_all<double>(b, "/jobs/raster/cl/points", H5T_NATIVE_DOUBLE));
  EXPECT_EQ(h5::read_all<std::int64_t>(a, "/jobs/raster/cl/path_offsets", H5T_NATIVE_INT64),
            h5::read_all<std::int64_t>(b, "/jobs/raster/cl/path_offsets", H5T_NATIVE_INT64));
  EXPECT_EQ(h5::read_all<std::uint8_t>(a, "/jobs/raster/cl/contact_kind", H5T_NATIVE_UINT8),
            h5::read_all<std::uint8_t>(b, "/jobs/raster/cl/contact_kind", H5T_NATIVE_UINT8));
}

TEST(Cli, BadCommandLinesAreRejectedWithTheKey) {
  const auto dir = fixture_dir();
  const std::string mesh =
      " --mesh " + (dir / "part.stl").string() + " --quiet --out " + (dir / "x.h5").string();
  CmdResult r = ncpath("raster" + mesh + " --step 0");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("step must be a positive number"), std::string::npos) << r.output;
  r = ncpath("raster" + mesh + " --tool ball:-2");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("diameter"), std::string::npos) << r.output;
  r = ncpath("raster" + mesh + " --no-such-option 3");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("no-such-option"), std::string::npos) << r.output;
  r = ncpath("run " + (dir / "absent.toml").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("absent.toml"), std::string::npos);
}

TEST(Cli, OffsetWritesLoopsLevelsAndGraph) {
  const auto dir = fixture_dir();
  // 100 x 60 rectangle with a circular island of radius 5 at (50, 30), written by hand.
  std::ofstream(dir / "pocket.toml") << R"(
[[loop]]
segments = [ { line = [[0, 0], [100, 0]] }, { line_to = [100, 60] }, { line_to = [0, 60] },
             { line_to = [0, 0] } ]
[[circle]]
center = [50, 30]
radius = 5
)";
  const CmdResult r =
      ncpath("offset --profile " + (dir / "pocket.toml").string() +
             " --tool flat:6 --stepover 50% --depth 2 --quiet --out " + (dir / "off.h5").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  h5::Id f = h5::open_read(dir / "off.h5");
  const auto level =
      h5::read_all<std::int64_t>(f, "/jobs/offset/offset/loop_level", H5T_NATIVE_INT64);
  const auto area = h5::read_all<double>(f, "/jobs/offset/offset/loop_area", H5T_NATIVE_DOUBLE);
  ASSERT_GE(level.size(), 2u);
  // Level 1 at d = 3 + m (m = 0.01, the polylines' chordal tolerance, kept on the free side:
  // docs/architecture.md): the rectangle 94 x 54 less m on every side and the island grown
  // to radius 8 + m.
  EXPECT_EQ(level[0], 1);
  const double m = 0.01;
  EXPECT_NEAR(area[0] + area[1], -(94.0 - 2 * m) * (54.0 - 2 * m) + M_PI * (8 + m) * (8 + m), 1e-6);
  const auto pts = h5::read_all<double>(f, "/jobs/offset/cl/points", H5T_NATIVE_DOUBLE);
  EXPECT_EQ(pts[2], -2.0);  // written at the depth
  const auto edges =
      h5::read_all<std::int64_t>(f, "/jobs/offset/offset/ogh_edges", H5T_NATIVE_INT64);
  EXPECT_GT(edges.size(), 0u);
  for (std::size_t k = 0; k + 1 < edges.size(); k += 2)
    EXPECT_EQ(level[edges[k]], level[edges[k + 1]] + 1);  // a parent is one level up
  // A profile that does not close is reported with the entity.
  std::ofstream(dir / "open.toml") << "[[polyline]]\npoints = [[0,0],[10,0],[10,10]]\n";
  const CmdResult bad =
      ncpath("offset --profile " + (dir / "open.toml").string() +
             " --tool flat:6 --stepover 2 --quiet --out " + (dir / "bad.h5").string());
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.output.find("invalid_input"), std::string::npos) << bad.output;
}

TEST(Cli, GcodeIsWrittenWithASafeHeightAboveThePart) {
  const auto dir = fixture_dir();  // part.stl: z in [1, 3]
  CmdResult r =
      ncpath("raster --mesh " + (dir / "part.stl").string() +
             " --tool ball:4 --interval 4 --step 1 --quiet --out " + (dir / "g.h5").string() +
             " --gcode " + (dir / "g.ngc").string() + " --dialect grbl --feed 1500");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string g = slurp(dir / "g.ngc");
  EXPECT_NE(g.find("G21 G90 G17"), std::string::npos);
  EXPECT_NE(g.find("F1500"), std::string::npos);
  EXPECT_EQ(g.find("G40"), std::string::npos);  // not in the Grbl preamble
  // Safe height: 5 mm above the part's top (the height field peaks just under z = 3).
  const auto at = g.find("G0 Z");
  ASSERT_NE(at, std::string::npos);
  const double safe = std::stod(g.substr(at + 4, 8));
  EXPECT_GT(safe, 7.9);
  EXPECT_LE(safe, 8.0);
  EXPECT_NE(g.find("M2"), std::string::npos);
  // A safe height below the part is refused, naming the key.
  r = ncpath("raster --mesh " + (dir / "part.stl").string() +
             " --tool ball:4 --interval 4 --step 1 --quiet --out " + (dir / "g2.h5").string() +
             " --gcode " + (dir / "g2.ngc").string() + " --safe-z 2");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("gcode.safe_z"), std::string::npos) << r.output;
  // Pocket loops come out with arcs.
  std::ofstream(dir / "disc.toml") << "[[circle]]\ncenter = [0, 0]\nradius = 20\n";
  r = ncpath("offset --profile " + (dir / "disc.toml").string() +
             " --tool flat:6 --stepover 3 --depth 2 --quiet --out " + (dir / "p.h5").string() +
             " --gcode " + (dir / "p.ngc").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string p = slurp(dir / "p.ngc");
  EXPECT_TRUE(p.find("G2 ") != std::string::npos || p.find("G3 ") != std::string::npos);
  EXPECT_NE(p.find("Z-2.0000"), std::string::npos);
}

TEST(Cli, HelpDocumentsEveryOption) {
  const CmdResult top = ncpath("--help");
  for (const char* s : {"raster", "drop", "run"})
    EXPECT_NE(top.output.find(s), std::string::npos) << s;
  const CmdResult r = ncpath("raster --help");
  for (const char* s : {"--mesh", "--tool", "--interval", "--step", "--out", "--threads",
                        "--direction", "--margin", "--rect", "--adaptive", "--min-step",
                        "--floor-z", "--fit-xy", "--scale", "--translate", "--quiet"})
    EXPECT_NE(r.output.find(s), std::string::npos) << s;
  EXPECT_NE(ncpath("drop --help").output.find("--points"), std::string::npos);
  const CmdResult o = ncpath("offset --help");
  for (const char* s : {"--profile", "--stepover", "--stock", "--depth", "--tolerance",
                        "--join-tolerance", "--tool", "--out"})
    EXPECT_NE(o.output.find(s), std::string::npos) << s;
}

// Jobs run at the same time write what they write one at a time: every dataset, attribute
// and statistic but the timings, in batch order, a failing job failing alone, no spool file
// left. Also under a memory budget so small that every job runs alone.
TEST(Cli, ConcurrentJobsWriteWhatJobsOneAtATimeWrite) {
  const auto dir = fixture_dir();
  test::write_seven_job_batch(dir);
  const char* runs[][2] = {{"one.h5", "--concurrent-jobs 1"},
                           {"many.h5", "--concurrent-jobs 2"},
                           {"tight.h5", "--concurrent-jobs 2 --memory-limit 1"}};
  for (const auto& run : runs) {
    const CmdResult r = ncpath("run " + (dir / "batch.toml").string() + " --quiet --out " +
                               (dir / run[0]).string() + " " + run[1]);
    EXPECT_EQ(r.exit_code, 1) << run[1] << ": " << r.output;  // the missing input fails
    EXPECT_NE(r.output.find("7 job(s), 6 ok, 1 failed"), std::string::npos) << r.output;
  }
  auto timing = [](const std::string& name) {
    return name.ends_with("_s") || name.ends_with("/peak_rss_bytes");
  };
  EXPECT_TRUE(h5::same_content(dir / "one.h5", dir / "many.h5", timing));
  EXPECT_TRUE(h5::same_content(dir / "one.h5", dir / "tight.h5", timing));
  h5::Id f = h5::open_read(dir / "many.h5");
  h5::Id missing(H5Gopen2(f, "/jobs/missing", H5P_DEFAULT));
  EXPECT_EQ(h5::attr_str(missing, "status"), "invalid_input");
  h5::Id pencil(H5Gopen2(f, "/jobs/pencil", H5P_DEFAULT));
  EXPECT_EQ(h5::attr_str(pencil, "status"), "ok");
  EXPECT_GT(h5::read_all<double>(f, "/jobs/raster2/cl/points", H5T_NATIVE_DOUBLE).size(), 30u);
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    EXPECT_EQ(entry.path().string().find(".spool-"), std::string::npos) << entry.path();
}

TEST(Cli, BadMemoryLimitIsNamed) {
  const auto dir = fixture_dir();
  std::ofstream(dir / "b.toml") << "output = \"x.h5\"\nmemory_limit = \"lots\"\n[[job]]\n"
                                << "input = \"part.stl\"\ntool = \"ball:4\"\n";
  CmdResult r = ncpath("run " + (dir / "b.toml").string() + " --quiet");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("memory_limit"), std::string::npos) << r.output;
  std::ofstream(dir / "c.toml") << "output = \"x.h5\"\n[[job]]\n"
                                << "input = \"part.stl\"\ntool = \"ball:4\"\n";
  r = ncpath("run " + (dir / "c.toml").string() + " --quiet --memory-limit 8X");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--memory-limit"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace ncpath
