// Drop-cutter kernel against one triangle: analytic cases per cutter, and random triangles
// against the independent oracles of tests/support/oracle.hpp.
#include "kernels/cutters/drop_cutter.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "tests/support/oracle.hpp"

namespace ncpath {
namespace {

constexpr double kTol = 1e-9;

CutterContact drop_tri(const Cutter& c, const Vec3& a, const Vec3& b, const Vec3& d, double x,
                       double y) {
  PreparedFacet f;
  EXPECT_TRUE(prepare_facet(a, b, d, f));
  CutterContact best;
  drop_facet(c, f, x, y, 0, best);
  return best;
}

const Cutter kCutters[] = {ball_cutter(10), flat_cutter(10), bull_nose_cutter(10, 2)};

TEST(DropCutter, HorizontalPlaneGivesPlaneHeightForEveryCutter) {
  for (const Cutter& c : kCutters) {
    const CutterContact r = drop_tri(c, {-100, -100, 3.5}, {100, -100, 3.5}, {0, 100, 3.5}, 1, 2);
    EXPECT_NEAR(r.tip_z, 3.5, kTol) << cutter_type_name(c.type);
    EXPECT_EQ(r.kind, ContactKind::kFacet);
  }
}

// Plane z = g*x (slope angle alpha = atan g). Derived by hand:
//   ball:  tip = z(x) + R/cos(alpha) - R
//   flat:  tip = z(x) + R*g              (the rim point uphill)
//   bull:  tip = z(x) + a*g + r/cos(alpha) - r
TEST(DropCutter, TiltedPlaneMatchesClosedForms) {
  for (double g : {0.1, 0.7, 2.5}) {
    const double cosa = 1 / std::sqrt(1 + g * g);
    const Vec3 A{-100, -100, -100 * g}, B{100, -100, 100 * g}, C{0, 100, 0};
    const double x = 3, y = 1, z = g * x;
    const double R = 5, r = 2, a = 3;
    EXPECT_NEAR(drop_tri(ball_cutter(10), A, B, C, x, y).tip_z, z + R / cosa - R, kTol);
    EXPECT_NEAR(drop_tri(flat_cutter(10), A, B, C, x, y).tip_z, z + R * g, kTol);
    EXPECT_NEAR(drop_tri(bull_nose_cutter(10, 2), A, B, C, x, y).tip_z, z + a * g + r / cosa - r,
                kTol);
  }
}

// V-groove along x: flanks z = |y| tan(beta). On the groove axis:
//   ball: R/cos(beta) - R; flat: R tan(beta); bull: a tan(beta) + r/cos(beta) - r.
TEST(DropCutter, VGrooveOnAxis) {
  for (double beta_deg : {10.0, 30.0, 60.0}) {
    const double t = std::tan(beta_deg * M_PI / 180), cb = std::cos(beta_deg * M_PI / 180);
    const Vec3 l0{-50, 0, 0}, l1{50, 0, 0};
    const Vec3 left0{-50, -40, 40 * t}, right0{-50, 40, 40 * t}, left1{50, -40, 40 * t};
    const Vec3 right1{50, 40, 40 * t};
    for (const Cutter& c : kCutters) {
      PreparedFacet f[4];
      prepare_facet(l0, l1, left0, f[0]);
      prepare_facet(l1, left1, left0, f[1]);
      prepare_facet(l0, right0, l1, f[2]);
      prepare_facet(l1, right0, right1, f[3]);
      CutterContact best;
      for (std::uint32_t k = 0; k < 4; ++k) drop_facet(c, f[k], 0.3, 0, k, best);
      const double R = c.radius, r = c.corner_radius, a = R - r;
      const double expect = c.type == CutterType::kBall   ? R / cb - R
                            : c.type == CutterType::kFlat ? R * t
                                                          : a * t + r / cb - r;
      EXPECT_NEAR(best.tip_z, expect, kTol) << cutter_type_name(c.type) << " " << beta_deg;
    }
  }
}

// Vertical wall x = 0, 0 <= z <= 7, tool axis at distance d: the top edge is horizontal,
// so tip = 7 - h(d) for every cutter, and nothing when d > R.
TEST(DropCutter, VerticalWallTopEdge) {
  const Vec3 a{0, -20, 0}, b{0, 20, 0}, c{0, 20, 7}, e{0, -20, 7};
  for (const Cutter& cut : kCutters) {
    for (double d : {0.0, 1.0, 2.9, 4.0, 4.99}) {
      PreparedFacet f[2];
      ASSERT_TRUE(prepare_facet(a, b, c, f[0]));
      ASSERT_TRUE(prepare_facet(a, c, e, f[1]));
      ASSERT_TRUE(f[0].vertical);
      CutterContact best;
      drop_facet(cut, f[0], d, 0.5, 0, best);
      drop_facet(cut, f[1], d, 0.5, 1, best);
      EXPECT_NEAR(best.tip_z, 7 - test::h_profile(cut.radius, cut.corner_radius, d), kTol)
          << cutter_type_name(cut.type) << " d=" << d;
    }
    CutterContact none = drop_tri(cut, a, b, c, 5.01, 0.5);
    EXPECT_EQ(none.kind, ContactKind::kNone);
  }
}

TEST(DropCutter, SingleVertex) {
  for (const Cutter& c : kCutters)
    for (double rho : {0.0, 2.0, 3.5, 4.5, 5.0}) {
      double tip;
      ASSERT_TRUE(drop_on_vertex(c, {1, 2, 3}, 1 + rho * 0.6, 2 + rho * 0.8, tip));
      EXPECT_NEAR(tip, 3 - test::h_profile(c.radius, c.corner_radius, rho), kTol);
    }
  double tip;
  EXPECT_FALSE(drop_on_vertex(ball_cutter(10), {0, 0, 0}, 5.001, 0, tip));
}

// Sloped single edge: compare with golden-section maximisation over the edge.
TEST(DropCutter, SingleEdgeAgainstGoldenSection) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> U(-6, 6);
  int contacts = 0;
  for (const Cutter& c : kCutters)
    for (int i = 0; i < 3000; ++i) {
      const Vec3 p{U(rng), U(rng), U(rng)}, q{U(rng), U(rng), U(rng)};
      const double x = U(rng), y = U(rng);
      double tip;
      Vec3 cc;
      if (!drop_on_edge(c, p, q, x, y, tip, cc)) continue;
      ++contacts;
      const double oracle = test::tip_for_segment(c.radius, c.corner_radius, p, q, x, y);
      EXPECT_NEAR(tip, oracle, 1e-9) << cutter_type_name(c.type) << " case " << i;
      // The contact point is on the edge and the tool touches it there.
      EXPECT_NEAR(test::tip_for_point(c.radius, c.corner_radius, cc, x, y), tip, 1e-9);
    }
  EXPECT_GT(contacts, 1000);
}

// Random triangles: the kernel's tip is reached by its own contact point (so it is not
// too high) and no point of the triangle asks for a higher tip (so it is not too low).
TEST(DropCutter, RandomTrianglesMatchOracle) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> U(-8, 8);
  for (const Cutter& c : kCutters) {
    int kinds[4] = {0, 0, 0, 0};
    for (int i = 0; i < 1500; ++i) {
      const Vec3 a{U(rng), U(rng), U(rng)}, b{U(rng), U(rng), U(rng)}, d{U(rng), U(rng), U(rng)};
      const double x = U(rng) * 0.7, y = U(rng) * 0.7;
      const CutterContact r = drop_tri(c, a, b, d, x, y);
      const double lower = test::tip_lower_bound(c.radius, c.corner_radius, a, b, d, x, y);
      ++kinds[static_cast<int>(r.kind)];
      if (r.kind == ContactKind::kNone) {
        EXPECT_EQ(lower, -std::numeric_limits<double>::infinity()) << "missed contact " << i;
        continue;
      }
      EXPECT_GE(r.tip_z, lower - 1e-9) << cutter_type_name(c.type) << " gouge, case " << i;
      EXPECT_NEAR(test::tip_for_point(c.radius, c.corner_radius, r.cc, x, y), r.tip_z, 1e-9)
          << cutter_type_name(c.type) << " contact point does not touch, case " << i;
      // The contact point lies on the triangle.
      EXPECT_LT(test::point_triangle_distance(r.cc, a, b, d), 1e-9);
      if (c.type == CutterType::kBall) {
        // Ball: the centre is exactly R from the triangle.
        const Vec3 centre{x, y, r.tip_z + c.radius};
        EXPECT_NEAR(test::point_triangle_distance(centre, a, b, d), c.radius, 1e-9);
      }
    }
    // Every contact kind was exercised.
    EXPECT_GT(kinds[1], 20) << cutter_type_name(c.type);
    EXPECT_GT(kinds[2], 20) << cutter_type_name(c.type);
    EXPECT_GT(kinds[3], 20) << cutter_type_name(c.type);
  }
}

TEST(DropCutter, DegenerateFacetIsRejected) {
  PreparedFacet f;
  EXPECT_FALSE(prepare_facet({0, 0, 0}, {1, 1, 1}, {2, 2, 2}, f));
}

TEST(Cutter, ValidateNamesTheBadValue) {
  EXPECT_EQ(validate(ball_cutter(6)), "");
  EXPECT_NE(validate(ball_cutter(-1)).find("diameter"), std::string::npos);
  EXPECT_NE(validate(bull_nose_cutter(6, 4)).find("corner radius 4"), std::string::npos);
  EXPECT_NE(validate(bull_nose_cutter(6, 0)).find("corner radius"), std::string::npos);
  EXPECT_EQ(validate(bull_nose_cutter(6, 3)), "");  // r == R is allowed (a ball)
}

}  // namespace
}  // namespace ncpath
