// Cut direction of clean-up paths (kernels/cleanup/cut_direction.hpp), spindle M3: climb keeps
// the material on the right of travel. Exact cases: the foot of a vertical wall (material
// vector of length 1 toward the wall), a symmetric V-groove (none), a vertical corner (no xy
// travel), the average of the material vectors at a chord's ends; a loop around a pocket
// floor, whose walls are outside, is climb counter-clockwise (the pocket operation's
// convention, engine/pocket_path.hpp); reversing a path negates its score. And the greedy
// ordering (kernels/cleanup/pencil.hpp) never reverses a fixed path.
#include "kernels/cleanup/cut_direction.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "kernels/cleanup/pencil.hpp"

namespace ncpath {
namespace {

using Normals = std::vector<std::array<Vec3, 2>>;

const Vec3 kUp(0, 0, 1);

// The floor (0, 0, 1) and a vertical wall whose outward unit normal (into the pocket) is n.
std::array<Vec3, 2> floor_wall(const Vec3& n) { return {kUp, n}; }

TEST(CutDirection, FootOfAWallIsClimbWithTheWallOnTheRight) {
  // Wall at x = 5 facing -x; the crease at x = 3.75 along y. m = (1, 0): toward the wall.
  const Vec2 m = material_vector(kUp, Vec3(-1, 0, 0));
  EXPECT_EQ(m, Vec2(1, 0));
  const std::vector<Vec3> north = {{3.75, -2, 0}, {3.75, 0.5, 0}, {3.75, 3, 0}};
  const Normals b(3, floor_wall(Vec3(-1, 0, 0)));
  // Travelling +y the wall (+x) is on the right: climb, score = xy length * |m|.
  const CutSideScore s = cut_side_score(north, b);
  EXPECT_DOUBLE_EQ(s.score, 5);
  EXPECT_DOUBLE_EQ(s.xy_length, 5);
  EXPECT_EQ(cut_side(s), 1);
  EXPECT_FALSE(reverse_for(CutDirection::kClimb, 1));
  EXPECT_TRUE(reverse_for(CutDirection::kConventional, 1));
  EXPECT_FALSE(reverse_for(CutDirection::kAny, 1));
  // Travelling -y it is on the left: conventional.
  std::vector<Vec3> south(north.rbegin(), north.rend());
  const CutSideScore r = cut_side_score(south, b);
  EXPECT_DOUBLE_EQ(r.score, -5);
  EXPECT_EQ(cut_side(r), -1);
  EXPECT_TRUE(reverse_for(CutDirection::kClimb, -1));
  EXPECT_FALSE(reverse_for(CutDirection::kConventional, -1));
}

TEST(CutDirection, SymmetricGrooveAndVerticalCornerHaveNoSide) {
  const double h = 1 / std::sqrt(2.0);
  const std::vector<Vec3> groove = {{0, 0, 1}, {0, 4, 1}, {0, 9, 1}};
  const Normals v(3, {Vec3(h, 0, h), Vec3(-h, 0, h)});
  const CutSideScore s = cut_side_score(groove, v);
  EXPECT_EQ(s.score, 0);
  EXPECT_DOUBLE_EQ(s.xy_length, 9);
  EXPECT_EQ(cut_side(s), 0);
  for (CutDirection d : {CutDirection::kAny, CutDirection::kClimb, CutDirection::kConventional})
    EXPECT_FALSE(reverse_for(d, 0));
  // Two walls meeting in a vertical corner: a large material vector, but no xy travel.
  const std::vector<Vec3> corner = {{3.75, 3.75, 0}, {3.75, 3.75, 1}, {3.75, 3.75, 1.75}};
  const Normals w(3, {Vec3(-1, 0, 0), Vec3(0, -1, 0)});
  const CutSideScore c = cut_side_score(corner, w);
  EXPECT_EQ(c.xy_length, 0);
  EXPECT_EQ(cut_side(c), 0);
  // A lopsided crease just above the neutral threshold has a side, just below it none.
  const std::vector<Vec3> line = {{0, 0, 0}, {0, 10, 0}};
  for (double k : {2.0, 0.5}) {
    const double e = k * tol::kCutSideNeutral;  // m = (e, 0): material toward +x
    const Normals tilt(2, {Vec3(-e, 0, 1), Vec3(0, 0, 0)});
    EXPECT_EQ(cut_side(cut_side_score(line, tilt)), k > 1 ? 1 : 0) << k;
  }
}

TEST(CutDirection, MaterialVectorsAreAveragedOverEachChord) {
  // Chord 1 (+x, length 2): m from (0, -1) to (0, -3), mean (0, -2): the right of +x is -y,
  // so +4. Chord 2 (+y, length 1): m (0, -3) to (1, 0), mean (0.5, -1.5): right of +y is +x,
  // so +0.5.
  const std::vector<Vec3> path = {{0, 0, 0}, {2, 0, 0.5}, {2, 1, 0.5}};
  const Normals b = {std::array<Vec3, 2>{Vec3(0, 1, 0), Vec3(0, 0, 1)},
                     std::array<Vec3, 2>{Vec3(0, 2, 0), Vec3(0, 1, 0)},
                     std::array<Vec3, 2>{Vec3(-1, 0, 0), Vec3(0, 0, 1)}};
  const CutSideScore s = cut_side_score(path, b);
  EXPECT_DOUBLE_EQ(s.score, 4.5);
  EXPECT_DOUBLE_EQ(s.xy_length, 3);
}

TEST(CutDirection, PocketFloorLoopIsClimbCounterClockwiseAndReversalNegates) {
  // The floor creases of a square pocket [-5, 5]^2 for a ball of radius 1.25: the square of
  // half side 3.75, each side with its wall's normal (pointing into the pocket).
  const double c = 3.75;
  std::vector<Vec3> loop;
  Normals b;
  const Vec2 corners[] = {{-c, -c}, {c, -c}, {c, c}, {-c, c}, {-c, -c}};
  const Vec3 inward[] = {Vec3(0, 1, 0), Vec3(-1, 0, 0), Vec3(0, -1, 0), Vec3(1, 0, 0)};
  for (int side = 0; side < 4; ++side)
    for (int k = 0; k < 10; ++k) {  // counter-clockwise: -y wall, +x wall, +y wall, -x wall
      const Vec2 q = corners[side] + (corners[side + 1] - corners[side]) * (k / 10.0);
      loop.emplace_back(q.x(), q.y(), 0);
      b.push_back(floor_wall(inward[side]));
    }
  loop.push_back(loop.front());
  b.push_back(b.front());
  const CutSideScore s = cut_side_score(loop, b);
  // Every chord has its wall on the right: its length each. But the last chord of each side
  // ends at the corner, where the next wall's vector is averaged in; that one lies along the
  // chord, so the chord counts half: 8c - 4 * (2c / 10) / 2.
  EXPECT_GT(s.score, 0);
  EXPECT_NEAR(s.score, 8 * c - 4 * 0.1 * c, 1e-12);
  EXPECT_EQ(cut_side(s), 1);
  std::reverse(loop.begin(), loop.end());
  std::reverse(b.begin(), b.end());
  const CutSideScore r = cut_side_score(loop, b);
  EXPECT_NEAR(r.score, -s.score, 1e-12);
  EXPECT_EQ(cut_side(r), -1);
}

TEST(CutDirection, NamesRoundTrip) {
  for (CutDirection d : {CutDirection::kAny, CutDirection::kClimb, CutDirection::kConventional}) {
    CutDirection back = CutDirection::kAny;
    ASSERT_TRUE(parse_cut_direction(cut_direction_name(d), back)) << cut_direction_name(d);
    EXPECT_EQ(back, d);
  }
  CutDirection out = CutDirection::kClimb;
  EXPECT_FALSE(parse_cut_direction("Climb", out));
  EXPECT_FALSE(parse_cut_direction("down", out));
  EXPECT_EQ(out, CutDirection::kClimb);
  EXPECT_STREQ(cut_direction_name(CutDirection::kConventional), "conventional");
}

TEST(OrderPaths, FixedPathsAreNeverReversed) {
  // From the end of path 0 at (0, 0, 0), path 1 ends nearest (its back at (1, 0, 0), its
  // front at (5, 0, 0)); path 2 starts at (3, 0, 0).
  const std::vector<std::vector<Vec3>> paths = {
      {{-1, 0, 0}, {0, 0, 0}}, {{5, 0, 0}, {1, 0, 0}}, {{3, 0, 0}, {3, 4, 0}}};
  const std::vector<OrderedPath> free = order_paths(paths);
  ASSERT_EQ(free.size(), 3u);
  EXPECT_EQ(free[1].index, 1u);
  EXPECT_TRUE(free[1].reversed);
  const std::vector<std::uint8_t> fixed = {0, 1, 0};
  const std::vector<OrderedPath> kept = order_paths(paths, fixed);
  ASSERT_EQ(kept.size(), 3u);
  // Path 1 may only be entered at its front (5, 0, 0): path 2's start (3, 0, 0) is nearer.
  EXPECT_EQ(kept[1].index, 2u);
  EXPECT_FALSE(kept[1].reversed);
  EXPECT_EQ(kept[2].index, 1u);
  EXPECT_FALSE(kept[2].reversed);
}

}  // namespace
}  // namespace ncpath
