// Fillet-cut options (engine/fillet.hpp): stock to leave and cut direction.
//
// Stock s on the filleted V-groove of fillet_test.cpp (cleanup_test_meshes.hpp; flanks z = |x|,
// fillet radius rho = 3; reference R_ref = 5, clean-up r = 1.5): both balls keep s from the part,
// so every pass puts the clean-up ball's centre (tip + r z) at distance r + s from the mesh (brute
// force), and the passes span from one reference contact to the other: the grown reference ball
// (R_ref + s) touches the flanks, and the grown small ball, moved from its centre along a flank's
// normal by (R_ref + s) - (r + s), has its centre at x = -+(R_ref - r) / sqrt 2 whatever s. The
// passes are those of balls grown by s (R_ref + s, r + s, no stock) raised by s.
//
// Direction, spindle M3 (climb: the material on the right of travel), on a V-groove along y
// with a steep flank z = 2x on x > 0 and a shallow one z = -x / 2 on x < 0 (90 degrees
// apart): the crease's material vector -(b1 + b2) points to +x, toward the steep flank. Climb
// passes therefore all run +y, conventional ones -y, one way each, joined by one-point rapids
// to the next pass's first point and no link at depth; direction any keeps the zig-zag
// linked at depth.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/fillet.hpp"
#include "tests/engine/cleanup_test_meshes.hpp"

namespace ncpath {
namespace {

// Flanks z = 2x (x in [0, 5]) and z = -x / 2 (x in [-10, 0]), along y in [-8, 8].
TriangleMesh lopsided_groove() {
  TriangleMesh m;
  m.vertices = {{-10, -8, 5}, {0, -8, 0}, {5, -8, 10}, {-10, 8, 5}, {0, 8, 0}, {5, 8, 10}};
  m.facets = {{0, 1, 4}, {0, 4, 3}, {1, 2, 5}, {1, 5, 4}};
  return m;
}

TEST(FilletStock, PassesKeepTheStockFromTheFilletedGroove) {
  const double rho = 3, R_ref = 5, r = 1.5, s = 0.3;
  const TriangleMesh mesh = test_meshes::filleted_groove(rho, 48);
  FilletParams p;
  p.reference_diameter = 2 * R_ref;
  p.stepover = 0.3;
  p.pencil.interval = 0.5;
  p.pencil.step_down = 0;
  p.stock = s;
  RunControl control;
  const FilletResult res = run_fillet(mesh, ball_cutter(2 * r), p, control);
  ASSERT_GT(res.stats.passes, 3u);
  ASSERT_EQ(res.stats.pencil.paths, 1u);
  double x_min = INFINITY, x_max = -INFINITY;
  for (std::size_t k = 0; k < res.paths.size(); ++k) {
    if (res.kinds[k] != PathKind::kCut) continue;
    const auto& path = res.paths[k];
    for (std::size_t i = 0; i < path.size(); ++i) {
      const Vec3 c = path[i] + Vec3(0, 0, r);
      const double d = test_meshes::point_mesh_distance(mesh, c);
      ASSERT_GE(d, r + s - 1e-6) << "closer than the stock at " << path[i].transpose();
      ASSERT_LE(d, r + s + 1e-6) << "not touching the stock at " << path[i].transpose();
      if (i + 1 < path.size())
        for (int j = 1; j < 8; ++j) {
          const Vec3 q = c + (path[i + 1] + Vec3(0, 0, r) - c) * (j / 8.0);
          ASSERT_GE(test_meshes::point_mesh_distance(mesh, q), r + s - 1e-6)
              << "chord at " << q.transpose();
        }
      x_min = std::min(x_min, path[i].x());
      x_max = std::max(x_max, path[i].x());
    }
  }
  const double side = (R_ref - r) / std::sqrt(2.0);
  EXPECT_NEAR(x_min, -side, 1e-6);
  EXPECT_NEAR(x_max, side, 1e-6);

  // The balls grown by s without stock: the same passes, s lower.
  FilletParams g = p;
  g.stock = 0;
  g.reference_diameter = 2 * (R_ref + s);
  const FilletResult grown = run_fillet(mesh, ball_cutter(2 * (r + s)), g, control);
  ASSERT_EQ(grown.paths.size(), res.paths.size());
  for (std::size_t k = 0; k < res.paths.size(); ++k) {
    ASSERT_EQ(grown.kinds[k], res.kinds[k]) << k;
    ASSERT_EQ(grown.paths[k].size(), res.paths[k].size()) << k;
    for (std::size_t i = 0; i < res.paths[k].size(); ++i)
      EXPECT_LE((res.paths[k][i] - Vec3(0, 0, s) - grown.paths[k][i]).norm(), 1e-9)
          << k << " " << i;
  }
}

TEST(FilletStock, BadStockIsRefused) {
  const TriangleMesh mesh = test_meshes::filleted_groove(3, 8);
  FilletParams p;
  p.reference_diameter = 10;
  RunControl control;
  p.stock = -1.5;  // the clean-up ball's radius: nothing left of it
  EXPECT_THROW(run_fillet(mesh, ball_cutter(3), p, control), std::invalid_argument);
  p.stock = NAN;
  EXPECT_THROW(run_fillet(mesh, ball_cutter(3), p, control), std::invalid_argument);
  // The nested pencil params' stock and direction are not the fillet's: refused, not ignored.
  p.stock = 0;
  p.pencil.stock = 0.2;
  EXPECT_NE(validate(p).find("pencil.stock must be 0"), std::string::npos) << validate(p);
  p.pencil.stock = 0;
  p.pencil.direction = CutDirection::kClimb;
  EXPECT_NE(validate(p).find("pencil.direction must be any"), std::string::npos) << validate(p);
}

TEST(FilletDirection, OneWayPassesWithTheSteepFlankOnTheCuttingSide) {
  const TriangleMesh mesh = lopsided_groove();
  // The flanks' upward normals: the bi-contact vectors of the reference crease.
  const Vec3 steep = Vec3(-2, 0, 1).normalized(), shallow = Vec3(0.5, 0, 1).normalized();
  ASSERT_NEAR(steep.dot(shallow), 0, 1e-15);  // 90 degrees apart
  FilletParams p;
  p.reference_diameter = 5;
  p.stepover = 0.3;
  p.pencil.interval = 0.5;
  p.pencil.step_down = 0;
  RunControl control;
  const FilletResult any = run_fillet(mesh, ball_cutter(2), p, control);
  ASSERT_EQ(any.stats.pencil.paths, 1u);
  ASSERT_GE(any.stats.passes, 3u);
  // Any: zig-zag, linked at depth.
  for (std::size_t k = 0; k < any.kinds.size(); ++k)
    ASSERT_EQ(any.kinds[k], k % 2 == 0 ? PathKind::kCut : PathKind::kLinkAtDepth) << k;
  EXPECT_EQ(any.stats.neutral_passes, 0u);

  for (CutDirection d : {CutDirection::kClimb, CutDirection::kConventional}) {
    const bool climb = d == CutDirection::kClimb;
    SCOPED_TRACE(cut_direction_name(d));
    p.direction = d;
    const FilletResult res = run_fillet(mesh, ball_cutter(2), p, control);
    EXPECT_EQ(res.stats.passes, any.stats.passes);
    EXPECT_EQ(res.stats.neutral_passes, 0u);
    EXPECT_NEAR(res.stats.cut_length, any.stats.cut_length, 1e-9);
    ASSERT_EQ(res.kinds.size(), any.kinds.size());
    for (std::size_t k = 0; k < res.paths.size(); ++k) {
      const auto& path = res.paths[k];
      if (k % 2 == 1) {  // a one-point rapid to the next pass's first point
        ASSERT_EQ(res.kinds[k], PathKind::kRapid) << k;
        ASSERT_EQ(path.size(), 1u);
        ASSERT_LT(k + 1, res.paths.size());
        EXPECT_EQ(path[0], res.paths[k + 1].front());
        continue;
      }
      ASSERT_EQ(res.kinds[k], PathKind::kCut) << k;
      // The material (+x, the steep flank) on the right of travel: +y when climbing.
      for (std::size_t i = 1; i < path.size(); ++i)
        EXPECT_EQ(path[i].y() > path[i - 1].y(), climb) << "pass " << k << " point " << i;
      const std::vector<std::array<Vec3, 2>> b(path.size(), {steep, shallow});
      const CutSideScore score = cut_side_score(path, b);
      EXPECT_EQ(score.score > 0, climb) << "pass " << k << " score " << score.score;
    }
  }
}

}  // namespace
}  // namespace ncpath
