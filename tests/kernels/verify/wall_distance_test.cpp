// The verifier's wall distances (kernels/verify/wall_distance.*): analytic answers for lines,
// arcs and rational circles, and brute force over dense curve samples (the tests' own de
// Boor evaluation, tests/support/pocket_oracle.hpp) for random cubic NURBS.
#include "kernels/verify/wall_distance.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "kernels/curves/segment.hpp"
#include "tests/kernels/curves/nurbs_test_util.hpp"
#include "tests/support/pocket_oracle.hpp"

namespace ncpath {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Brute force: the distance from [p0, p1] to dense samples (chord tol) of a curve, less tol.
double brute_force(const Vec2& p0, const Vec2& p1, const std::vector<Vec2>& pts) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k + 1 < pts.size(); ++k)
    best = std::min(best, segment_segment_gap(p0, p1, pts[k], pts[k + 1]));
  return best;
}

TEST(WallDistance, SegmentsAnalytic) {
  EXPECT_DOUBLE_EQ(point_segment_distance(Vec2(1, 2), Vec2(0, 0), Vec2(4, 0)), 2);
  EXPECT_DOUBLE_EQ(point_segment_distance(Vec2(7, 4), Vec2(0, 0), Vec2(4, 0)), 5);
  EXPECT_EQ(segment_segment_gap(Vec2(0, -1), Vec2(0, 1), Vec2(-1, 0), Vec2(1, 0)), 0);  // cross
  EXPECT_DOUBLE_EQ(segment_segment_gap(Vec2(0, 1), Vec2(3, 1), Vec2(1, -2), Vec2(2, -2)), 3);
  // Collinear, disjoint.
  EXPECT_DOUBLE_EQ(segment_segment_gap(Vec2(0, 0), Vec2(1, 0), Vec2(3, 0), Vec2(5, 0)), 2);
}

TEST(WallDistance, SegmentToArcAnalytic) {
  // Upper half circle r = 5 around the origin, counter-clockwise from (5, 0) to (-5, 0).
  const Seg2 arc = make_arc(Vec2(5, 0), Vec2(-5, 0), Vec2(0, 0), true);
  // A horizontal chord above the top: the top point (0, 5) is nearest.
  EXPECT_NEAR(segment_curve_gap(Vec2(-1, 7), Vec2(1, 7), arc), 2, 1e-12);
  // Inside the circle, below the top: the ends are nearest, 5 - sqrt(1 + 9).
  EXPECT_NEAR(segment_curve_gap(Vec2(-1, 3), Vec2(1, 3), arc), 5 - std::sqrt(10.0), 1e-12);
  // A longer chord at y = 3 reaches past x = 4 where the circle is: it crosses.
  EXPECT_EQ(segment_curve_gap(Vec2(-6, 3), Vec2(6, 3), arc), 0);
  // Crossing the arc: 0.
  EXPECT_EQ(segment_curve_gap(Vec2(0, 0), Vec2(0, 9), arc), 0);
  // Below the x axis, the arc's lower half is missing: the ends are nearest.
  EXPECT_NEAR(segment_curve_gap(Vec2(-1, -3), Vec2(1, -3), arc), std::hypot(4, 3), 1e-12);
  // A segment whose foot is off its end: the end point to the circle.
  EXPECT_NEAR(segment_curve_gap(Vec2(10, 10), Vec2(20, 10), arc), std::hypot(10, 10) - 5, 1e-12);
}

TEST(WallDistance, RationalCircleIsExact) {
  // A NURBS circle of radius 4: distance from a segment is |distance to centre - 4|.
  const Nurbs2 c = test::circle9(Vec2(1, -2), 4);
  const std::vector<BezierPiece> pieces = bezier_pieces(c);
  ASSERT_EQ(pieces.size(), 4u);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-10, 10);
  for (int k = 0; k < 200; ++k) {
    const Vec2 p0(u(rng), u(rng)), p1 = p0 + Vec2(u(rng), u(rng)) * 0.2;
    double best = 1e9;
    for (const BezierPiece& b : pieces)
      best = std::min(best, segment_bezier_gap(p0, p1, b, 1e9, 1e-8));
    // Exact: segment vs circle.
    const Seg2 half1 = make_arc(Vec2(5, -2), Vec2(-3, -2), Vec2(1, -2), true);
    const Seg2 half2 = make_arc(Vec2(-3, -2), Vec2(5, -2), Vec2(1, -2), true);
    const double exact =
        std::min(segment_curve_gap(p0, p1, half1), segment_curve_gap(p0, p1, half2));
    EXPECT_LE(best, exact + 1e-12) << k;  // a lower bound
    EXPECT_GE(best, exact - 1e-8) << k;   // within the resolution
  }
}

TEST(WallDistance, RandomCubicsAgainstDenseSamples) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-30, 30);
  for (unsigned seed = 1; seed <= 6; ++seed) {
    const Nurbs2 c = test::random_cubic(seed, 9, seed % 2 == 0);
    std::vector<Vec2> pts;
    test::append_nurbs_points(c, 1e-7, pts);
    pts.push_back(test::nurbs_eval(c, c.knots.back()));
    const std::vector<BezierPiece> pieces = bezier_pieces(c);
    for (int k = 0; k < 50; ++k) {
      const Vec2 p0(u(rng), u(rng)), p1 = p0 + Vec2(u(rng), u(rng)) * 0.1;
      double best = 1e9;
      for (const BezierPiece& b : pieces)
        best = std::min(best, segment_bezier_gap(p0, p1, b, 1e9, 1e-7));
      const double bf = brute_force(p0, p1, pts);
      // Samples' chords lie within 1e-7 of the curve; the verifier within its resolution.
      EXPECT_NEAR(best, bf, 3e-7) << "seed " << seed << " query " << k;
    }
  }
}

TEST(WallDistance, WallSetMatchesPerCurveMinimumAndCaps) {
  // A square pocket of lines with a NURBS circle island.
  Region reg;
  const Vec2 corners[] = {{0, 0}, {0, 50}, {50, 50}, {50, 0}};  // clockwise
  for (int k = 0; k < 4; ++k)
    reg.boundary.curves.push_back({make_line(corners[k], corners[(k + 1) % 4]), -1});
  Profile island;
  island.nurbs.push_back(test::circle9(Vec2(25, 25), 5));
  island.curves.push_back({make_line(Vec2(30, 25), Vec2(30, 25)), 0});
  reg.islands.push_back(island);
  const double cap = 4;
  const WallSet walls({reg}, cap);
  EXPECT_NEAR(walls.distance(Vec2(2, 10), Vec2(2, 40), 1e-8), 2, 1e-12);   // the x = 0 wall
  EXPECT_NEAR(walls.distance(Vec2(25, 32), Vec2(26, 32), 1e-8), 2, 1e-8);  // the island
  EXPECT_EQ(walls.distance(Vec2(12, 12), Vec2(13, 13), 1e-8), cap);        // out of reach
  EXPECT_EQ(walls.distance(Vec2(-1, 25), Vec2(1, 25), 1e-8), 0);           // crossing
}

}  // namespace
}  // namespace ncpath
