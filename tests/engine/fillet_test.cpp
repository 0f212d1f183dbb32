// Fillet-cut (engine/fillet.hpp): a 90-degree V-groove whose floor is a fillet of radius rho
// (faceted finely), reference ball R_ref > rho (it rides on the flanks and leaves the
// fillet), clean-up ball r < rho. Checks: every pass point's ball touches the part (distance
// to the mesh r, brute force) and never cuts into it, also along the chords; the material
// left on the fillet (distance from each part point between the reference contacts to the
// nearest clean-up ball surface) is within the scallop height; no passes on a plain convex
// part; the reference must be the larger ball.
#include "engine/fillet.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "tests/engine/cleanup_test_meshes.hpp"

namespace ncpath {
namespace {

TEST(Fillet, CleansTheFilletTheReferenceBallLeft) {
  const double rho = 3, R_ref = 5, r = 1.5, h = 0.01;
  const TriangleMesh mesh = test_meshes::filleted_groove(rho, 48);
  FilletParams p;
  p.reference_diameter = 2 * R_ref;
  p.scallop = h;
  p.pencil.interval = 0.5;
  p.pencil.step_down = 0;
  RunControl control;
  const FilletResult res = run_fillet(mesh, ball_cutter(2 * r), p, control);
  ASSERT_GT(res.stats.passes, 3u);
  ASSERT_EQ(res.stats.pencil.paths, 1u);
  // Every pass point: the small ball touches the part and does not cut into it; chords too.
  std::vector<Vec3> centres;
  for (std::size_t k = 0; k < res.paths.size(); ++k) {
    if (res.kinds[k] != PathKind::kCut) continue;
    const auto& path = res.paths[k];
    for (std::size_t i = 0; i < path.size(); ++i) {
      const Vec3 c = path[i] + Vec3(0, 0, r);
      const double d = test_meshes::point_mesh_distance(mesh, c);
      ASSERT_GE(d, r - 1e-6) << "gouge at " << path[i].transpose();
      ASSERT_LE(d, r + 1e-6) << "not touching at " << path[i].transpose();
      centres.push_back(c);
      if (i + 1 < path.size())
        for (int s = 1; s < 8; ++s) {
          const Vec3 q = c + (path[i + 1] + Vec3(0, 0, r) - c) * (s / 8.0);
          ASSERT_GE(test_meshes::point_mesh_distance(mesh, q), r - 1e-6)
              << "chord gouge at " << q.transpose();
          centres.push_back(q);
        }
    }
  }
  // Material left on the fillet and the flanks up to the reference contacts (|x| <=
  // R_ref / sqrt 2), away from the groove's ends: within the scallop height (plus the
  // faceting of the arc, rho (1 - cos(pi / 4 / 48)) < 1e-3 mm).
  const double faceting = rho * (1 - std::cos(0.25 * std::numbers::pi / 48));
  double worst = 0;
  for (double y = -5; y <= 5; y += 0.37)
    for (double a = -0.75 * std::numbers::pi; a <= -0.25 * std::numbers::pi; a += 0.01) {
      const Vec3 s(rho * std::cos(a), y, rho * std::sqrt(2.0) + rho * std::sin(a));
      double left = INFINITY;
      for (const Vec3& c : centres) left = std::min(left, (s - c).norm() - r);
      worst = std::max(worst, left);
    }

  EXPECT_LE(worst, h + faceting + 1e-6);
  EXPECT_GT(worst, 0.1 * h);  // it does leave cusps (the check is not vacuous)
}

TEST(Fillet, RejectsBadInput) {
  const TriangleMesh mesh = test_meshes::filleted_groove(3, 8);
  FilletParams p;
  p.reference_diameter = 4;
  RunControl control;
  EXPECT_THROW(run_fillet(mesh, ball_cutter(6), p, control), std::invalid_argument);
  p.reference_diameter = 10;
  EXPECT_THROW(run_fillet(mesh, flat_cutter(3), p, control), std::invalid_argument);
  p.scallop = 0;
  EXPECT_THROW(run_fillet(mesh, ball_cutter(3), p, control), std::invalid_argument);
}

}  // namespace
}  // namespace ncpath
