// The pencil command and the pencil job end to end (issue 6): a ball in a V-groove z = |x|
// (bi-contact angle 90 degrees) gives one path along the groove's floor at the analytic height
// R (sqrt 2 - 1) and pencil points with the flanks' normals; with a threshold above 90 degrees
// it gives none; every statistic with its unit, G-code. With --stock s the path and the
// pencil points are at the height of a ball of radius R + s, plus s; --direction is recorded
// and the groove, symmetric, has no material side (neutral_paths 1).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "tests/batch/cli_job_checks.hpp"
#include "tests/batch/cli_run.hpp"
#include "tests/batch/mesh_op_cli_support.hpp"

namespace ncpath {
namespace {

namespace h5 = out::test;
using test::CmdResult;
using test::ncpath;
using namespace mesh_op_cli;

constexpr double kR = 2;  // ball:4; the groove (scan_cli::groove): |x| <= 10, y in [0, 20]

TEST(PencilCli, AVGrooveGivesOnePathAlongItsFloor) {
  const auto dir = scan_cli::fixture_dir("pencil_groove");
  scan_cli::write_off(dir / "groove.off", scan_cli::groove(false));
  // No z-levels: the drive planes alone find the crease (z-levels would add the groove's
  // ends, where the flanks meet the end edges' capsules).
  const CmdResult r = ncpath("pencil --mesh " + (dir / "groove.off").string() +
                             " --tool ball:4 --interval 0.5 --step-down 0 --quiet --out " +
                             (dir / "g.h5").string() + " --gcode " + (dir / "g.ngc").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  h5::Id f = h5::open_read(dir / "g.h5");
  cli_checks::expect_job_ok(f, "pencil", "pencil", {"\"step_down\":0.0"});

  // One cut path at x = 0, tip z = R (sqrt 2 - 1), along the whole groove.
  const double tip = kR * (std::sqrt(2.0) - 1);
  const ClOut cl = read_cl(f, "pencil");
  ASSERT_EQ(cl.kind.size(), 1u);
  EXPECT_EQ(cl.kind[0], 0);
  const std::size_t n = cl.pts.size() / 3;
  ASSERT_GE(n, 2u);
  double y_min = INFINITY, y_max = -INFINITY;
  const bool towards_y = cl.point(n - 1)[1] > cl.point(0)[1];
  for (std::size_t i = 0; i < n; ++i) {
    const Row q = cl.point(i);
    EXPECT_NEAR(q[0], 0, 1e-9) << i;
    EXPECT_NEAR(q[2], tip, 1e-9) << i;
    y_min = std::min(y_min, q[1]);
    y_max = std::max(y_max, q[1]);
    if (i > 0) {
      EXPECT_EQ(q[1] > cl.point(i - 1)[1], towards_y) << i;  // monotone along y
    }
  }
  EXPECT_NEAR(y_min, 0, 1e-9);
  EXPECT_NEAR(y_max, 20, 1e-9);

  // Pencil points: one per x line (y = 0, 0.5, ..., 20) at the floor, the flanks' normals
  // (1, 0, 1) / sqrt 2 and (-1, 0, 1) / sqrt 2 (in the order the line met them), 90 degrees.
  const PencilOut p = read_pencil(f, "pencil");
  ASSERT_EQ(p.angle.size(), 41u);
  const double h = 1 / std::sqrt(2.0);
  std::vector<bool> seen(41, false);
  for (std::size_t i = 0; i < p.angle.size(); ++i) {
    SCOPED_TRACE("point " + std::to_string(i));
    const Row pos = row(p.position, i), b1 = row(p.b1, i), b2 = row(p.b2, i);
    EXPECT_NEAR(pos[0], 0, 1e-9);
    EXPECT_NEAR(pos[2], tip, 1e-9);
    const double k = pos[1] / 0.5;
    ASSERT_NEAR(k, std::round(k), 1e-9);
    ASSERT_TRUE(k >= 0 && k <= 40);
    EXPECT_FALSE(seen[std::size_t(std::lround(k))]);
    seen[std::size_t(std::lround(k))] = true;
    EXPECT_NEAR(p.angle[i], M_PI / 2, 1e-9);
    EXPECT_NEAR(std::abs(b1[0]), h, 1e-9);
    EXPECT_NEAR(b2[0], -b1[0], 1e-9);
    for (const Row& b : {b1, b2}) {
      EXPECT_NEAR(b[1], 0, 1e-9);
      EXPECT_NEAR(b[2], h, 1e-9);
    }
    EXPECT_EQ(p.family[i], 0);  // x lines: the y lines run along the crease and never cross it
    EXPECT_EQ(p.kept[i], 1);
  }
  for (const auto& [name, cols, unit] :
       {std::tuple{"point_position", 3, "mm"}, std::tuple{"point_b1", 3, ""},
        std::tuple{"point_b2", 3, ""}, std::tuple{"point_angle", 0, "rad"},
        std::tuple{"point_family", 0, ""}, std::tuple{"point_kept", 0, ""}}) {
    std::vector<hsize_t> shape{41};
    if (cols) shape.push_back(hsize_t(cols));
    expect_dataset(f, std::string("/jobs/pencil/pencil/") + name, shape, unit);
  }

  // Statistics: the drive planes reach one interval more than the ball's radius (2 mm) beyond
  // the part's box: x lines y = -2.5 ... 22.5 and y lines x = -12.5 ... 12.5, every 0.5.
  const scan_cli::Stats st{f, "pencil"};
  EXPECT_EQ(st["planes"], 102);
  EXPECT_EQ(st["levels"], 0);
  // 41 on the groove and 4 past its open ends, where the ball hangs on the two end edges
  // (centre (0, 20 + d, zc) at distance R from the lines z = |x|: zc = sqrt(2 (R^2 - d^2)), tip
  // zc - R above the floor z = 0 for d = 0.5 and 1, below it for d = 1.5 and 2).
  EXPECT_EQ(st["candidates"], 45);
  EXPECT_EQ(st["hanging_points"], 4);
  EXPECT_EQ(st["pencil_points"], 41);
  EXPECT_EQ(st["kept_points"], 41);
  EXPECT_EQ(st["paths"], 1);
  EXPECT_GE(st["chains"], 1);
  // (lifted_points may count raises at the rounding level: the z check above bounds them.)
  EXPECT_LE(st["lifted_points"], double(n));
  EXPECT_NEAR(st["traced_length"], 20, 1e-6);
  EXPECT_EQ(st["air_length"], 0);
  EXPECT_EQ(st["points"], double(n));
  for (const char* s : {"traced_length", "air_length"}) EXPECT_EQ(st.unit(s), "mm") << s;
  for (const char* s : {"elements_s", "scan_s", "zlevel_s", "link_s", "refine_s", "check_s",
                        "compute_s", "write_s", "read_s"})
    EXPECT_EQ(st.unit(s), "s") << s;
  for (const char* s : {"planes", "levels", "candidates", "pencil_points", "kept_points", "chains",
                        "refined_points", "lifted_points", "paths", "points"})
    EXPECT_EQ(st.unit(s), "") << s;
  EXPECT_GE(st["compute_s"], st["scan_s"]);

  // G-code: rapids 5 mm above the groove's top (z = 10).
  cli_checks::expect_gcode_has(dir / "g.ngc", {"G0 Z15.0000", "M2"});
}

TEST(PencilCli, StockAndDirection) {
  const auto dir = scan_cli::fixture_dir("pencil_stock");
  scan_cli::write_off(dir / "groove.off", scan_cli::groove(false));
  const double s = 0.3;
  const CmdResult r = ncpath("pencil --mesh " + (dir / "groove.off").string() +
                             " --tool ball:4 --interval 0.5 --step-down 0 --stock 0.3 "
                             "--direction climb --quiet --out " +
                             (dir / "s.h5").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  h5::Id f = h5::open_read(dir / "s.h5");
  cli_checks::expect_job_ok(f, "pencil", "", {"\"stock\":0.3", "\"direction\":\"climb\""});
  // The centre of the ball of radius R + s in the 90-degree groove is (R + s) sqrt 2 above
  // its floor; the tool tip R below the centre.
  const double tip = (kR + s) * std::sqrt(2.0) - kR;
  const ClOut cl = read_cl(f, "pencil");
  ASSERT_EQ(cl.kind.size(), 1u);
  ASSERT_GE(cl.pts.size(), 6u);
  for (std::size_t i = 0; i < cl.pts.size() / 3; ++i) {
    EXPECT_NEAR(cl.point(i)[0], 0, 1e-9) << i;
    EXPECT_NEAR(cl.point(i)[2], tip, 1e-9) << i;
  }
  const PencilOut p = read_pencil(f, "pencil");
  ASSERT_EQ(p.angle.size(), 41u);
  for (std::size_t i = 0; i < p.angle.size(); ++i) EXPECT_NEAR(row(p.position, i)[2], tip, 1e-9);
  const scan_cli::Stats st{f, "pencil"};
  EXPECT_EQ(st["paths"], 1);
  EXPECT_EQ(st["neutral_paths"], 1);  // symmetric: no material side, climb or not
  EXPECT_EQ(st.unit("neutral_paths"), "");
  EXPECT_NEAR(st["traced_length"], 20, 1e-6);
}

TEST(PencilCli, AThresholdAboveTheGroovesAngleGivesNoPath) {
  const auto dir = scan_cli::fixture_dir("pencil_threshold");
  scan_cli::write_off(dir / "groove.off", scan_cli::groove(false));
  std::ofstream(dir / "jobs.toml") << R"(
output = "out.h5"
[[job]]
name = "steep"
operation = "pencil"
input = "groove.off"
tool = "ball:4"
params = { interval = 0.5, step_down = 0, min_angle = 100 }
)";
  const CmdResult r = ncpath("run " + (dir / "jobs.toml").string() + " --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  h5::Id f = h5::open_read(dir / "out.h5");
  cli_checks::expect_job_ok(f, "steep", "");
  const ClOut cl = read_cl(f, "steep");
  EXPECT_TRUE(cl.pts.empty());
  EXPECT_TRUE(cl.kind.empty());
  const PencilOut p = read_pencil(f, "steep");
  EXPECT_TRUE(p.angle.empty());
  expect_dataset(f, "/jobs/steep/pencil/point_position", {0, 3}, "mm");
  const scan_cli::Stats st{f, "steep"};
  EXPECT_EQ(st["candidates"], 45);  // the same junctions, all below the threshold
  EXPECT_EQ(st["pencil_points"], 0);
  EXPECT_EQ(st["paths"], 0);
  EXPECT_EQ(st["points"], 0);
  EXPECT_EQ(st["traced_length"], 0);
}

}  // namespace
}  // namespace ncpath
