// kernels/mesh/mesh_transform: analytic placements, validation messages, degenerate facets.
#include "kernels/mesh/mesh_transform.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <limits>
#include <string>

namespace ncpath {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// Two facets whose vertices span the axis-aligned box [lo, hi] (both corners included), so
// the mesh's bounding box is exactly [lo, hi].
TriangleMesh box_mesh(const Vec3& lo, const Vec3& hi) {
  TriangleMesh m;
  m.vertices = {lo, Vec3(hi.x(), lo.y(), lo.z()), Vec3(hi.x(), hi.y(), lo.z()), hi,
                Vec3(lo.x(), hi.y(), hi.z())};
  m.facets = {{0, 1, 2}, {2, 3, 4}};
  return m;
}

bool starts_with(const std::string& s, const std::string& prefix) {
  return s.rfind(prefix, 0) == 0;
}

TEST(MeshTransformTest, FitXyMakesTheLongestXySideN) {
  TriangleMesh m = box_mesh(Vec3(0, 0, 0), Vec3(2, 1, 0.5));  // 2 x 1 footprint
  MeshTransform t;
  t.fit_xy_mm = 100;
  const TransformOutcome out = apply_transform(t, m);
  ASSERT_TRUE(out.ok()) << out.error;
  EXPECT_DOUBLE_EQ(out.scale, 50);
  const Aabb3 b = bounding_box(m);
  EXPECT_DOUBLE_EQ(b.hi.x() - b.lo.x(), 100);
  EXPECT_DOUBLE_EQ(b.hi.y() - b.lo.y(), 50);
  EXPECT_DOUBLE_EQ(b.hi.z() - b.lo.z(), 25);  // uniform: z scales too
  EXPECT_EQ(b.lo, Vec3(0, 0, 0));             // about the origin
}

TEST(MeshTransformTest, FitXyUsesYWhenItIsLongerAndIgnoresUnreferencedVertices) {
  TriangleMesh m = box_mesh(Vec3(-1, -1, 0), Vec3(0, 2, 1));  // 1 x 3 footprint
  m.vertices.push_back(Vec3(100, 100, 100));                  // referenced by no facet
  MeshTransform t;
  t.fit_xy_mm = 30;
  const TransformOutcome out = apply_transform(t, m);
  ASSERT_TRUE(out.ok()) << out.error;
  EXPECT_DOUBLE_EQ(out.scale, 10);
  const Aabb3 b = bounding_box(m);
  EXPECT_DOUBLE_EQ(b.hi.y() - b.lo.y(), 30);
  EXPECT_DOUBLE_EQ(b.hi.x() - b.lo.x(), 10);
  EXPECT_EQ(m.vertices.back(), Vec3(1000, 1000, 1000));  // moved with the rest
}

TEST(MeshTransformTest, ScaleThenTranslate) {
  TriangleMesh m = box_mesh(Vec3(1, 2, 3), Vec3(4, 5, 6));
  const TriangleMesh before = m;
  MeshTransform t;
  t.scale = 2;
  t.translate = Vec3(10, -20, 0.5);
  ASSERT_TRUE(apply_transform(t, m).ok());
  for (std::size_t i = 0; i < m.vertices.size(); ++i)
    EXPECT_EQ(m.vertices[i], 2 * before.vertices[i] + Vec3(10, -20, 0.5)) << i;
  EXPECT_EQ(m.facets, before.facets);
}

TEST(MeshTransformTest, ScaleComposesWithFit) {
  TriangleMesh m = box_mesh(Vec3(0, 0, 0), Vec3(2, 1, 1));
  MeshTransform t;
  t.scale = 3;
  t.fit_xy_mm = 10;  // s = 3 * 10 / 2
  const TransformOutcome out = apply_transform(t, m);
  ASSERT_TRUE(out.ok());
  EXPECT_DOUBLE_EQ(out.scale, 15);
  const Aabb3 b = bounding_box(m);
  EXPECT_DOUBLE_EQ(b.hi.x() - b.lo.x(), 30);
}

TEST(MeshTransformTest, TwoScalesComposeToTheirProduct) {
  TriangleMesh a = box_mesh(Vec3(-1, 0.5, 2), Vec3(3, 4, 5));
  TriangleMesh b = a;
  MeshTransform s1, s2, s12;
  s1.scale = 0.25;
  s2.scale = 8;
  s12.scale = 2;
  ASSERT_TRUE(apply_transform(s1, a).ok());
  ASSERT_TRUE(apply_transform(s2, a).ok());
  ASSERT_TRUE(apply_transform(s12, b).ok());
  for (std::size_t i = 0; i < a.vertices.size(); ++i) EXPECT_EQ(a.vertices[i], b.vertices[i]);
}

TEST(MeshTransformTest, InvalidValuesNameTheKeyAndLeaveTheMeshAlone) {
  const TriangleMesh original = box_mesh(Vec3(0, 0, 0), Vec3(2, 1, 1));
  struct Case {
    MeshTransform t;
    std::string key;
  };
  std::vector<Case> cases;
  for (double s : {0.0, -1.0, kNaN, kInf}) {
    MeshTransform t;
    t.scale = s;
    cases.push_back({t, "scale:"});
  }
  for (double f : {0.0, -5.0, kNaN, kInf}) {
    MeshTransform t;
    t.fit_xy_mm = f;
    cases.push_back({t, "fit_xy:"});
  }
  for (double x : {kNaN, kInf}) {
    MeshTransform t;
    t.translate = Vec3(0, x, 0);
    cases.push_back({t, "translate:"});
  }
  for (const Case& c : cases) {
    EXPECT_TRUE(starts_with(validate(c.t), c.key)) << validate(c.t);
    TriangleMesh m = original;
    const TransformOutcome out = apply_transform(c.t, m);
    EXPECT_FALSE(out.ok());
    EXPECT_TRUE(starts_with(out.error, c.key)) << out.error;
    EXPECT_EQ(m.vertices, original.vertices);
  }
  EXPECT_EQ(validate(MeshTransform{}), "");
  MeshTransform neg;
  neg.scale = -2;
  EXPECT_NE(validate(neg).find("-2"), std::string::npos) << validate(neg);
}

TEST(MeshTransformTest, FitNeedsAnXyExtent) {
  TriangleMesh vertical;  // a facet standing on one xy point
  vertical.vertices = {Vec3(1, 1, 0), Vec3(1, 1, 1), Vec3(1, 1, 2)};
  vertical.facets = {{0, 1, 2}};
  const TriangleMesh before = vertical;
  MeshTransform t;
  t.fit_xy_mm = 10;
  const TransformOutcome out = apply_transform(t, vertical);
  EXPECT_TRUE(starts_with(out.error, "fit_xy:")) << out.error;
  EXPECT_NE(out.error.find("zero extent"), std::string::npos) << out.error;
  EXPECT_EQ(vertical.vertices, before.vertices);

  TriangleMesh empty;
  EXPECT_TRUE(starts_with(apply_transform(t, empty).error, "fit_xy:"));
  // Without a fit an empty mesh is fine: nothing to move.
  EXPECT_TRUE(apply_transform(MeshTransform{}, empty).ok());
}

TEST(MeshTransformTest, OverflowIsRefused) {
  TriangleMesh m = box_mesh(Vec3(0, 0, 0), Vec3(1e300, 1, 1));
  const TriangleMesh before = m;
  MeshTransform t;
  t.scale = 1e10;
  const TransformOutcome out = apply_transform(t, m);
  EXPECT_TRUE(starts_with(out.error, "scale:")) << out.error;
  EXPECT_EQ(m.vertices, before.vertices);
}

TEST(MeshTransformTest, DegenerateFacets) {
  TriangleMesh m;
  m.vertices = {Vec3(0, 0, 0),     Vec3(1, 0, 0),    Vec3(0, 1, 0),   Vec3(2, 0, 0),
                Vec3(0, 1e-10, 0), Vec3(0, 1e-8, 0), Vec3(kNaN, 0, 0)};
  m.facets = {
      {0, 1, 2},  // area2 = 1
      {0, 0, 1},  // repeated vertex
      {0, 1, 3},  // collinear
      {0, 1, 4},  // area2 = 1e-10 * 1: fine at the default tolerance 1e-18
      {4, 5, 0},  // on the y axis: collinear
      {0, 1, 6},  // NaN: no normal
  };
  EXPECT_DOUBLE_EQ(facet_area2(m.vertices[0], m.vertices[1], m.vertices[2]), 1.0);
  EXPECT_EQ(count_degenerate_facets(m), 4u);
  EXPECT_EQ(count_degenerate_facets(m, 1e-9), 5u);  // the sliver too at a coarser tolerance
  EXPECT_TRUE(is_degenerate_facet(Vec3(0, 0, 0), Vec3(1e-9, 0, 0), Vec3(0, 1e-10, 0)));  // 1e-19
  EXPECT_FALSE(is_degenerate_facet(Vec3(0, 0, 0), Vec3(1e-9, 0, 0), Vec3(0, 1e-8, 0)));  // 1e-17

  TriangleMesh copy = m;
  EXPECT_EQ(remove_degenerate_facets(copy), 4u);
  ASSERT_EQ(copy.facets.size(), 2u);
  EXPECT_EQ(copy.facets[0], m.facets[0]);  // order kept
  EXPECT_EQ(copy.facets[1], m.facets[3]);
  EXPECT_EQ(copy.vertices.size(), m.vertices.size());
}

TEST(MeshTransformTest, FacetUnitNormal) {
  EXPECT_EQ(facet_unit_normal(Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 3, 0)), Vec3(0, 0, 1));
  EXPECT_EQ(facet_unit_normal(Vec3(0, 0, 0), Vec3(0, 3, 0), Vec3(2, 0, 0)), Vec3(0, 0, -1));
  EXPECT_EQ(facet_unit_normal(Vec3(0, 0, 0), Vec3(1, 1, 1), Vec3(2, 2, 2)), Vec3::Zero());
  const Vec3 n = facet_unit_normal(Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1));
  EXPECT_NEAR((n - Vec3(1, 1, 1) / std::sqrt(3.0)).norm(), 0, 1e-15);
}

}  // namespace
}  // namespace ncpath
