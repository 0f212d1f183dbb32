// The pocket command and the pocket job end to end: the linked path in HDF5 (kinds, depths,
// continuity), every statistic with its unit, the G-code program, thread determinism, and
// bad parameters reported with the key (or, for a tool too big, with the boundary's entity).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "tests/batch/cli_run.hpp"
#include "tests/batch/io/dxf_test_util.hpp"
#include "tests/batch/output/h5_read.hpp"

namespace ncpath {
namespace {

namespace h5 = out::test;
using test::CmdResult;
using test::ncpath;
using test::slurp;

// A 60 x 40 rectangle with a circular island of radius 5 at (30, 20): one connected pocket.
constexpr const char* kPlate = R"(
[[loop]]
segments = [ { line = [[0, 0], [60, 0]] }, { line_to = [60, 40] }, { line_to = [0, 40] },
             { line_to = [0, 0] } ]
[[circle]]
center = [30, 20]
radius = 5
)";

// A folder of its own per test (ctest runs the tests of this binary in parallel processes)
// holding plate.toml.
std::filesystem::path fixture_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const auto dir = h5::out_dir(std::string("pocket_cli_") + (info ? info->name() : "none"));
  std::ofstream(dir / "plate.toml") << kPlate;
  return dir;
}

std::string args(const std::filesystem::path& dir, const std::string& out) {
  return "pocket --profile " + (dir / "plate.toml").string() + " --quiet --out " +
         (dir / out).string();
}

double stat(hid_t f, const std::string& job, const std::string& name) {
  const auto v = h5::read_all<double>(f, "/jobs/" + job + "/stats/" + name, H5T_NATIVE_DOUBLE);
  return v.empty() ? NAN : v[0];
}

std::string stat_unit(hid_t f, const std::string& job, const std::string& name) {
  const std::string path = "/jobs/" + job + "/stats/" + name;
  h5::Id ds(H5Dopen2(f, path.c_str(), H5P_DEFAULT), "open " + path);
  return h5::has_attr(ds, "unit") ? h5::attr_str(ds, "unit") : "";
}

TEST(PocketCli, WritesOneLinkedPathWithStatsAndGcode) {
  const auto dir = fixture_dir();
  const CmdResult r =
      ncpath(args(dir, "p.h5") + " --tool flat:6 --stepover 50% --depth 4 --stepdown 2 --gcode " +
             (dir / "p.ngc").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  h5::Id f = h5::open_read(dir / "p.h5");
  h5::Id job(H5Gopen2(f, "/jobs/pocket", H5P_DEFAULT));
  EXPECT_EQ(h5::attr_str(job, "operation"), "pocket");
  EXPECT_EQ(h5::attr_str(job, "status"), "ok");
  const std::string params = h5::attr_str(job, "params");
  for (const char* s : {"\"stepover\":3.0", "\"depth\":4.0", "\"stepdown\":2.0",
                        "\"order\":\"outward\"", "\"milling\":\"climb\"", "\"safe_z\":5.0"})
    EXPECT_NE(params.find(s), std::string::npos) << s << " in " << params;

  const auto pts = h5::read_all<double>(f, "/jobs/pocket/cl/points", H5T_NATIVE_DOUBLE);
  const auto off = h5::read_all<std::int64_t>(f, "/jobs/pocket/cl/path_offsets", H5T_NATIVE_INT64);
  const auto kind = h5::read_all<std::uint8_t>(f, "/jobs/pocket/cl/path_kind", H5T_NATIVE_UINT8);
  const auto contact =
      h5::read_all<std::uint8_t>(f, "/jobs/pocket/cl/contact_kind", H5T_NATIVE_UINT8);
  ASSERT_GT(kind.size(), 2u);
  ASSERT_EQ(off.size(), kind.size() + 1);
  ASSERT_EQ(static_cast<std::size_t>(off.back()) * 3, pts.size());
  EXPECT_TRUE(std::all_of(contact.begin(), contact.end(), [](std::uint8_t c) { return c == 0; }));
  // Cuts and links at depth; z between the floor and the safe height; the floor reached;
  // links at the depth of a pass (never above the top).
  EXPECT_NE(std::find(kind.begin(), kind.end(), 0), kind.end());
  EXPECT_NE(std::find(kind.begin(), kind.end(), 1), kind.end());
  double z_min = INFINITY;
  for (std::size_t k = 0; k < kind.size(); ++k)
    for (std::int64_t i = off[k]; i < off[k + 1]; ++i) {
      const double z = pts[3 * i + 2];
      EXPECT_GE(z, -4 - 1e-9);
      EXPECT_LE(z, 5 + 1e-9);
      if (kind[k] == 1) {
        EXPECT_LT(z, 0) << "link path " << k << " above the top";
      }
      z_min = std::min(z_min, z);
    }
  EXPECT_NEAR(z_min, -4, 1e-9);
  // One path: each path starts where the previous one ended.
  for (std::size_t k = 1; k < kind.size(); ++k) {
    if (off[k] == off[k - 1] || off[k + 1] == off[k]) continue;
    const std::int64_t end = off[k] - 1, start = off[k];
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(pts[3 * end + c], pts[3 * start + c], 1e-9)
          << "between paths " << k - 1 << " and " << k;
  }

  // Every statistic of the planner, with its unit.
  EXPECT_GT(stat(f, "pocket", "cut_length"), 0);
  EXPECT_EQ(stat(f, "pocket", "uncut_area_after"), 0);
  EXPECT_EQ(stat(f, "pocket", "depth_passes"), 2);
  EXPECT_EQ(stat(f, "pocket", "components"), 1);
  EXPECT_EQ(stat(f, "pocket", "retractions"), 0);  // one connected pocket
  EXPECT_EQ(stat(f, "pocket", "open_fragments"), 0);
  EXPECT_GT(stat(f, "pocket", "loops"), 2);
  EXPECT_EQ(stat(f, "pocket", "points"), static_cast<double>(off.back()));
  EXPECT_GE(stat(f, "pocket", "helix_entries") + stat(f, "pocket", "ramp_entries") +
                stat(f, "pocket", "plunge_entries"),
            1);
  for (const char* s : {"cleanup_length", "cut_length", "link_length", "rapid_length",
                        "slotting_length", "largest_gap_closed"})
    EXPECT_EQ(stat_unit(f, "pocket", s), "mm") << s;
  for (const char* s : {"uncut_area_before", "uncut_area_after", "unreachable_area"})
    EXPECT_EQ(stat_unit(f, "pocket", s), "mm^2") << s;
  for (const char* s :
       {"offset_s", "uncut_s", "link_s", "path_s", "read_s", "write_s", "compute_s"})
    EXPECT_EQ(stat_unit(f, "pocket", s), "s") << s;
  for (const char* s : {"loops", "levels", "links", "cleanup_curves", "gcode_arcs"})
    EXPECT_EQ(stat_unit(f, "pocket", s), "") << s;

  const std::string g = slurp(dir / "p.ngc");
  EXPECT_NE(g.find("G21 G90"), std::string::npos);
  EXPECT_NE(g.find("Z-4.0000"), std::string::npos);
  EXPECT_TRUE(g.find("G2 ") != std::string::npos || g.find("G3 ") != std::string::npos);
  EXPECT_NE(g.find("M2"), std::string::npos);
}

TEST(PocketCli, OneAndTwoThreadsWriteIdenticalPaths) {
  const auto dir = fixture_dir();
  for (const char* t : {"1", "2"}) {
    const CmdResult r = ncpath(args(dir, std::string("t") + t + ".h5") +
                               " --tool flat:4 --stepover 1.5 --depth 3 --threads " + t);
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
  h5::Id a = h5::open_read(dir / "t1.h5");
  h5::Id b = h5::open_read(dir / "t2.h5");
  EXPECT_EQ(h5::read_all<double>(a, "/jobs/pocket/cl/points", H5T_NATIVE_DOUBLE),
            h5::read_all<double>(b, "/jobs/pocket/cl/points", H5T_NATIVE_DOUBLE));
  EXPECT_EQ(h5::read_all<std::int64_t>(a, "/jobs/pocket/cl/path_offsets", H5T_NATIVE_INT64),
            h5::read_all<std::int64_t>(b, "/jobs/pocket/cl/path_offsets", H5T_NATIVE_INT64));
  EXPECT_EQ(h5::read_all<std::uint8_t>(a, "/jobs/pocket/cl/path_kind", H5T_NATIVE_UINT8),
            h5::read_all<std::uint8_t>(b, "/jobs/pocket/cl/path_kind", H5T_NATIVE_UINT8));
}

// Exit code 1, status invalid_parameter in the file, and `expected` in the printed message.
void expect_invalid_parameter(const std::filesystem::path& dir, const std::string& command,
                              const std::string& expected) {
  const std::string out = (dir / "bad.h5").string();
  const CmdResult r = ncpath(command + " --quiet --out " + out);
  EXPECT_EQ(r.exit_code, 1) << command << "\n" << r.output;
  EXPECT_NE(r.output.find("invalid_parameter"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(expected), std::string::npos) << expected << " in: " << r.output;
  h5::Id f = h5::open_read(out);
  h5::Id job(H5Gopen2(f, "/jobs/pocket", H5P_DEFAULT));
  EXPECT_EQ(h5::attr_str(job, "status"), "invalid_parameter");
  EXPECT_NE(h5::attr_str(job, "message").find(expected), std::string::npos);
}

TEST(PocketCli, BadParametersAreRejectedWithTheKey) {
  const auto dir = fixture_dir();
  const std::string plate = "pocket --profile " + (dir / "plate.toml").string();
  expect_invalid_parameter(dir, plate + " --tool flat:6 --depth 2 --stepover 0",
                           "stepover must be a positive number");
  expect_invalid_parameter(dir, plate + " --tool flat:6 --depth 2 --stepover 6.5",
                           "larger than the tool diameter 6 mm");
  expect_invalid_parameter(dir, plate + " --tool flat:6 --depth 2 --stepover 101%",
                           "larger than the tool diameter");
  expect_invalid_parameter(dir, plate + " --tool flat:6 --depth -1", "depth must be a positive");
  expect_invalid_parameter(dir, plate + " --tool flat:6 --depth 2 --ramp-angle 90",
                           "ramp_angle must be in (0, 90)");
  expect_invalid_parameter(dir, plate + " --tool flat:6 --depth 2 --safe-z 0.5",
                           "below the clearance height 1 mm");
  // CLI11 rejects what it can see: a missing depth, an unknown order.
  CmdResult r = ncpath(plate + " --quiet --out " + (dir / "x.h5").string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("--depth"), std::string::npos) << r.output;
  r = ncpath(plate + " --depth 2 --order sideways --quiet --out " + (dir / "x.h5").string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("sideways"), std::string::npos) << r.output;
}

// The message of an ok job (its status checked).
std::string ok_message(const std::filesystem::path& file, const std::string& job_name) {
  h5::Id f = h5::open_read(file);
  h5::Id job(H5Gopen2(f, ("/jobs/" + job_name).c_str(), H5P_DEFAULT));
  EXPECT_EQ(h5::attr_str(job, "status"), "ok");
  return h5::attr_str(job, "message");
}

// A DXF circle of radius 5 (handle 2F) and a 20 mm cutter: nothing to cut, an ok job with no
// point whose message says so and names the circle.
TEST(PocketCli, ATooBigToolIsNothingToCutAndNamesTheBoundarysEntity) {
  const auto dir = fixture_dir();
  const std::string dxf = test::dxf_entities(test::pairs(
      {"0", "CIRCLE", "5", "2F", "8", "0", "10", "0", "20", "0", "30", "0", "40", "5"}));
  std::ofstream(dir / "hole.dxf", std::ios::binary) << dxf;
  const CmdResult r = ncpath("pocket --profile " + (dir / "hole.dxf").string() +
                             " --tool flat:20 --depth 2 --quiet --out " + (dir / "x.h5").string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  const std::string message = ok_message(dir / "x.h5", "pocket");
  EXPECT_EQ(message.rfind("warning: nothing to cut (0 points)", 0), 0u) << message;
  EXPECT_NE(message.find("the tool does not fit in region 0 (boundary: CIRCLE 2F): left out"),
            std::string::npos)
      << message;
}

// Two pockets, one 4 mm wide: the 6 mm tool cuts the other and the job names the one it
// leaves out; the verifier checks the path against both.
TEST(PocketCli, OneRegionTooSmallDoesNotSinkTheOthers) {
  const auto dir = fixture_dir();
  std::ofstream(dir / "two.toml") << R"(
[[circle]]
center = [0, 0]
radius = 20
[[circle]]
center = [50, 0]
radius = 2
)";
  const CmdResult r = ncpath("pocket --profile " + (dir / "two.toml").string() +
                             " --tool flat:6 --depth 2 --quiet --out " + (dir / "two.h5").string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  const std::string message = ok_message(dir / "two.h5", "pocket");
  EXPECT_EQ(message,
            "warning: the tool does not fit in region 1 (boundary: circle 1): left out");
  h5::Id f = h5::open_read(dir / "two.h5");
  EXPECT_EQ(stat(f, "pocket", "regions_left_out"), 1);
  EXPECT_EQ(stat(f, "pocket", "verify_max_gouge"), 0);
  const auto pts = h5::read_all<double>(f, "/jobs/pocket/cl/points", H5T_NATIVE_DOUBLE);
  ASSERT_GT(pts.size(), 30u);
  for (std::size_t i = 0; i + 2 < pts.size(); i += 3)
    if (pts[i + 2] < 0) EXPECT_LE(std::hypot(pts[i], pts[i + 1]), 20 - 3 + 1e-6);
}

// A string statistic of a job ("" when absent).
std::string string_stat(hid_t f, const std::string& job, const std::string& name) {
  const std::string path = "/jobs/" + job + "/stats/" + name;
  if (H5Lexists(f, path.c_str(), H5P_DEFAULT) <= 0) return "";
  h5::Id ds(H5Dopen2(f, path.c_str(), H5P_DEFAULT), "open " + path);
  std::string v = h5::value_bytes(ds, false);
  return v.empty() ? v : v.substr(0, v.size() - 1);  // one string, '\0'-terminated
}

// A 4 x 2 rectangle, in the units of its $INSUNITS (code "" for none).
std::string rectangle_dxf(const std::string& insunits) {
  std::string header = test::pairs({"0", "SECTION", "2", "HEADER", "9", "$ACADVER", "1", "AC1015"});
  if (!insunits.empty()) header += test::pairs({"9", "$INSUNITS", "70", insunits});
  return header + test::pairs({"0", "ENDSEC"}) +
         test::dxf_entities(test::pairs({"0", "LWPOLYLINE", "5", "2A", "8", "0", "90", "4", "70",
                                         "1", "10", "0", "20", "0", "10", "4", "20", "0", "10",
                                         "4", "20", "2", "10", "0", "20", "2"}));
}

// The issue's inch drawing: 101.6 x 50.8 mm, pocketed with a 6 mm tool inside it; the units
// are recorded; a drawing without units is pocketed as mm with a warning in the job's message;
// --units overrides the drawing.
TEST(PocketCli, DrawingUnitsScaleThePartAndAreRecorded) {
  const auto dir = fixture_dir();
  auto run = [&](const std::string& file, const std::string& insunits, const std::string& extra,
                 int exit_code = 0) {
    std::ofstream(dir / file, std::ios::binary) << rectangle_dxf(insunits);
    const CmdResult r = ncpath("pocket --profile " + (dir / file).string() +
                               " --depth 2 --quiet --out " + (dir / (file + ".h5")).string() +
                               extra);
    EXPECT_EQ(r.exit_code, exit_code) << r.output;
    return h5::open_read(dir / (file + ".h5"));
  };
  auto x_extent = [](hid_t f) {
    const auto pts = h5::read_all<double>(f, "/jobs/pocket/cl/points", H5T_NATIVE_DOUBLE);
    double lo = 1e300, hi = -1e300;
    for (std::size_t i = 0; i + 2 < pts.size(); i += 3)
      if (pts[i + 2] < 0) lo = std::min(lo, pts[i]), hi = std::max(hi, pts[i]);
    return std::make_pair(lo, hi);
  };
  {
    h5::Id f = run("inch.dxf", "1", " --tool flat:6");
    h5::Id job(H5Gopen2(f, "/jobs/pocket", H5P_DEFAULT));
    EXPECT_EQ(h5::attr_str(job, "message"), "");
    EXPECT_EQ(string_stat(f, "pocket", "units"), "inch");
    EXPECT_EQ(string_stat(f, "pocket", "units_from"), "$INSUNITS");
    EXPECT_EQ(stat(f, "pocket", "mm_per_unit"), 25.4);
    // The tool's centre stays 3 mm inside the walls and reaches them (to the tolerance).
    const auto [lo, hi] = x_extent(f);
    EXPECT_NEAR(lo, 3, 0.02);
    EXPECT_NEAR(hi, 101.6 - 3, 0.02);
  }
  {
    // As mm the 6 mm tool does not fit: nothing to cut, and the message names the guess.
    h5::Id f = run("none.dxf", "", " --tool flat:6");
    h5::Id job(H5Gopen2(f, "/jobs/pocket", H5P_DEFAULT));
    EXPECT_EQ(h5::attr_str(job, "status"), "ok");
    const std::string message = h5::attr_str(job, "message");
    EXPECT_EQ(message.rfind("warning: nothing to cut", 0), 0u) << message;
    EXPECT_NE(message.find("warning: the drawing declares no units"), std::string::npos);
    EXPECT_NE(message.find("; the tool does not fit in region 0"), std::string::npos) << message;
  }
  {
    h5::Id f = run("none.dxf", "", " --tool flat:1");
    h5::Id job(H5Gopen2(f, "/jobs/pocket", H5P_DEFAULT));
    EXPECT_EQ(h5::attr_str(job, "status"), "ok");
    EXPECT_NE(h5::attr_str(job, "message").find("warning: the drawing declares no units"),
              std::string::npos);
    EXPECT_EQ(string_stat(f, "pocket", "units_from"), "default");
    EXPECT_NE(string_stat(f, "pocket", "input_warning"), "");
  }
  {
    h5::Id f = run("override.dxf", "1", " --tool flat:6 --units cm");
    EXPECT_EQ(string_stat(f, "pocket", "units_from"), "job");
    EXPECT_NEAR(x_extent(f).second, 40 - 3, 0.02);
    h5::Id job(H5Gopen2(f, "/jobs/pocket", H5P_DEFAULT));
    EXPECT_NE(h5::attr_str(job, "params").find("\"units\":\"cm\""), std::string::npos);
  }
  expect_invalid_parameter(dir,
                           "pocket --profile " + (dir / "inch.dxf").string() +
                               " --tool flat:6 --depth 2 --units furlong",
                           "--units must be one of mm, cm");
}

// The issue's small loop: a 1.2 mm circle and a 2 mm tool give no offset loop; the job is ok
// (nothing is wrong with the input) but says that nothing was cut.
TEST(PocketCli, AnOffsetJobWithNothingToCutSaysSo) {
  const auto dir = fixture_dir();
  std::ofstream(dir / "small.toml") << "[[circle]]\ncenter = [0, 0]\nradius = 0.6\n";
  const CmdResult r = ncpath("offset --profile " + (dir / "small.toml").string() +
                             " --tool flat:2 --stepover 1 --quiet --out " +
                             (dir / "small.h5").string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("nothing to cut"), std::string::npos) << r.output;
  h5::Id f = h5::open_read(dir / "small.h5");
  h5::Id job(H5Gopen2(f, "/jobs/offset", H5P_DEFAULT));
  EXPECT_EQ(h5::attr_str(job, "status"), "ok");
  EXPECT_EQ(h5::attr_str(job, "message").rfind("warning: nothing to cut (0 points)", 0), 0u);
}

TEST(PocketCli, BatchJobsReportUnknownKeysAndRunTheOthers) {
  const auto dir = fixture_dir();
  std::ofstream(dir / "jobs.toml") << R"(
output = "out.h5"
[[job]]
name = "good"
operation = "pocket"
input = "plate.toml"
tool = "flat:6"
params = { depth = 3, stepdown = 1.5, order = "inward", milling = "conventional", clearance = 2 }
gcode = { path = "good.ngc", dialect = "grbl", safe_z = 10 }
[[job]]
name = "typo"
operation = "pocket"
input = "plate.toml"
tool = "flat:6"
params = { depth = 3, stepovr = 2 }
)";
  const CmdResult r = ncpath("run " + (dir / "jobs.toml").string() + " --quiet");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("2 job(s), 1 ok, 1 failed"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("'params.stepovr' is not a known key"), std::string::npos) << r.output;
  h5::Id f = h5::open_read(dir / "out.h5");
  h5::Id good(H5Gopen2(f, "/jobs/good", H5P_DEFAULT));
  EXPECT_EQ(h5::attr_str(good, "status"), "ok");
  EXPECT_NE(h5::attr_str(good, "params").find("\"stepover\":3.0"), std::string::npos);  // 50%
  EXPECT_EQ(stat(f, "good", "depth_passes"), 2);
  // Rapids (if any) at the G-code's safe height; the program starts there.
  const auto pts = h5::read_all<double>(f, "/jobs/good/cl/points", H5T_NATIVE_DOUBLE);
  for (std::size_t i = 2; i < pts.size(); i += 3) EXPECT_LE(pts[i], 10 + 1e-9);
  EXPECT_NE(slurp(dir / "good.ngc").find("G0 Z10.0000"), std::string::npos);
  h5::Id typo(H5Gopen2(f, "/jobs/typo", H5P_DEFAULT));
  EXPECT_EQ(h5::attr_str(typo, "status"), "invalid_parameter");
  EXPECT_NE(h5::attr_str(typo, "message").find("params.stepovr"), std::string::npos);
}

TEST(PocketCli, HelpDocumentsEveryOption) {
  const CmdResult r = ncpath("pocket --help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* s :
       {"--profile", "--tool",    "--stepover",     "--depth",      "--stepdown",
        "--out",     "--gcode",   "--stock",        "--tolerance",  "--join-tolerance",
        "--order",   "--milling", "--helix-radius", "--ramp-angle", "--clearance",
        "--safe-z",  "--threads", "--dialect",      "--feed",       "--plunge-feed",
        "--spindle", "--name",    "--quiet",        "--units"})
    EXPECT_NE(r.output.find(s), std::string::npos) << s;
  EXPECT_NE(ncpath("--help").output.find("pocket"), std::string::npos);
}

}  // namespace
}  // namespace ncpath
