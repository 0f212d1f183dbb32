// Pencil-cut (engine/pencil.hpp): analytic creases. A V-groove z = a |x| gives one pencil
// path along its floor at the analytic height R (sqrt(1 + a^2) - 1) when its bi-contact
// angle 2 atan(a) is above the threshold, and none below; a box pocket gives the four
// floor-wall creases, the four vertical wall-wall creases (found by the z-levels) and, above
// them, the creases of the rim edges' cylinders, every path point within the tolerance of
// one of them; a boss on a plate gives the loop around its foot, arcs about its vertical
// edges included; a faceted hemisphere (convex) gives none; no path point or chord
// gouges (brute-force distance from the ball to the mesh).
#include "engine/pencil.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "kernels/cleanup/pencil.hpp"
#include "tests/engine/mesh_test_support.hpp"
#include "tests/kernels/scan/scan_test_support.hpp"

namespace ncpath {
namespace {

TEST(Pencil, VGrooveAboveAndBelowTheThreshold) {
  const double R = 2.5;
  PencilParams p;
  p.interval = 0.5;
  p.step_down = 0;
  p.min_angle_deg = 30;
  for (double a : {1.0, 0.5, 0.2}) {
    const double beta = 2 * std::atan(a) * 180 / std::numbers::pi;  // 90, 53.1, 22.6 degrees
    RunControl control;
    const TriangleMesh mesh = scan_test::v_groove(a);
    const PencilResult r = run_pencil(mesh, ball_cutter(2 * R), p, control);
    if (beta < p.min_angle_deg) {
      EXPECT_TRUE(r.paths.empty()) << "a " << a;
      EXPECT_EQ(r.stats.pencil_points, 0u);
      continue;
    }
    ASSERT_EQ(r.paths.size(), 1u) << "a " << a;
    const double z = R * (std::sqrt(1 + a * a) - 1);
    for (const Vec3& q : r.paths[0]) {
      EXPECT_NEAR(q.x(), 0, 1e-9);
      EXPECT_NEAR(q.z(), z, 1e-9);
    }
    // Along the whole groove (the x lines cross it every interval over y in [-10, 10]).
    EXPECT_NEAR(r.stats.traced_length, 20, 1e-6);
    for (const PencilPoint& pt : r.points)
      EXPECT_NEAR(pt.angle * 180 / std::numbers::pi, beta, 1e-6);
    test_meshes::expect_no_gouge(mesh, r.paths, R);
  }
}

TEST(Pencil, BoxPocketFloorAndCornerCreases) {
  const double R = 1.25;
  PencilParams p;
  p.interval = 0.5;
  p.step_down = 0.3;
  RunControl control;
  const TriangleMesh mesh = scan_test::box_pocket();
  const PencilResult r = run_pencil(mesh, ball_cutter(2 * R), p, control);
  const double c = 5 - R;  // the ball centre's reach to the walls
  // Distance from q to the creases of the CL surface: the floor-wall lines (tip z 0, |x| or
  // |y| = c, the other within c), the vertical corner lines (|x| = |y| = c, tip z from 0 to
  // 3 - R) and above them the creases of the two rim edges' cylinders (on the diagonal
  // |x| = |y| = s, tip z = 3 + sqrt(R^2 - (5 - s)^2) - R, s from c to 5), sampled finely.
  auto crease_distance = [&](const Vec3& q) {
    const double ax = std::abs(q.x()), ay = std::abs(q.y());
    double d = INFINITY;
    for (const Vec2& l : {Vec2(ax, ay), Vec2(ay, ax)})  // floor: |first| = c
      d = std::min(d, std::hypot(std::hypot(l.x() - c, std::max(0.0, l.y() - c)), q.z()));
    d = std::min(d, std::hypot(std::hypot(ax - c, ay - c),
                               std::max({0.0, -q.z(), q.z() - (3 - R)})));
    for (int k = 0; k <= 20000; ++k) {
      const double s = c + (5 - c) * k / 20000.0;
      const double z = 3 + std::sqrt(std::max(0.0, R * R - (5 - s) * (5 - s))) - R;
      d = std::min(d, (Vec3(ax, ay, q.z()) - Vec3(s, s, z)).norm());
    }
    return d;
  };
  ASSERT_FALSE(r.paths.empty());
  double floor_length = 0, corner_length = 0;
  for (const auto& path : r.paths)
    for (std::size_t i = 0; i < path.size(); ++i) {
      EXPECT_LE(crease_distance(path[i]), p.tolerance) << "off the creases: "
                                                       << path[i].transpose();
      if (i == 0) continue;
      const Vec3 d = path[i] - path[i - 1];
      (std::abs(d.z()) > 1e-9 ? corner_length : floor_length) += d.norm();
    }
  // The floor creases form the square of side 2c; the corners rise (z-levels every 0.3 mm).
  EXPECT_NEAR(floor_length, 8 * c, 1.0);
  EXPECT_GT(corner_length, 4 * 1.0);
  test_meshes::expect_no_gouge(mesh, r.paths, R);
}

// A rectangular boss (2a x 2b, height h) standing on a plate (open mesh, top at z 0).
TriangleMesh boss_on_plate(double a, double b, double h) {
  TriangleMesh m;
  const double o = 20;
  m.vertices = {{-o, -o, 0}, {o, -o, 0}, {o, o, 0}, {-o, o, 0},  // 0-3 plate
                {-a, -b, 0}, {a, -b, 0}, {a, b, 0}, {-a, b, 0},  // 4-7 boss foot
                {-a, -b, h}, {a, -b, h}, {a, b, h}, {-a, b, h}}; // 8-11 boss top
  m.facets = {{0, 1, 5},  {0, 5, 4},   {1, 2, 6},  {1, 6, 5},
              {2, 3, 7},  {2, 7, 6},   {3, 0, 4},  {3, 4, 7},  // plate around the boss
              {8, 9, 10}, {8, 10, 11},                         // boss top
              {4, 5, 9},  {4, 9, 8},   {5, 6, 10}, {5, 10, 9},
              {6, 7, 11}, {6, 11, 10}, {7, 4, 8},  {7, 8, 11}};  // boss walls
  return m;
}

// The crease at a boss's foot: the ball on the plate touching the boss runs around it at tip
// z 0, its centre on the boss's outline offset by R, whose corners are quarter circles about
// the vertical edges (every chord of them cuts the edge sideways: lifting straight up cannot
// clear it, moving away from both contacts can). One loop of length 4a + 4b + 2 pi R.
TEST(Pencil, BossFootIncludingTheArcsAroundItsVerticalEdges) {
  const double a = 8, b = 5, h = 4, R = 3;
  PencilParams p;
  p.interval = 0.5;
  p.step_down = 0;
  RunControl control;
  const TriangleMesh mesh = boss_on_plate(a, b, h);
  const PencilResult r = run_pencil(mesh, ball_cutter(2 * R), p, control);
  // Distance from q to the crease: the outline offset by R at z 0.
  auto crease_distance = [&](const Vec3& q) {
    const double dx = std::max(0.0, std::abs(q.x()) - a), dy = std::max(0.0, std::abs(q.y()) - b);
    return std::hypot(std::hypot(dx, dy) - R, q.z());
  };
  ASSERT_FALSE(r.paths.empty());
  for (const auto& path : r.paths)
    for (const Vec3& q : path)
      EXPECT_LE(crease_distance(q), p.tolerance) << "off the crease: " << q.transpose();
  // Every point of the loop (sampled every 0.01 mm) lies within the tolerance of a chord.
  auto path_distance = [&](const Vec3& s) {
    double d = INFINITY;
    for (const auto& path : r.paths)
      for (std::size_t i = 1; i < path.size(); ++i) {
        const Vec3 u = path[i] - path[i - 1];
        const double t = std::clamp((s - path[i - 1]).dot(u) / u.squaredNorm(), 0.0, 1.0);
        d = std::min(d, (path[i - 1] + t * u - s).norm());
      }
    return d;
  };
  const double loop = 4 * a + 4 * b + 2 * std::numbers::pi * R;
  double worst = 0;
  for (int k = 0; k < int(loop / 0.01); ++k) {
    // Arc-length parameter along the loop: the side x = a + R upwards, then the arc about
    // (a, b), and so on around the four sides and corners.
    double t = k * 0.01;
    const double sides[4] = {2 * b, 2 * a, 2 * b, 2 * a}, arc = 0.5 * std::numbers::pi * R;
    const Vec2 corner[4] = {{a, b}, {-a, b}, {-a, -b}, {a, -b}};
    Vec3 q;
    for (int e = 0; e < 4; ++e) {
      const double ang = 0.5 * std::numbers::pi * e;
      const Vec2 n(std::cos(ang), std::sin(ang)), along(-n.y(), n.x());
      if (t <= sides[e]) {
        const Vec2 xy = corner[(e + 3) % 4] + R * n + t * along;
        q = Vec3(xy.x(), xy.y(), 0);
        break;
      }
      t -= sides[e];
      if (t <= arc) {
        const double phi = ang + t / R;
        q = Vec3(corner[e].x() + R * std::cos(phi), corner[e].y() + R * std::sin(phi), 0);
        break;
      }
      t -= arc;
    }
    worst = std::max(worst, path_distance(q));
  }
  EXPECT_LE(worst, p.tolerance);
  // Traced once, as one closed path: each family follows the arcs past their 45-degree points
  // (before the pieces were kept once, neighbouring sides' pieces overlapped on each arc by up
  // to 2 interval / sin 45 degrees, and the loop came as 4 paths). Its chords are inscribed in
  // the arcs with sagitta h <= tolerance, each shorter than its arc by at most h / (3 R) of it.
  ASSERT_EQ(r.paths.size(), 1u);
  // (Closed up to the chord check's lifts of the two ends, each by its own chord.)
  EXPECT_LE((r.paths[0].front() - r.paths[0].back()).norm(), p.tolerance);
  EXPECT_GE(r.stats.traced_length, loop - 2 * std::numbers::pi * p.tolerance / 3);
  EXPECT_LE(r.stats.traced_length, loop + p.tolerance);
  test_meshes::expect_no_gouge(mesh, r.paths, R);
}

TEST(Pencil, ConvexHemisphereHasNoPencilPath) {
  const TriangleMesh m = scan_test::uv_hemisphere(10, 12, 32, Vec3(0, 0, 0));
  PencilParams p;
  p.interval = 0.5;
  p.step_down = 1;
  RunControl control;
  const PencilResult r = run_pencil(m, ball_cutter(5), p, control);
  EXPECT_EQ(r.stats.pencil_points, 0u);
  EXPECT_TRUE(r.paths.empty());
}

TEST(Pencil, ChordErrorBound) {
  // Tangents at 30 degrees either side of a chord of length 2: the tangent lines meet at
  // height tan(30) above the middle.
  const double t = std::numbers::pi / 6;
  const Vec3 a(0, 0, 0), b(2, 0, 0);
  const Vec3 ta(std::cos(t), std::sin(t), 0), tb(std::cos(t), -std::sin(t), 0);
  EXPECT_NEAR(chord_error(a, ta, b, tb), std::tan(t), 1e-12);
  EXPECT_NEAR(chord_error(a, Vec3(1, 0, 0), b, Vec3(1, 0, 0)), 0, 1e-15);
}

TEST(Pencil, RejectsBadInput) {
  PencilParams p;
  RunControl control;
  p.min_angle_deg = 0;
  EXPECT_THROW(run_pencil(scan_test::v_groove(1), ball_cutter(5), p, control),
               std::invalid_argument);
  p = PencilParams{};
  EXPECT_THROW(run_pencil(scan_test::v_groove(1), flat_cutter(5), p, control),
               std::invalid_argument);
}

}  // namespace
}  // namespace ncpath
