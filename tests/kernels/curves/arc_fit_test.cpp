// kernels/curves/arc_fit: exact circles and helices (one arc, right centre and radius), corners
// kept, and a random wiggly path checked both ways (input points and chords to the moves,
// move samples to the input polyline) with the move geometry worked out here, independently
// of kernels/curves/segment.
#include "kernels/curves/arc_fit.hpp"

#include <gtest/gtest.h>

#include "tests/support/oracle.hpp"

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

namespace ncpath {
namespace {

constexpr double kPi = std::numbers::pi;

// One move with its start made explicit.
struct Move3 {
  SegKind kind;
  Vec3 a, b;
  Vec2 c;
};

Vec3 pt(const std::vector<double>& xyz, std::size_t i) {
  return Vec3(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
}

std::vector<Move3> chain(const std::vector<double>& xyz, const std::vector<FitMove>& mv) {
  std::vector<Move3> out;
  Vec3 a = pt(xyz, 0);
  for (const FitMove& m : mv) {
    out.push_back({m.kind, a, m.end, m.centre});
    a = m.end;
  }
  return out;
}

// Signed sweep of an arc move, from its kind: (0, 2 pi] ccw, [-2 pi, 0) cw.
double sweep_of(const Move3& m) {
  const double a0 = std::atan2(m.a.y() - m.c.y(), m.a.x() - m.c.x());
  const double a1 = std::atan2(m.b.y() - m.c.y(), m.b.x() - m.c.x());
  double d = a1 - a0;
  if (m.kind == SegKind::kArcCcw) {
    while (d <= 0) d += 2 * kPi;
    while (d > 2 * kPi) d -= 2 * kPi;
  } else {
    while (d >= 0) d -= 2 * kPi;
    while (d < -2 * kPi) d += 2 * kPi;
  }
  return d;
}

// Point at u in [0, 1] of a move (helix: z linear in angle).
Vec3 eval(const Move3& m, double u) {
  if (m.kind == SegKind::kLine) return m.a + u * (m.b - m.a);
  const double r = (m.a.head<2>() - m.c).norm();
  const double a0 = std::atan2(m.a.y() - m.c.y(), m.a.x() - m.c.x());
  const double ang = a0 + u * sweep_of(m);
  return Vec3(m.c.x() + r * std::cos(ang), m.c.y() + r * std::sin(ang),
              m.a.z() + u * (m.b.z() - m.a.z()));
}

double seg_dist(const Vec3& a, const Vec3& b, const Vec3& p) {
  return ncpath::test::point_segment_distance(a, b, p);
}

// Upper bound of the distance from p to a move (exact for lines; for arcs the point of the
// helix at p's own angle, or an end point).
double move_dist(const Move3& m, const Vec3& p) {
  if (m.kind == SegKind::kLine) return seg_dist(m.a, m.b, p);
  double best = std::fmin((p - m.a).norm(), (p - m.b).norm());
  const double sw = sweep_of(m);
  const double r = (m.a.head<2>() - m.c).norm();
  const double a0 = std::atan2(m.a.y() - m.c.y(), m.a.x() - m.c.x());
  double d = std::atan2(p.y() - m.c.y(), p.x() - m.c.x()) - a0;  // offset in the arc's sense
  if (sw > 0) {
    while (d < 0) d += 2 * kPi;
  } else {
    while (d > 0) d -= 2 * kPi;
  }
  if (std::abs(d) <= std::abs(sw)) {
    const double u = d / sw;
    const double zr = m.a.z() + u * (m.b.z() - m.a.z());
    best = std::fmin(best, std::hypot((p.head<2>() - m.c).norm() - r, p.z() - zr));
  }
  return best;
}

// Checks the fitted path against its input, both ways, and the chaining contract.
void expect_same_path(const std::vector<double>& xyz, const std::vector<FitMove>& mv, double tol) {
  const std::size_t n = xyz.size() / 3;
  ASSERT_FALSE(mv.empty());
  EXPECT_EQ(mv.back().end, pt(xyz, n - 1));
  EXPECT_EQ(mv.back().end_index, n - 1);
  std::uint32_t prev = 0;
  for (const FitMove& m : mv) {
    EXPECT_GT(m.end_index, prev);
    EXPECT_EQ(m.end, pt(xyz, m.end_index));
    prev = m.end_index;
  }
  // Move j covers the input points first[j] .. last[j]: each point and chord is compared with
  // the moves covering it, each move with the input chords it covers (a local, stricter check).
  const std::vector<Move3> ms = chain(xyz, mv);
  std::vector<std::size_t> first(mv.size()), last(mv.size());
  for (std::size_t j = 0; j < mv.size(); ++j) {
    first[j] = j == 0 ? 0 : mv[j - 1].end_index;
    last[j] = mv[j].end_index;
  }
  const double slack = 1e-9;
  std::size_t j = 0;
  for (std::size_t i = 0; i + 1 < n; ++i) {
    while (last[j] < i + 1) ++j;  // move j covers the chord i -> i + 1
    ASSERT_LE(move_dist(ms[j], pt(xyz, i)), tol + slack) << "point " << i;
    ASSERT_LE(move_dist(ms[j], pt(xyz, i + 1)), tol + slack) << "point " << i + 1;
    for (int k = 1; k < 8; ++k) {
      const Vec3 q = pt(xyz, i) + (k / 8.0) * (pt(xyz, i + 1) - pt(xyz, i));
      ASSERT_LE(move_dist(ms[j], q), tol + slack) << "chord " << i;
    }
  }
  for (std::size_t m = 0; m < ms.size(); ++m) {
    for (int k = 0; k <= 50; ++k) {
      const Vec3 q = eval(ms[m], k / 50.0);
      double best = INFINITY;
      for (std::size_t i = first[m]; i < last[m]; ++i) {
        best = std::fmin(best, seg_dist(pt(xyz, i), pt(xyz, i + 1), q));
      }
      ASSERT_LE(best, tol + slack) << "move " << m << " sample " << k;
    }
  }
}

std::vector<double> circle_points(const Vec2& c, double r, double a0, double a1, double z0,
                                  double z1, int n) {
  std::vector<double> xyz;
  for (int i = 0; i < n; ++i) {
    const double u = static_cast<double>(i) / (n - 1);
    const double a = a0 + u * (a1 - a0);
    xyz.insert(xyz.end(), {c.x() + r * std::cos(a), c.y() + r * std::sin(a), z0 + u * (z1 - z0)});
  }
  return xyz;
}

TEST(ArcFit, CcwCircleIsOneArc) {
  const Vec2 c(3, -2);
  const std::vector<double> xyz = circle_points(c, 10, 0.3, 0.3 + 4.0, 1.5, 1.5, 100);
  std::vector<FitMove> mv;
  fit_arcs(xyz, {}, mv);
  ASSERT_EQ(mv.size(), 1u);
  EXPECT_EQ(mv[0].kind, SegKind::kArcCcw);
  EXPECT_NEAR((mv[0].centre - c).norm(), 0, 1e-9);
  EXPECT_NEAR((pt(xyz, 0).head<2>() - mv[0].centre).norm(), 10, 1e-9);
  expect_same_path(xyz, mv, 0.005);
}

TEST(ArcFit, CwHelixIsOneArc) {
  const Vec2 c(-7, 4);
  const std::vector<double> xyz = circle_points(c, 5, 2.0, 2.0 - 4.5, 0, -3, 150);
  std::vector<FitMove> mv;
  fit_arcs(xyz, {}, mv);
  ASSERT_EQ(mv.size(), 1u);
  EXPECT_EQ(mv[0].kind, SegKind::kArcCw);
  EXPECT_NEAR((mv[0].centre - c).norm(), 0, 1e-9);
  EXPECT_NEAR(mv[0].end.z(), -3, 1e-12);
  expect_same_path(xyz, mv, 0.005);
}

TEST(ArcFit, NoisyCircleKeepsCentreWithinTol) {
  const double tol = 0.005;
  const Vec2 c(50, 50);
  std::vector<double> xyz = circle_points(c, 20, 0, 3.5, -2, -2, 300);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> noise(-0.2 * tol, 0.2 * tol);
  for (std::size_t i = 1; i + 1 < xyz.size() / 3; ++i) {
    const Vec2 d = (pt(xyz, i).head<2>() - c).normalized() * noise(rng);
    xyz[3 * i] += d.x();
    xyz[3 * i + 1] += d.y();
  }
  std::vector<FitMove> mv;
  fit_arcs(xyz, {.tol = tol}, mv);
  EXPECT_LE(mv.size(), 3u);
  for (const FitMove& m : mv) {
    ASSERT_EQ(m.kind, SegKind::kArcCcw);
    EXPECT_LE((m.centre - c).norm(), tol);
  }
  expect_same_path(xyz, mv, tol);
}

TEST(ArcFit, ClosedCircleRespectsMaxSweep) {
  const Vec2 c(0, 0);
  const std::vector<double> xyz = circle_points(c, 15, 0, -2 * kPi, -1, -1, 200);
  std::vector<FitMove> mv;
  fit_arcs(xyz, {}, mv);
  ASSERT_EQ(mv.size(), 2u);
  const std::vector<Move3> ms = chain(xyz, mv);
  for (const Move3& m : ms) {
    EXPECT_EQ(m.kind, SegKind::kArcCw);
    EXPECT_LE(std::abs(sweep_of(m)), 1.5 * kPi + 1e-12);
    EXPECT_NEAR(m.c.norm(), 0, 1e-9);
  }
  expect_same_path(xyz, mv, 0.005);
}

TEST(ArcFit, SharpCornerIsKept) {
  std::vector<double> xyz;
  for (int i = 0; i <= 10; ++i) xyz.insert(xyz.end(), {double(i), 0.0, 0.0});
  for (int i = 1; i <= 10; ++i) xyz.insert(xyz.end(), {10.0, double(i), 0.0});
  std::vector<FitMove> mv;
  fit_arcs(xyz, {}, mv);
  ASSERT_EQ(mv.size(), 2u);
  EXPECT_EQ(mv[0].kind, SegKind::kLine);
  EXPECT_EQ(mv[0].end, Vec3(10, 0, 0));
  EXPECT_EQ(mv[1].kind, SegKind::kLine);
  expect_same_path(xyz, mv, 0.005);
}

TEST(ArcFit, CornerBetweenArcAndLineIsKept) {
  // A quarter circle, then a line leaving its end at 30 degrees to the tangent.
  std::vector<double> xyz = circle_points(Vec2(0, 0), 10, 0, kPi / 2, 0, 0, 40);
  const Vec2 dir(-std::cos(kPi / 6), -std::sin(kPi / 6));  // tangent is (-1, 0)
  for (int i = 1; i <= 20; ++i) {
    const Vec2 p = Vec2(0, 10) + 0.5 * i * dir;
    xyz.insert(xyz.end(), {p.x(), p.y(), 0.0});
  }
  std::vector<FitMove> mv;
  fit_arcs(xyz, {}, mv);
  bool corner = false;
  for (const FitMove& m : mv) corner = corner || m.end_index == 39;
  EXPECT_TRUE(corner);
  expect_same_path(xyz, mv, 0.005);
}

TEST(ArcFit, RandomWigglyPathStaysWithinTol) {
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> turn(-0.25, 0.25);
  std::uniform_real_distribution<double> step(0.05, 0.6);
  std::uniform_real_distribution<double> dz(-0.02, 0.02);
  std::uniform_real_distribution<double> coin(0, 1);
  std::vector<double> xyz = {0, 0, 0};
  double heading = 0;
  double curvature = 0;
  Vec3 p(0, 0, 0);
  for (int i = 0; i < 3000; ++i) {
    // Runs of constant curvature (arcs), straight runs, occasional corners.
    if (coin(rng) < 0.05) curvature = coin(rng) < 0.3 ? 0 : turn(rng);
    heading += curvature;
    if (coin(rng) < 0.01) heading += 2 * turn(rng) * 4;
    const double s = step(rng);
    p += Vec3(s * std::cos(heading), s * std::sin(heading), coin(rng) < 0.1 ? dz(rng) : 0);
    xyz.insert(xyz.end(), {p.x(), p.y(), p.z()});
  }
  for (const double tol : {0.005, 0.05}) {
    std::vector<FitMove> mv;
    fit_arcs(xyz, {.tol = tol}, mv);
    EXPECT_LT(mv.size(), 3000u);
    int arcs = 0;
    for (const FitMove& m : mv) arcs += m.kind != SegKind::kLine;
    EXPECT_GT(arcs, 0);
    expect_same_path(xyz, mv, tol);
  }
}

TEST(ArcFit, HugeRadiusBecomesLines) {
  // Radius 1e5 mm over 60 mm: sagitta 4.5e-3 mm per 60 mm, more than tol 1e-3 over the whole.
  const double r = 1e5;
  const std::vector<double> xyz =
      circle_points(Vec2(0, -r), r, kPi / 2 + 3e-4, kPi / 2 - 3e-4, 0, 0, 200);
  std::vector<FitMove> mv;
  fit_arcs(xyz, {.tol = 1e-3}, mv);
  EXPECT_GT(mv.size(), 1u);
  for (const FitMove& m : mv) EXPECT_EQ(m.kind, SegKind::kLine);
  expect_same_path(xyz, mv, 1e-3);
}

TEST(ArcFit, NonLinearZIsNotOneHelix) {
  std::vector<double> xyz = circle_points(Vec2(0, 0), 10, 0, 3, 0, 0, 100);
  for (std::size_t i = 0; i < 100; ++i) xyz[3 * i + 2] = std::sin(3.0 * i / 99.0 * kPi);
  std::vector<FitMove> mv;
  fit_arcs(xyz, {}, mv);
  EXPECT_GT(mv.size(), 1u);
  expect_same_path(xyz, mv, 0.005);
}

TEST(ArcFit, BackTrackingIsNotOneLine) {
  const std::vector<double> xyz = {0, 0, 0, 5, 0, 0, 2, 0, 0, 10, 0, 0};
  std::vector<FitMove> mv;
  fit_arcs(xyz, {}, mv);
  EXPECT_EQ(mv.size(), 3u);
  expect_same_path(xyz, mv, 0.005);
}

TEST(ArcFit, ShortInputs) {
  std::vector<FitMove> mv;
  fit_arcs(std::vector<double>{}, {}, mv);
  fit_arcs(std::vector<double>{1, 2, 3}, {}, mv);
  EXPECT_TRUE(mv.empty());
  const std::vector<double> two = {1, 2, 3, 1, 2, 3};  // duplicate point: one null line
  fit_arcs(two, {}, mv);
  ASSERT_EQ(mv.size(), 1u);
  EXPECT_EQ(mv[0].kind, SegKind::kLine);
}

TEST(ArcFit, LinesOnlyWhenArcsDisabled) {
  const std::vector<double> xyz = circle_points(Vec2(1, 1), 10, 0, 3, 0, 0, 100);
  std::vector<FitMove> mv;
  fit_arcs(xyz, {.allow_arcs = false}, mv);
  for (const FitMove& m : mv) EXPECT_EQ(m.kind, SegKind::kLine);
  expect_same_path(xyz, mv, 0.005);
}

}  // namespace
}  // namespace ncpath
