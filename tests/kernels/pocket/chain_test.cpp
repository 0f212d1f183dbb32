#include "kernels/pocket/chain.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "kernels/curves/nurbs.hpp"
#include "kernels/curves/segment.hpp"

namespace ncpath {
namespace {

// A soup under construction: every curve gets its own named source.
struct Soup {
  std::vector<ProfileCurve> curves;
  std::vector<Nurbs2> nurbs;
  std::vector<SourceEntity> sources;

  std::uint32_t src(const std::string& handle, const std::string& type) {
    sources.push_back({handle, type});
    return static_cast<std::uint32_t>(sources.size() - 1);
  }
  void line(const std::string& h, Vec2 a, Vec2 b) {
    curves.push_back({make_line(a, b, src(h, "LINE")), -1});
  }
  void rect(const std::string& h, double x0, double y0, double x1, double y1) {
    line(h + "a", {x0, y0}, {x1, y0});
    line(h + "b", {x1, y0}, {x1, y1});
    line(h + "c", {x1, y1}, {x0, y1});
    line(h + "d", {x0, y1}, {x0, y0});
  }
  void circle(const std::string& h, Vec2 c, double r) {
    const std::uint32_t s = src(h, "CIRCLE");
    curves.push_back({make_arc(c + Vec2(r, 0), c - Vec2(r, 0), c, true, s), -1});
    curves.push_back({make_arc(c - Vec2(r, 0), c + Vec2(r, 0), c, true, s), -1});
  }
  ChainResult chain(double tol = tol::kProfileJoin) const {
    return chain_and_nest(curves, nurbs, sources, tol);
  }
};

// Twice the signed area of a profile, computed independently by sampling (chords).
double area2(const Profile& p) {
  double a = 0;
  for (const ProfileCurve& c : p.curves) {
    std::vector<Vec2> pts;
    for (int k = 0; k <= 256; ++k) {
      const double t = k / 256.0;
      pts.push_back(c.nurbs >= 0
                        ? nurbs_point(p.nurbs[c.nurbs],
                                      nurbs_t0(p.nurbs[c.nurbs]) + t * (nurbs_t1(p.nurbs[c.nurbs]) -
                                                                        nurbs_t0(p.nurbs[c.nurbs])))
                        : point_at(c.seg, t));
    }
    for (int k = 0; k < 256; ++k) a += pts[k].x() * pts[k + 1].y() - pts[k].y() * pts[k + 1].x();
  }
  return a;
}

// Consecutive curves share bitwise equal points, and the last ends at the first's start.
void expect_chained(const Profile& p) {
  ASSERT_FALSE(p.curves.empty());
  for (std::size_t i = 0; i < p.curves.size(); ++i) {
    const ProfileCurve& c = p.curves[i];
    const ProfileCurve& d = p.curves[(i + 1) % p.curves.size()];
    EXPECT_EQ(c.seg.b, d.seg.a) << "curve " << i;
    if (c.nurbs >= 0) {
      EXPECT_EQ(p.nurbs[c.nurbs].ctrl.front(), c.seg.a);
      EXPECT_EQ(p.nurbs[c.nurbs].ctrl.back(), c.seg.b);
    }
  }
}

TEST(ChainAndNest, ScrambledSquareBecomesOneClockwiseLoop) {
  Soup s;
  s.line("1", {0, 0}, {100, 0});
  s.line("2", {0, 100}, {100, 100});  // reversed relative to a loop
  s.line("3", {100, 100}, {100, 0});
  s.line("4", {0, 0}, {0, 100});
  const ChainResult r = s.chain();
  ASSERT_EQ(r.error, "");
  ASSERT_EQ(r.regions.size(), 1u);
  const Profile& b = r.regions[0].boundary;
  EXPECT_EQ(b.curves.size(), 4u);
  expect_chained(b);
  EXPECT_NEAR(area2(b), -2 * 100 * 100, 1e-9);  // clockwise
  EXPECT_EQ(r.largest_gap_closed, 0);
  EXPECT_TRUE(r.regions[0].islands.empty());
}

TEST(ChainAndNest, NestedIslandAndPocketInIslandHole) {
  Soup s;
  s.rect("outer", 0, 0, 100, 100);   // depth 0: pocket
  s.rect("island", 20, 20, 80, 80);  // depth 1: island
  s.circle("hole", {50, 50}, 25);    // depth 2: a pocket inside the island
  s.rect("inner", 45, 45, 55, 55);   // depth 3: its island
  s.circle("side", {10, 10}, 5);     // depth 1: second island of the outer pocket
  const ChainResult r = s.chain();
  ASSERT_EQ(r.error, "");
  ASSERT_EQ(r.regions.size(), 2u);
  const Region& outer = r.regions[0];
  const Region& inner = r.regions[1];
  EXPECT_NEAR(area2(outer.boundary), -2 * 100 * 100, 1e-9);
  ASSERT_EQ(outer.islands.size(), 2u);
  for (const Profile& i : outer.islands) EXPECT_GT(area2(i), 0);
  EXPECT_LT(area2(inner.boundary), 0);
  EXPECT_NEAR(area2(inner.boundary), -2 * std::numbers::pi * 25 * 25,
              2 * std::numbers::pi * 25 * 25 * 1e-4);
  ASSERT_EQ(inner.islands.size(), 1u);
  EXPECT_NEAR(area2(inner.islands[0]), 2 * 10 * 10, 1e-9);
  for (const Region& g : r.regions) {
    expect_chained(g.boundary);
    for (const Profile& i : g.islands) expect_chained(i);
  }
}

// Random order and directions give the same loops (as sets of |area|) and orientations.
TEST(ChainAndNest, RandomOrderAndDirectionsInvariant) {
  Soup base;
  base.rect("o", 0, 0, 200, 120);
  base.circle("c1", {40, 40}, 15);
  base.rect("r1", 100, 20, 180, 100);
  base.circle("c2", {140, 60}, 20);
  const ChainResult ref = base.chain();
  ASSERT_EQ(ref.error, "");
  std::mt19937 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    Soup s = base;
    std::shuffle(s.curves.begin(), s.curves.end(), rng);
    for (ProfileCurve& c : s.curves)
      if (rng() % 2) c.seg = reversed(c.seg);
    const ChainResult r = s.chain();
    ASSERT_EQ(r.error, "");
    ASSERT_EQ(r.regions.size(), ref.regions.size());
    std::vector<double> a_ref, a;
    for (const Region& g : ref.regions) a_ref.push_back(area2(g.boundary));
    for (const Region& g : r.regions) a.push_back(area2(g.boundary));
    std::sort(a_ref.begin(), a_ref.end());
    std::sort(a.begin(), a.end());
    for (std::size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(a[i], a_ref[i], 1e-6);
    for (const Region& g : r.regions) {
      EXPECT_LT(area2(g.boundary), 0);
      expect_chained(g.boundary);
      for (const Profile& i : g.islands) EXPECT_GT(area2(i), 0);
    }
  }
}

TEST(ChainAndNest, NurbsCurveIsReversedWhenNeeded) {
  Soup s;
  // Upper arch from (10,0) over to (0,0) as a rational quadratic, closed by a line below.
  Nurbs2 n;
  n.degree = 2;
  n.ctrl = {{10, 0}, {5, 10}, {0, 0}};
  n.weights = {1, 0.7, 1};
  n.knots = {0, 0, 0, 1, 1, 1};
  s.nurbs.push_back(n);
  ProfileCurve pc;
  pc.seg = make_line({10, 0}, {0, 0}, s.src("S1", "SPLINE"));
  pc.nurbs = 0;
  s.curves.push_back(pc);
  s.line("L1", {0, 0}, {10, 0});
  const ChainResult r = s.chain();
  ASSERT_EQ(r.error, "");
  ASSERT_EQ(r.regions.size(), 1u);
  const Profile& b = r.regions[0].boundary;
  expect_chained(b);
  EXPECT_LT(area2(b), 0);  // the input ran counter-clockwise: reversed, NURBS included
  ASSERT_EQ(b.nurbs.size(), 1u);
  const ProfileCurve* arch = b.curves[0].nurbs >= 0 ? &b.curves[0] : &b.curves[1];
  EXPECT_EQ(arch->seg.a, Vec2(0, 0));
  EXPECT_EQ(b.nurbs[arch->nurbs].ctrl.front(), Vec2(0, 0));
}

TEST(ChainAndNest, SmallGapsAreSnappedAndReported) {
  Soup s;
  s.line("1", {0, 0}, {10, 0});
  s.line("2", {10, 4e-7}, {10, 10});
  s.line("3", {10, 10}, {0, 10});
  s.curves.push_back({make_arc({0, 10}, {0, 0}, {0, 5}, true, s.src("4", "ARC")), -1});
  const ChainResult r = s.chain();
  ASSERT_EQ(r.error, "");
  EXPECT_NEAR(r.largest_gap_closed, 4e-7, 1e-15);
  expect_chained(r.regions[0].boundary);

  Soup g = s;
  g.curves[1].seg = make_line({10, 1e-3}, {10, 10}, g.curves[1].seg.source);
  const ChainResult open = g.chain();
  EXPECT_EQ(open.error,
            "open profile: LINE 1 ends at (10, 0) and no other curve ends within 1e-06 mm of it");
  const ChainResult loose = g.chain(tol::kProfileJoinLoose);
  ASSERT_EQ(loose.error, "");
  EXPECT_NEAR(loose.largest_gap_closed, 1e-3, 1e-12);
  const Profile& b = loose.regions[0].boundary;
  expect_chained(b);
  for (const ProfileCurve& c : b.curves)
    if (c.seg.is_arc()) {  // the snapped arc still has both ends on its circle
      EXPECT_NEAR((c.seg.a - c.seg.c).norm(), c.seg.r, 1e-12);
      EXPECT_NEAR((c.seg.b - c.seg.c).norm(), c.seg.r, 1e-12);
    }
}

TEST(ChainAndNest, OpenChainNamesHandleAndPoint) {
  Soup s;
  s.rect("ok", 0, 0, 10, 10);
  s.line("2F", {20, 0}, {30, 0});
  s.line("30", {30, 0}, {30, 7.5});
  const ChainResult r = s.chain();
  EXPECT_EQ(
      r.error,
      "open profile: LINE 2F starts at (20, 0) and no other curve ends within 1e-06 mm of it");
  EXPECT_TRUE(r.regions.empty());
}

TEST(ChainAndNest, DuplicateEntitiesAreNamed) {
  Soup s;
  s.rect("r", 0, 0, 10, 10);
  s.line("DUP", {10, 10}, {10, 0});  // same as "rb", reversed
  const ChainResult r = s.chain();
  EXPECT_EQ(r.error, "duplicate curves: LINE rb and LINE DUP overlap between (10, 0) and (10, 10)");
}

TEST(ChainAndNest, BranchingIsAnError) {
  Soup s;
  s.rect("r", 0, 0, 10, 10);
  s.line("X", {10, 10}, {20, 20});
  s.line("Y", {20, 20}, {10, 0});
  const ChainResult r = s.chain();
  EXPECT_EQ(
      r.error.find("branching profile: 3 curve ends meet at (10, 0): LINE ra, LINE rb, LINE Y"), 0u)
      << r.error;
}

TEST(ChainAndNest, SelfIntersectingBoundaryIsAnError) {
  Soup s;  // a bow tie crossing at (5, 5)
  s.line("1", {0, 0}, {10, 10});
  s.line("2", {10, 10}, {10, 0});
  s.line("3", {10, 0}, {0, 10});
  s.line("4", {0, 10}, {0, 0});
  const ChainResult r = s.chain();
  EXPECT_EQ(r.error,
            "self-intersecting profile: loop through LINE 1 intersects itself at (5, 5) (LINE 1 "
            "and LINE 3)")
      << r.error;
}

TEST(ChainAndNest, CrossingLoopsAreAnError) {
  Soup s;
  s.rect("a", 0, 0, 10, 10);
  s.circle("C", {10, 5}, 2);
  const ChainResult r = s.chain();
  EXPECT_EQ(r.error.find("intersecting profiles: "), 0u) << r.error;
  EXPECT_NE(r.error.find("CIRCLE C"), std::string::npos) << r.error;
}

TEST(ChainAndNest, EmptyAndDegenerateInput) {
  EXPECT_EQ(Soup().chain().error, "no curves to chain");
  Soup s;
  s.line("Z", {0, 0}, {0, 0});  // both ends at one vertex, no area
  EXPECT_EQ(s.chain().error, "loop through LINE Z encloses no area");
}

}  // namespace
}  // namespace ncpath
