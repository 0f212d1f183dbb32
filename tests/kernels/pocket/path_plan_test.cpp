// Path determination, entries and pinched uncut loops: invariants that follow from the
// method, checked on shapes whose levels are known.
//  - every offset loop is cut exactly once, in full: the cutting moves of the planned path
//    add up to the summed loop lengths (clean-up loops aside);
//  - the path is continuous and one part needs loops - 1 links (a tree);
//  - every loop-to-loop link is at most one stepover long (it then lies inside the outer
//    loop's region), every clean-up link at most the tool radius;
//  - helix and ramp: on their circle / loop, ending at the start point at the bottom,
//    descending no steeper than the angle.
#include "kernels/pocket/path_plan.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "kernels/geom/tolerance.hpp"
#include "kernels/pocket/entry.hpp"
#include "kernels/pocket/offset_levels.hpp"
#include "kernels/pocket/uncut.hpp"
#include "tests/support/shapes2d.hpp"

namespace ncpath {
namespace {

struct Planned {
  OffsetLevels levels;
  std::vector<PlanLoop> loops;
  std::vector<SameLevelEdge> extra;
  std::vector<std::vector<std::uint32_t>> parts;
  std::vector<PlannedPath> paths;
};

// Levels of `input` at R, then every `step`; one planned path per part, starting at the
// first vertex of the part's deepest loop.
Planned plan(const std::vector<std::vector<Seg2>>& input, double r, double step, bool outward,
             bool climb) {
  Planned p;
  p.levels = offset_levels(input, r, step);
  const OffsetLevels& lv = p.levels;
  // Level regions: loops of one level grouped into a clockwise loop and its holes.
  std::vector<std::uint32_t> group(lv.loops.size(), 0);
  for (std::size_t k = 0; k < lv.level_start.size(); ++k) {
    const std::size_t b = k == 0 ? 0 : lv.level_start[k - 1], e = lv.level_start[k];
    std::vector<const OffsetLoop*> level;
    for (std::size_t i = b; i < e; ++i) level.push_back(&lv.loops[i].loop);
    for (const auto& g : group_regions(level))
      for (std::uint32_t m : g) group[b + m] = static_cast<std::uint32_t>(b + g[0]);
  }
  for (std::size_t i = 0; i < lv.loops.size(); ++i)
    p.loops.push_back(
        {&lv.loops[i].loop.segs, lv.loops[i].level, lv.loops[i].loop.parents, group[i]});
  p.extra = same_level_edges(p.loops);
  p.parts = connected_parts(p.loops, p.extra);
  PlanParams pp{r, step, outward, climb};
  for (const auto& part : p.parts) {
    std::uint32_t root = part[0];
    for (std::uint32_t l : part)
      if (outward ? p.loops[l].level > p.loops[root].level : p.loops[l].level < p.loops[root].level)
        root = l;
    p.paths.push_back(
        plan_part(p.loops, p.extra, {}, part, root, p.loops[root].segs->front().a, pp));
  }
  return p;
}

void check_invariants(const Planned& p, double step) {
  for (std::size_t k = 0; k < p.paths.size(); ++k) {
    const PlannedPath& path = p.paths[k];
    SCOPED_TRACE("part " + std::to_string(k));
    ASSERT_FALSE(path.moves.empty());
    EXPECT_LT((path.moves.front().seg.a - path.start).norm(), 1e-9);
    double cut = 0, loops = 0;
    for (std::size_t i = 0; i < path.moves.size(); ++i) {
      const Move2& m = path.moves[i];
      if (i > 0) {
        EXPECT_LT((path.moves[i - 1].seg.b - m.seg.a).norm(), 1e-9) << "gap before " << i;
      }
      if (m.kind == MoveKind::kCut) cut += length(m.seg);
      // A link is a segment of at most one stepover, or travel along a loop (cut already).
      if (m.kind == MoveKind::kLink && length(m.seg) > step + tol::kLinkSlack) {
        double off = 1e9;
        for (std::uint32_t l : path.loops)
          for (const Seg2& s : *p.loops[l].segs)
            off = std::min(off, std::max({distance(s, m.seg.a), distance(s, m.seg.b),
                                          distance(s, point_at(m.seg, 0.5))}));
        EXPECT_LT(off, 1e-9) << "link " << i << " of " << length(m.seg) << " mm";
      }
    }
    for (std::uint32_t l : path.loops) loops += loop_length(*p.loops[l].segs);
    EXPECT_NEAR(cut, loops, 1e-6 * loops) << "every loop cut exactly once";
    EXPECT_EQ(path.links, path.loops.size() - 1);
    EXPECT_EQ(path.long_links, 0u);
    // The way back ends at the start.
    if (!path.back.empty()) {
      EXPECT_LT((path.back.front().seg.a - path.moves.back().seg.b).norm(), 1e-9);
      EXPECT_LT((path.back.back().seg.b - path.start).norm(), 1e-9);
    }
  }
}

TEST(PathPlan, RectangleOneChainOfLoops) {
  for (bool outward : {true, false})
    for (bool climb : {true, false}) {
      const Planned p = plan({test::rectangle(0, 0, 60, 40, true)}, 3, 2.5, outward, climb);
      ASSERT_EQ(p.paths.size(), 1u);
      EXPECT_EQ(p.paths[0].loops.size(), p.levels.loops.size());
      check_invariants(p, 2.5);
      // Climb milling cutting outward runs against the stored (clockwise) direction: the
      // first loop is then counter-clockwise.
      const double a2 = loop_area2(p.paths[0].first_loop);
      EXPECT_EQ(a2 > 0, outward == climb);
    }
}

TEST(PathPlan, IslandsAndNeck) {
  // Two islands: loops around each merge with the boundary's.
  std::vector<std::vector<Seg2>> two = {test::rectangle(0, 0, 100, 60, true),
                                        test::circle({30, 30}, 10, false),
                                        test::rounded_rectangle(55, 15, 80, 45, 4, false)};
  check_invariants(plan(two, 3, 3, true, true), 3);
  check_invariants(plan(two, 3, 3, false, true), 3);
  // A dumbbell: levels split into two branches at the neck.
  std::vector<Seg2> bell;
  const Vec2 pts[] = {{0, 0},    {40, 0},  {40, 15}, {60, 15}, {60, 0},  {100, 0},
                      {100, 40}, {60, 40}, {60, 25}, {40, 25}, {40, 40}, {0, 40}};
  for (int i = 0; i < 12; ++i) bell.push_back(make_line(pts[i], pts[(i + 1) % 12]));
  const Planned p = plan({test::maybe_reverse(bell, true, true)}, 3, 3, true, true);
  ASSERT_EQ(p.paths.size(), 1u);
  check_invariants(p, 3);
}

TEST(PathPlan, RingNeedsSameLevelLink) {
  // A circular pocket with a concentric island: the boundary's and the island's levels
  // never merge (the ring vanishes first), so only a same-level link joins them.
  const Planned p =
      plan({test::circle({0, 0}, 30, true), test::circle({0, 0}, 10, false)}, 3, 3, true, true);
  EXPECT_EQ(p.extra.size(), 1u);
  ASSERT_EQ(p.paths.size(), 1u);
  check_invariants(p, 3);
  // The same-level link crosses the ring between the innermost loops: 21 - 19 = 2 mm.
  EXPECT_NEAR((p.extra[0].pa - p.extra[0].pb).norm(), 2.0, 1e-6);
}

TEST(PathPlan, SeparatePartsArePlannedApart) {
  // Two squares far apart are two parts (a retraction between them is unavoidable).
  const Planned p =
      plan({test::rectangle(0, 0, 30, 30, true), test::rectangle(50, 0, 80, 30, true)}, 3, 3, true,
           true);
  EXPECT_EQ(p.paths.size(), 2u);
  check_invariants(p, 3);
}

TEST(PathPlan, CleanupLoopsAreVisitedOnce) {
  // Stepover = tool diameter on a rectangle: corner and centre uncut regions.
  const double r = 3, step = 6;
  const OffsetLevels lv = offset_levels({test::rectangle(0, 0, 60, 40, true)}, r, step);
  ASSERT_EQ(lv.loops.size(), 3u);
  std::vector<PlanLoop> loops;
  for (std::uint32_t i = 0; i < lv.loops.size(); ++i)
    loops.push_back({&lv.loops[i].loop.segs, lv.loops[i].level, lv.loops[i].loop.parents, i});
  std::vector<CleanupLoop> cleanups;
  double uncut_length = 0;
  for (std::uint32_t i = 0; i < lv.loops.size(); ++i) {
    std::vector<const OffsetLoop*> inner;
    if (i + 1 < lv.loops.size()) inner.push_back(&lv.loops[i + 1].loop);
    for (const OffsetLoop& u : uncut_between({&lv.loops[i].loop}, inner, r)) {
      CleanupLoop c{u.segs, {}};
      for (std::uint32_t q : u.parents) c.bounds.push_back(i + q);
      uncut_length += loop_length(u.segs);
      cleanups.push_back(std::move(c));
    }
  }
  // 4 corners in each of the two bands, and the centre.
  EXPECT_EQ(cleanups.size(), 9u);
  const std::vector<SameLevelEdge> extra;
  PlannedPath path = plan_part(loops, extra, cleanups, {0, 1, 2}, 2, lv.loops[2].loop.segs[0].a,
                               {r, step, true, true});
  EXPECT_EQ(path.cleanup_curves, 9u);
  EXPECT_TRUE(path.unattached.empty());
  double cleanup = 0;
  for (std::size_t i = 0; i < path.moves.size(); ++i) {
    const Move2& m = path.moves[i];
    if (m.kind == MoveKind::kCleanup) cleanup += length(m.seg);
    if (m.kind == MoveKind::kCleanupLink) {
      EXPECT_LE(length(m.seg), r + tol::kLinkSlack);
    }
    if (i > 0) {
      EXPECT_LT((path.moves[i - 1].seg.b - m.seg.a).norm(), 1e-9);
    }
  }
  EXPECT_NEAR(cleanup, uncut_length, 1e-9 * uncut_length);
}

TEST(SplitPinched, BridgeBetweenTwoSquaresIsDropped) {
  // Two unit squares (clockwise) joined by a bridge travelled there and back.
  const Vec2 a(0, 0), b(0, 1), c(1, 1), d(1, 0.5), e(3, 0.5), f(3, 1), g(4, 1), h(4, 0), i(3, 0),
      j(1, 0);
  std::vector<Seg2> l = {make_line(a, b), make_line(b, c), make_line(c, d), make_line(d, e),
                         make_line(e, f), make_line(f, g), make_line(g, h), make_line(h, i),
                         make_line(i, e), make_line(e, d), make_line(d, j), make_line(j, a)};
  OffsetLoop loop;
  loop.segs = l;
  loop.area2 = loop_area2(l);
  loop.parents = {7};
  std::vector<OffsetLoop> out;
  split_pinched(loop, out);
  ASSERT_EQ(out.size(), 2u);
  for (const OffsetLoop& o : out) {
    EXPECT_NEAR(o.area2, -2.0, 1e-12);  // unit squares, clockwise
    EXPECT_EQ(o.parents, std::vector<std::uint32_t>{7});
  }
}

TEST(Entry, HelixStaysOnItsCircleAndDescendsGently) {
  const Vec2 c(10, 5), s(12, 5);
  const double angle = 3 * std::numbers::pi / 180, chord = 1e-3;
  const std::vector<Vec3> h = helix_points(c, s, 1, -4, angle, true, chord);
  ASSERT_GE(h.size(), 3u);
  EXPECT_LT((h.front() - Vec3(12, 5, 1)).norm(), 1e-12);
  EXPECT_LT((h.back() - Vec3(12, 5, -4)).norm(), 1e-12);
  double xy = 0;
  for (std::size_t k = 1; k < h.size(); ++k) {
    EXPECT_NEAR((h[k].head<2>() - c).norm(), 2.0, 1e-12);
    const double step = (h[k] - h[k - 1]).head<2>().norm();
    xy += step;
    EXPECT_LE(h[k].z(), h[k - 1].z());
    // Chords are shorter than their arcs by at most the sagitta's share: 1 % slack.
    EXPECT_LE(h[k - 1].z() - h[k].z(), std::tan(angle) * step * 1.01 + 1e-12);
    // Counter-clockwise around the centre.
    const Vec2 u = h[k - 1].head<2>() - c, v = h[k].head<2>() - c;
    EXPECT_GT(u.x() * v.y() - u.y() * v.x(), 0);
  }
  // Descent over whole turns plus one turn at the bottom: 5 mm at 3 degrees needs
  // 95.4 mm = 8 turns of 12.57 mm.
  const int turns = static_cast<int>(std::ceil(5 / (2 * std::numbers::pi * 2 * std::tan(angle))));
  // (The chords are shorter than the circle by less than 0.1 %.)
  const double circle = 2 * std::numbers::pi * 2;
  EXPECT_NEAR(xy, (turns + 1) * circle, 1e-3 * (turns + 1) * circle);
}

TEST(Entry, RampFollowsTheLoopAndEndsAtItsStart) {
  const std::vector<Seg2> loop = test::rectangle(0, 0, 20, 10, false);  // 60 mm round
  const double angle = 3 * std::numbers::pi / 180;
  for (double drop : {2.0, 5.0}) {
    const std::vector<Vec3> r = ramp_points(loop, 0, -drop, angle, 1e-3);
    ASSERT_GE(r.size(), 2u);
    EXPECT_LT((r.front() - Vec3(0, 0, 0)).norm(), 1e-12);
    EXPECT_LT((r.back() - Vec3(0, 0, -drop)).norm(), 1e-12);
    double xy = 0;
    for (std::size_t k = 1; k < r.size(); ++k) {
      const double step = (r[k] - r[k - 1]).head<2>().norm();
      xy += step;
      EXPECT_LE(r[k - 1].z() - r[k].z(), std::tan(angle) * step + 1e-12);
      double d = 1e9;
      for (const Seg2& s : loop) d = std::min(d, distance(s, Vec2(r[k].head<2>())));
      EXPECT_LT(d, 1e-12);
    }
    // Whole turns: the ramp needs drop / tan(3 deg) mm: 38 (one turn), 95 (two).
    EXPECT_NEAR(xy, 60.0 * std::ceil(drop / std::tan(angle) / 60), 1e-9);
  }
}

}  // namespace
}  // namespace ncpath
