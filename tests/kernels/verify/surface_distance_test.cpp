// The verifier's queries on a NURBS bottom (kernels/verify/surface_distance.*): analytic
// distances to a tilted plane and to a cylinder vault, and heights over plan points.
#include "kernels/verify/surface_distance.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/kernels/surface/surface_test_util.hpp"

namespace ncpath {
namespace {

TEST(SurfaceProbe, TiltedPlaneDistancesAndHeights) {
  const double a = 0.3, b = -0.2, c = -5;
  const NurbsSurface s = test::tilted_plane(a, b, c, -10, -10, 30, 20);
  const SurfaceProbe probe(s, 2.0);
  EXPECT_GT(probe.pieces(), 1u);
  const Vec3 n = Vec3(-a, -b, 1).normalized();
  const auto signed_dist = [&](const Vec3& p) { return (p - Vec3(0, 0, c)).dot(n); };
  for (const Vec3& p : {Vec3(1, 2, 3), Vec3(10, 5, 0), Vec3(20, -5, 6)}) {
    const Vec3 q = p + Vec3(3, 1, 0.5);  // a segment above the plane: nearest at an end
    const double want = std::min(signed_dist(p), signed_dist(q));
    EXPECT_NEAR(probe.segment_distance(p, q, 100), want, 1e-9) << p.transpose();
    double z = 0;
    ASSERT_TRUE(probe.height_at(p.head<2>(), z));
    EXPECT_NEAR(z, a * p.x() + b * p.y() + c, 1e-9);
  }
  double z = 0;
  EXPECT_FALSE(probe.height_at(Vec2(100, 100), z));                         // not over the surface
  EXPECT_EQ(probe.segment_distance(Vec3(1, 1, 50), Vec3(2, 2, 50), 3), 3);  // capped
}

TEST(SurfaceProbe, CylinderVaultIsExactAlongItsAxis) {
  // A quadratic rational half cylinder of radius 10 along y (the vault z = sqrt(100 - x^2)).
  NurbsSurface s;
  s.degree_u = 2;
  s.degree_v = 1;
  s.nu = 5;
  s.nv = 2;
  const double w = std::sqrt(0.5);
  const Vec3 ring[5] = {{10, 0, 0}, {10, 0, 10}, {0, 0, 10}, {-10, 0, 10}, {-10, 0, 0}};
  const double rw[5] = {1, w, 1, w, 1};
  for (int i = 0; i < 5; ++i)
    for (double y : {0.0, 40.0}) {
      s.ctrl.emplace_back(ring[i].x(), y, ring[i].z());
      s.weights.push_back(rw[i]);
    }
  s.knots_u = {0, 0, 0, 1, 1, 2, 2, 2};
  s.knots_v = {0, 0, 1, 1};
  const SurfaceProbe probe(s, 3.0);
  // A ball centre segment along the axis direction at height 13 above the axis: distance 3.
  EXPECT_NEAR(probe.segment_distance(Vec3(0, 5, 13), Vec3(0, 35, 13), 20), 3, 1e-9);
  // Across the top, off to the side: the nearest point lies on the circle.
  const Vec3 p(6, 10, 12), q(6, 20, 12);
  EXPECT_NEAR(probe.segment_distance(p, q, 20), std::hypot(6, 12) - 10, 1e-9);
  double z = 0;
  ASSERT_TRUE(probe.height_at(Vec2(6, 12), z));
  EXPECT_NEAR(z, 8, 1e-9);
}

}  // namespace
}  // namespace ncpath
