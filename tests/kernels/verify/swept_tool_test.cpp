// Swept tool against one triangle: analytic gaps and gouges per cutter, and, as an
// independent second method, the drop-cutter (kernels/cutters/drop_cutter.*): the gouge of a
// point move is how far the tip is below the drop height, and the gouge of a move is the
// largest such depth along it.
#include "kernels/verify/swept_tool.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>  // cross

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "kernels/cutters/drop_cutter.hpp"

namespace ncpath {
namespace {

constexpr double kGapTol = 1e-9;   // GJK distances are good to ~1e-11 mm
constexpr double kLiftTol = 4e-9;  // resolution (1e-9) + contact tolerance (1e-9) + rounding

struct Tri {
  Vec3 a, b, c;
};

// A large horizontal triangle at height z whose interior holds [-50, 50]^2.
Tri floor_at(double z) { return {{-200, -100, z}, {200, -100, z}, {0, 250, z}}; }

SweptTool tool_of(const Cutter& c, double shank = 50, double stock = 0) {
  SweptTool t;
  t.cutter = c;
  t.shank = shank;
  t.stock = stock;
  return t;
}

double gap(const SweptTool& t, const Vec3& p0, const Vec3& p1, const Tri& f) {
  return swept_gap(t, p0, p1, f.a, f.b, f.c);
}
double gouge(const SweptTool& t, const Vec3& p0, const Vec3& p1, const Tri& f) {
  return swept_gouge(t, p0, p1, f.a, f.b, f.c);
}

const Cutter kCutters[] = {ball_cutter(6), flat_cutter(6), bull_nose_cutter(8, 1)};

TEST(SweptTool, EveryCutterTouchesAFloorAtTipHeight) {
  for (const Cutter& c : kCutters) {
    const SweptTool t = tool_of(c);
    const Tri f = floor_at(0);
    for (const Vec3& p1 : {Vec3(1, 2, 0), Vec3(7, -3, 0)}) {
      EXPECT_NEAR(gap(t, {1, 2, 0}, p1, f), 0, kGapTol) << cutter_type_name(c.type);
      EXPECT_EQ(gouge(t, {1, 2, 0}, p1, f), 0) << cutter_type_name(c.type);
    }
    EXPECT_NEAR(gap(t, {1, 2, 0.2}, {5, 2, 0.2}, f), 0.2, kGapTol);
  }
}

TEST(SweptTool, BallBelowFloorGougesByTheDepth) {
  const SweptTool t = tool_of(ball_cutter(6));
  const Tri f = floor_at(0);
  EXPECT_NEAR(gap(t, {0, 0, -0.1}, {0, 0, -0.1}, f), -0.1, kGapTol);
  EXPECT_NEAR(gouge(t, {0, 0, -0.1}, {0, 0, -0.1}, f), 0.1, kLiftTol);
  // A sloped move is cut in by its lowest end.
  EXPECT_NEAR(gouge(t, {0, 0, 0.3}, {10, 0, -0.25}, f), 0.25, kLiftTol);
}

// Roof along y: ridge at x = 0, height H, flanks z = H - k|x|. A ball over the ridge touches
// the ridge line, so its drop height is H - R + sqrt(R^2 - x^2) for |x| <= R sin(theta)
// (tan theta = k), and on the flanks H - k|x| + R (sqrt(1 + k^2) - 1).
struct Roof {
  double H = 10, k = 0.5;
  Tri left{{0, -30, 10}, {0, 30, 10}, {-20, 0, 0}};
  Tri right{{0, -30, 10}, {0, 30, 10}, {20, 0, 0}};
};

TEST(SweptTool, BallOverRidgeClearAtTheEndsCutsInTheMiddle) {
  const Roof roof;
  const double R = 3, g = 0.3;
  const SweptTool t = tool_of(ball_cutter(2 * R));
  const Vec3 p0{-5, 0, roof.H - g}, p1{5, 0, roof.H - g};
  for (const Tri& f : {roof.left, roof.right}) {
    EXPECT_GT(gap(t, p0, p0, f), 1.0);  // drop height at |x| = 5 is H - 2.146
    EXPECT_GT(gap(t, p1, p1, f), 1.0);
    EXPECT_NEAR(gap(t, p0, p1, f), -g, kGapTol);  // over the ridge: R - g from the edge
    EXPECT_NEAR(gouge(t, p0, p1, f), g, kLiftTol);
  }
  // Sloped: z = zm + s x. The deepest point is in the ridge zone where
  // d/dx (sqrt(R^2 - x^2) - s x) = 0, x* = -s R / sqrt(1 + s^2): gouge H - R + R sqrt(1 + s^2) -
  // zm.
  const double s = 0.2, zm = roof.H - g;
  const double expected = roof.H - R + R * std::sqrt(1 + s * s) - zm;
  const Vec3 q0{-5, 0, zm - 5 * s}, q1{5, 0, zm + 5 * s};
  const double worst = std::max(gouge(t, q0, q1, roof.left), gouge(t, q0, q1, roof.right));
  EXPECT_NEAR(worst, expected, kLiftTol);
  EXPECT_EQ(gouge(t, q0, q0, roof.left), 0);
  EXPECT_EQ(gouge(t, q1, q1, roof.right), 0);
}

TEST(SweptTool, FlatBelowFloorGougesByTheDepth) {
  const SweptTool t = tool_of(flat_cutter(6));
  const Tri f{{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}};  // smaller than the cutter
  EXPECT_NEAR(gouge(t, {0, 0, -0.05}, {0, 0, -0.05}, f), 0.05, kLiftTol);
  EXPECT_NEAR(gouge(t, {-4, 0, -0.05}, {4, 0, -0.05}, f), 0.05, kLiftTol);
  EXPECT_EQ(gouge(t, {0, 0, 0}, {0, 0, 0}, f), 0);
}

// Vertical wall triangle in the plane x = w, apex (top) at z = 5 on y = 0.
Tri wall_at(double w) { return {{w, -20, -5}, {w, 20, -5}, {w, 0, 5}}; }

TEST(SweptTool, FlatBesideWall) {
  const double R = 3;
  const SweptTool t = tool_of(flat_cutter(2 * R));
  const Vec3 p{0, 0, 0};
  // 0.02 inside the wall: cleared only when the flat bottom rises above the apex.
  EXPECT_LT(gap(t, p, p, wall_at(R - 0.02)), -1e-9);
  EXPECT_NEAR(gouge(t, p, p, wall_at(R - 0.02)), 5, kLiftTol);
  EXPECT_NEAR(gap(t, p, p, wall_at(R + 0.02)), 0.02, kGapTol);
  EXPECT_EQ(gouge(t, p, p, wall_at(R + 0.02)), 0);
  // Sliding along the wall at exactly R is a touch, not a cut.
  EXPECT_EQ(gouge(t, {0, -10, 0}, {0, 10, 0}, wall_at(R)), 0);
  EXPECT_EQ(gouge(t, {0, -10, 0}, {0, 10, 0}, wall_at(-R)), 0);
}

// Plane z = -k x. The bull-nose touches it with the torus on the uphill side (x - a):
//   tip = -k (x - a) + r (sqrt(1 + k^2) - 1).
TEST(SweptTool, BullOnSlopedPlaneMatchesContactHeight) {
  const double R = 4, r = 1, a = R - r;
  const SweptTool t = tool_of(bull_nose_cutter(2 * R, r));
  for (double k : {0.2, 0.8, 2.0}) {
    const Tri f{{-60, -60, 60 * k}, {60, -60, -60 * k}, {0, 80, 0}};
    auto tip = [&](double x) { return -k * (x - a) + r * (std::sqrt(1 + k * k) - 1); };
    const Vec3 p0{-2, 1, tip(-2)}, p1{2, 3, tip(2)};
    EXPECT_NEAR(gap(t, p0, p0, f), 0, kGapTol) << k;
    EXPECT_NEAR(gap(t, p0, p1, f), 0, kGapTol) << k;
    EXPECT_EQ(gouge(t, p0, p1, f), 0) << k;
    const Vec3 down{0, 0, 0.07};
    EXPECT_NEAR(gouge(t, p0 - down, p1 - down, f), 0.07, kLiftTol) << k;
  }
}

// Ball R = 3; the wall x = 2.9 spans z in [10, 20], far above the ball part (top at z = 6).
TEST(SweptTool, ShankHitsAWallTheBottomClears) {
  const double R = 3, w = 2.9;
  const Tri f{{w, -5, 10}, {w, 5, 10}, {w, 0, 20}};
  const Vec3 p{0, 0, 0};
  const SweptTool long_shank = tool_of(ball_cutter(2 * R), 50);
  EXPECT_NEAR(gap(long_shank, p, p, f), w - R, kGapTol);
  // Cleared when the bottom at distance w (R - sqrt(R^2 - w^2) above the tip) passes z = 20.
  EXPECT_NEAR(gouge(long_shank, p, p, f), 20 - (R - std::sqrt(R * R - w * w)), kLiftTol);
  // A 4 mm shank ends at z = 7 (capsule to 10): nearest wall point (w, 0, 10).
  const SweptTool short_shank = tool_of(ball_cutter(2 * R), 4);
  EXPECT_NEAR(gap(short_shank, p, p, f), std::hypot(w, 3.0) - R, kGapTol);
  EXPECT_EQ(gouge(short_shank, p, p, f), 0);
}

TEST(SweptTool, StockGrowsTheTool) {
  const Tri f = floor_at(0);
  const SweptTool ball = tool_of(ball_cutter(6), 50, 0.3);
  EXPECT_NEAR(gouge(ball, {0, 0, 0}, {4, 0, 0}, f), 0.3, kLiftTol);
  EXPECT_NEAR(gap(ball, {0, 0, 0.5}, {4, 0, 0.5}, f), 0.2, kGapTol);
  EXPECT_EQ(gouge(ball, {0, 0, 0.3}, {4, 0, 0.3}, f), 0);
  const SweptTool flat = tool_of(flat_cutter(6), 50, 0.1);
  EXPECT_NEAR(gouge(flat, {0, 0, 0}, {0, 0, 0}, f), 0.1, kLiftTol);
  EXPECT_NEAR(gap(flat, {0, 0, 0}, {0, 0, 0}, wall_at(3.15)), 0.05, kGapTol);
}

TEST(SweptTool, InvariantUnderReversalPermutationAndTranslation) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> U(-4, 4);
  for (const Cutter& c : kCutters) {
    const SweptTool t = tool_of(c, 20, 0.05);
    for (int i = 0; i < 200; ++i) {
      const Vec3 a{U(rng), U(rng), U(rng)}, b{U(rng), U(rng), U(rng)}, d{U(rng), U(rng), U(rng)};
      const Vec3 p0{U(rng), U(rng), U(rng)}, p1{U(rng), U(rng), U(rng)};
      const Vec3 shift{123.25, -77.5, 9.75};
      const double g = swept_gap(t, p0, p1, a, b, d);
      EXPECT_NEAR(swept_gap(t, p1, p0, d, a, b), g, kGapTol);
      EXPECT_NEAR(swept_gap(t, p0 + shift, p1 + shift, a + shift, b + shift, d + shift), g, 1e-8);
      const double h = swept_gouge(t, p0, p1, a, b, d);
      EXPECT_NEAR(swept_gouge(t, p1, p0, b, d, a), h, kLiftTol);
      EXPECT_EQ(h > 0, g < -tol::kVerifyContact);
      if (h > 0) {  // the reported lift clears, a little less does not
        const Vec3 up{0, 0, h}, less{0, 0, h - 1e-7};
        EXPECT_GE(swept_gap(t, p0 + up, p1 + up, a, b, d),
                  -tol::kVerifyContact - 2 * tol::kGjkDistance);
        EXPECT_LT(swept_gap(t, p0 + less, p1 + less, a, b, d), -tol::kVerifyContact);
      }
    }
  }
}

// The cheap bounds callers cull with never exceed what they bound.
TEST(SweptTool, PlaneAndProfileBoundsAreLowerBounds) {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> U(-4, 4);
  for (const Cutter& c : kCutters) {
    for (double stock : {0.0, 0.2}) {
      const SweptTool t = tool_of(c, 10, stock);
      const Cutter profile = swept_profile(t);
      EXPECT_DOUBLE_EQ(profile.radius, c.radius + stock);
      for (int i = 0; i < 300; ++i) {
        const Vec3 a{U(rng), U(rng), U(rng)}, b{U(rng), U(rng), U(rng)}, d{U(rng), U(rng), U(rng)};
        const Vec3 p0{U(rng), U(rng), U(rng)}, p1{U(rng), U(rng), U(rng)};
        const Vec3 n = (b - a).cross(d - a).normalized();
        const double lo = std::min({n.dot(a), n.dot(b), n.dot(d)});
        const double hi = std::max({n.dot(a), n.dot(b), n.dot(d)});
        const double g = swept_gap(t, p0, p1, a, b, d);
        EXPECT_LE(swept_plane_gap(t, p0, p1, n, lo, hi), std::max(g, 0.0) + 1e-12);
        // Over a point at horizontal distance rho from the tip, the body is no lower than the
        // profile: a tiny triangle around such a point just below it is not cut into.
        const double rho = std::abs(U(rng)) * 0.2 * (c.radius + stock);
        const Vec3 q = p0 + Vec3(rho, 0, profile_height(profile, rho) - stock - 1e-6);
        const Vec3 e1{1e-4, 0, 0}, e2{0, 1e-4, 0};
        EXPECT_EQ(swept_gouge(t, p0, p0, q, q + e1, q + e2), 0) << cutter_type_name(c.type);
      }
    }
  }
}

// ---- Against the drop-cutter ----

// Drop height of the cutter onto one triangle at (x, y), or -inf; the contact point in cc.
double drop_z(const Cutter& c, const PreparedFacet& f, double x, double y, Vec3* cc = nullptr) {
  CutterContact best;
  drop_facet(c, f, x, y, 0, best);
  if (cc) *cc = best.cc;
  return best.tip_z;
}

struct RandomTriangle {
  Vec3 v[3];
  PreparedFacet f;
};

RandomTriangle random_triangle(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> U(-5, 5);
  RandomTriangle t;
  do {
    for (Vec3& p : t.v) p = Vec3(U(rng), U(rng), 0.6 * U(rng));
  } while (!prepare_facet(t.v[0], t.v[1], t.v[2], t.f));
  return t;
}

// Point moves: gouge(tip at z) == max(0, drop_z - z). Contacts on the corner within 1e-4 r of
// its vertical tangent are skipped: there the vertical lift is ill-conditioned (the contact
// tolerance of 1e-9 mm along the surface normal is up to ~1e-6 mm vertically). The flat
// cutter (sharp, closed form) is checked everywhere.
TEST(SweptTool, PointMoveGougeEqualsDropCutterDepth) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> X(-7, 7), depth(0.001, 2.0);
  for (const Cutter& c : kCutters) {
    const SweptTool t = tool_of(c);
    int checked = 0;
    for (int i = 0; i < 3000; ++i) {
      const RandomTriangle tri = random_triangle(rng);
      const double x = X(rng), y = X(rng);
      Vec3 cc;
      const double dz = drop_z(c, tri.f, x, y, &cc);
      if (!std::isfinite(dz)) continue;
      const double a = c.flat_radius(), r = c.corner_radius;
      if (r > 0 && std::hypot(cc.x() - x, cc.y() - y) - a > r * (1 - 1e-4)) continue;
      const double d = depth(rng);
      const Vec3 below{x, y, dz - d}, above{x, y, dz + d};
      EXPECT_NEAR(swept_gouge(t, below, below, tri.v[0], tri.v[1], tri.v[2]), d, 1e-7)
          << cutter_type_name(c.type) << " sample " << i;
      EXPECT_EQ(swept_gouge(t, above, above, tri.v[0], tri.v[1], tri.v[2]), 0);
      EXPECT_GT(swept_gap(t, above, above, tri.v[0], tri.v[1], tri.v[2]), 0);
      const Vec3 at{x, y, dz};
      EXPECT_LT(swept_gouge(t, at, at, tri.v[0], tri.v[1], tri.v[2]), 1e-7);
      ++checked;
    }
    EXPECT_GT(checked, 1000) << cutter_type_name(c.type);
  }
}

// Largest depth of the tip below the drop height along the move: dense samples, then a
// golden-section refinement around the best one (the depth is piecewise smooth), and the
// depth where the triangle enters or leaves the cutter's reach (found by bisection): there
// the flat cutter's depth jumps from nothing to a side contact, often its largest value.
double deepest_along(const Cutter& c, const PreparedFacet& f, const Vec3& p0, const Vec3& p1) {
  constexpr double kNone = -1e9;
  auto depth = [&](double s) {
    const Vec3 p = p0 + s * (p1 - p0);
    const double dz = drop_z(c, f, p.x(), p.y());
    return std::isfinite(dz) ? dz - p.z() : kNone;
  };
  constexpr int kSamples = 400;
  std::vector<double> v(kSamples + 1);
  for (int i = 0; i <= kSamples; ++i) v[i] = depth(double(i) / kSamples);
  const int best = int(std::max_element(v.begin(), v.end()) - v.begin());
  double result = std::max(v[best], 0.0);
  for (int i = 0; i < kSamples; ++i) {
    if ((v[i] == kNone) == (v[i + 1] == kNone)) continue;
    double in = double(v[i] == kNone ? i + 1 : i) / kSamples;  // in reach
    double out = double(v[i] == kNone ? i : i + 1) / kSamples;
    for (int it = 0; it < 80; ++it) {
      const double mid = 0.5 * (in + out);
      (depth(mid) == kNone ? out : in) = mid;
    }
    result = std::max(result, depth(in));
  }
  double lo = std::max(0, best - 1) / double(kSamples);
  double hi = std::min(kSamples, best + 1) / double(kSamples);
  const double g = (std::sqrt(5.0) - 1) / 2;
  for (int it = 0; it < 80; ++it) {
    const double m1 = hi - g * (hi - lo), m2 = lo + g * (hi - lo);
    const bool rising = depth(m1) < depth(m2);
    (rising ? lo : hi) = rising ? m1 : m2;
  }
  return std::max(result, depth(0.5 * (lo + hi)));
}

// Moves: the swept gouge is the deepest point gouge along the move (raising the swept tool
// by h clears it iff every position along the move is cleared).
TEST(SweptTool, MoveGougeEqualsDeepestDropCutterDepthAlongIt) {
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> X(-6, 6), Z(-1.5, 0.5), D(-4, 4);
  for (const Cutter& c : kCutters) {
    const SweptTool t = tool_of(c);
    int gouging = 0;
    for (int i = 0; i < 400; ++i) {
      const RandomTriangle tri = random_triangle(rng);
      const Vec3 m{X(rng), X(rng), 0};
      const Vec3 half{D(rng), D(rng), 0};
      Vec3 p0 = m - half, p1 = m + half;
      // Heights around the triangle's drop at the ends so that many moves cut in.
      const double top = std::max({tri.v[0].z(), tri.v[1].z(), tri.v[2].z()});
      p0.z() = top + Z(rng) - 1;
      p1.z() = top + Z(rng) - 1;
      const double expected = deepest_along(c, tri.f, p0, p1);
      const double got = swept_gouge(t, p0, p1, tri.v[0], tri.v[1], tri.v[2]);
      // The oracle's golden section may stop short of a kink's peak by ~1e-9.
      EXPECT_NEAR(got, expected, 1e-6) << cutter_type_name(c.type) << " move " << i;
      gouging += expected > 0;
    }
    EXPECT_GT(gouging, 100) << cutter_type_name(c.type);
  }
}

}  // namespace
}  // namespace ncpath
