// Pocket offsets through the engine: analytic levels and areas, identical results for any
// thread count.
#include "engine/pocket_offset.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "engine/parallel.hpp"
#include "tests/support/shapes2d.hpp"

namespace ncpath {
namespace {

Profile profile_of(const std::vector<Seg2>& segs) {
  Profile p;
  for (const Seg2& s : segs) p.curves.push_back({s, -1});
  return p;
}

TEST(PocketOffset, RectangleLevelsAndAreas) {
  Region r;
  r.boundary = profile_of(test::rectangle(0, 0, 100, 60, true));
  PocketOffsetParams p;
  p.tool_radius = 3;
  p.stepover = 2;
  const PocketOffsetResult res = offset_pocket({r}, p);
  // d_k = 3 + 2 (k - 1) < 30: 14 levels, one loop each.
  ASSERT_EQ(res.loops.size(), 14u);
  EXPECT_EQ(res.levels, 14u);
  for (std::size_t k = 0; k < res.loops.size(); ++k) {
    const double d = 3 + 2.0 * k;
    EXPECT_EQ(res.loops[k].level, k + 1);
    EXPECT_NEAR(-res.loops[k].loop.area2 / 2, (100 - 2 * d) * (60 - 2 * d), 1e-9);
    if (k > 0) EXPECT_EQ(res.loops[k].loop.parents, std::vector<std::uint32_t>{std::uint32_t(k - 1)});
  }
}

TEST(PocketOffset, StockIsLeftOnWallsAndIslands) {
  Region r;
  r.boundary = profile_of(test::circle({0, 0}, 50, true));
  r.islands.push_back(profile_of(test::circle({0, 0}, 10, false)));
  PocketOffsetParams p;
  p.tool_radius = 4;
  p.stock = 0.5;
  p.stepover = 100;  // one level
  const PocketOffsetResult res = offset_pocket({r}, p);
  ASSERT_EQ(res.loops.size(), 2u);
  const double pi = std::numbers::pi;
  EXPECT_NEAR(res.loops[0].loop.area2 / 2 + res.loops[1].loop.area2 / 2,
              -pi * 45.5 * 45.5 + pi * 14.5 * 14.5, 1e-9);
}

TEST(PocketOffset, OneAndManyThreadsGiveTheSameLoops) {
  std::vector<Region> regions(3);
  regions[0].boundary = profile_of(test::rounded_rectangle(0, 0, 120, 80, 10, true));
  regions[0].islands.push_back(profile_of(test::circle({30, 40}, 8, false)));
  regions[0].islands.push_back(profile_of(test::circle({90, 40}, 8, false)));
  regions[1].boundary = profile_of(test::slot(60, 15, true));
  regions[2].boundary = profile_of(test::circle({300, 0}, 40, true));
  PocketOffsetParams p;
  p.tool_radius = 2;
  p.stepover = 1.5;
  PocketOffsetResult one, many;
  {
    par::ThreadLimit limit(1);
    one = offset_pocket(regions, p);
  }
  {
    par::ThreadLimit limit(4);
    many = offset_pocket(regions, p);
  }
  ASSERT_EQ(one.loops.size(), many.loops.size());
  for (std::size_t k = 0; k < one.loops.size(); ++k) {
    EXPECT_EQ(one.loops[k].loop.parents, many.loops[k].loop.parents);
    ASSERT_EQ(one.loops[k].loop.segs.size(), many.loops[k].loop.segs.size());
    for (std::size_t s = 0; s < one.loops[k].loop.segs.size(); ++s) {
      EXPECT_EQ(one.loops[k].loop.segs[s].a, many.loops[k].loop.segs[s].a);
      EXPECT_EQ(one.loops[k].loop.segs[s].b, many.loops[k].loop.segs[s].b);
    }
  }
  EXPECT_EQ(one.open_fragments, 0u);
}

}  // namespace
}  // namespace ncpath
