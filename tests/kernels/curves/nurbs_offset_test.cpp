// kernels/curves/nurbs_offset*: Tiller-Hanson offsets checked against analytic circles and,
// for free-form curves, against distances to the original computed by dense sampling plus a
// local search (test/nurbs_test_util.hpp), never by the offset code. Self-loops must be cut.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "kernels/curves/nurbs.hpp"
#include "tests/kernels/curves/nurbs_test_util.hpp"

namespace ncpath {
namespace {

using test::CurveDistance;
using test::eval;
using test::params;

// Dense samples of all pieces.
std::vector<std::vector<Vec2>> sample_pieces(const NurbsOffset& o, int per_piece) {
  std::vector<std::vector<Vec2>> out;
  for (const Nurbs2& p : o.pieces) {
    out.emplace_back();
    for (double t : params(p, per_piece)) out.back().push_back(eval(p, t));
  }
  return out;
}

// Every result point is at distance |d| (+- tol) from the original, and every true offset
// point C(t) + d N_right(t) (from the oracle's tangent) is within tol of the result.
void expect_offset_of(const Nurbs2& curve, double d, double tol, const NurbsOffset& o) {
  ASSERT_EQ(o.error, "");
  ASSERT_FALSE(o.pieces.empty());
  for (const Nurbs2& p : o.pieces) ASSERT_EQ(validate(p), "");
  EXPECT_LE(o.max_deviation, tol);
  const CurveDistance dist(curve);
  const auto pts = sample_pieces(o, 1500);
  for (const auto& pl : pts)
    for (const Vec2& q : pl) ASSERT_NEAR(dist(q), std::abs(d), tol) << q.transpose();
  for (double t : params(curve, 700)) {
    const Vec2 tg = test::tangent(curve, t);
    const Vec2 q = eval(curve, t) + d * Vec2(tg.y(), -tg.x());
    double best = INFINITY;
    for (const auto& pl : pts) best = std::min(best, test::polyline_distance(pl, q));
    ASSERT_LE(best, tol) << "t=" << t;
  }
}

TEST(NurbsOffset, CircleOffsetsAreCircles) {
  const Vec2 c(10, -4);
  const double r = 5;
  const Nurbs2 circle = test::circle9(c, r);
  // Counter-clockwise circle: right = outside (r + d), left = inside (r - |d|).
  for (double d : {1.0, -1.0, 3.5, -4.0}) {
    const NurbsOffset o = nurbs_offset(circle, d, 1e-3);
    ASSERT_EQ(o.error, "");
    ASSERT_EQ(o.pieces.size(), 1u) << d;
    EXPECT_LE(o.max_deviation, 1e-3);
    for (double t : params(o.pieces[0], 2000))
      ASSERT_NEAR((eval(o.pieces[0], t) - c).norm(), r + d, 1e-3) << d << " " << t;
    // The offset control polygon of a rational circle is exact: no refinement needed.
    EXPECT_EQ(o.knots_inserted, 0) << d;
  }
}

TEST(NurbsOffset, OffsetInsideBeyondTheRadiusLeavesNothing) {
  // Offsetting a circle inwards by more than its radius runs backwards everywhere.
  const NurbsOffset o = nurbs_offset(test::circle9(Vec2(0, 0), 5), -7, 1e-3);
  EXPECT_EQ(o.error, "");
  EXPECT_TRUE(o.pieces.empty());
}

TEST(NurbsOffset, RandomCubicsBothSides) {
  for (unsigned seed : {1u, 2u, 3u}) {
    const Nurbs2 n = test::random_cubic(seed, 12, seed == 3);
    // Keep |d| below the smallest curvature radius (checked here) so there is no loop.
    double min_radius = INFINITY;
    for (double t : params(n, 3000))
      min_radius = std::min(min_radius, 1 / std::abs(nurbs_curvature(n, t)));
    const double d = std::min(1.5, 0.5 * min_radius);
    ASSERT_GT(d, 0.05) << "test curve too sharp for seed " << seed;
    for (double sd : {d, -d}) {
      SCOPED_TRACE(testing::Message() << "seed " << seed << " d " << sd);
      const NurbsOffset o = nurbs_offset(n, sd, 0.01);
      EXPECT_GT(o.knots_inserted, 0);
      ASSERT_EQ(o.pieces.size(), 1u);
      expect_offset_of(n, sd, 0.01, o);
    }
  }
}

TEST(NurbsOffset, TighterToleranceRefinesMore) {
  const Nurbs2 n = test::random_cubic(4, 10, false);
  const NurbsOffset a = nurbs_offset(n, 0.8, 0.05), b = nurbs_offset(n, 0.8, 0.0005);
  EXPECT_LE(a.max_deviation, 0.05);
  EXPECT_LE(b.max_deviation, 0.0005);
  EXPECT_GT(b.knots_inserted, a.knots_inserted);
}

TEST(NurbsOffset, LoopOfASharpBendIsCutOut) {
  // A V-shaped cubic turning left at its bottom with a small radius there: offset to the left
  // (inside the bend) by more than that radius makes a swallowtail.
  const Nurbs2 n = test::clamped(3, {{-10, 10}, {-1, -8}, {1, -8}, {10, 10}});
  double min_radius = INFINITY;
  for (double t : params(n, 4000))
    min_radius = std::min(min_radius, 1 / std::abs(nurbs_curvature(n, t)));
  const double d = -6.0;
  ASSERT_LT(min_radius, 0.5 * std::abs(d));
  const NurbsOffset o = nurbs_offset(n, d, 0.005);
  ASSERT_EQ(o.error, "");
  ASSERT_EQ(o.pieces.size(), 2u);
  // The pieces meet at the loop's crossing point, which lies on the symmetry axis x = 0.
  EXPECT_EQ(o.pieces[0].ctrl.back(), o.pieces[1].ctrl.front());
  EXPECT_NEAR(o.pieces[0].ctrl.back().x(), 0, 1e-6);
  // No self-intersection left, within or between pieces.
  const auto pts = sample_pieces(o, 2000);
  std::vector<Vec2> all = pts[0];
  all.insert(all.end(), pts[1].begin() + 1, pts[1].end());
  EXPECT_EQ(test::self_crossings(all, false), 0);
  // Without the loop, every point of the result is at distance |d| from the curve.
  const CurveDistance dist(n);
  for (const auto& pl : pts)
    for (const Vec2& q : pl) ASSERT_NEAR(dist(q), std::abs(d), 0.005) << q.transpose();
  // The untrimmed offset would cross itself: the oracle's own offset polyline does.
  std::vector<Vec2> raw;
  for (double t : params(n, 4000)) {
    const Vec2 tg = test::tangent(n, t);
    raw.push_back(eval(n, t) + d * Vec2(tg.y(), -tg.x()));
  }
  EXPECT_GT(test::self_crossings(raw, false), 0);
}

TEST(NurbsOffset, ClosedEllipseInsideLosesBothEndLoops) {
  // Ellipse a = 10, b = 3: curvature radius b^2 / a = 0.9 at the major-axis ends. Offsetting
  // inwards by 2 (< b) leaves two swallowtails, one of them across the seam.
  const Nurbs2 e = nurbs_ellipse(Vec2(0, 0), Vec2(10, 0), 0.3, 0, 2 * std::numbers::pi);
  const double d = -2;  // counter-clockwise: left = inside
  const NurbsOffset o = nurbs_offset(e, d, 0.005);
  ASSERT_EQ(o.error, "");
  ASSERT_EQ(o.pieces.size(), 2u);
  EXPECT_EQ(o.pieces[0].ctrl.back(), o.pieces[1].ctrl.front());
  EXPECT_EQ(o.pieces[1].ctrl.back(), o.pieces[0].ctrl.front());
  const CurveDistance dist(e, 8000);
  const auto pts = sample_pieces(o, 2000);
  for (const auto& pl : pts) {
    EXPECT_EQ(test::self_crossings(pl, false), 0);
    for (const Vec2& q : pl) ASSERT_NEAR(dist(q), 2, 0.005) << q.transpose();
  }
  // By symmetry the two crossing points lie on the major axis (y = 0).
  EXPECT_NEAR(o.pieces[0].ctrl.front().y(), 0, 1e-6);
  EXPECT_NEAR(o.pieces[1].ctrl.front().y(), 0, 1e-6);
}

TEST(NurbsOffset, WavyCurveLosesEveryCrestLoopButKeepsTheSeamCrossing) {
  // 12 waves of amplitude 3 around radius 50 (counter-clockwise), curvature radius about 5.8
  // at the crests. Inwards by 8 every crest makes a swallowtail. The clamped seam is a
  // corner, whose offsets cross globally: that crossing must not swallow the whole curve.
  std::vector<Vec2> ctrl;
  const int count = 123;
  for (int i = 0; i < count; ++i) {
    const double a = 2 * std::numbers::pi * i / (count - 1);
    const double r = 50 + 3 * std::sin(12 * a);
    ctrl.emplace_back(r * std::cos(a), r * std::sin(a));
  }
  ctrl.back() = ctrl.front();
  const Nurbs2 n = test::clamped(3, ctrl);
  const NurbsOffset o = nurbs_offset(n, -8, 0.01);
  ASSERT_EQ(o.error, "");
  ASSERT_EQ(o.pieces.size(), 13u);  // 12 cuts in an open chain (the seam is not G1)
  const CurveDistance dist(n, 12000);
  const auto pts = sample_pieces(o, 400);
  for (std::size_t k = 0; k < pts.size(); ++k) {
    EXPECT_EQ(test::self_crossings(pts[k], false), 0) << k;
    if (k == 0 || k + 1 == pts.size()) continue;  // these overlap at the seam corner
    EXPECT_EQ(o.pieces[k - 1].ctrl.back(), o.pieces[k].ctrl.front());
    for (const Vec2& q : pts[k]) ASSERT_NEAR(dist(q), 8, 0.01) << k << ": " << q.transpose();
  }
}

}  // namespace
}  // namespace ncpath
