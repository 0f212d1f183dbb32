// Pocket tool paths (engine/pocket_path.*) against independent oracles: the area the tool
// disc sweeps along the CL polylines at each depth pass, as Clipper computes it, must cover
// the region the tool can reach (the opening of the pocket by the tool radius) and stay
// inside the pocket minus the stock; plus invariants read straight off the ClChunk
// (continuity, heights, lengths, retractions, descent angle), analytic areas, bad input and
// 1-thread vs 2-thread byte equality. Nothing here uses kernels/pocket geometry as an oracle.
#include "engine/pocket_path.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>
#include <set>
#include <stdexcept>
#include <string>

#include "engine/parallel.hpp"
#include "tests/support/pocket_oracle.hpp"
#include "tests/support/shapes2d.hpp"

namespace ncpath {
namespace {

using test::ClPath;

constexpr double kPi = std::numbers::pi;
constexpr double kZEps = 1e-9;        // mm: heights are computed, not measured
constexpr double kJoinEps = 1e-9;     // mm: consecutive paths share their end points
constexpr double kUncutAfter = 1e-4;  // mm^2: "no uncut area" after the clean-up curves
constexpr double kWideArea = 1e-4;    // mm^2: what may survive the erosion of a sliver
constexpr double kSampleStep = 0.02;  // mm between point tests along entries
constexpr double kLengthRel = 1e-3;   // stats lengths vs polyline lengths (chords vs arcs)

// --- Input shapes --------------------------------------------------------------------------------

// Closed polygon of lines, oriented clockwise (cw = true) or counter-clockwise.
std::vector<Seg2> polygon(std::vector<Vec2> pts, bool cw) {
  double a2 = 0;
  for (std::size_t k = 0; k < pts.size(); ++k) {
    const Vec2& p = pts[k];
    const Vec2& q = pts[(k + 1) % pts.size()];
    a2 += p.x() * q.y() - q.x() * p.y();
  }
  if ((a2 < 0) != cw) std::reverse(pts.begin(), pts.end());
  std::vector<Seg2> segs;
  for (std::size_t k = 0; k < pts.size(); ++k)
    segs.push_back(make_line(pts[k], pts[(k + 1) % pts.size()]));
  return segs;
}

Region region_of(const std::vector<Seg2>& boundary,
                 const std::vector<std::vector<Seg2>>& islands = {}) {
  Region r;
  r.boundary = profile_of(boundary);
  for (const auto& i : islands) r.islands.push_back(profile_of(i));
  return r;
}

// A closed clamped cubic NURBS blob: a wavy ring around c0, clockwise, radius 25 to 35;
// rational and with a circular island when `rational`. The clamped ends meet at a corner
// (the first and last legs of the control polygon are not collinear) when `corner`, else the
// curve starts in the middle of a leg and closes smoothly (G1).
Region nurbs_blob(bool rational, bool corner, const Vec2& c0 = Vec2(40, 40)) {
  Nurbs2 c;
  c.degree = 3;
  const int n = 24;
  for (int k = 0; k < n; ++k) {
    const double a = -2 * kPi * k / n;  // clockwise
    const double r = 30 + 5 * std::sin(3 * a);
    c.ctrl.emplace_back(c0.x() + r * std::cos(a), c0.y() + r * std::sin(a));
  }
  if (!corner) c.ctrl.insert(c.ctrl.begin(), 0.5 * (c.ctrl.front() + c.ctrl.back()));
  c.ctrl.push_back(c.ctrl.front());  // clamped ends meet: closed
  for (std::size_t k = 0; k < c.ctrl.size(); ++k)
    c.weights.push_back(rational && k > 0 && k + 1 < c.ctrl.size() ? 1.0 + 0.6 * std::sin(1.7 * k)
                                                                   : 1.0);
  const std::size_t m = c.ctrl.size();
  c.knots.assign(4, 0.0);  // clamped uniform on [0, 1]
  for (std::size_t k = 1; k + 3 < m; ++k) c.knots.push_back(static_cast<double>(k) / (m - 3));
  c.knots.insert(c.knots.end(), 4, 1.0);
  Region r;
  r.boundary.nurbs.push_back(c);
  r.boundary.curves.push_back({make_line(c.ctrl.front(), c.ctrl.back()), 0});
  if (rational) r.islands.push_back(profile_of(test::circle(c0, 6, false)));
  return r;
}

PocketPathParams base_params() {
  PocketPathParams p;
  p.tool_radius = 3;
  p.stepover = 3;
  p.chordal_tolerance = 1e-3;
  p.tolerance = 1e-3;
  p.top = 0;
  p.depth = 1;
  p.stepdown = 0;
  p.clearance = 1;
  p.safe_z = 5;
  return p;
}

// --- Checks -----------------------------------------------------------------------------------

double total_perimeter(const std::vector<Region>& regions) {
  double len = 0;
  for (const Region& r : regions) {
    len += test::profile_length(r.boundary);
    for (const Profile& i : r.islands) len += test::profile_length(i);
  }
  return len;
}

// Distance, mm, by which the swept or the reference boundaries may move along a wall: the CL
// polylines (chords within chordal_tolerance of the exact arcs), the engine's NURBS-to-arcs
// conversion (within tolerance), the oracle's discretised input (kOracleChord) and Clipper's
// inscribed round joins (kOracleArcTol).
double distance_band(const std::vector<Region>& regions, const PocketPathParams& p) {
  bool nurbs = false;
  for (const Region& r : regions) nurbs = nurbs || !r.boundary.nurbs.empty();
  return p.chordal_tolerance + test::kOracleChord + test::kOracleArcTol + (nurbs ? p.tolerance : 0);
}

// Area bound for the Clipper comparisons, mm^2: the band above along every wall, twice (chords
// on both sides of an arc), plus integer rounding at 1 nm.
double area_bound(const std::vector<Region>& regions, const PocketPathParams& p) {
  return 2 * distance_band(regions, p) * total_perimeter(regions) + 1e-4;
}

std::vector<double> pass_levels(const PocketPathParams& p) {
  const int n = p.stepdown > 0 ? static_cast<int>(std::ceil(p.depth / p.stepdown - 1e-9)) : 1;
  std::vector<double> z;
  for (int k = 1; k <= n; ++k)
    z.push_back(p.top - (k == n ? p.depth : std::min(k * p.stepdown, p.depth)));
  return z;
}

void check_structure(const ClChunk& cl) {
  ASSERT_EQ(cl.path_sizes.size(), cl.path_kinds.size());
  std::size_t points = 0;
  for (std::uint32_t n : cl.path_sizes) {
    EXPECT_GE(n, 2u) << "a path of fewer than 2 points";
    points += n;
  }
  ASSERT_EQ(cl.xyz.size(), 3 * points);
  EXPECT_EQ(cl.contact.size(), points);
  for (std::uint8_t k : cl.path_kinds) EXPECT_LE(k, 2u);
  for (double v : cl.xyz) ASSERT_TRUE(std::isfinite(v));
}

// Each path starts where the previous one ended.
void check_continuity(const ClChunk& cl) {
  const std::vector<ClPath> paths = test::cl_paths(cl);
  for (std::size_t k = 1; k < paths.size(); ++k) {
    const Vec3 end = test::cl_point(cl, paths[k - 1].first + paths[k - 1].size - 1);
    const Vec3 start = test::cl_point(cl, paths[k].first);
    EXPECT_LE((end - start).norm(), kJoinEps) << "path " << k << " starts at " << start.transpose()
                                              << ", previous ended at " << end.transpose();
  }
}

// Heights: feed moves between the floor and the clearance plane, horizontal feed moves in
// the material only at pass levels (and every pass level cut), rapids horizontal only at
// safe_z and never descending below the clearance plane.
void check_heights(const ClChunk& cl, const PocketPathParams& p) {
  const std::vector<double> levels = pass_levels(p);
  const double floor = p.top - p.depth;
  std::set<std::size_t> levels_cut;
  bool rapid_at_safe = false;
  for (const ClPath& path : test::cl_paths(cl)) {
    for (std::size_t i = path.first; i < path.first + path.size; ++i) {
      const Vec3 q = test::cl_point(cl, i);
      if (test::is_feed(path.kind)) {
        EXPECT_GE(q.z(), floor - kZEps) << "feed point below the floor: " << q.transpose();
        EXPECT_LE(q.z(), p.top + p.clearance + kZEps)
            << "feed point above the clearance plane: " << q.transpose();
      } else {
        rapid_at_safe = rapid_at_safe || q.z() >= p.safe_z - kZEps;
        EXPECT_LE(q.z(), p.safe_z + kZEps) << q.transpose();
      }
      if (i == path.first) continue;
      const Vec3 a = test::cl_point(cl, i - 1);
      const double dxy = std::hypot(q.x() - a.x(), q.y() - a.y());
      if (test::is_feed(path.kind)) {
        if (std::abs(q.z() - a.z()) > kZEps || dxy <= kZEps || q.z() > p.top + kZEps) continue;
        bool at_level = false;
        for (std::size_t l = 0; l < levels.size(); ++l)
          if (std::abs(q.z() - levels[l]) <= kZEps) {
            at_level = true;
            levels_cut.insert(l);
          }
        EXPECT_TRUE(at_level) << "horizontal feed move at z = " << q.z()
                              << ", not a pass level, at " << q.transpose();
      } else {
        if (dxy > kZEps) {
          EXPECT_TRUE(a.z() >= p.safe_z - kZEps && q.z() >= p.safe_z - kZEps)
              << "rapid across the stock below safe_z: " << a.transpose() << " -> "
              << q.transpose();
        }
        if (q.z() < a.z() - kZEps) {
          EXPECT_GE(q.z(), p.top + p.clearance - kZEps)
              << "rapid descending below the clearance plane to " << q.transpose();
        }
      }
    }
  }
  EXPECT_TRUE(rapid_at_safe) << "no rapid reaches safe_z";
  EXPECT_EQ(levels_cut.size(), levels.size()) << "some pass level has no horizontal cut";
}

// Without plunge entries, the tool never descends into uncut material steeper than the
// ramp angle. Material below the lowest height reached since the last rapid is uncut (a
// descent through what earlier passes cleared may be steep).
void check_descent(const ClChunk& cl, const PocketPathParams& p, const PocketPathStats& s) {
  if (s.plunge_entries > 0) return;
  const double slope = std::tan(p.ramp_angle_deg * kPi / 180) * 1.01;  // chords vs helix
  double cleared = p.top;
  for (const ClPath& path : test::cl_paths(cl)) {
    if (!test::is_feed(path.kind)) {
      cleared = p.top;
      continue;
    }
    for (std::size_t i = path.first + 1; i < path.first + path.size; ++i) {
      const Vec3 a = test::cl_point(cl, i - 1), b = test::cl_point(cl, i);
      const double into = std::min(a.z(), cleared) - b.z();
      if (into > kZEps) {
        const double dxy = std::hypot(b.x() - a.x(), b.y() - a.y());
        EXPECT_LE(into, slope * dxy + kZEps)
            << "descent steeper than " << p.ramp_angle_deg << " deg: " << a.transpose() << " -> "
            << b.transpose();
      }
      cleared = std::min(cleared, b.z());
    }
  }
}

void check_lengths(const ClChunk& cl, const PocketPathStats& s) {
  double cut = 0, link = 0, rapid = 0;
  for (const ClPath& path : test::cl_paths(cl)) {
    const double len = test::path_length(cl, path);
    (path.kind == PathKind::kCut ? cut : path.kind == PathKind::kLinkAtDepth ? link : rapid) += len;
  }
  EXPECT_NEAR(s.cut_length + s.link_length, cut + link, kLengthRel * (cut + link) + 1e-6);
  EXPECT_NEAR(s.cut_length, cut, kLengthRel * cut + 1e-6);
  EXPECT_NEAR(s.link_length, link, kLengthRel * link + 1e-6);
  EXPECT_NEAR(s.rapid_length, rapid, kLengthRel * rapid + 1e-6);
  EXPECT_LE(s.cleanup_length, s.cut_length + s.link_length + 1e-6);
}

// Coverage at every pass and containment of all feed moves, against Clipper.
void check_areas(const std::vector<Region>& regions, const PocketPathParams& p,
                 const PocketPath& out) {
  const double R = p.tool_radius;
  const double bound = area_bound(regions, p);
  const test::clip::Paths region = test::region_paths(regions);
  const test::clip::Paths allowed = test::offset_closed(region, -p.stock);
  const test::clip::Paths centres = test::offset_closed(region, -(R + p.stock));
  const test::clip::Paths reachable = test::offset_closed(centres, R);
  // Two measures each: the area (bounded by the band along the walls) and what is left after
  // eroding by twice the band: slivers along the walls vanish, a missed or gouged spot of any
  // real width does not (an uncut corner cusp of 0.4 mm^2 is far below the area bound of a
  // 60 x 40 rectangle but survives the erosion).
  // Containment is checked pass by pass on the swept area, and for the moves between pass
  // levels (entries) by point tests against the region the tool centre may reach.
  const double w = 2 * distance_band(regions, p);
  const std::vector<double> levels = pass_levels(p);
  for (double z : levels) {
    const auto runs = test::runs_at_z(out.cl, z);
    ASSERT_FALSE(runs.empty()) << "nothing cut at z = " << z;
    const test::clip::Paths swept = test::sweep(runs, R);
    const test::clip::Paths missed = test::difference(reachable, swept);
    EXPECT_LE(test::area(missed), bound) << "reachable area not swept at z = " << z
                                         << " (reachable " << test::area(reachable) << " mm^2)";
    EXPECT_LE(test::area(test::offset_closed(missed, -w)), kWideArea)
        << "a reachable spot wider than " << 2 * w << " mm is not swept at z = " << z;
    const test::clip::Paths outside = test::difference(swept, allowed);
    EXPECT_LE(test::area(outside), bound) << "the tool leaves the pocket minus stock at z = " << z;
    EXPECT_LE(test::area(test::offset_closed(outside, -w)), kWideArea)
        << "the tool gouges deeper than " << 2 * w << " mm at z = " << z;
  }
  const double out_by =
      test::max_outside(centres, test::runs_between_levels(out.cl, levels), kSampleStep);
  EXPECT_LE(out_by, 2 * distance_band(regions, p))
      << "an entry or a move between passes leaves the pocket minus stock by " << out_by << " mm";
  if (p.stock == 0) {
    // stock 0: the unreachable material is the pocket minus its opening.
    const double unreachable = test::area(region) - test::area(reachable);
    EXPECT_NEAR(out.stats.unreachable_area, unreachable, bound);
  }
}

// Every check of this file on one job; `components` is what the test expects (and is
// checked against Clipper's erosion too).
void check_job(const std::vector<Region>& regions, const PocketPathParams& p, const PocketPath& out,
               std::size_t components) {
  const PocketPathStats& s = out.stats;
  const test::clip::Paths eroded =
      test::offset_closed(test::region_paths(regions), -(p.tool_radius + p.stock));
  ASSERT_EQ(test::outer_count(eroded), components) << "the test's expectation is wrong";
  check_structure(out.cl);
  if (::testing::Test::HasFatalFailure()) return;
  EXPECT_EQ(s.open_fragments, 0u);
  EXPECT_EQ(s.components, components);
  EXPECT_EQ(s.retractions, components - 1);
  EXPECT_EQ(test::count_retractions(out.cl, p.safe_z), components - 1);
  EXPECT_EQ(s.depth_passes, pass_levels(p).size());
  EXPECT_GE(s.loops, components);
  EXPECT_GE(s.levels, 1u);
  // A tree over the loops of each component: one link fewer than loops.
  EXPECT_EQ(s.links, s.loops - s.components);
  const std::uint64_t entries = s.helix_entries + s.ramp_entries + s.plunge_entries;
  EXPECT_GE(entries, components);
  EXPECT_LE(entries, components * s.depth_passes);
  EXPECT_LE(s.uncut_area_after, kUncutAfter);
  EXPECT_GE(s.uncut_area_before, s.uncut_area_after);
  EXPECT_GE(s.slotting_length, 0);
  EXPECT_LE(s.slotting_length, s.cut_length + 1e-9);
  check_continuity(out.cl);
  check_heights(out.cl, p);
  check_descent(out.cl, p, s);
  check_lengths(out.cl, s);
  check_areas(regions, p, out);
}

void run_case(const std::vector<Region>& regions, const PocketPathParams& p,
              std::size_t components) {
  PocketPath out;
  ASSERT_NO_THROW(out = plan_pocket(regions, p));
  check_job(regions, p, out, components);
}

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
