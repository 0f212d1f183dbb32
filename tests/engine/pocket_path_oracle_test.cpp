// The pocket path oracle can fail (a missed middle, a gouge, a retraction, a small missed
// square are caught), and bad pocket parameters are rejected by name.
#include <gtest/gtest.h>

#include <cstring>
#include <stdexcept>
#include <string>

#include "engine/parallel.hpp"
#include "tests/engine/pocket_path_checks.hpp"

namespace ncpath {
namespace {

using namespace pocket_test;

// --- The oracle itself can fail ---------------------------------------------------------------

ClChunk chunk_of(const std::vector<std::vector<Vec3>>& paths, const std::vector<PathKind>& kinds) {
  ClChunk cl;
  for (std::size_t k = 0; k < paths.size(); ++k) {
    for (const Vec3& q : paths[k]) {
      cl.xyz.insert(cl.xyz.end(), {q.x(), q.y(), q.z()});
      cl.contact.push_back(0);
    }
    cl.path_sizes.push_back(static_cast<std::uint32_t>(paths[k].size()));
    cl.path_kinds.push_back(static_cast<std::uint8_t>(kinds[k]));
  }
  return cl;
}

TEST(PocketPathOracle, SweepOfAPointAndASegmentAreAnalytic) {
  const double r = 3;
  const double disc = test::area(test::sweep({{Vec2(1, 2)}}, r));
  EXPECT_NEAR(disc, kPi * r * r, 2 * kPi * r * test::kOracleArcTol);
  const double stadium = test::area(test::sweep({{Vec2(0, 0), Vec2(10, 0)}}, r));
  EXPECT_NEAR(stadium, kPi * r * r + 10 * 2 * r, 2 * kPi * r * test::kOracleArcTol);
}

TEST(PocketPathOracle, NurbsEvaluationMatchesAnExactRationalCircle) {
  const double w = std::sqrt(0.5);
  Nurbs2 c;  // rational quadratic full circle of radius 10
  c.degree = 2;
  c.ctrl = {{10, 0},    {10, 10}, {0, 10},   {-10, 10}, {-10, 0},
            {-10, -10}, {0, -10}, {10, -10}, {10, 0}};
  c.weights = {1, w, 1, w, 1, w, 1, w, 1};
  c.knots = {0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 4};
  for (double t = 0; t <= 4; t += 0.01) EXPECT_NEAR(test::nurbs_eval(c, t).norm(), 10, 1e-12);
  std::vector<Vec2> pts;
  test::append_nurbs_points(c, test::kOracleChord, pts);
  const double a = test::area({test::to_clip(pts)});
  EXPECT_NEAR(a, kPi * 100, 2 * kPi * 10 * test::kOracleChord);
}

// A single loop at the tool radius in a 20 x 20 square leaves the middle uncut; the same
// loop shifted by 1 mm gouges the wall; a retraction between two cuts is counted once.
TEST(PocketPathOracle, DetectsUncutMiddleGougeAndRetraction) {
  const std::vector<Region> regions = {region_of(test::rectangle(0, 0, 20, 20, true))};
  const std::vector<Vec3> loop = {{3, 3, -1}, {3, 17, -1}, {17, 17, -1}, {17, 3, -1}, {3, 3, -1}};
  const test::clip::Paths reachable =
      test::offset_closed(test::offset_closed(test::region_paths(regions), -3), 3);
  const ClChunk one = chunk_of({loop}, {PathKind::kCut});
  const double missed =
      test::area(test::difference(reachable, test::sweep(test::runs_at_z(one, -1), 3)));
  EXPECT_NEAR(missed, 8 * 8, 0.01);
  std::vector<Vec3> shifted = loop;
  for (Vec3& q : shifted) q.x() += 1;
  const ClChunk two = chunk_of({shifted}, {PathKind::kCut});
  const double outside = test::area(
      test::difference(test::sweep(test::feed_polylines(two), 3), test::region_paths(regions)));
  // The band x in [20, 21] beside the loop's right side, plus the caps' circular segments.
  EXPECT_NEAR(outside, 14 + 9 * std::acos(2.0 / 3) - 2 * std::sqrt(5.0), 0.01);
  const ClChunk three = chunk_of({{{3, 3, 5}, {3, 3, -1}},
                                  loop,
                                  {{3, 3, -1}, {3, 3, 5}},
                                  {{3, 3, 5}, {5, 5, 5}},
                                  {{5, 5, 5}, {5, 5, -1}},
                                  {{5, 5, -1}, {5, 5, 5}}},
                                 {PathKind::kRapid, PathKind::kCut, PathKind::kRapid,
                                  PathKind::kRapid, PathKind::kCut, PathKind::kRapid});
  EXPECT_EQ(test::count_retractions(three, 5), 1u);
}

// One loop at the tool radius in a 12.2 mm square misses a 0.2 x 0.2 mm square in the middle:
// 0.04 mm^2, below the area bound of the square's walls, but the erosion by twice the band
// keeps it.
TEST(PocketPathOracle, ErosionKeepsASmallMissedSquare) {
  const std::vector<Region> regions = {region_of(test::rectangle(0, 0, 12.2, 12.2, true))};
  const PocketPathParams p = base_params();
  const std::vector<Vec3> loop = {
      {3, 3, -1}, {3, 9.2, -1}, {9.2, 9.2, -1}, {9.2, 3, -1}, {3, 3, -1}};
  const test::clip::Paths reachable =
      test::offset_closed(test::offset_closed(test::region_paths(regions), -3), 3);
  const test::clip::Paths missed = test::difference(
      reachable, test::sweep(test::runs_at_z(chunk_of({loop}, {PathKind::kCut}), -1), 3));
  EXPECT_NEAR(test::area(missed), 0.04, 1e-4);
  EXPECT_LT(test::area(missed), area_bound(regions, p));
  const double w = 2 * distance_band(regions, p);
  EXPECT_NEAR(test::area(test::offset_closed(missed, -w)), (0.2 - 2 * w) * (0.2 - 2 * w), 1e-4);
}

// --- Bad input ----------------------------------------------------------------------------------

void expect_invalid(const std::vector<Region>& r, const PocketPathParams& p,
                    const std::string& mention) {
  try {
    plan_pocket(r, p);
    ADD_FAILURE() << "no exception; expected one mentioning \"" << mention << "\"";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(mention), std::string::npos) << e.what();
  }
}

TEST(PocketPath, BadParametersAreRejectedByName) {
  const std::vector<Region> r = {region_of(test::rectangle(0, 0, 60, 40, true))};
  EXPECT_EQ(validate(base_params()), "");
  struct Bad {
    const char* mention;
    void (*set)(PocketPathParams&);
  };
  const Bad bad[] = {
      {"stepover", [](PocketPathParams& p) { p.stepover = 0; }},
      {"stepover", [](PocketPathParams& p) { p.stepover = -1; }},
      {"stepover", [](PocketPathParams& p) { p.stepover = 6.01; }},  // > 2 R
      {"depth", [](PocketPathParams& p) { p.depth = 0; }},
      {"depth", [](PocketPathParams& p) { p.depth = -2; }},
      {"stock", [](PocketPathParams& p) { p.stock = -0.1; }},
      {"tool", [](PocketPathParams& p) { p.tool_radius = 0; }},
      {"safe_z", [](PocketPathParams& p) { p.safe_z = p.top + p.clearance - 0.1; }},
      {"stepdown", [](PocketPathParams& p) { p.stepdown = -1; }},
      {"ramp", [](PocketPathParams& p) { p.ramp_angle_deg = 0; }},
      {"ramp", [](PocketPathParams& p) { p.ramp_angle_deg = 90; }},
  };
  for (const Bad& b : bad) {
    PocketPathParams p = base_params();
    b.set(p);
    SCOPED_TRACE(b.mention);
    const std::string msg = validate(p);
    EXPECT_NE(msg.find(b.mention), std::string::npos) << "validate: \"" << msg << "\"";
    expect_invalid(r, p, b.mention);
  }
  PocketPathParams ok = base_params();
  ok.stepover = 6;  // = 2 R: allowed
  EXPECT_EQ(validate(ok), "");
}

TEST(PocketPath, ToolLargerThanThePocketDoesNotFit) {
  const std::vector<Region> r = {region_of(test::rectangle(0, 0, 60, 40, true)),
                                 region_of(test::rectangle(100, 0, 104, 4, true))};
  expect_invalid(r, base_params(), "does not fit");
  expect_invalid(r, base_params(), "region 1");  // the second one, counted from 0
}

}  // namespace
}  // namespace ncpath
