// The pocket3d command and job end to end (issue 7): the seed-000 case study in HDF5 (CL
// paths of every kind, a CC point and a unit normal per CL point that agree with the CL
// point, the interval of every offset loop, every statistic with its unit, G-code), thread
// determinism, and the problems a user can make: a tool that is not a ball, a malformed
// surface, a pocket the surface does not cover, a surface above the stock top.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
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

const std::filesystem::path kPockets =
    std::filesystem::path(NCPATH_SOURCE_DIR) / "datasets/pockets";

// The paper's values on the seed-000 case study.
std::string case_study(const std::filesystem::path& out) {
  return "pocket3d --profile " + (kPockets / "seed000.toml").string() + " --surface " +
         (kPockets / "seed000_bottom.toml").string() +
         " --tool ball:12 --scallop 0.4 --eps 0.5 --delta 0.5 --quiet --out " + out.string();
}

// A 60 x 40 plate with a circular island, and bottoms over it.
constexpr const char* kPlate = R"(
[[loop]]
segments = [ { line = [[0, 0], [60, 0]] }, { line_to = [60, 40] }, { line_to = [0, 40] },
             { line_to = [0, 0] } ]
[[circle]]
center = [30, 20]
radius = 5
)";

// A bicubic patch over [x0, x1] x [-10, 50]: a gentle dome, z from -10 to about -6.6, plus dz.
std::string dome(double x0, double x1, double dz = 0) {
  std::string s = "[bezier_grid]\npatches_u = 1\npatches_v = 1\nctrl = [\n";
  const double z[4] = {-10, -7, -7, -10};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      s += "[" + std::to_string(x0 + (x1 - x0) * i / 3) + ", " + std::to_string(-10 + 20 * j) +
           ", " + std::to_string(0.5 * (z[i] + z[j]) + dz) + "],\n";
  return s + "]\n";
}

std::filesystem::path fixture_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const auto dir = h5::out_dir(std::string("pocket3d_cli_") + (info ? info->name() : "none"));
  std::ofstream(dir / "plate.toml") << kPlate;
  std::ofstream(dir / "dome.toml") << dome(-10, 70);
  return dir;
}

std::string plate(const std::filesystem::path& dir, const std::string& surface = "dome.toml") {
  return "pocket3d --profile " + (dir / "plate.toml").string() + " --surface " +
         (dir / surface).string();
}

// The statistics of one job in a CL file: stats[name] is the value as a double (NaN when
// absent), stats.unit(name) its unit attribute ("" when none).
struct Stats {
  hid_t file;
  std::string job;
  std::string path(const std::string& name) const { return "/jobs/" + job + "/stats/" + name; }
  double operator[](const std::string& name) const {
    const std::vector<double> v = h5::read_all<double>(file, path(name), H5T_NATIVE_DOUBLE);
    return v.empty() ? NAN : v.front();
  }
  std::string unit(const std::string& name) const {
    h5::Id ds(H5Dopen2(file, path(name).c_str(), H5P_DEFAULT), "open " + path(name));
    return h5::has_attr(ds, "unit") ? h5::attr_str(ds, "unit") : std::string();
  }
};

std::vector<hsize_t> dims(hid_t f, const std::string& path) {
  h5::Id ds(H5Dopen2(f, path.c_str(), H5P_DEFAULT), "open " + path);
  return h5::dims_of(ds);
}

TEST(Pocket3dCli, CaseStudyWritesPathsContactsNormalsIntervalsAndStats) {
  const auto dir = fixture_dir();
  const CmdResult r = ncpath(case_study(dir / "p.h5") + " --gcode " + (dir / "p.ngc").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  h5::Id f = h5::open_read(dir / "p.h5");
  const Stats st{f, "pocket3d"};
  h5::Id job(H5Gopen2(f, "/jobs/pocket3d", H5P_DEFAULT));
  EXPECT_EQ(h5::attr_str(job, "operation"), "pocket3d");
  EXPECT_EQ(h5::attr_str(job, "status"), "ok");
  // The verifier (issue 16): no gouge, and the scallop bound kept inside the outermost pass
  // (it was exceeded, 0.954 > 0.9, where the first level's chords ran inside their loop
  // round the R20 corner and the grid counted the band outside them).
  EXPECT_EQ(st["verify_max_gouge"], 0);
  EXPECT_EQ(st["verify_scallop_bound"], 0.9);
  EXPECT_LE(st["verify_max_scallop"], st["verify_scallop_bound"]);
  EXPECT_GT(st["verify_max_scallop"], 0.4);  // the grid does see the scallops
  const std::string params = h5::attr_str(job, "params");
  for (const char* s : {"\"scallop\":0.4", "\"eps\":0.5", "\"delta\":0.5", "\"tolerance\":0.01",
                        "seed000_bottom.toml", "\"safe_z\":5.0"})
    EXPECT_NE(params.find(s), std::string::npos) << s << " in " << params;

  const std::string g = "/jobs/pocket3d/";
  const auto pts = h5::read_all<double>(f, g + "cl/points", H5T_NATIVE_DOUBLE);
  const auto off = h5::read_all<std::int64_t>(f, g + "cl/path_offsets", H5T_NATIVE_INT64);
  const auto kind = h5::read_all<std::uint8_t>(f, g + "cl/path_kind", H5T_NATIVE_UINT8);
  const auto cc = h5::read_all<double>(f, g + "pocket3d/cc_points", H5T_NATIVE_DOUBLE);
  const auto nrm = h5::read_all<double>(f, g + "pocket3d/normals", H5T_NATIVE_DOUBLE);
  const std::size_t n = pts.size() / 3;
  ASSERT_GT(n, 100u);
  ASSERT_EQ(static_cast<std::size_t>(off.back()), n);
  EXPECT_EQ(dims(f, g + "pocket3d/cc_points"), (std::vector<hsize_t>{n, 3}));
  EXPECT_EQ(dims(f, g + "pocket3d/normals"), (std::vector<hsize_t>{n, 3}));
  for (std::uint8_t k : {0, 1, 2})
    EXPECT_NE(std::find(kind.begin(), kind.end(), k), kind.end()) << "path kind " << int{k};

  // Every cut and link point has a contact, except the start of the plunge (at the clearance
  // plane, z = 1); its normal is a unit upward vector; the CL point is the tip of the ball
  // touching there (tip = cc + R n - R z), raised by at most max_lift (chord lifting).
  const double r_ball = 6, max_lift = st["max_lift"];
  std::size_t with_contact = 0;
  for (std::size_t k = 0; k < kind.size(); ++k) {
    const auto b = static_cast<std::size_t>(off[k]), e = static_cast<std::size_t>(off[k + 1]);
    for (std::size_t i = b; i < e; ++i) {
      const double* c = &cc[3 * i];
      const double* m = &nrm[3 * i];
      const double* p = &pts[3 * i];
      EXPECT_EQ(std::isfinite(c[0]), std::isfinite(m[0])) << "point " << i;
      if (!std::isfinite(c[0])) {
        EXPECT_TRUE(kind[k] == 2 || (i == b && p[2] == 1)) << "point " << i << " lacks contact";
        continue;
      }
      if (i > b || k == 0) ++with_contact;  // else its path's predecessor's last point again
      EXPECT_NEAR(std::hypot(m[0], m[1], m[2]), 1, 1e-9) << "point " << i;
      EXPECT_GT(m[2], 0) << "point " << i;
      EXPECT_NEAR(p[0], c[0] + r_ball * m[0], 1e-6) << "point " << i;
      EXPECT_NEAR(p[1], c[1] + r_ball * m[1], 1e-6) << "point " << i;
      const double lift = p[2] - (c[2] + r_ball * (m[2] - 1));
      EXPECT_GE(lift, -1e-6) << "point " << i;
      EXPECT_LE(lift, max_lift + 1e-6) << "point " << i;
      EXPECT_LT(p[2], 0) << "point " << i << " above the stock top";
    }
  }
  // cl_points counts the planner's points; a point equal to the one before it (a chord of
  // length 0) is written once.
  const double cl_points = st["cl_points"];
  EXPECT_LE(static_cast<double>(with_contact), cl_points);
  EXPECT_GE(static_cast<double>(with_contact), 0.99 * cl_points);

  // One level and one interval per offset loop: 0 on level 1, at least min_interval after.
  const auto level = h5::read_all<std::int64_t>(f, g + "pocket3d/loop_level", H5T_NATIVE_INT64);
  const auto interval = h5::read_all<double>(f, g + "pocket3d/loop_interval", H5T_NATIVE_DOUBLE);
  ASSERT_EQ(level.size(), interval.size());
  EXPECT_EQ(static_cast<double>(level.size()), st["loops"]);
  EXPECT_EQ(static_cast<double>(*std::max_element(level.begin(), level.end())), st["levels"]);
  for (std::size_t k = 0; k < level.size(); ++k) {
    if (level[k] == 1) {
      EXPECT_EQ(interval[k], 0) << "loop " << k;
    } else {
      EXPECT_GE(interval[k], st["min_interval"]) << "loop " << k;
      EXPECT_LE(interval[k], st["max_interval"]) << "loop " << k;
    }
  }
  // Against the flat-bottom chord 2 sqrt(2 R h - h^2) = 4.31 mm: the dome (curvature radius
  // over 200 mm in the pocket) widens it by under 2 %, its slopes shrink it in plan; a last
  // level, where the full interval leaves nothing, is at half of it.
  const double flat = 2 * std::sqrt(2 * 6 * 0.4 - 0.4 * 0.4);
  std::vector<double> steps;
  for (std::size_t k = 0; k < level.size(); ++k)
    if (level[k] > 1) steps.push_back(interval[k]);
  ASSERT_FALSE(steps.empty());
  std::sort(steps.begin(), steps.end());
  EXPECT_GT(steps[steps.size() / 2], 0.8 * flat);
  EXPECT_GT(st["min_interval"], 0);
  EXPECT_LT(st["max_interval"], 1.02 * flat);

  EXPECT_EQ(st["points"], static_cast<double>(n));
  EXPECT_EQ(st["components"], 1);
  EXPECT_EQ(st["open_fragments"], 0);
  EXPECT_GT(st["drops"], st["cl_points"]);
  EXPECT_EQ(st["surface_control_points"], 16);
  for (const char* s : {"max_lift", "min_interval", "max_interval", "cut_length", "link_length",
                        "rapid_length", "largest_gap_closed"})
    EXPECT_EQ(st.unit(s), "mm") << s;
  for (const char* s : {"uncut_area_before", "uncut_area_after", "unreachable_area"})
    EXPECT_EQ(st.unit(s), "mm^2") << s;
  for (const char* s : {"offset_s", "uncut_s", "link_s", "cl_s", "read_s", "surface_read_s",
                        "write_s", "compute_s"})
    EXPECT_EQ(st.unit(s), "s") << s;
  for (const char* s : {"loops", "levels", "components", "links", "cleanup_curves", "retractions",
                        "cl_points", "drops", "lifted_points", "open_fragments", "points"})
    EXPECT_EQ(st.unit(s), "") << s;
  EXPECT_EQ(dims(f, g + "stats/surface_sha256"), std::vector<hsize_t>{});  // a scalar string

  const std::string program = slurp(dir / "p.ngc");
  EXPECT_NE(program.find("G21 G90"), std::string::npos);
  EXPECT_NE(program.find("M2"), std::string::npos);
}

TEST(Pocket3dCli, OneAndTwoThreadsWriteIdenticalDatasets) {
  const auto dir = fixture_dir();
  for (const char* t : {"1", "2"}) {
    const CmdResult r =
        ncpath(case_study(dir / (std::string("t") + t + ".h5")) + " --threads " + t);
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
  h5::Id a = h5::open_read(dir / "t1.h5");
  h5::Id b = h5::open_read(dir / "t2.h5");
  const std::string g = "/jobs/pocket3d/";
  for (const char* d :
       {"cl/points", "pocket3d/cc_points", "pocket3d/normals", "pocket3d/loop_interval"}) {
    // NaN != NaN: compare bytes.
    const auto x = h5::read_all<double>(a, g + d, H5T_NATIVE_DOUBLE);
    const auto y = h5::read_all<double>(b, g + d, H5T_NATIVE_DOUBLE);
    ASSERT_EQ(x.size(), y.size()) << d;
    EXPECT_EQ(std::memcmp(x.data(), y.data(), x.size() * sizeof(double)), 0) << d;
  }
  EXPECT_EQ(h5::read_all<std::int64_t>(a, g + "cl/path_offsets", H5T_NATIVE_INT64),
            h5::read_all<std::int64_t>(b, g + "cl/path_offsets", H5T_NATIVE_INT64));
  EXPECT_EQ(h5::read_all<std::uint8_t>(a, g + "cl/path_kind", H5T_NATIVE_UINT8),
            h5::read_all<std::uint8_t>(b, g + "cl/path_kind", H5T_NATIVE_UINT8));
  EXPECT_EQ(h5::read_all<std::int64_t>(a, g + "pocket3d/loop_level", H5T_NATIVE_INT64),
            h5::read_all<std::int64_t>(b, g + "pocket3d/loop_level", H5T_NATIVE_INT64));
}

// Exit code 1, `status` in the file and the output, and `expected` in the message.
void expect_failure(const std::filesystem::path& dir, const std::string& command,
                    const std::string& status, const std::string& expected) {
  const std::string out = (dir / "bad.h5").string();
  const CmdResult r = ncpath(command + " --quiet --out " + out);
  EXPECT_EQ(r.exit_code, 1) << command << "\n" << r.output;
  EXPECT_NE(r.output.find(status), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(expected), std::string::npos) << expected << " in: " << r.output;
  h5::Id f = h5::open_read(out);
  h5::Id job(H5Gopen2(f, "/jobs/pocket3d", H5P_DEFAULT));
  EXPECT_EQ(h5::attr_str(job, "status"), status);
  EXPECT_NE(h5::attr_str(job, "message").find(expected), std::string::npos);
}

TEST(Pocket3dCli, ThePlateOverADomeIsCut) {
  const auto dir = fixture_dir();
  const CmdResult r = ncpath(plate(dir) +
                             " --tool ball:6 --scallop 0.05 --eps 0.05 --delta 0.05 "
                             "--quiet --out " +
                             (dir / "d.h5").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  h5::Id f = h5::open_read(dir / "d.h5");
  const Stats st{f, "pocket3d"};
  EXPECT_EQ(st["uncut_area_after"], 0);
  EXPECT_EQ(st["retractions"], 0);
  EXPECT_GT(st["levels"], 3);
}

TEST(Pocket3dCli, ToolsOtherThanABallAreRejected) {
  const auto dir = fixture_dir();
  expect_failure(dir, plate(dir) + " --tool flat:6 --scallop 0.1", "invalid_parameter",
                 "pocket3d needs a ball-end mill (ball:D)");
  expect_failure(dir, plate(dir) + " --tool bull:6:1 --scallop 0.1", "invalid_parameter",
                 "got a bullnose cutter");
  expect_failure(dir, plate(dir) + " --tool ball:6 --scallop 3", "invalid_parameter",
                 "between 0 and the ball radius 3 mm");
  expect_failure(dir, plate(dir) + " --tool ball:6 --scallop 0.1 --safe-z 0.5", "invalid_parameter",
                 "below the clearance height 1 mm");
  // CLI11 rejects what it can see: no scallop, no surface, no tool.
  for (const char* missing : {"--scallop", "--surface", "--tool"}) {
    std::string cmd = "pocket3d --profile " + (dir / "plate.toml").string();
    if (std::string(missing) != "--surface") cmd += " --surface " + (dir / "dome.toml").string();
    if (std::string(missing) != "--scallop") cmd += " --scallop 0.1";
    if (std::string(missing) != "--tool") cmd += " --tool ball:6";
    const CmdResult r = ncpath(cmd + " --quiet --out " + (dir / "x.h5").string());
    EXPECT_NE(r.exit_code, 0) << missing;
    EXPECT_NE(r.output.find(missing), std::string::npos) << missing << ": " << r.output;
  }
}

TEST(Pocket3dCli, BadSurfacesAreInvalidInputWithTheReadersMessage) {
  const auto dir = fixture_dir();
  std::ofstream(dir / "short.toml") << "[nurbs_surface]\ndegree_u = 1\ndegree_v = 1\nnu = 2\n"
                                       "nv = 2\nctrl = [[0, 0, -1], [0, 40, -1], [60, 0, -1]]\n";
  expect_failure(dir, plate(dir, "short.toml") + " --tool ball:6 --scallop 0.1", "invalid_input",
                 "ctrl has 3 points, nu * nv = 4");
  expect_failure(dir, plate(dir, "missing.toml") + " --tool ball:6 --scallop 0.1", "invalid_input",
                 "missing.toml");
}

TEST(Pocket3dCli, APocketTheSurfaceDoesNotCoverIsNamed) {
  const auto dir = fixture_dir();
  std::ofstream(dir / "half.toml") << dome(-10, 30);
  expect_failure(dir, plate(dir, "half.toml") + " --tool ball:6 --scallop 0.1", "invalid_parameter",
                 "outside the bottom surface");
  // A bottom above the stock top z = 0.
  std::ofstream(dir / "high.toml") << dome(-10, 70, 20);
  expect_failure(dir, plate(dir, "high.toml") + " --tool ball:6 --scallop 0.1", "invalid_input",
                 "rises above the stock top");
}

// A DXF circle of radius 5 (handle 2F) over the dome and a ball of radius 10: nothing to cut,
// an ok job with no point whose message says so and names the circle.
TEST(Pocket3dCli, ATooBigBallIsNothingToCutAndNamesTheBoundarysEntity) {
  const auto dir = fixture_dir();
  const std::string dxf = test::dxf_entities(test::pairs(
      {"0", "CIRCLE", "5", "2F", "8", "0", "10", "0", "20", "0", "30", "0", "40", "5"}));
  std::ofstream(dir / "hole.dxf", std::ios::binary) << dxf;
  const auto out = dir / "big.h5";
  const CmdResult r = ncpath("pocket3d --profile " + (dir / "hole.dxf").string() + " --surface " +
                             (dir / "dome.toml").string() +
                             " --tool ball:20 --scallop 0.1 --quiet --out " + out.string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  h5::Id f = h5::open_read(out);
  h5::Id job(H5Gopen2(f, "/jobs/pocket3d", H5P_DEFAULT));
  EXPECT_EQ(h5::attr_str(job, "status"), "ok");
  const std::string message = h5::attr_str(job, "message");
  EXPECT_EQ(message.rfind("warning: nothing to cut (0 points)", 0), 0u) << message;
  EXPECT_NE(message.find("the tool does not fit in region 0 (boundary: CIRCLE 2F): left out"),
            std::string::npos)
      << message;
}

TEST(Pocket3dCli, BatchJobsTakeTheSurfaceRelativeToTheBatchFile) {
  const auto dir = fixture_dir();
  std::filesystem::create_directories(dir / "surfaces");
  std::ofstream(dir / "surfaces" / "bottom.toml") << dome(-10, 70);
  std::ofstream(dir / "jobs.toml") << R"(
output = "out.h5"
[[job]]
name = "dome"
operation = "pocket3d"
input = "plate.toml"
surface = "surfaces/bottom.toml"
tool = "ball:6"
params = { scallop = 0.1, eps = 0.1, delta = 0.05, order = "inward", clearance = 2 }
gcode = { path = "dome.ngc", safe_z = 10 }
[[job]]
name = "no-surface"
operation = "pocket3d"
input = "plate.toml"
tool = "ball:6"
params = { scallop = 0.1 }
)";
  const CmdResult r = ncpath("run " + (dir / "jobs.toml").string() + " --quiet");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("2 job(s), 1 ok, 1 failed"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("'surface' is required"), std::string::npos) << r.output;
  h5::Id f = h5::open_read(dir / "out.h5");
  h5::Id good(H5Gopen2(f, "/jobs/dome", H5P_DEFAULT));
  EXPECT_EQ(h5::attr_str(good, "status"), "ok") << h5::attr_str(good, "message");
  EXPECT_NE(h5::attr_str(good, "params").find("\"tolerance\":0.01"), std::string::npos);
  EXPECT_GT((Stats{f, "dome"}["cl_points"]), 0);
  // Rapids at the G-code's safe height; the program starts there.
  const auto pts = h5::read_all<double>(f, "/jobs/dome/cl/points", H5T_NATIVE_DOUBLE);
  for (std::size_t i = 2; i < pts.size(); i += 3) EXPECT_LE(pts[i], 10 + 1e-9);
  EXPECT_NE(slurp(dir / "dome.ngc").find("G0 Z10.0000"), std::string::npos);
}

TEST(Pocket3dCli, HelpDocumentsEveryOption) {
  const CmdResult r = ncpath("pocket3d --help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* s :
       {"--profile",        "--surface", "--tool",    "--scallop",   "--eps",
        "--delta",          "--out",     "--gcode",   "--stock",     "--tolerance",
        "--join-tolerance", "--order",   "--milling", "--clearance", "--safe-z",
        "--min-interval",   "--threads", "--dialect", "--feed",      "--plunge-feed",
        "--spindle",        "--name",    "--quiet"})
    EXPECT_NE(r.output.find(s), std::string::npos) << s;
  EXPECT_EQ(r.output.find("--stepover"), std::string::npos);
  EXPECT_NE(ncpath("--help").output.find("pocket3d"), std::string::npos);
}

}  // namespace
}  // namespace ncpath
