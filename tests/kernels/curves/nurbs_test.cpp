// kernels/curves/nurbs_{eval,edit,ellipse,polyline}: evaluation against the Cox-de Boor
// recursion and analytic circles / ellipses, derivatives against finite differences, and
// editing operations (knot insertion, split, reversal) that must leave the curve unchanged.
#include "kernels/curves/nurbs.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "tests/kernels/curves/nurbs_test_util.hpp"

namespace ncpath {
namespace {

using test::circle9;
using test::eval;
using test::params;
using test::random_cubic;

constexpr double kPi = std::numbers::pi;

TEST(NurbsEval, CircleLiesOnCircle) {
  const Vec2 c(100, -50);
  const double r = 7.5;
  const Nurbs2 n = circle9(c, r);
  ASSERT_EQ(validate(n), "");
  for (double t : params(n, 997)) EXPECT_NEAR((nurbs_point(n, t) - c).norm(), r, 1e-12) << t;
  // Quarter points are the control points at weight 1.
  EXPECT_NEAR((nurbs_point(n, 0.25) - Vec2(100, -42.5)).norm(), 0, 1e-12);
  EXPECT_NEAR((nurbs_point(n, 0.5) - Vec2(92.5, -50)).norm(), 0, 1e-12);
}

TEST(NurbsEval, CircleCurvatureIsOneOverRadius) {
  const Nurbs2 n = circle9(Vec2(3, 4), 2.5);
  for (double t : params(n, 301)) EXPECT_NEAR(nurbs_curvature(n, t), 1 / 2.5, 1e-10) << t;
  const Nurbs2 rev = nurbs_reversed(n);
  for (double t : params(rev, 101)) EXPECT_NEAR(nurbs_curvature(rev, t), -1 / 2.5, 1e-10) << t;
}

TEST(NurbsEval, MatchesCoxDeBoorForManyDegrees) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-5, 5), W(0.3, 3);
  for (int p = 1; p <= 6; ++p) {
    std::vector<Vec2> ctrl;
    std::vector<double> w;
    for (int i = 0; i < p + 5; ++i) {
      ctrl.emplace_back(U(rng), U(rng));
      w.push_back(W(rng));
    }
    Nurbs2 n = test::clamped(p, ctrl, w);
    if (p >= 2) n.knots[p + 2] = n.knots[p + 1];  // a double interior knot
    ASSERT_EQ(validate(n), "") << p;
    for (double t : params(n, 211))
      EXPECT_NEAR((nurbs_point(n, t) - eval(n, t)).norm(), 0, 1e-12) << "p=" << p << " t=" << t;
  }
}

TEST(NurbsEval, DerivativesMatchFiniteDifferences) {
  const Nurbs2 n = random_cubic(3, 9, true);
  const double h = 1e-4;
  for (double t : params(n, 57)) {
    if (t - 2 * h < nurbs_t0(n) || t + 2 * h > nurbs_t1(n)) continue;
    Vec2 d0, d1, d2;
    nurbs_derivatives(n, t, d0, d1, d2);
    const Vec2 pm = eval(n, t - h), p0 = eval(n, t), pp = eval(n, t + h);
    const Vec2 fd1 = (pp - pm) / (2 * h), fd2 = (pp - 2 * p0 + pm) / (h * h);
    EXPECT_NEAR((d0 - p0).norm(), 0, 1e-12);
    // Knots are integers: a probe straddling one sees the C2 cubic's second derivative only
    // to O(h) there, hence the looser bound on d2.
    EXPECT_NEAR((d1 - fd1).norm(), 0, 1e-5 * (1 + d1.norm())) << t;
    EXPECT_NEAR((d2 - fd2).norm(), 0, 1e-3 * (1 + d2.norm())) << t;
  }
}

TEST(NurbsEval, EndsAreExactlyTheEndControlPoints) {
  const Nurbs2 n = random_cubic(11, 8, true);
  EXPECT_EQ(nurbs_point(n, nurbs_t0(n)), n.ctrl.front());
  EXPECT_EQ(nurbs_point(n, nurbs_t1(n)), n.ctrl.back());
}

TEST(NurbsValidate, RejectsInvalidCurvesWithTheReason) {
  const Nurbs2 good = random_cubic(1, 6, true);
  ASSERT_EQ(validate(good), "");
  auto expect_msg = [](const Nurbs2& n, const std::string& part) {
    const std::string m = validate(n);
    EXPECT_NE(m.find(part), std::string::npos) << "got: '" << m << "', wanted: " << part;
  };
  Nurbs2 n = good;
  n.degree = 0;
  expect_msg(n, "degree must be >= 1");
  n = good;
  n.knots.pop_back();
  expect_msg(n, "knot count");
  n = good;
  n.weights.pop_back();
  expect_msg(n, "weight count");
  n = good;
  n.weights[2] = 0;
  expect_msg(n, "weight 2 is not > 0");
  n = good;
  n.ctrl[1].x() = std::nan("");
  expect_msg(n, "control point 1 is not finite");
  n = good;
  std::swap(n.knots[4], n.knots[5]);
  expect_msg(n, "decrease");
  n = good;
  n.knots[0] = -1;
  expect_msg(n, "not clamped");
  n = good;
  n.knots[n.knots.size() - 4] = n.knots.back() - 0.5;
  expect_msg(n, "not clamped");
  n = good;
  n.ctrl.resize(3);
  n.weights.resize(3);
  expect_msg(n, "at least 4 control points");
  n = test::clamped(2, {{0, 0}, {1, 0}, {2, 1}, {3, 0}, {4, 0}, {5, 1}});  // 0 0 0 1 2 3 4 4 4
  ASSERT_EQ(validate(n), "");
  n.knots = {0, 0, 0, 1, 1, 1, 3, 3, 3};
  expect_msg(n, "multiplicity 3 > degree");
  // Other operations refuse invalid input instead of reading out of bounds.
  EXPECT_TRUE(nurbs_polyline(n, 0.1).empty());
  EXPECT_TRUE(nurbs_to_arcs(n, 0.1, 0).empty());
}

// Many samples of `a` at t equal `b` at map(t).
void expect_same_curve(const Nurbs2& a, const Nurbs2& b, double tol = 1e-12) {
  for (double t : params(a, 613)) ASSERT_NEAR((eval(a, t) - eval(b, t)).norm(), 0, tol) << t;
}

TEST(NurbsEdit, KnotInsertionLeavesTheCurveUnchanged) {
  const Nurbs2 n = random_cubic(5, 10, true);
  // A new knot, an existing one (raising its multiplicity), and one inserted three times.
  for (auto [t, times] : {std::pair{2.37, 1}, {4.0, 1}, {5.5, 3}, {0.001, 2}}) {
    const Nurbs2 m = nurbs_insert_knot(n, t, times);
    ASSERT_EQ(validate(m), "");
    EXPECT_EQ(m.ctrl.size(), n.ctrl.size() + times) << t;
    EXPECT_EQ(std::count(m.knots.begin(), m.knots.end(), t),
              std::count(n.knots.begin(), n.knots.end(), t) + times);
    expect_same_curve(n, m);
  }
  // Beyond multiplicity = degree nothing changes (the curve stays continuous).
  const Nurbs2 full = nurbs_insert_knot(n, 4.0, 10);
  EXPECT_EQ(std::count(full.knots.begin(), full.knots.end(), 4.0), 3);
  expect_same_curve(n, full);
  // A circle stays a circle.
  const Nurbs2 c = nurbs_insert_knot(circle9(Vec2(1, 2), 3), 0.6, 2);
  for (double t : params(c, 101)) EXPECT_NEAR((eval(c, t) - Vec2(1, 2)).norm(), 3, 1e-12);
}

TEST(NurbsEdit, SplitHalvesReproduceTheCurve) {
  const Nurbs2 n = random_cubic(9, 11, true);
  for (double ts : {0.3, 3.0, 4.71, 7.999}) {
    Nurbs2 l, r;
    nurbs_split(n, ts, l, r);
    ASSERT_EQ(validate(l), "");
    ASSERT_EQ(validate(r), "");
    EXPECT_EQ(nurbs_t0(l), nurbs_t0(n));
    EXPECT_EQ(nurbs_t1(l), ts);
    EXPECT_EQ(nurbs_t0(r), ts);
    EXPECT_EQ(nurbs_t1(r), nurbs_t1(n));
    EXPECT_EQ(l.ctrl.back(), r.ctrl.front());
    for (double t : params(n, 400)) {
      const Nurbs2& part = t <= ts ? l : r;
      EXPECT_NEAR((eval(part, t) - eval(n, t)).norm(), 0, 1e-12) << ts << " " << t;
    }
  }
}

TEST(NurbsEdit, ReversalRunsBackwards) {
  const Nurbs2 n = random_cubic(13, 9, true);
  const Nurbs2 r = nurbs_reversed(n);
  ASSERT_EQ(validate(r), "");
  EXPECT_EQ(r.ctrl.front(), n.ctrl.back());
  EXPECT_EQ(r.ctrl.back(), n.ctrl.front());
  const double s = nurbs_t0(n) + nurbs_t1(n);
  for (double t : params(n, 333)) {
    EXPECT_NEAR((eval(r, s - t) - eval(n, t)).norm(), 0, 1e-12) << t;
    const double k = nurbs_curvature(n, t);
    EXPECT_NEAR(nurbs_curvature(r, s - t), -k, 1e-9 * (1 + std::abs(k)));
  }
  const Nurbs2 rr = nurbs_reversed(r);
  EXPECT_EQ(rr.ctrl, n.ctrl);
  expect_same_curve(n, rr);
}

TEST(NurbsEllipse, PointsSatisfyTheImplicitEquation) {
  const Vec2 c(-20, 35);
  const Vec2 major(8 * std::cos(0.6), 8 * std::sin(0.6));
  const double ratio = 0.35, a = 8, b = 8 * ratio;
  const Vec2 u = major / a, v(-u.y(), u.x());
  for (auto [s, e] : {std::pair{0.0, 2 * kPi}, {0.3, 1.2}, {-1.0, 3.5}, {2.0, 2.0 + 1.6}}) {
    const Nurbs2 n = nurbs_ellipse(c, major, ratio, s, e);
    ASSERT_EQ(validate(n), "");
    const int spans = static_cast<int>(std::ceil((e - s) / (kPi / 2) - 1e-12));
    EXPECT_EQ(static_cast<int>(n.ctrl.size()), 2 * spans + 1) << s << " " << e;
    for (double t : params(n, 499)) {
      const Vec2 q = eval(n, t) - c;
      const double x = q.dot(u) / a, y = q.dot(v) / b;
      EXPECT_NEAR(x * x + y * y, 1, 1e-12) << t;
    }
    // End points at the ellipse parameters start and end (counter-clockwise).
    const Vec2 ps = c + a * std::cos(s) * u + b * std::sin(s) * v;
    const Vec2 pe = c + a * std::cos(e) * u + b * std::sin(e) * v;
    EXPECT_NEAR((nurbs_point(n, nurbs_t0(n)) - ps).norm(), 0, 1e-12);
    EXPECT_NEAR((nurbs_point(n, nurbs_t1(n)) - pe).norm(), 0, 1e-12);
    // Counter-clockwise: the ellipse angle increases monotonically.
    double prev = std::atan2(0, 1), acc = 0;
    bool first = true;
    for (double t : params(n, 200)) {
      const Vec2 q = eval(n, t) - c;
      const double ang = std::atan2(q.dot(v) / b, q.dot(u) / a);
      if (!first) {
        double dlt = ang - prev;
        if (dlt < -kPi) dlt += 2 * kPi;
        EXPECT_GE(dlt, 0);
        acc += dlt;
      }
      first = false;
      prev = ang;
    }
    EXPECT_NEAR(acc, e - s, 1e-9);
  }
  const Nurbs2 full = nurbs_ellipse(c, major, ratio, 0, 2 * kPi);
  EXPECT_EQ(full.ctrl.front(), full.ctrl.back());
  EXPECT_NE(validate(nurbs_ellipse(c, major, ratio, 1, 1)), "");
}

TEST(NurbsPolyline, ChordsStayWithinTolerance) {
  for (double tol : {0.1, 0.01, 0.001}) {
    for (const Nurbs2& n : {random_cubic(21, 12, true), circle9(Vec2(5, 5), 20)}) {
      const std::vector<Vec2> pl = nurbs_polyline(n, tol);
      ASSERT_GE(pl.size(), 2u);
      EXPECT_EQ(pl.front(), n.ctrl.front());
      EXPECT_EQ(pl.back(), n.ctrl.back());
      // Every dense curve sample is within tol of the polyline.
      double worst = 0;
      for (double t : params(n, 20000))
        worst = std::max(worst, test::polyline_distance(pl, eval(n, t)));
      EXPECT_LE(worst, tol * (1 + 1e-9)) << tol;
      // ... and not absurdly finer than needed: a chord of the circle r = 20 deviating by tol
      // spans 2 acos(1 - tol / r), so 2 pi / that (plus knots) chords are enough; allow 4x.
      if (n.degree == 2) {
        const double need = 2 * kPi / (2 * std::acos(1 - tol / 20));
        EXPECT_LE(static_cast<double>(pl.size()), 4 * need + 8) << tol;
      }
    }
  }
}

}  // namespace
}  // namespace ncpath
