// The zlevel command and the zlevel job end to end (issue 5): the contours of a plate with a
// box pocket against the analytic answer at two levels, one where the ball passes under the
// pocket's rim (sides R inside the walls, horizontal bi-contact vectors at the corners) and
// one above the rim's reach; segment geometry evaluated as docs/hdf5-schema.md describes it,
// records tied to the cut paths of cl/, every statistic with its unit, G-code.
#include <gtest/gtest.h>

#include <algorithm>
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

// Ball radius (ball:4); the plate's half width, top; the pocket's half width.
constexpr double kR = 2, kPlate = 10, kTop = 3, kPocket = 5;

// How far beyond a top edge the region {drop-cutter tip z >= L} reaches: the whole ball
// radius while the ball centre (L + R) is below the edge (the ball passes under it, a
// shadow), else the horizontal radius of the ball's section at the edge's height.
double reach(double level) {
  const double above = level + kR - kTop;
  return above <= 0 ? kR : std::sqrt(kR * kR - above * above);
}

double shoelace(const ClOut& cl, std::size_t path) {
  double a = 0;
  for (auto i = cl.off[path]; i + 1 < cl.off[path + 1]; ++i) {
    const Row p = cl.point(i), q = cl.point(i + 1);
    a += p[0] * q[1] - q[0] * p[1];
  }
  return a / 2;
}

// Distance from (x, y) to the outer contour at reach d: the plate's square grown by d with
// round corners (negative inside).
double outer_distance(double x, double y, double d) {
  const double a = std::abs(x) - kPlate, b = std::abs(y) - kPlate;
  if (a > 0 && b > 0) return std::hypot(a, b) - d;
  return std::max(a, b) - d;
}

// Checks contour k (cut path k) of a job at `level`.
void check_contour(const ClOut& cl, const ZLevelOut& z, std::size_t k, double level,
                   double tolerance) {
  SCOPED_TRACE("contour " + std::to_string(k) + " at z = " + std::to_string(level));
  const double d = reach(level), h = kPocket - d;  // outer reach; the hole's half side
  const bool hole = z.contour_hole[k] == 1;
  EXPECT_EQ(z.contour_level[k], level);

  // The polyline: closed, at the level, on the contour (holes: the square, exactly) or
  // outside it within the tolerance (outer loops: arcs by circumscribed polygons).
  const std::size_t p = cl.cut_paths[k];
  const auto first = cl.off[p], last = cl.off[p + 1] - 1;
  ASSERT_GT(last - first, 3);
  for (int c = 0; c < 3; ++c) EXPECT_EQ(cl.pts[3 * first + c], cl.pts[3 * last + c]);
  for (auto i = first; i <= last; ++i) {
    const Row q = cl.point(i);
    EXPECT_EQ(q[2], level);
    if (hole) {
      EXPECT_NEAR(std::max(std::abs(q[0]), std::abs(q[1])), h, 1e-9) << i;
    } else {
      const double dist = outer_distance(q[0], q[1], d);
      EXPECT_GE(dist, -1e-9) << i;
      EXPECT_LE(dist, tolerance + 1e-9) << i;
    }
  }
  // Holes run clockwise, outer boundaries counter-clockwise.
  const double area = shoelace(cl, p);
  if (hole) {
    EXPECT_NEAR(area, -4 * h * h, 1e-9);
  } else {
    const double exact = std::pow(2 * (kPlate + d), 2) - (4 - M_PI) * d * d;
    EXPECT_GT(area, exact - 1e-9);
    EXPECT_LT(area, exact + 8 * (kPlate + d) * tolerance);
  }

  // Segments: a closed chain at the level; lines on the analytic sides, arcs round the
  // plate's corners, evaluated from their geometry columns.
  const std::vector<std::size_t> segs = scan_cli::rows_of(z.seg_path, k);
  ASSERT_GE(segs.size(), 4u);
  double turn = 0;  // arcs' total angle
  for (std::size_t n = 0; n < segs.size(); ++n) {
    const std::size_t i = segs[n];
    SCOPED_TRACE("segment " + std::to_string(i));
    const Row a = row(z.seg_start, i), b = row(z.seg_end, i);
    const Row next = row(z.seg_start, segs[(n + 1) % segs.size()]);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(b[c], next[c], 1e-9);
    EXPECT_EQ(a[2], level);
    EXPECT_EQ(b[2], level);
    const std::array<double, 7> g = z.geometry(i);
    const scan_cli::Element e = scan_cli::ScanOut::element(z.seg_element, i);
    if (hole) {
      // A side of the square at h, shadowed by the rim's edge when the ball passes under it.
      ASSERT_EQ(z.seg_kind[i], 0);
      for (double v : g) EXPECT_EQ(v, 0);
      const bool along_x = std::abs(a[1] - b[1]) < 1e-9;
      const int fixed = along_x ? 1 : 0;
      EXPECT_NEAR(std::abs(a[fixed]), h, 1e-9);
      EXPECT_NEAR(b[fixed], a[fixed], 1e-9);
      EXPECT_EQ(z.seg_shadow[i], level + kR < kTop ? 1 : 0);
      // An edge of the walls from the rim (where the ball passes under the rim, the walls'
      // edges shadow the same line and may take turns).
      EXPECT_EQ(e.kind, 1);
      EXPECT_TRUE(e.a >= 4 && e.a <= 7 && e.b >= 4 && e.b <= 11) << e.a << " " << e.b;
      continue;
    }
    EXPECT_EQ(z.seg_shadow[i], level + kR < kTop ? 1 : 0);
    if (z.seg_kind[i] == 0) {  // a side of the plate's square grown by d
      const bool along_x = std::abs(a[1] - b[1]) < 1e-9;
      const int fixed = along_x ? 1 : 0;
      EXPECT_NEAR(std::abs(a[fixed]), kPlate + d, 1e-9);
      EXPECT_NEAR(b[fixed], a[fixed], 1e-9);
      EXPECT_EQ(e.kind, 1);  // an edge of the plate's outline
      EXPECT_TRUE(e.a >= 0 && e.a <= 3 && e.b >= 0 && e.b <= 3) << e.a << " " << e.b;
      continue;
    }
    // A quarter circle of radius d round a corner of the plate, whose vertex is the element.
    ASSERT_EQ(z.seg_kind[i], 1);
    EXPECT_NEAR(std::abs(g[0]), kPlate, 1e-12);
    EXPECT_NEAR(std::abs(g[1]), kPlate, 1e-12);
    EXPECT_NEAR(g[2], d, 1e-12);
    EXPECT_NEAR(g[3], d, 1e-12);
    EXPECT_GT(g[6], g[5]);  // counter-clockwise
    turn += g[6] - g[5];
    const auto pa = arc_point(g, g[5]), pb = arc_point(g, g[6]);
    EXPECT_NEAR(pa[0], a[0], 1e-9);
    EXPECT_NEAR(pa[1], a[1], 1e-9);
    EXPECT_NEAR(pb[0], b[0], 1e-9);
    EXPECT_NEAR(pb[1], b[1], 1e-9);
    for (double f : {0.25, 0.5, 0.75}) {  // inside the corner's quadrant, on the contour
      const auto q = arc_point(g, g[5] + f * (g[6] - g[5]));
      EXPECT_NEAR(outer_distance(q[0], q[1], d), 0, 1e-9);
      EXPECT_GT(std::abs(q[0]), kPlate);
      EXPECT_GT(std::abs(q[1]), kPlate);
    }
    EXPECT_EQ(e.kind, 2);
    const std::array<double, 2> corner{e.a == 0 || e.a == 3 ? -kPlate : kPlate,
                                       e.a < 2 ? -kPlate : kPlate};
    EXPECT_TRUE(e.a >= 0 && e.a <= 3) << e.a;
    EXPECT_EQ(g[0], corner[0]);
    EXPECT_EQ(g[1], corner[1]);
  }
  if (!hole) {
    EXPECT_NEAR(turn, 2 * M_PI, 1e-9);
  }

  // Junctions: the hole's four corners are sharp concave, the ball touching both walls' rims
  // (b horizontal when it passes under them); b1 belongs to the side the tool arrives along.
  // Elsewhere the contour continues smoothly (tangent: b1 = b2).
  std::size_t corners = 0;
  for (std::size_t j : scan_cli::rows_of(z.jun_path, k)) {
    SCOPED_TRACE("junction " + std::to_string(j));
    const Row pos = row(z.jun_position, j), b1 = row(z.jun_b1, j), b2 = row(z.jun_b2, j);
    EXPECT_EQ(pos[2], level);
    const bool corner =
        hole && std::abs(std::abs(pos[0]) - h) < 1e-9 && std::abs(std::abs(pos[1]) - h) < 1e-9;
    if (!corner) {
      EXPECT_EQ(z.jun_kind[j], 2);
      EXPECT_LT(z.jun_angle[j], 1e-6);  // acos near 1: 1e-16 in the cosine is 1e-8 here
      continue;
    }
    ++corners;
    EXPECT_EQ(z.jun_kind[j], 1);
    // From the rim edge at x = sx 5 (z = 3) to the ball centre (sx h, y, level + R).
    const double sx = pos[0] > 0 ? 1 : -1, sy = pos[1] > 0 ? 1 : -1;
    const double up = std::max(0.0, level + kR - kTop) / kR, across = -reach(level) / kR;
    const Row wall_x{sx * across, 0, up}, wall_y{0, sy * across, up};
    // The segment the tool arrives along ends at the junction.
    std::size_t in = segs.size();
    for (std::size_t n = 0; n < segs.size(); ++n) {
      const Row e = row(z.seg_end, segs[n]);
      if (std::hypot(e[0] - pos[0], e[1] - pos[1]) < 1e-9) in = n;
    }
    ASSERT_LT(in, segs.size());
    const Row ia = row(z.seg_start, segs[in]);
    const bool arrives_along_x = std::abs(ia[1] - pos[1]) < 1e-9;  // along the wall y = sy 5
    const Row& want1 = arrives_along_x ? wall_y : wall_x;
    const Row& want2 = arrives_along_x ? wall_x : wall_y;
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(b1[c], want1[c], 1e-9);
      EXPECT_NEAR(b2[c], want2[c], 1e-9);
    }
    EXPECT_NEAR(z.jun_angle[j], std::acos(up * up), 1e-9);
  }
  EXPECT_EQ(corners, hole ? 4u : 0u);
}

TEST(ZLevelCli, BatchJobOnABoxPocketGivesTheAnalyticContours) {
  const auto dir = scan_cli::fixture_dir("zlevel_pocket");
  scan_cli::write_off(dir / "plate.off", plate_pocket());
  std::ofstream(dir / "jobs.toml") << R"(
output = "out.h5"
[[job]]
name = "pocket"
operation = "zlevel"
input = "plate.off"
tool = "ball:4"
params = { levels = [0.5, 2.0], tolerance = 0.001 }
gcode = { path = "pocket.ngc" }
)";
  const CmdResult r = ncpath("run " + (dir / "jobs.toml").string() + " --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  h5::Id f = h5::open_read(dir / "out.h5");
  cli_checks::expect_job_ok(f, "pocket", "zlevel", {"\"levels\":[0.5,2.0]"});
  const ClOut cl = read_cl(f, "pocket");
  const ZLevelOut z = read_zlevel(f, "pocket");

  // Levels from the top down; each has the plate's outline and the pocket's hole.
  ASSERT_EQ(cl.cut_paths.size(), 4u);
  ASSERT_EQ(z.contour_level.size(), 4u);
  ASSERT_EQ(z.contour_hole.size(), 4u);
  for (std::size_t k = 0; k < 4; ++k) {
    const double level = k < 2 ? 2.0 : 0.5;
    check_contour(cl, z, k, level, 0.001);
  }
  EXPECT_EQ(z.contour_hole[0] + z.contour_hole[1], 1);
  EXPECT_EQ(z.contour_hole[2] + z.contour_hole[3], 1);
  // A one-point rapid before every contour but the first, at that contour's first point.
  ASSERT_EQ(cl.kind.size(), 7u);
  for (std::size_t p = 0; p < 7; ++p) {
    EXPECT_EQ(cl.kind[p], p % 2 == 0 ? 0 : 2) << "path " << p;
    if (p % 2 == 1) {
      ASSERT_EQ(cl.off[p + 1] - cl.off[p], 1);
      for (int c = 0; c < 3; ++c)
        EXPECT_EQ(cl.pts[3 * cl.off[p] + c], cl.pts[3 * cl.off[p + 1] + c]);
    }
  }
  // Rows in cutting order, naming cut paths.
  for (const auto* path : {&z.seg_path, &z.jun_path})
    for (std::size_t i = 0; i < path->size(); ++i) {
      ASSERT_GE((*path)[i], 0);
      ASSERT_LT((*path)[i], 4);
      if (i > 0) {
        ASSERT_LE((*path)[i - 1], (*path)[i]);
      }
    }

  // Shapes, units, descriptions.
  const std::string g = "/jobs/pocket/zlevel/";
  const hsize_t n = z.seg_kind.size(), m = z.jun_kind.size();
  const struct {
    const char* name;
    std::vector<hsize_t> shape;
    const char* unit;
  } want[] = {
      {"segment_path", {n}, ""},         {"segment_kind", {n}, ""},
      {"segment_shadow", {n}, ""},       {"segment_element", {n, 3}, ""},
      {"segment_start", {n, 3}, "mm"},   {"segment_end", {n, 3}, "mm"},
      {"segment_geometry", {n, 7}, ""},  {"junction_path", {m}, ""},
      {"junction_kind", {m}, ""},        {"junction_position", {m, 3}, "mm"},
      {"junction_b1", {m, 3}, ""},       {"junction_b2", {m, 3}, ""},
      {"junction_element1", {m, 3}, ""}, {"junction_element2", {m, 3}, ""},
      {"junction_angle", {m}, "rad"},    {"contour_level", {4}, "mm"},
      {"contour_hole", {4}, ""},
  };
  for (const auto& w : want) expect_dataset(f, g + w.name, w.shape, w.unit);
  h5::Id kinds(H5Dopen2(f, (g + "segment_kind").c_str(), H5P_DEFAULT));
  EXPECT_NE(h5::attr_str(kinds, "description").find("2=elliptic_arc"), std::string::npos);

  // Statistics: the plate has 18 facets, 29 edges (25 shared, 4 on the outline), 12 vertices.
  const scan_cli::Stats st{f, "pocket"};
  EXPECT_EQ(st["levels"], 2);
  EXPECT_EQ(st["contours"], 4);
  EXPECT_EQ(st["holes"], 2);
  EXPECT_EQ(st["segments"], double(n));
  EXPECT_EQ(st["junctions"], double(m));
  EXPECT_EQ(st["junctions_sharp_concave"], 8);
  EXPECT_EQ(st["junctions_convex"], 0);
  EXPECT_EQ(st["junctions_sharp_concave"] + st["junctions_tangent"], double(m));
  EXPECT_EQ(st["open_chains"], 0);
  EXPECT_GT(st["candidates"], 0);
  EXPECT_LE(st["candidates"], 2 * (18 + 29));  // facets and edges, per level
  EXPECT_EQ(st["offset_facets"], 18);
  EXPECT_EQ(st["offset_edges"], 29);
  EXPECT_EQ(st["offset_vertices"], 12);
  EXPECT_EQ(st["top_z"], kTop);
  EXPECT_EQ(st["bottom_z"], 0);
  double cut_points = 0;
  for (std::size_t p : cl.cut_paths) cut_points += double(cl.off[p + 1] - cl.off[p]);
  EXPECT_EQ(st["cut_points"], cut_points);
  EXPECT_EQ(st["points"], double(cl.pts.size() / 3));
  EXPECT_EQ(st["points"], cut_points + 3);  // and the three rapids
  for (const char* s : {"top_z", "bottom_z"}) EXPECT_EQ(st.unit(s), "mm") << s;
  for (const char* s : {"elements_s", "compute_s", "write_s", "read_s", "total_s"})
    EXPECT_EQ(st.unit(s), "s") << s;
  for (const char* s :
       {"levels", "contours", "holes", "segments", "junctions", "junctions_sharp_concave",
        "junctions_convex", "junctions_tangent", "candidates", "open_chains", "offset_facets",
        "offset_edges", "offset_vertices", "cut_points", "points", "facets_read"})
    EXPECT_EQ(st.unit(s), "") << s;
  EXPECT_EQ(st.text("input_format"), "off");

  // G-code: rapids 5 mm above the plate's top (z = 3), the contours at their levels.
  cli_checks::expect_gcode_has(dir / "pocket.ngc", {"G0 Z8.0000", "Z0.5000", "M2"});
  EXPECT_GT(st["gcode_lines"] + st["gcode_arcs"], 0);
}

TEST(ZLevelCli, StepDownFromTheTopOnTheCommandLine) {
  const auto dir = scan_cli::fixture_dir("zlevel_step");
  scan_cli::write_off(dir / "plate.off", plate_pocket());
  // Levels 3 - 0.75 k above the lowest point z = 0: 2.25, 1.5, 0.75.
  const CmdResult r = ncpath("zlevel --mesh " + (dir / "plate.off").string() +
                             " --tool ball:4 --step-down 0.75 --tolerance 0.002 --quiet --out " +
                             (dir / "s.h5").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  h5::Id f = h5::open_read(dir / "s.h5");
  const ClOut cl = read_cl(f, "zlevel");
  const ZLevelOut z = read_zlevel(f, "zlevel");
  const double levels[] = {2.25, 1.5, 0.75};
  ASSERT_EQ(z.contour_level.size(), 6u);
  for (std::size_t k = 0; k < 6; ++k) check_contour(cl, z, k, levels[k / 2], 0.002);
  const scan_cli::Stats st{f, "zlevel"};
  EXPECT_EQ(st["levels"], 3);
  EXPECT_NE(h5::attr_str(h5::Id(H5Gopen2(f, "/jobs/zlevel", H5P_DEFAULT)), "params")
                .find("\"step_down\":0.75"),
            std::string::npos);
}

}  // namespace
}  // namespace ncpath
