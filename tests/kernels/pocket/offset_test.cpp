// Exact offsets of line/arc loops: analytic areas and perimeters, distance oracle,
// robustness cases.
#include "kernels/pocket/offset.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "kernels/curves/intersect.hpp"
#include "tests/support/shapes2d.hpp"

namespace ncpath {
namespace {

constexpr double kPi = std::numbers::pi;

double area(const OffsetLoop& l) { return l.area2 / 2; }

// Every sampled point of every result loop is exactly d from the input (closest input
// segment), computed with the segment distance, independent of the offset code path.
void expect_at_distance(const OffsetResult& r, const std::vector<std::vector<Seg2>>& in, double d) {
  for (const OffsetLoop& l : r.loops)
    for (const Seg2& s : l.segs)
      for (double t : {0.0, 0.25, 0.5, 0.75}) {
        const Vec2 p = point_at(s, t);
        double best = 1e300;
        for (const auto& loop : in)
          for (const Seg2& q : loop) best = std::min(best, distance(q, p));
        EXPECT_NEAR(best, d, 1e-9) << "at " << p.transpose();
      }
}

void expect_closed(const OffsetResult& r) {
  for (const OffsetLoop& l : r.loops)
    for (std::size_t k = 0; k < l.segs.size(); ++k)
      EXPECT_EQ(l.segs[k].b, l.segs[(k + 1) % l.segs.size()].a);
  EXPECT_EQ(r.stats.open_fragments, 0u);
}

TEST(Offset, RectangleShrinksExactly) {
  const std::vector<std::vector<Seg2>> in = {test::rectangle(0, 0, 100, 60, true)};
  for (double d : {1.0, 10.0, 29.0}) {
    const OffsetResult r = offset_loops(in, d);
    ASSERT_EQ(r.loops.size(), 1u) << d;
    EXPECT_NEAR(area(r.loops[0]), -(100 - 2 * d) * (60 - 2 * d), 1e-9);
    EXPECT_NEAR(loop_length(r.loops[0].segs), 2 * (100 + 60 - 4 * d), 1e-9);
    expect_closed(r);
    expect_at_distance(r, in, d);
  }
  EXPECT_TRUE(offset_loops(in, 30.0).loops.empty());  // the 60 mm side is used up
  EXPECT_TRUE(offset_loops(in, 31.0).loops.empty());
}

TEST(Offset, CircleShrinksAndIslandGrows) {
  const std::vector<std::vector<Seg2>> pocket = {test::circle({5, 5}, 40, true)};
  const OffsetResult r = offset_loops(pocket, 15);
  ASSERT_EQ(r.loops.size(), 1u);
  EXPECT_NEAR(area(r.loops[0]), -kPi * 25 * 25, 1e-9);
  expect_at_distance(r, pocket, 15);
  const std::vector<std::vector<Seg2>> island = {test::circle({0, 0}, 5, false)};
  const OffsetResult g = offset_loops(island, 3);
  ASSERT_EQ(g.loops.size(), 1u);
  EXPECT_NEAR(area(g.loops[0]), kPi * 8 * 8, 1e-9);
}

// A square island grows into a rounded square: s^2 + 4 s d + pi d^2.
TEST(Offset, SquareIslandGetsRoundCorners) {
  const std::vector<std::vector<Seg2>> in = {test::rectangle(0, 0, 10, 10, false)};
  const OffsetResult r = offset_loops(in, 2);
  ASSERT_EQ(r.loops.size(), 1u);
  EXPECT_NEAR(area(r.loops[0]), 100 + 4 * 10 * 2 + kPi * 4, 1e-9);
  EXPECT_NEAR(loop_length(r.loops[0].segs), 40 + 2 * kPi * 2, 1e-9);
  expect_at_distance(r, in, 2);
}

// Rounded rectangle: corner radius 8; an offset of 5 keeps radius 3 corners; an offset of
// exactly 8 makes them sharp (the arcs vanish); 12 gives a sharp-cornered rectangle.
TEST(Offset, RoundedRectangleCornersShrinkThenVanish) {
  const std::vector<std::vector<Seg2>> in = {test::rounded_rectangle(0, 0, 100, 50, 8, true)};
  for (double d : {5.0, 8.0, 12.0}) {
    const OffsetResult r = offset_loops(in, d);
    ASSERT_EQ(r.loops.size(), 1u) << d;
    const double w = 100 - 2 * d, h = 50 - 2 * d, rr = std::max(0.0, 8 - d);
    EXPECT_NEAR(-area(r.loops[0]), w * h - (4 - kPi) * rr * rr, 1e-9) << d;
    EXPECT_NEAR(loop_length(r.loops[0].segs), 2 * (w + h) - (8 - 2 * kPi) * rr, 1e-9) << d;
    expect_closed(r);
    expect_at_distance(r, in, d);
  }
}

TEST(Offset, SlotCollapsesAtItsRadius) {
  const std::vector<std::vector<Seg2>> in = {test::slot(40, 6, true)};
  const OffsetResult r = offset_loops(in, 2);
  ASSERT_EQ(r.loops.size(), 1u);
  EXPECT_NEAR(-area(r.loops[0]), 40 * 8 + kPi * 16, 1e-9);
  EXPECT_TRUE(offset_loops(in, 6).loops.empty());  // exactly the arc radius: nothing left
  EXPECT_TRUE(offset_loops(in, 7).loops.empty());
}

// Circle pocket with two circular islands: disjoint, then an island meets the boundary
// (the pocket becomes one loop around a "lake"), then islands merge.
TEST(Offset, IslandsMeetBoundaryAndMerge) {
  const std::vector<std::vector<Seg2>> in = {test::circle({0, 0}, 50, true),
                                             test::circle({25, 0}, 5, false),
                                             test::circle({-12, 0}, 5, false)};
  {
    const OffsetResult r = offset_loops(in, 3);  // all disjoint
    ASSERT_EQ(r.loops.size(), 3u);
    double total = 0;
    for (const OffsetLoop& l : r.loops) total += area(l);
    EXPECT_NEAR(total, -kPi * 47 * 47 + 2 * kPi * 8 * 8, 1e-9);
    expect_at_distance(r, in, 3);
  }
  {
    // d = 11: islands grow to radius 16, centres 37 apart -> still apart; the right island
    // (25 + 16 = 41) crosses the shrunken boundary (50 - 11 = 39): they merge into one loop.
    const OffsetResult r = offset_loops(in, 11);
    expect_closed(r);
    expect_at_distance(r, in, 11);
    ASSERT_EQ(r.loops.size(), 2u);  // the boundary-with-lake loop and the left island
  }
  {
    // d = 19: islands of radius 24, 37 apart: they have merged with each other too.
    const OffsetResult r = offset_loops(in, 19);
    expect_closed(r);
    expect_at_distance(r, in, 19);
  }
}

// A ring pocket thinner than twice the offset: boundary and island offsets pass each other
// without crossing, and nothing may remain.
TEST(Offset, ThinRingIsUsedUpWithoutCrossings) {
  const std::vector<std::vector<Seg2>> in = {test::circle({0, 0}, 50, true),
                                             test::circle({0, 0}, 48, false)};
  EXPECT_TRUE(offset_loops(in, 3).loops.empty());
  const OffsetResult half = offset_loops(in, 0.5);  // 1 mm of ring left
  EXPECT_EQ(half.loops.size(), 2u);
  const double pi = 3.141592653589793;
  EXPECT_NEAR(half.loops[0].area2 / 2 + half.loops[1].area2 / 2, -pi * (49.5 * 49.5 - 48.5 * 48.5),
              1e-9);
}

TEST(Offset, ThinNeckSplitsPocketInTwo) {
  // Two 40x40 squares joined by a 4 mm wide, 10 mm long neck (one clockwise loop).
  const std::vector<Vec2> p = {{0, 0},   {40, 0},  {40, 18}, {50, 18}, {50, 0},  {90, 0},
                               {90, 40}, {50, 40}, {50, 22}, {40, 22}, {40, 40}, {0, 40}};
  std::vector<Seg2> loop;
  for (std::size_t k = p.size(); k-- > 0;)  // reversed: clockwise
    loop.push_back(make_line(p[(k + 1) % p.size()], p[k]));
  const std::vector<std::vector<Seg2>> in = {loop};
  ASSERT_LT(loop_area2(loop), 0);
  EXPECT_EQ(offset_loops(in, 1).loops.size(), 1u);
  const OffsetResult r = offset_loops(in, 3);  // the neck (half width 2) is gone
  ASSERT_EQ(r.loops.size(), 2u);
  // Each square keeps a small bulge towards the neck, bounded by radius-3 arcs around the
  // neck's corners (40, 18) and (40, 22): 2 * integral_0^2 (3 - sqrt(9 - t^2)) dt.
  const double bulge = 2 * (6 - (std::sqrt(5.0) + 4.5 * std::asin(2.0 / 3.0)));
  for (const OffsetLoop& l : r.loops) EXPECT_NEAR(-area(l), 34 * 34 + bulge, 1e-9);
  expect_at_distance(r, in, 3);
}

TEST(Offset, ReversedInputDirectionGivesTheSameRegion) {
  // Island given clockwise by mistake is an error of the caller; here: the same pocket
  // with its segments listed from another start point gives the same area.
  std::vector<Seg2> a = test::rounded_rectangle(0, 0, 80, 30, 5, true);
  std::rotate(a.begin(), a.begin() + 3, a.end());
  const OffsetResult r0 = offset_loops({test::rounded_rectangle(0, 0, 80, 30, 5, true)}, 4);
  const OffsetResult r1 = offset_loops({a}, 4);
  ASSERT_EQ(r0.loops.size(), 1u);
  ASSERT_EQ(r1.loops.size(), 1u);
  EXPECT_NEAR(r0.loops[0].area2, r1.loops[0].area2, 1e-9);
}

TEST(Offset, CollinearDuplicateAndTinySegments) {
  // A rectangle whose bottom side is cut into pieces, one of 1e-7 mm, plus a duplicate
  // vertex (zero-length segment).
  std::vector<Seg2> l = {make_line({0, 0}, {30, 0}),
                         make_line({30, 0}, {30.0000001, 0}),
                         make_line({30.0000001, 0}, {30.0000001, 0}),
                         make_line({30.0000001, 0}, {100, 0}),
                         make_line({100, 0}, {100, 50}),
                         make_line({100, 50}, {0, 50}),
                         make_line({0, 50}, {0, 0})};
  std::vector<Seg2> cw;
  for (auto it = l.rbegin(); it != l.rend(); ++it) cw.push_back(reversed(*it));
  const OffsetResult r = offset_loops({cw}, 5);
  ASSERT_EQ(r.loops.size(), 1u);
  EXPECT_NEAR(-area(r.loops[0]), 90 * 40, 1e-9);
  expect_closed(r);
}

TEST(Offset, WindingNumber) {
  const std::vector<Seg2> c = test::circle({0, 0}, 10, false);
  EXPECT_EQ(winding_number(c, {0, 0}), 1);
  EXPECT_EQ(winding_number(c, {9.9, 0}), 1);
  EXPECT_EQ(winding_number(c, {10.1, 0}), 0);
  EXPECT_EQ(winding_number(test::rectangle(0, 0, 5, 5, true), {1, 1}), -1);
}

}  // namespace
}  // namespace ncpath
