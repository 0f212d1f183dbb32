// Uncut regions between levels, against Clipper: the band between two levels minus the area
// swept by the tool disc along both levels' loops (Clipper's closed-line offset of the
// discretised loops), independent of the offset code.
#include "kernels/pocket/uncut.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <clipper.hpp>
#include <cmath>
#include <numbers>
#include <random>

#include "bench/wave_shapes.hpp"
#include "kernels/pocket/offset_levels.hpp"
#include "tests/support/shapes2d.hpp"

namespace ncpath {
namespace {

constexpr double kScale = 1e6;
constexpr double kChord = 1e-4;

ClipperLib::Path to_path(const std::vector<Seg2>& loop) {
  std::vector<Vec2> pts;
  for (const Seg2& s : loop) append_polyline(s, kChord, pts);
  ClipperLib::Path path;
  for (const Vec2& p : pts)
    path.emplace_back(static_cast<ClipperLib::cInt>(std::llround(p.x() * kScale)),
                      static_cast<ClipperLib::cInt>(std::llround(p.y() * kScale)));
  return path;
}

double area_of(const ClipperLib::Paths& ps) {
  double a = 0;
  for (const auto& p : ps) a += ClipperLib::Area(p);
  return a / (kScale * kScale);
}

// Area of the band between two levels left uncut by a tool of radius r on both levels.
double clipper_uncut_area(const std::vector<Seg2>& outer, const std::vector<Seg2>& inner,
                          double r) {
  ClipperLib::Paths band_paths = {to_path(outer), to_path(inner)};
  ClipperLib::Paths band;
  {
    ClipperLib::Clipper c;
    c.AddPaths(band_paths, ClipperLib::ptSubject, true);
    c.Execute(ClipperLib::ctUnion, band, ClipperLib::pftEvenOdd, ClipperLib::pftEvenOdd);
  }
  ClipperLib::Paths swept;
  {
    ClipperLib::ClipperOffset off;
    off.ArcTolerance = kChord * kScale;
    off.AddPaths(band_paths, ClipperLib::jtRound, ClipperLib::etClosedLine);
    off.Execute(swept, r * kScale);
  }
  ClipperLib::Clipper c;
  c.AddPaths(band, ClipperLib::ptSubject, true);
  c.AddPaths(swept, ClipperLib::ptClip, true);
  ClipperLib::Paths rest;
  c.Execute(ClipperLib::ctDifference, rest, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
  return area_of(rest);
}

double ours(const std::vector<OffsetLoop>& loops) {
  double a = 0;
  for (const OffsetLoop& l : loops) a += -l.area2 / 2;
  return a;
}

void check_levels(const std::vector<std::vector<Seg2>>& pocket, double r, double step,
                  int expect_uncut_min) {
  const OffsetLevels lv = offset_levels(pocket, r, step);
  ASSERT_GE(lv.level_start.size(), 3u);
  int bands_with_uncut = 0;
  for (std::size_t k = 0; k + 1 < lv.level_start.size(); ++k) {
    const std::size_t b0 = k == 0 ? 0 : lv.level_start[k - 1], e0 = lv.level_start[k];
    const std::size_t e1 = lv.level_start[k + 1];
    if (e0 - b0 != 1 || e1 - e0 != 1) continue;  // single loops only: one band
    const OffsetLoop& outer = lv.loops[b0].loop;
    const OffsetLoop& inner = lv.loops[e0].loop;
    const std::vector<OffsetLoop> u = uncut_between({&outer}, {&inner}, r);
    bands_with_uncut += !u.empty();
    // The quick test may only say "cut" when there is nothing.
    if (band_cut({&outer}, {&inner}, r)) {
      EXPECT_TRUE(u.empty()) << "band " << k;
    }
    const double oracle = clipper_uncut_area(outer.segs, inner.segs, r);
    const double perimeter = loop_length(outer.segs) + loop_length(inner.segs);
    EXPECT_NEAR(ours(u), oracle, 6 * kChord * perimeter + 1e-6) << "band " << k;
  }
  EXPECT_GE(bands_with_uncut, expect_uncut_min);
}

TEST(Uncut, NarrowStepoverLeavesNothing) {
  check_levels({test::rectangle(0, 0, 100, 60, true)}, 3, 2, 0);
  const OffsetLevels lv = offset_levels({test::rectangle(0, 0, 100, 60, true)}, 3, 2);
  EXPECT_TRUE(uncut_between({&lv.loops[0].loop}, {&lv.loops[1].loop}, 3).empty());
}

TEST(Uncut, WideStepoverLeavesCornerUncut) {
  // Sharp rectangle corners: with a wide stepover the corner bisector has points farther
  // than R from both loops; Clipper says how much.
  check_levels({test::rectangle(0, 0, 100, 60, true)}, 3, 5.8, 1);
  const OffsetLevels lv = offset_levels({test::rectangle(0, 0, 100, 60, true)}, 3, 5.8);
  EXPECT_EQ(uncut_between({&lv.loops[0].loop}, {&lv.loops[1].loop}, 3).size(), 4u);
}

TEST(Uncut, StepoverOfTheToolDiameterAndCentreUncut) {
  check_levels({test::rounded_rectangle(0, 0, 120, 80, 4, true)}, 3, 6, 0);
  // Centre uncut: what the innermost loop leaves inside itself.
  const std::vector<std::vector<Seg2>> slotp = {test::slot(50, 9, true)};
  const OffsetLevels lv = offset_levels(slotp, 3, 6);
  ASSERT_EQ(lv.level_start.size(), 1u);  // 9 - 3 = 6 < 9: one level only
  // The only loop is a slot of half-width 6; the tool on it clears 3 mm on each side, so a
  // centre slot of half-width 3 stays: 50 * 6 + pi * 3^2.
  const std::vector<OffsetLoop> centre = uncut_between({&lv.loops[0].loop}, {}, 3);
  ASSERT_EQ(centre.size(), 1u);
  EXPECT_NEAR(-centre[0].area2 / 2, 300 + 3.141592653589793 * 9, 1e-9);
}

// The quick sufficient test: says "cut" for smooth concentric bands, never when the
// dissection finds uncut material (random wavy pockets, many stepovers).
TEST(Uncut, QuickBandTestIsSound) {
  const std::vector<std::vector<Seg2>> disc = {test::circle({0, 0}, 40, true)};
  const OffsetLevels lv = offset_levels(disc, 3, 4.5);
  for (std::size_t k = 0; k + 1 < lv.loops.size(); ++k)
    EXPECT_TRUE(band_cut({&lv.loops[k].loop}, {&lv.loops[k + 1].loop}, 3)) << k;
  std::mt19937 rng(11);
  int said_cut = 0, found_uncut = 0;
  for (int trial = 0; trial < 12; ++trial) {
    // A star-shaped polygon of 40 vertices with random radii.
    std::uniform_real_distribution<double> rad(25, 40);
    std::vector<Vec2> pts;
    for (int i = 0; i < 40; ++i) {
      const double a = -2 * 3.141592653589793 * i / 40;  // clockwise
      const double rr = rad(rng);
      pts.emplace_back(rr * std::cos(a), rr * std::sin(a));
    }
    std::vector<Seg2> loop;
    for (int i = 0; i < 40; ++i) loop.push_back(make_line(pts[i], pts[(i + 1) % 40]));
    const double step = std::uniform_real_distribution<double>(3.2, 6)(rng);
    const OffsetLevels levels = offset_levels({loop}, 3, step);
    for (std::size_t k = 0; k + 1 < levels.level_start.size(); ++k) {
      const std::size_t b0 = k == 0 ? 0 : levels.level_start[k - 1], e0 = levels.level_start[k];
      std::vector<const OffsetLoop*> outer, inner;
      for (std::size_t i = b0; i < e0; ++i) outer.push_back(&levels.loops[i].loop);
      for (std::size_t i = e0; i < levels.level_start[k + 1]; ++i)
        inner.push_back(&levels.loops[i].loop);
      const bool quick = band_cut(outer, inner, 3);
      const bool empty = uncut_between(outer, inner, 3).empty();
      said_cut += quick;
      found_uncut += !empty;
      if (quick) {
        EXPECT_TRUE(empty) << "trial " << trial << " band " << k;
      }
    }
  }
  EXPECT_GT(said_cut, 0);
  EXPECT_GT(found_uncut, 0);
}

// Sharp corners keep R^2 (1 - pi/4) each that a tool of radius R cannot reach; a rounded
// rectangle whose corner radius is at least R keeps nothing; an island's convex corners are
// no obstacle.
TEST(Uncut, UnreachableCorners) {
  const double r = 3, pi = 3.141592653589793;
  const Reach sharp = tool_reach({test::rectangle(0, 0, 100, 60, true)}, r);
  EXPECT_NEAR(sharp.unreachable_area, 4 * r * r * (1 - pi / 4), 1e-9);
  ASSERT_EQ(sharp.reachable.size(), 1u);
  EXPECT_NEAR(-sharp.reachable[0].area2 / 2, 6000 - 4 * r * r * (1 - pi / 4), 1e-9);
  EXPECT_NEAR(tool_reach({test::rounded_rectangle(0, 0, 100, 60, 4, true)}, r).unreachable_area, 0,
              1e-9);
  const Reach with_island =
      tool_reach({test::rectangle(0, 0, 100, 60, true), test::rectangle(40, 20, 60, 40, false)}, r);
  EXPECT_NEAR(with_island.unreachable_area, 4 * r * r * (1 - pi / 4), 1e-9);
}

// The windowed dissection (uncut_between) against the complete one (uncut_between_full)
// over every band of multi-level offsets, as plan_pocket forms them (a level region and the
// next level's loops inside it, the centre band for regions with no next level): the same
// regions, in the same order, with the same areas, parents and segments. band_cut may only
// say "cut" when the complete dissection finds nothing. Returns the number of regions.
int expect_windowed_matches_full(const std::vector<std::vector<Seg2>>& pocket, double r,
                                 double step, std::uint32_t max_levels, int* bands_said_cut) {
  const OffsetLevels lv = offset_levels(pocket, r, step, max_levels);
  int regions = 0;
  for (std::size_t k = 0; k < lv.level_start.size(); ++k) {
    const std::size_t b = k == 0 ? 0 : lv.level_start[k - 1], e = lv.level_start[k];
    std::vector<const OffsetLoop*> level;
    for (std::size_t i = b; i < e; ++i) level.push_back(&lv.loops[i].loop);
    for (const std::vector<std::uint32_t>& members : group_regions(level)) {
      std::vector<const OffsetLoop*> outer, inner;
      for (const std::uint32_t m : members) outer.push_back(level[m]);
      if (k + 1 < lv.level_start.size())
        for (std::size_t i = e; i < lv.level_start[k + 1]; ++i) {
          const std::vector<std::uint32_t>& par = lv.loops[i].loop.parents;
          if (!par.empty() &&
              std::find(members.begin(), members.end(), par[0] - b) != members.end())
            inner.push_back(&lv.loops[i].loop);
        }
      const std::vector<OffsetLoop> fast = uncut_between(outer, inner, r);
      const std::vector<OffsetLoop> full = uncut_between_full(outer, inner, r);
      const bool cut = band_cut(outer, inner, r);
      *bands_said_cut += cut;
      if (cut) {
        EXPECT_TRUE(full.empty()) << "level " << k;
      }
      EXPECT_EQ(fast.size(), full.size()) << "level " << k;
      if (fast.size() != full.size()) continue;
      for (std::size_t i = 0; i < fast.size(); ++i) {
        EXPECT_NEAR(fast[i].area2 / 2, full[i].area2 / 2, 1e-9) << "level " << k << " region " << i;
        EXPECT_EQ(fast[i].parents, full[i].parents) << "level " << k << " region " << i;
        // The same loop from the same piece: the windows hold every piece the complete
        // dissection keeps, cut at the same crossings.
        EXPECT_EQ(fast[i].segs.size(), full[i].segs.size()) << "level " << k << " region " << i;
        if (fast[i].segs.size() != full[i].segs.size()) continue;
        for (std::size_t q = 0; q < fast[i].segs.size(); ++q) {
          EXPECT_EQ(fast[i].segs[q].kind, full[i].segs[q].kind);
          EXPECT_LE((fast[i].segs[q].a - full[i].segs[q].a).norm(), 1e-12);
        }
      }
      regions += static_cast<int>(full.size());
    }
  }
  return regions;
}

// Random star polygons of lines and bulge arcs, some with islands, at stepovers between R
// and 2R.
TEST(Uncut, WindowedMatchesFullOnRandomStars) {
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> rad(25, 40), bulge(-0.25, 0.25), u(0, 1);
  const double r = 1.5;
  int regions = 0, said_cut = 0;
  for (int trial = 0; trial < 6; ++trial) {
    const int n = 24 + 6 * trial;
    std::vector<Vec2> pts;
    for (int k = 0; k < n; ++k) {
      const double a = -2 * std::numbers::pi * (k + 0.3 * u(rng)) / n;  // clockwise
      const double rr = rad(rng);
      pts.emplace_back(rr * std::cos(a), rr * std::sin(a));
    }
    std::vector<std::vector<Seg2>> pocket(1);
    for (int k = 0; k < n; ++k)
      pocket[0].push_back(u(rng) < 0.5 ? make_line(pts[k], pts[(k + 1) % n])
                                       : make_bulge_segment(pts[k], pts[(k + 1) % n], bulge(rng)));
    if (trial % 2 == 1) {
      pocket.push_back(test::circle({-6 + 3 * u(rng), 3 * u(rng)}, 3, false));
      pocket.push_back(test::rectangle(6, -4, 10 + 3 * u(rng), 2, false));
    }
    for (const double f : {1.2, 1.6, 2.0})
      regions += expect_windowed_matches_full(pocket, r, f * r, 1000, &said_cut);
  }
  EXPECT_GT(regions, 100);
  EXPECT_GT(said_cut, 0);
}

// The benchmark's wavy loop with its 12 islands, reduced to 2,000 segments, at the
// benchmark's tool and stepover (the first 9 levels: the islands and the bands they split).
TEST(Uncut, WindowedMatchesFullOnWaveWithIslands) {
  std::vector<std::vector<Seg2>> pocket = {bench::wave_loop(2000, 8.85)};
  for (const std::vector<Seg2>& island : bench::twelve_islands()) pocket.push_back(island);
  int said_cut = 0;
  EXPECT_GT(expect_windowed_matches_full(pocket, 0.5, 0.9, 9, &said_cut), 50);
}

}  // namespace
}  // namespace ncpath
