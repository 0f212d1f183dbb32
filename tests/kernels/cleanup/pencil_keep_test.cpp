// pencil_keep (kernels/cleanup/pencil.hpp): which layer family traces a pencil point.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "kernels/cleanup/pencil.hpp"

namespace ncpath {
namespace {

// A candidate whose crease tangent is t: b1, b2 are unit vectors perpendicular to t, 90 deg
// apart (b1 x b2 = t up to sign).
PencilCandidate with_tangent(const Vec3& t, std::uint8_t family) {
  const Vec3 u = t.normalized();
  const Vec3 a = (std::abs(u.z()) < 0.9 ? Vec3(0, 0, 1) : Vec3(1, 0, 0)).cross(u).normalized();
  const Vec3 b = u.cross(a);
  PencilCandidate c;
  c.b1 = a;
  c.b2 = b;
  c.family = family;
  return c;
}

const bool kAll[3] = {true, true, true};

TEST(PencilKeep, TheFamilyWhoseLayersCrossMostSteeply) {
  // A crease along x crosses the planes x = const (y lines, family 1) square on.
  EXPECT_FALSE(pencil_keep(with_tangent({1, 0, 0}, 0), kAll));
  EXPECT_TRUE(pencil_keep(with_tangent({1, 0, 0}, 1), kAll));
  EXPECT_FALSE(pencil_keep(with_tangent({1, 0, 0}, 2), kAll));
  // Along y: the x lines (planes y = const).
  EXPECT_TRUE(pencil_keep(with_tangent({0, 1, 0}, 0), kAll));
  EXPECT_FALSE(pencil_keep(with_tangent({0, 1, 0}, 1), kAll));
  // Vertical: the z-levels, unless they were not scanned.
  EXPECT_TRUE(pencil_keep(with_tangent({0.1, 0.05, 1}, 2), kAll));
  EXPECT_FALSE(pencil_keep(with_tangent({0.1, 0.05, 1}, 0), kAll));
  // Without z-levels: |t . x| = 0.1 > |t . y| = 0.05, the planes x = const (family 1).
  const bool no_z[3] = {true, true, false};
  EXPECT_FALSE(pencil_keep(with_tangent({0.1, 0.05, 1}, 0), no_z));
  EXPECT_TRUE(pencil_keep(with_tangent({0.1, 0.05, 1}, 1), no_z));
}

// A crease at 45 degrees in xy: the points of both families must agree whatever rounding
// does to their tangents (perturbations far below kPencilFamilyTie), so the crease is traced
// once, by the lower family (x lines).
TEST(PencilKeep, A45DegreeCreaseGoesToOneFamilyDespiteRounding) {
  for (double e : {0.0, 1e-15, -1e-15, 1e-12, -1e-12, 3e-11}) {
    for (double z : {0.0, 0.3}) {
      const Vec3 t(1 + e, 1 - e, z);
      EXPECT_TRUE(pencil_keep(with_tangent(t, 0), kAll)) << e << " " << z;
      EXPECT_FALSE(pencil_keep(with_tangent(t, 1), kAll)) << e << " " << z;
    }
  }
  // Clearly off 45 degrees the steeper family wins either way: |t . y| > |t . x| is the
  // x lines' (planes y = const), |t . x| > |t . y| the y lines'.
  EXPECT_TRUE(pencil_keep(with_tangent({1, 1.001, 0}, 0), kAll));
  EXPECT_FALSE(pencil_keep(with_tangent({1, 1.001, 0}, 1), kAll));
  EXPECT_FALSE(pencil_keep(with_tangent({1.001, 1, 0}, 0), kAll));
  EXPECT_TRUE(pencil_keep(with_tangent({1.001, 1, 0}, 1), kAll));
}

}  // namespace
}  // namespace ncpath
