// Pencil-cut options (engine/pencil.hpp): stock to leave and cut direction.
//
// Stock s: the ball centre runs on the offset surface at distance R + s. In a V-groove
// z = a |x| the ball of radius rho touching both flanks has its centre rho sqrt(1 + a^2)
// above the groove line (its distance to the flank z = a x is zc / sqrt(1 + a^2) = rho), and
// the tool tip is R below the centre: z = (R + s) sqrt(1 + a^2) - R, for a positive or a
// negative stock; every point keeps R + s from the mesh (brute force); a stock that leaves no
// ball (s <= -R) is refused.
//
// Cut direction, spindle M3 (climb: the material on the right of travel). In a box pocket
// the floor-wall creases have the wall as their material side: climb runs each with its wall
// on the right (counter-clockwise around the pocket, as a climb-milled pocket wall), and
// conventional on the left; the wall is found from the point's position, not from the
// engine's vectors. Both give exactly the pieces of direction any, some reversed; the
// vertical corners and the rim creases above them, which have no material side, are counted
// as neutral.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "engine/pencil.hpp"
#include "tests/engine/mesh_test_support.hpp"
#include "tests/kernels/scan/scan_test_support.hpp"

namespace ncpath {
namespace {

// Tool tips lowered by s: the tips of the ball of radius R + s with the same centres.
std::vector<std::vector<Vec3>> lowered(std::vector<std::vector<Vec3>> paths, double s) {
  for (auto& path : paths)
    for (Vec3& q : path) q.z() -= s;
  return paths;
}

TEST(PencilStock, VGrooveAtTheHeightOfTheOffsetBall) {
  const double R = 2.5;
  for (double a : {1.0, 0.5}) {
    for (double s : {0.3, -0.5}) {
      SCOPED_TRACE("a " + std::to_string(a) + ", stock " + std::to_string(s));
      PencilParams p;
      p.interval = 0.5;
      p.step_down = 0;
      p.min_angle_deg = 30;
      p.stock = s;
      RunControl control;
      const TriangleMesh mesh = scan_test::v_groove(a);
      const PencilResult r = run_pencil(mesh, ball_cutter(2 * R), p, control);
      ASSERT_EQ(r.paths.size(), 1u);
      const double z = (R + s) * std::sqrt(1 + a * a) - R;
      // Not the height without stock: the check below can tell them apart.
      ASSERT_GT(std::abs(z - R * (std::sqrt(1 + a * a) - 1)), 0.1);
      for (const Vec3& q : r.paths[0]) {
        EXPECT_NEAR(q.x(), 0, 1e-9);
        EXPECT_NEAR(q.z(), z, 1e-9);
      }
      ASSERT_FALSE(r.points.empty());
      for (const PencilPoint& pt : r.points) EXPECT_NEAR(pt.position.z(), z, 1e-9);
      EXPECT_NEAR(r.stats.traced_length, 20, 1e-6);
      // The ball (centre = tip + R z) keeps R + s from the mesh.
      test_meshes::expect_no_gouge(mesh, lowered(r.paths, s), R + s);
    }
  }
}

TEST(PencilStock, AStockThatLeavesNoBallIsRefused) {
  const double R = 2.5;
  RunControl control;
  for (double s : {-R, -R - 0.1, double(NAN), double(INFINITY)}) {
    PencilParams p;
    p.stock = s;
    EXPECT_THROW(run_pencil(scan_test::v_groove(1), ball_cutter(2 * R), p, control),
                 std::invalid_argument)
        << s;
  }
  EXPECT_NE(validate_stock(-R, R).find("stock must be greater than minus the ball radius (-2.5"),
            std::string::npos)
      << validate_stock(-R, R);
  EXPECT_EQ(validate_stock(-R + 0.01, R), "");
  PencilParams p;
  p.stock = INFINITY;
  EXPECT_NE(validate(p).find("stock must be a finite number of mm"), std::string::npos);
}

struct BoxRuns {
  PencilResult any, climb, conventional;
};

BoxRuns box_runs(double R) {
  PencilParams p;
  p.interval = 0.5;
  p.step_down = 0.3;
  BoxRuns runs;
  const TriangleMesh mesh = scan_test::box_pocket();
  RunControl control;
  runs.any = run_pencil(mesh, ball_cutter(2 * R), p, control);
  p.direction = CutDirection::kClimb;
  runs.climb = run_pencil(mesh, ball_cutter(2 * R), p, control);
  p.direction = CutDirection::kConventional;
  runs.conventional = run_pencil(mesh, ball_cutter(2 * R), p, control);
  return runs;
}

TEST(PencilDirection, BoxPocketFloorCreasesKeepTheWallOnTheCuttingSide) {
  const double R = 1.25, c = 5 - R;
  const BoxRuns runs = box_runs(R);
  const PencilResult& any = runs.any;
  ASSERT_FALSE(any.paths.empty());
  EXPECT_EQ(any.stats.neutral_paths, 0u);
  // Direction any is the default: without the option the paths are those of `any`.
  EXPECT_EQ(PencilParams{}.direction, CutDirection::kAny);
  for (const PencilResult* r : {&runs.climb, &runs.conventional}) {
    const bool climb = r == &runs.climb;
    SCOPED_TRACE(climb ? "climb" : "conventional");
    // The same pieces, each possibly reversed (with its bi-contact vectors).
    ASSERT_EQ(r->paths.size(), any.paths.size());
    EXPECT_NEAR(r->stats.traced_length, any.stats.traced_length, 1e-9);
    for (std::size_t k = 0; k < r->paths.size(); ++k) {
      const auto& path = r->paths[k];
      ASSERT_EQ(r->path_normals[k].size(), path.size());
      std::vector<Vec3> back(path.rbegin(), path.rend());
      const bool found = std::any_of(any.paths.begin(), any.paths.end(),
                                     [&](const auto& q) { return q == path || q == back; });
      EXPECT_TRUE(found) << "piece " << k << " is not one of direction any";
    }
    // Floor chords: the wall from the chord's position, on the right (climb) or left.
    double floor_length = 0;
    std::size_t floorless = 0;
    for (const auto& path : r->paths) {
      bool on_floor = false;
      for (std::size_t i = 1; i < path.size(); ++i) {
        const Vec3 d = path[i] - path[i - 1], mid = 0.5 * (path[i] + path[i - 1]);
        if (std::abs(d.z()) > 1e-9 || std::abs(mid.z()) > 1e-9 || d.head<2>().norm() < 1e-9)
          continue;
        Vec2 wall;
        if (std::abs(std::abs(mid.x()) - c) < 1e-6 && std::abs(mid.y()) < c - 1e-6)
          wall = Vec2(std::copysign(1.0, mid.x()), 0);
        else if (std::abs(std::abs(mid.y()) - c) < 1e-6 && std::abs(mid.x()) < c - 1e-6)
          wall = Vec2(0, std::copysign(1.0, mid.y()));
        else
          continue;
        on_floor = true;
        floor_length += d.head<2>().norm();
        const double right = d.y() * wall.x() - d.x() * wall.y();  // (t x z) . wall
        const double ccw = mid.x() * d.y() - mid.y() * d.x();      // about the pocket's axis
        if (climb) {
          EXPECT_GT(right, 0) << "wall not on the right at " << mid.transpose();
          EXPECT_GT(ccw, 0) << mid.transpose();
        } else {
          EXPECT_LT(right, 0) << "wall not on the left at " << mid.transpose();
          EXPECT_LT(ccw, 0) << mid.transpose();
        }
      }
      if (!on_floor) ++floorless;
    }
    // Nearly the whole square of side 2c was checked.
    EXPECT_GT(floor_length, 8 * c - 1.0);
    // The pieces off the floor (corners and rim creases) have no material side.
    EXPECT_GT(floorless, 0u);
    EXPECT_EQ(r->stats.neutral_paths, floorless);
  }
}

}  // namespace
}  // namespace ncpath
