#pragma once
// Shared by the pocket path tests (pocket_path_test.cpp: the shapes of issue 4;
// pocket_path_oracle_test.cpp: the oracle's own tests and bad input): input shapes, and the
// checks every case runs against independent oracles — the area the tool disc sweeps along
// the CL polylines at each depth pass, as Clipper computes it, must cover the region the
// tool can reach (the opening of the pocket by the tool radius) and stay inside the pocket
// minus the stock; plus invariants read straight off the ClChunk (continuity, heights,
// lengths, retractions, descent angle). Nothing here uses kernels/pocket geometry as an
// oracle.
#include "engine/pocket_path.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>
#include <set>
#include <stdexcept>
#include <string>

#include "tests/support/pocket_oracle.hpp"
#include "tests/support/shapes2d.hpp"

namespace ncpath::pocket_test {

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
inline std::vector<Seg2> polygon(std::vector<Vec2> pts, bool cw) {
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

inline Region region_of(const std::vector<Seg2>& boundary,
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
inline Region nurbs_blob(bool rational, bool corner, const Vec2& c0 = Vec2(40, 40)) {
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

inline PocketPathParams base_params() {
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

inline double total_perimeter(const std::vector<Region>& regions) {
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
inline double distance_band(const std::vector<Region>& regions, const PocketPathParams& p) {
  bool nurbs = false;
  for (const Region& r : regions) nurbs = nurbs || !r.boundary.nurbs.empty();
  return p.chordal_tolerance + test::kOracleChord + test::kOracleArcTol + (nurbs ? p.tolerance : 0);
}

// Area bound for the Clipper comparisons, mm^2: the band above along every wall, twice (chords
// on both sides of an arc), plus integer rounding at 1 nm.
inline double area_bound(const std::vector<Region>& regions, const PocketPathParams& p) {
  return 2 * distance_band(regions, p) * total_perimeter(regions) + 1e-4;
}

inline std::vector<double> pass_levels(const PocketPathParams& p) {
  const int n = p.stepdown > 0 ? static_cast<int>(std::ceil(p.depth / p.stepdown - 1e-9)) : 1;
  std::vector<double> z;
  for (int k = 1; k <= n; ++k)
    z.push_back(p.top - (k == n ? p.depth : std::min(k * p.stepdown, p.depth)));
  return z;
}

inline void check_structure(const ClChunk& cl) {
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
inline void check_continuity(const ClChunk& cl) {
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
inline void check_heights(const ClChunk& cl, const PocketPathParams& p) {
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
inline void check_descent(const ClChunk& cl, const PocketPathParams& p, const PocketPathStats& s) {
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

inline void check_lengths(const ClChunk& cl, const PocketPathStats& s) {
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
inline void check_areas(const std::vector<Region>& regions, const PocketPathParams& p,
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
inline void check_job(const std::vector<Region>& regions, const PocketPathParams& p,
                      const PocketPath& out, std::size_t components) {
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

inline void run_case(const std::vector<Region>& regions, const PocketPathParams& p,
                     std::size_t components) {
  PocketPath out;
  ASSERT_NO_THROW(out = plan_pocket(regions, p));
  check_job(regions, p, out, components);
}

}  // namespace ncpath::pocket_test
