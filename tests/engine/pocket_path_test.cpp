// Pocket tool paths (engine/pocket_path.*) on the shapes of issue 4, each run through the
// independent checks of pocket_path_checks.hpp; analytic areas; 1-thread vs 2-thread byte
// equality.
#include <gtest/gtest.h>

#include <cstring>
#include <stdexcept>
#include <string>

#include "engine/parallel.hpp"
#include "tests/engine/pocket_path_checks.hpp"

namespace ncpath {
namespace {

using namespace pocket_test;

// --- Shapes of issue 4 --------------------------------------------------------------------------

TEST(PocketPath, RectangleFivePasses) {
  PocketPathParams p = base_params();
  p.stepover = 4;
  p.depth = 10;
  p.stepdown = 2;
  run_case({region_of(test::rectangle(0, 0, 60, 40, true))}, p, 1);
}

TEST(PocketPath, LShape) {
  const std::vector<Region> r = {
      region_of(polygon({{0, 0}, {60, 0}, {60, 20}, {25, 20}, {25, 50}, {0, 50}}, true))};
  run_case(r, base_params(), 1);
}

// Two 40 mm squares joined by a 10 mm wide corridor: one component at level 1, split into
// two from level 2 on.
TEST(PocketPath, DumbbellSplitsAtANeck) {
  const std::vector<Region> r = {region_of(polygon({{0, 0},
                                                    {40, 0},
                                                    {40, 15},
                                                    {60, 15},
                                                    {60, 0},
                                                    {100, 0},
                                                    {100, 40},
                                                    {60, 40},
                                                    {60, 25},
                                                    {40, 25},
                                                    {40, 40},
                                                    {0, 40}},
                                                   true))};
  PocketPathParams p = base_params();
  p.stepover = 4;
  run_case(r, p, 1);
}

TEST(PocketPath, TwoIslandsWithStock) {
  const std::vector<Region> r = {
      region_of(test::rectangle(0, 0, 100, 60, true),
                {test::circle({30, 30}, 8, false), test::rectangle(60, 20, 75, 40, false)})};
  PocketPathParams p = base_params();
  p.stepover = 4;
  p.stock = 0.5;
  run_case(r, p, 1);
}

std::vector<Region> five_islands() {
  std::vector<std::vector<Seg2>> islands;
  for (const Vec2& c : {Vec2(20, 20), Vec2(60, 20), Vec2(100, 20), Vec2(40, 60), Vec2(80, 60)})
    islands.push_back(test::circle(c, 5, false));
  return {region_of(test::rectangle(0, 0, 120, 80, true), islands)};
}

TEST(PocketPath, FiveIslands) {
  PocketPathParams p = base_params();
  p.stepover = 3.5;
  run_case(five_islands(), p, 1);
}

// The same with stepover 4: level 4 lies at d = 15 from the islands, where the offset circles
// of islands 40 mm apart (radius 5 + 15 = 20) touch each other.
TEST(PocketPath, FiveIslandsWhoseOffsetsTouchAtALevel) {
  PocketPathParams p = base_params();
  p.stepover = 4;
  run_case(five_islands(), p, 1);
}

// Islands 3 mm apart with a 6 mm tool: the tool cannot pass between them, their level-1
// loops merge and the gap is unreachable.
TEST(PocketPath, IslandsThatMerge) {
  const std::vector<Region> r = {
      region_of(test::rectangle(0, 0, 100, 60, true),
                {test::circle({40, 30}, 6, false), test::circle({55, 30}, 6, false)})};
  run_case(r, base_params(), 1);
}

TEST(PocketPath, NurbsBlob) {
  PocketPathParams p = base_params();
  p.stepover = 4;
  run_case({nurbs_blob(false, false)}, p, 1);
}

TEST(PocketPath, RationalNurbsBlobWithIsland) {
  PocketPathParams p = base_params();
  p.stepover = 4;
  run_case({nurbs_blob(true, false)}, p, 1);
}

// The NURBS closes at a corner (its start and end): a valid boundary at any tolerance.
TEST(PocketPath, NurbsBlobClosingAtACorner) {
  for (double tol : {0.01, 0.001}) {
    SCOPED_TRACE(tol);
    PocketPathParams p = base_params();
    p.stepover = 4;
    p.tolerance = tol;
    run_case({nurbs_blob(false, true)}, p, 1);
  }
}

// Seed 001: two islands in a boundary, nested loops, two passes.
TEST(PocketPath, SeedOneTwoIslandsTwoPasses) {
  const std::vector<Region> r = {region_of(
      test::rectangle(0, 0, 100, 60, true),
      {test::circle({30, 30}, 10, false), test::rounded_rectangle(55, 15, 85, 45, 5, false)})};
  PocketPathParams p = base_params();
  p.depth = 2;
  p.stepdown = 1;
  run_case(r, p, 1);
}

TEST(PocketPath, TwoSeparateRegionsRetractOnce) {
  const std::vector<Region> r = {region_of(test::rectangle(0, 0, 40, 30, true)),
                                 region_of(test::circle({80, 15}, 15, true))};
  PocketPathParams p = base_params();
  p.depth = 2;
  p.stepdown = 1;
  run_case(r, p, 2);
}

// Stepover = tool diameter on a sharp rectangle: loops at d = 3, 9, 15 leave, before the
// clean-up curves, 4 corner cusps (R^2 - pi R^2 / 4 each) between each pair of consecutive
// loops and the 24 x 4 strip inside the innermost loop; afterwards nothing.
TEST(PocketPath, StepoverEqualToToolDiameter) {
  const std::vector<Region> r = {region_of(test::rectangle(0, 0, 60, 40, true))};
  PocketPathParams p = base_params();
  p.stepover = 6;
  PocketPath out;
  ASSERT_NO_THROW(out = plan_pocket(r, p));
  check_job(r, p, out, 1);
  const double cusp = 9 - 9 * kPi / 4;
  EXPECT_EQ(out.stats.loops, 3u);
  EXPECT_GT(out.stats.cleanup_curves, 0u);
  EXPECT_GT(out.stats.cleanup_length, 0);
  EXPECT_NEAR(out.stats.uncut_area_before, 24 * 4 + 8 * cusp, 1e-3 * (24 * 4 + 8 * cusp));
}

TEST(PocketPath, UnreachableCornersOfARectangle) {
  const std::vector<Region> r = {region_of(test::rectangle(0, 0, 60, 40, true))};
  PocketPathParams p = base_params();
  const PocketPath out = plan_pocket(r, p);
  const double R = p.tool_radius;
  const double corners = 4 * (R * R - kPi * R * R / 4);
  EXPECT_NEAR(out.stats.unreachable_area, corners, 1e-3 * corners);
}

// Signed area swept by the cut moves at the floor around c: > 0 for counter-clockwise.
double turning(const ClChunk& cl, double z, const Vec2& c) {
  double a2 = 0;
  for (const auto& run : test::runs_at_z(cl, z))
    for (std::size_t k = 1; k < run.size(); ++k) {
      const Vec2 u = run[k - 1] - c, v = run[k] - c;
      a2 += u.x() * v.y() - u.y() * v.x();
    }
  return a2 / 2;
}

// Climb milling with an M3 spindle keeps the material on the right of travel: cutting
// outward, the uncut material is outside each loop, so loops run counter-clockwise (the
// usual "climb a pocket counter-clockwise"); conventional reverses them.
TEST(PocketPath, ClimbAndConventionalBothCoverInOppositeDirections) {
  const std::vector<Region> r = {region_of(test::rectangle(0, 0, 60, 40, true))};
  for (CutOrder order : {CutOrder::kOutward, CutOrder::kInward}) {
    SCOPED_TRACE(order == CutOrder::kOutward ? "outward" : "inward");
    PocketPathParams p = base_params();
    p.order = order;
    p.milling = Milling::kClimb;
    const PocketPath climb = plan_pocket(r, p);
    check_job(r, p, climb, 1);
    p.milling = Milling::kConventional;
    const PocketPath conv = plan_pocket(r, p);
    check_job(r, p, conv, 1);
    EXPECT_NE(climb.cl.xyz, conv.cl.xyz);
    const double a = turning(climb.cl, -1, {30, 20}), b = turning(conv.cl, -1, {30, 20});
    EXPECT_LT(a * b, 0) << "climb " << a << ", conventional " << b;
    if (order == CutOrder::kOutward) {
      EXPECT_GT(a, 0);
      EXPECT_LT(b, 0);
    }
  }
}

TEST(PocketPath, InwardAndOutwardBothCover) {
  const std::vector<Region> r = {
      region_of(test::rounded_rectangle(0, 0, 80, 50, 8, true),
                {test::circle({25, 25}, 6, false), test::rectangle(50, 18, 62, 32, false)})};
  PocketPathParams p = base_params();
  p.stepover = 4;
  p.order = CutOrder::kInward;
  const PocketPath inward = plan_pocket(r, p);
  check_job(r, p, inward, 1);
  p.order = CutOrder::kOutward;
  const PocketPath outward = plan_pocket(r, p);
  check_job(r, p, outward, 1);
  EXPECT_NE(inward.cl.xyz, outward.cl.xyz);
}

template <class T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

TEST(PocketPath, OneAndTwoThreadsGiveIdenticalBytes) {
  const std::vector<Region> r = {
      region_of(
          test::rectangle(0, 0, 100, 60, true),
          {test::circle({30, 30}, 10, false), test::rounded_rectangle(55, 15, 85, 45, 5, false)}),
      region_of(test::circle({160, 30}, 25, true)), nurbs_blob(true, false, {240, 40})};
  PocketPathParams p = base_params();
  p.depth = 2;
  p.stepdown = 1;
  p.stepover = 4;
  p.tolerance = 0.01;
  PocketPath one, two;
  {
    par::ThreadLimit limit(1);
    one = plan_pocket(r, p);
  }
  {
    par::ThreadLimit limit(2);
    two = plan_pocket(r, p);
  }
  EXPECT_TRUE(same_bytes(one.cl.xyz, two.cl.xyz));
  EXPECT_TRUE(same_bytes(one.cl.contact, two.cl.contact));
  EXPECT_TRUE(same_bytes(one.cl.path_sizes, two.cl.path_sizes));
  EXPECT_TRUE(same_bytes(one.cl.path_kinds, two.cl.path_kinds));
  EXPECT_EQ(one.stats.loops, two.stats.loops);
  EXPECT_EQ(one.stats.cleanup_curves, two.stats.cleanup_curves);
  EXPECT_EQ(one.stats.cut_length, two.stats.cut_length);
  EXPECT_EQ(one.stats.uncut_area_before, two.stats.uncut_area_before);
  EXPECT_EQ(one.stats.components, 3u);
}

}  // namespace
}  // namespace ncpath
