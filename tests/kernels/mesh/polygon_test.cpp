// kernels/mesh/polygon: convexity verdicts on exact cases and fan triangulations checked
// against analytic areas and the polygon's own orientation.
#include "kernels/mesh/polygon.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <limits>
#include <numbers>
#include <set>
#include <vector>

namespace ncpath {
namespace {

// Maps plane coordinates (u, v) into a tilted plane through `origin`.
struct Plane {
  Vec3 origin{0, 0, 0};
  Vec3 u{1, 0, 0};
  Vec3 v{0, 1, 0};
  Vec3 at(double a, double b) const { return origin + a * u + b * v; }
};

Plane tilted() {
  Plane p;
  p.origin = Vec3(1e3, -2e3, 500);  // far from the origin on purpose
  p.u = Vec3(1, 1, 1).normalized();
  p.v = Vec3(1, -1, 0).normalized();
  return p;
}

std::vector<Vec3> in_plane(const Plane& p, const std::vector<Vec2>& pts) {
  std::vector<Vec3> out;
  for (const Vec2& q : pts) out.push_back(p.at(q.x(), q.y()));
  return out;
}

std::vector<Vec3> regular(int k, const Plane& p, double r = 1) {
  std::vector<Vec2> pts;
  for (int i = 0; i < k; ++i) {
    const double t = 2 * std::numbers::pi * i / k;
    pts.emplace_back(r * std::cos(t), r * std::sin(t));
  }
  return in_plane(p, pts);
}

double fan_area(const std::vector<Vec3>& poly, const PolygonTriangulation& t) {
  double a = 0;
  for (const auto& tri : t.triangles)
    a += 0.5 * (poly[tri[1]] - poly[tri[0]]).cross(poly[tri[2]] - poly[tri[0]]).norm();
  return a;
}

TEST(PolygonTest, RegularPolygonsAreConvexWithKMinus2Triangles) {
  const Plane p = tilted();
  const Vec3 plane_normal = p.u.cross(p.v);
  for (int k = 3; k <= 12; ++k) {
    const auto poly = regular(k, p);
    const PolygonTriangulation t = triangulate_convex_polygon(poly);
    ASSERT_TRUE(t.check.convex()) << k << ": " << polygon_status_text(t.check.status);
    EXPECT_EQ(t.check.corners, static_cast<std::uint32_t>(k));
    ASSERT_EQ(t.triangles.size(), static_cast<std::size_t>(k - 2));
    EXPECT_NEAR(fan_area(poly, t), 0.5 * k * std::sin(2 * std::numbers::pi / k), 1e-9) << k;
    EXPECT_NEAR(t.check.normal.dot(plane_normal), 1.0, 1e-12) << k;  // CCW in (u, v)
    for (const auto& tri : t.triangles) {
      const Vec3 n = (poly[tri[1]] - poly[tri[0]]).cross(poly[tri[2]] - poly[tri[0]]);
      EXPECT_GT(n.dot(plane_normal), 0) << k;  // the fan keeps the polygon's winding
    }
  }
}

TEST(PolygonTest, ClockwisePolygonIsConvexWithTheOppositeNormal) {
  std::vector<Vec3> sq = {{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}};
  const PolygonCheck c = check_convex_polygon(sq);
  ASSERT_TRUE(c.convex());
  EXPECT_NEAR(c.normal.z(), -1.0, 1e-15);
}

TEST(PolygonTest, StraightVerticesAreNotCornersOfTheFan) {
  // A unit square with extra vertices in the middle of two edges (indices 1 and 4).
  std::vector<Vec3> poly = {{0, 0, 0}, {0.5, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0.5, 1, 0}, {0, 1, 0}};
  const PolygonTriangulation t = triangulate_convex_polygon(poly);
  ASSERT_TRUE(t.check.convex());
  EXPECT_EQ(t.check.corners, 4u);
  ASSERT_EQ(t.triangles.size(), 2u);
  EXPECT_NEAR(fan_area(poly, t), 1.0, 1e-15);
  for (const auto& tri : t.triangles)
    for (std::uint32_t i : tri) EXPECT_TRUE(i != 1 && i != 4) << i;
}

TEST(PolygonTest, ReflexVertexIsNonConvexAndNamed) {
  // An L: its reflex corner is index 3 (1, 1).
  const auto l = in_plane(tilted(), {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}});
  const PolygonTriangulation t = triangulate_convex_polygon(l);
  EXPECT_EQ(t.check.status, PolygonStatus::kNonConvex);
  EXPECT_EQ(t.check.vertex, 3u);
  EXPECT_TRUE(t.triangles.empty());
  // A dart, reflex at index 3; the same with the order reversed is reflex at the same point.
  std::vector<Vec3> dart = {{0, 0, 0}, {2, 1, 0}, {0, 2, 0}, {0.5, 1, 0}};
  EXPECT_EQ(check_convex_polygon(dart).status, PolygonStatus::kNonConvex);
  EXPECT_EQ(check_convex_polygon(dart).vertex, 3u);
  std::vector<Vec3> rev(dart.rbegin(), dart.rend());  // (0.5, 1) is now index 0
  EXPECT_EQ(check_convex_polygon(rev).status, PolygonStatus::kNonConvex);
  EXPECT_EQ(check_convex_polygon(rev).vertex, 0u);
}

TEST(PolygonTest, DoublingBackIsNonConvex) {
  // Up the edge x = 2 to (2, 1), then straight back down to (2, 0.5).
  std::vector<Vec3> spike = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {2, 0.5, 0}};
  const PolygonCheck c = check_convex_polygon(spike);
  EXPECT_EQ(c.status, PolygonStatus::kNonConvex);
  EXPECT_EQ(c.vertex, 2u);
}

TEST(PolygonTest, StarsAndBowTiesAreSelfIntersecting) {
  std::vector<Vec2> star;
  for (int i = 0; i < 5; ++i) {
    const double t = std::numbers::pi / 2 + 4 * std::numbers::pi * i / 5;
    star.emplace_back(std::cos(t), std::sin(t));
  }
  // All five turns are left turns: only the winding tells the pentagram from a pentagon.
  EXPECT_EQ(check_convex_polygon(in_plane(tilted(), star)).status,
            PolygonStatus::kSelfIntersecting);
  // Symmetric bow-tie: the two lobes cancel, zero net area, yet it is not a line.
  std::vector<Vec3> bowtie = {{0, 0, 0}, {1, 1, 0}, {1, 0, 0}, {0, 1, 0}};
  EXPECT_EQ(check_convex_polygon(bowtie).status, PolygonStatus::kSelfIntersecting);
  // Lopsided bow-tie: net area left, turns of both signs.
  std::vector<Vec3> lopsided = {{0, 0, 0}, {2, 2, 0}, {2, 0, 0}, {0, 1, 0}};
  EXPECT_EQ(check_convex_polygon(lopsided).status, PolygonStatus::kNonConvex);
}

TEST(PolygonTest, DegenerateInputs) {
  std::vector<Vec3> two = {{0, 0, 0}, {1, 0, 0}};
  EXPECT_EQ(check_convex_polygon(two).status, PolygonStatus::kTooFewVertices);
  EXPECT_EQ(check_convex_polygon(std::span<const Vec3>{}).status, PolygonStatus::kTooFewVertices);

  std::vector<Vec3> repeated = {{0, 0, 0}, {1, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const PolygonCheck r = check_convex_polygon(repeated);
  EXPECT_EQ(r.status, PolygonStatus::kZeroLengthEdge);
  EXPECT_EQ(r.vertex, 1u);
  std::vector<Vec3> closed = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 0}};  // repeats the first
  EXPECT_EQ(check_convex_polygon(closed).status, PolygonStatus::kZeroLengthEdge);
  EXPECT_EQ(check_convex_polygon(closed).vertex, 3u);

  std::vector<Vec3> line = {{0, 0, 0}, {1, 1, 1}, {3, 3, 3}, {2, 2, 2}};
  EXPECT_EQ(check_convex_polygon(line).status, PolygonStatus::kDegenerate);

  std::vector<Vec3> nan = {{0, 0, 0}, {1, 0, 0}, {0, std::numeric_limits<double>::quiet_NaN(), 0}};
  const PolygonCheck n = check_convex_polygon(nan);
  EXPECT_EQ(n.status, PolygonStatus::kNonFinite);
  EXPECT_EQ(n.vertex, 2u);
}

TEST(PolygonTest, SlightlyTwistedQuadIsJudgedByItsProjection) {
  std::vector<Vec3> quad = {{0, 0, 0}, {1, 0, 0.01}, {1, 1, 0}, {0, 1, 0.01}};
  const PolygonTriangulation t = triangulate_convex_polygon(quad);
  ASSERT_TRUE(t.check.convex());
  EXPECT_EQ(t.triangles.size(), 2u);
}

TEST(PolygonTest, StatusTextsAreDistinct) {
  std::set<std::string> texts;
  for (auto s : {PolygonStatus::kConvex, PolygonStatus::kTooFewVertices, PolygonStatus::kNonFinite,
                 PolygonStatus::kZeroLengthEdge, PolygonStatus::kDegenerate,
                 PolygonStatus::kNonConvex, PolygonStatus::kSelfIntersecting})
    texts.insert(polygon_status_text(s));
  EXPECT_EQ(texts.size(), 7u);
}

}  // namespace
}  // namespace ncpath
