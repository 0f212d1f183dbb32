// Verification end to end: the pocket DXFs users bring (glyph outlines as SPLINE/LINE soups,
// a CAD bracket with bulges, circles and an ellipse) through `ncpath pocket`, the verifier's
// statistics and status, the helix entries measured from the HDF5 points (an analytic
// bound, independent of the verifier), `ncpath verify` on the file, and `--verify off`.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
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

std::filesystem::path dataset(const char* name) {
  return std::filesystem::path(NCPATH_SOURCE_DIR) / "datasets" / "pockets" / name;
}

double stat(hid_t f, const std::string& job, const std::string& name) {
  const auto v = h5::read_all<double>(f, "/jobs/" + job + "/stats/" + name, H5T_NATIVE_DOUBLE);
  return v.empty() ? NAN : v[0];
}

// Widest xy spread of the points strictly between the first pass's floor and the feed
// height of each part's first cut path: the helix descent, which must stay on its circle of
// radius R/2 around a centre inside the pocket (the defect: circles of 16 and 23 mm).
double widest_entry(hid_t f, const std::string& job, double feed_z, double floor_z) {
  const auto pts = h5::read_all<double>(f, "/jobs/" + job + "/cl/points", H5T_NATIVE_DOUBLE);
  const auto off =
      h5::read_all<std::int64_t>(f, "/jobs/" + job + "/cl/path_offsets", H5T_NATIVE_INT64);
  const auto kind =
      h5::read_all<std::uint8_t>(f, "/jobs/" + job + "/cl/path_kind", H5T_NATIVE_UINT8);
  double widest = 0;
  std::vector<std::pair<double, double>> entry;
  for (std::size_t k = 0; k < kind.size(); ++k) {
    if (kind[k] == 2) {  // a rapid: the next part's entry starts
      entry.clear();
      continue;
    }
    for (auto i = off[k]; i < off[k + 1]; ++i) {
      const double z = pts[3 * i + 2];
      if (z < feed_z && z > floor_z) entry.emplace_back(pts[3 * i], pts[3 * i + 1]);
    }
    for (const auto& a : entry)
      for (const auto& b : entry)
        widest = std::max(widest, std::hypot(a.first - b.first, a.second - b.second));
  }
  return widest;
}

TEST(VerifyCli, GlyphAndBracketPocketsAreVerifiedClean) {
  const auto dir = h5::out_dir("verify_cli_glyphs");
  for (const char* name : {"glyph_eight.dxf", "glyph_percent.dxf", "glyph_g.dxf", "bracket.dxf"}) {
    const auto out = dir / (std::string(name) + ".h5");
    const CmdResult r = ncpath(
        "pocket --profile " + dataset(name).string() +
        " --tool flat:6 --stepover 50% --depth 3 --stepdown 3 --quiet --out " + out.string());
    ASSERT_EQ(r.exit_code, 0) << name << "\n" << r.output;
    h5::Id f = h5::open_read(out);
    h5::Id job(H5Gopen2(f, "/jobs/pocket", H5P_DEFAULT));
    EXPECT_EQ(h5::attr_str(job, "status"), "ok") << name;
    EXPECT_EQ(stat(f, "pocket", "verify_max_gouge"), 0) << name;
    EXPECT_GT(stat(f, "pocket", "verify_moves"), 100) << name;
    // Level 1 runs along the walls: the smallest clearance is the one-sided margins, small.
    EXPECT_GE(stat(f, "pocket", "verify_min_clearance"), 0) << name;
    EXPECT_LT(stat(f, "pocket", "verify_min_clearance"), 0.1) << name;
    if (stat(f, "pocket", "helix_entries") > 0 && stat(f, "pocket", "ramp_entries") == 0) {
      EXPECT_LE(widest_entry(f, "pocket", 1, -3), 3 + 1e-9) << name;
    }
    // The file re-checked by the verify command.
    const CmdResult v = ncpath("verify --in " + out.string());
    EXPECT_EQ(v.exit_code, 0) << v.output;
    EXPECT_NE(v.output.find("pocket: pocket,"), std::string::npos) << v.output;
    EXPECT_NE(v.output.find(": ok"), std::string::npos) << v.output;
  }
}

// A job whose units override the drawing's (the bracket, declared in mm, read as cm: ten
// times larger): `ncpath verify` reads the drawing again in the job's units, from the params
// it stored, and passes it; in the drawing's own mm the 10x paths would cut through its walls.
TEST(VerifyCli, VerifyCommandReadsTheDrawingInTheJobsUnits) {
  const auto dir = h5::out_dir("verify_cli_units");
  const auto out = dir / "cm.h5";
  const CmdResult r = ncpath("pocket --profile " + dataset("bracket.dxf").string() +
                             " --units cm --tool flat:6 --depth 2 --quiet --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  {
    h5::Id f = h5::open_read(out);
    EXPECT_EQ(stat(f, "pocket", "mm_per_unit"), 10);
    EXPECT_EQ(stat(f, "pocket", "verify_max_gouge"), 0);
  }
  const CmdResult v = ncpath("verify --in " + out.string());
  EXPECT_EQ(v.exit_code, 0) << v.output;
  EXPECT_NE(v.output.find(": ok"), std::string::npos) << v.output;
}

TEST(VerifyCli, VerifyOffWritesNoVerifierStatistics) {
  const auto dir = h5::out_dir("verify_cli_off");
  const auto out = dir / "off.h5";
  const CmdResult r = ncpath("pocket --profile " + dataset("bracket.dxf").string() +
                             " --tool flat:6 --depth 2 --verify off --quiet --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  h5::Id f = h5::open_read(out);
  EXPECT_LE(H5Lexists(f, "/jobs/pocket/stats/verify_max_gouge", H5P_DEFAULT), 0);
  EXPECT_GT(H5Lexists(f, "/jobs/pocket/stats/cut_length", H5P_DEFAULT), 0);
  const CmdResult bad =
      ncpath("pocket --profile " + dataset("bracket.dxf").string() +
             " --tool flat:6 --depth 2 --verify maybe --quiet --out " + (dir / "bad.h5").string());
  EXPECT_NE(bad.exit_code, 0);
}

TEST(VerifyCli, VerifyCommandChecksMeshJobsAndSkipsProbes) {
  const auto dir = h5::out_dir("verify_cli_mesh");
  io::write_binary_stl(dir / "part.stl", test::height_field(20, 40, [](double x, double y) {
                         return 2 + std::sin(x / 5) * std::cos(y / 4);
                       }));
  std::ofstream(dir / "xy.csv") << "1,1\n20,20\n";
  std::ofstream(dir / "jobs.toml") << R"(
output = "out.h5"
[[job]]
name = "finish"
input = "part.stl"
tool = "ball:4"
params = { interval = 2, step = 0.5 }
[[job]]
name = "probe"
operation = "drop"
input = "part.stl"
tool = "flat:3"
params = { points = "xy.csv" }
)";
  ASSERT_EQ(ncpath("run " + (dir / "jobs.toml").string() + " --quiet").exit_code, 0);
  // Relative input paths are as stored: run the command where the batch ran.
  const CmdResult v = ncpath("verify --in " + (dir / "out.h5").string());
  EXPECT_EQ(v.exit_code, 0) << v.output;
  EXPECT_NE(v.output.find("finish: raster,"), std::string::npos) << v.output;
  EXPECT_NE(v.output.find("probe: drop: not verified"), std::string::npos) << v.output;
}

// A raster job's output stage runs the chord guard, then the verifier (on each append),
// then the HDF5 writing, one after another on one thread: their times are disjoint parts
// of the job's, so write_s + chord_guard_s + verify_s cannot exceed total_s (write_s once
// counted the other two as well).
TEST(VerifyCli, WriteTimeLeavesOutTheGuardAndTheVerifier) {
  const auto dir = h5::out_dir("verify_cli_times");
  io::write_binary_stl(dir / "wavy.stl", test::height_field(40, 40, [](double x, double y) {
                         return 3 + std::sin(x / 3) * std::cos(y / 2);
                       }));
  const auto out = dir / "out.h5";
  const CmdResult r = ncpath("raster --mesh " + (dir / "wavy.stl").string() +
                             " --tool ball:4 --interval 0.25 --step 0.05 --quiet --out " +
                             out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  h5::Id f = h5::open_read(out);
  const double write = stat(f, "raster", "write_s"), guard = stat(f, "raster", "chord_guard_s");
  const double verify = stat(f, "raster", "verify_s"), total = stat(f, "raster", "total_s");
  EXPECT_GE(write, 0);
  EXPECT_GT(guard + verify, 0.2 * total);  // the stages this is about take real time
  EXPECT_LE(write + guard + verify, total) << write << " " << guard << " " << verify;
}

TEST(VerifyCli, VerifyCommandReportsMissingFileAndJob) {
  EXPECT_EQ(ncpath("verify --in /nonexistent/x.h5").exit_code, 2);
  const auto dir = h5::out_dir("verify_cli_missing");
  const auto out = dir / "p.h5";
  ASSERT_EQ(ncpath("pocket --profile " + dataset("glyph_g.dxf").string() +
                   " --tool flat:6 --depth 2 --quiet --out " + out.string())
                .exit_code,
            0);
  const CmdResult r = ncpath("verify --in " + out.string() + " --job nope");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("no job named 'nope'"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace ncpath
