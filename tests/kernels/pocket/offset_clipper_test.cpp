// Independent oracle: the area inside the exact offset loops equals the area of the region
// eroded by d as Clipper (Debian's libpolyclipping, used only in tests) computes it on a
// finely discretised copy of the input, within a bound that follows from the
// discretisation.
#include <gtest/gtest.h>

#include <clipper.hpp>
#include <numbers>
#include <random>

#include "kernels/curves/nurbs.hpp"
#include "kernels/pocket/offset.hpp"
#include "kernels/pocket/offset_levels.hpp"
#include "kernels/pocket/uncut.hpp"
#include "tests/support/shapes2d.hpp"

namespace ncpath {
namespace {

constexpr double kScale = 1e6;   // Clipper works in integers: 1 unit = 1 nm
constexpr double kChord = 1e-4;  // mm: discretisation of arcs for Clipper

ClipperLib::Path to_path(const std::vector<Seg2>& loop, double chord) {
  ClipperLib::Path path;
  std::vector<Vec2> pts;
  for (const Seg2& s : loop) append_polyline(s, chord, pts);
  for (const Vec2& p : pts)
    path.emplace_back(static_cast<ClipperLib::cInt>(std::llround(p.x() * kScale)),
                      static_cast<ClipperLib::cInt>(std::llround(p.y() * kScale)));
  return path;
}

double clipper_eroded_area(const std::vector<std::vector<Seg2>>& loops, double d,
                           double chord = kChord) {
  ClipperLib::Paths in;
  for (const auto& l : loops) in.push_back(to_path(l, chord));
  // Union first (orientation-independent), then offset the result inwards.
  ClipperLib::Clipper c;
  c.AddPaths(in, ClipperLib::ptSubject, true);
  ClipperLib::Paths region;
  c.Execute(ClipperLib::ctUnion, region, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
  ClipperLib::ClipperOffset off;
  off.ArcTolerance = chord * kScale;
  off.AddPaths(region, ClipperLib::jtRound, ClipperLib::etClosedPolygon);
  ClipperLib::Paths out;
  off.Execute(out, -d * kScale);
  double a = 0;
  for (const auto& p : out) a += ClipperLib::Area(p);
  return a / (kScale * kScale);
}

double exact_area(const OffsetResult& r) {
  double a = 0;
  for (const OffsetLoop& l : r.loops) a += -l.area2 / 2;  // pockets are clockwise
  return a;
}

// Region of the input: our loops are clockwise boundaries and counter-clockwise islands;
// Clipper's union with the non-zero rule needs the islands as holes, i.e. opposite to the
// boundary: reverse everything so the boundary is counter-clockwise.
std::vector<std::vector<Seg2>> for_clipper(const std::vector<std::vector<Seg2>>& loops) {
  return reversed_loops(loops);
}

void expect_matches_clipper(const std::vector<std::vector<Seg2>>& loops, double d) {
  double perimeter = 0;
  for (const auto& l : loops) perimeter += loop_length(l);
  const OffsetResult r = offset_loops(loops, d);
  EXPECT_EQ(r.stats.open_fragments, 0u);
  const double oracle = clipper_eroded_area(for_clipper(loops), d);
  // Chords of kChord inside arcs on both sides, plus integer rounding: a band of a few
  // kChord along the boundary.
  const double bound = 4 * kChord * perimeter + 1e-6;
  EXPECT_NEAR(exact_area(r), oracle, bound) << "d = " << d;
}

TEST(OffsetVsClipper, RoundedRectangleWithIslands) {
  const std::vector<std::vector<Seg2>> loops = {
      test::rounded_rectangle(0, 0, 150, 90, 12, true), test::circle({40, 45}, 10, false),
      test::rectangle(90, 20, 110, 70, false), test::circle({130, 20}, 4, false)};
  for (double d : {1.0, 4.5, 9.0, 14.0, 21.0, 30.0}) expect_matches_clipper(loops, d);
}

// Random star-shaped pockets of lines and arcs (bulges), with a random island.
TEST(OffsetVsClipper, RandomBulgePolygons) {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> R(40, 60), B(-0.3, 0.3), U(0, 1);
  for (int trial = 0; trial < 12; ++trial) {
    const int n = 5 + trial;
    std::vector<Vec2> pts;
    for (int k = 0; k < n; ++k) {
      const double a = -2 * std::numbers::pi * (k + 0.3 * U(rng)) / n;  // clockwise
      const double r = R(rng);
      pts.emplace_back(r * std::cos(a), r * std::sin(a));
    }
    std::vector<Seg2> loop;
    for (int k = 0; k < n; ++k)
      loop.push_back(make_bulge_segment(pts[k], pts[(k + 1) % n], B(rng)));
    std::vector<std::vector<Seg2>> loops = {loop};
    if (trial % 2 == 0) loops.push_back(test::circle({5 * U(rng), 5 * U(rng)}, 6, false));
    for (double d : {2.0, 7.5, 15.0}) expect_matches_clipper(loops, d);
  }
}

// Robustness cases of issue 3: tangent islands, an island touching the boundary, a
// near-full arc, a run of nearly equal arcs. Each must close and match Clipper.
TEST(OffsetVsClipper, TangentIslandsAndIslandOnBoundary) {
  const std::vector<std::vector<Seg2>> tangent = {
      test::rectangle(0, 0, 100, 60, true), test::circle({40, 30}, 5, false),
      test::circle({50, 30}, 5, false)};  // the islands touch at (45, 30)
  for (double d : {0.5, 2.0, 6.0}) expect_matches_clipper(tangent, d);
  const std::vector<std::vector<Seg2>> touching = {
      test::rectangle(0, 0, 100, 60, true), test::circle({50, 8}, 8, false)};  // touches y = 0
  for (double d : {0.5, 3.0, 12.0}) expect_matches_clipper(touching, d);
}

TEST(OffsetVsClipper, NearFullArcAndNearlyEqualArcs) {
  // A "D": an arc of 359.8 degrees closed by its short chord.
  const double a0 = 0.1 * std::numbers::pi / 180;
  const Vec2 p(30 * std::cos(a0), 30 * std::sin(a0)), q(30 * std::cos(-a0), 30 * std::sin(-a0));
  const std::vector<Seg2> d_shape = {make_arc(p, q, {0, 0}, true), make_line(q, p)};
  std::vector<Seg2> cw;
  for (auto it = d_shape.rbegin(); it != d_shape.rend(); ++it) cw.push_back(reversed(*it));
  for (double d : {0.5, 5.0, 20.0}) expect_matches_clipper({cw}, d);
  // A circle of radius 40 made of 90 arcs whose centres wander by 1e-9 mm.
  std::vector<Seg2> wobbly;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> J(-1e-9, 1e-9);
  Vec2 start(40, 0), prev = start;
  for (int k = 1; k <= 90; ++k) {
    const double a = -2 * std::numbers::pi * k / 90;  // clockwise
    const Vec2 c(J(rng), J(rng));
    const Vec2 next = k == 90 ? start : Vec2(40 * std::cos(a), 40 * std::sin(a));
    wobbly.push_back(make_arc(prev, next, c, false));
    prev = next;
  }
  for (double d : {0.5, 10.0, 39.0}) expect_matches_clipper({wobbly}, d);
}

// Levels of the issue-3 benchmark shape (fewer segments): every level closes, and the area
// at sampled levels equals Clipper's erosion of the input by the summed distance. With
// amplitude 10 the lobe tips have radius 2.9 mm, so arcs collapse after a few levels.
TEST(OffsetVsClipper, WaveLoopAllLevels) {
  for (double amplitude : {8.85, 10.0}) {
    auto wave = [&](double t) {
      const double r = 100 + amplitude * std::sin(20 * t);
      return Vec2(r * std::cos(t), r * std::sin(t));
    };
    const int n = 2000;
    std::vector<Seg2> loop;
    for (int k = 0; k < n; ++k) {  // clockwise: t decreasing; lines and bulge arcs alternate
      const double t0 = 2 * std::numbers::pi * (n - k) / n;
      const double t1 = 2 * std::numbers::pi * (n - k - 1) / n;
      const Vec2 a = k == 0 ? wave(0) : loop.back().b;
      const Vec2 b = k + 1 == n ? wave(0) : wave(t1);
      if (k % 2 == 0) {
        loop.push_back(make_line(a, b));
      } else {
        // Arc through the curve's midpoint: bulge from the sagitta.
        const Vec2 m = wave(0.5 * (t0 + t1));
        const Vec2 ab = b - a;
        const double h = ((m - a).x() * ab.y() - (m - a).y() * ab.x()) / ab.norm();  // right
        loop.push_back(make_bulge_segment(a, b, -2 * h / ab.norm()));
      }
    }
    const std::vector<std::vector<Seg2>> in = {loop};
    const OffsetLevels lv = offset_levels(in, 0.5, 0.5);
    EXPECT_EQ(lv.open_fragments, 0u) << amplitude;
    EXPECT_GT(lv.level_start.size(), 170u) << amplitude;
    const double chord = 2e-3;  // coarser: this shape is large
    for (std::size_t level = 1; level <= lv.level_start.size(); level += 60) {
      const std::size_t b = level == 1 ? 0 : lv.level_start[level - 2];
      const std::size_t e = lv.level_start[level - 1];
      double area = 0, perimeter = 0;
      for (std::size_t k = b; k < e; ++k) {
        area += -lv.loops[k].loop.area2 / 2;
        perimeter += loop_length(lv.loops[k].loop.segs);
      }
      const double oracle = clipper_eroded_area(for_clipper(in), 0.5 * level, chord);
      EXPECT_NEAR(area, oracle, 4 * chord * (perimeter + loop_length(loop)) + 1e-6)
          << "amplitude " << amplitude << " level " << level;
    }
  }
}

}  // namespace
}  // namespace ncpath

namespace ncpath {
namespace {

// An ellipse (30 x 10: end curvature radius 10^2/30 = 3.3 mm) as hundreds of short arcs,
// offset by more than its end radius: the end arcs turn inside out (swallowtails) and the
// result must still close and match Clipper. Also the same after a few levels (arcs of a
// fraction of a micrometre near the evolute) and a NURBS ellipse that closes at a corner.
TEST(OffsetVsClipper, ArcsSmallerThanTheDistanceTurnInsideOut) {
  const Nurbs2 e = nurbs_ellipse({0, 0}, {30, 0}, 1.0 / 3, 0, 2 * std::numbers::pi);
  std::vector<Seg2> arcs = nurbs_to_arcs(e, 1e-4, 0);
  ASSERT_GT(arcs.size(), 100u);
  std::vector<Seg2> cw;  // clockwise: material inside
  for (auto it = arcs.rbegin(); it != arcs.rend(); ++it) cw.push_back(reversed(*it));
  for (double d : {2.0, 3.5, 5.0, 8.0}) expect_matches_clipper({cw}, d);
  // Levels of 1.7 mm: every level closes (the tiny arcs near the ends included).
  const OffsetLevels lv = offset_levels({cw}, 1.7, 1.7);
  EXPECT_EQ(lv.open_fragments, 0u);
  EXPECT_EQ(lv.level_start.size(), 5u);  // 10 / 1.7: levels at 1.7 ... 8.5
}

// Offsets of two islands 2d apart touch at one point at that level: no crossing, both
// loops kept as they are (before, the ill-conditioned contact left open fragments).
TEST(OffsetVsClipper, OffsetsThatTouchExactly) {
  const std::vector<std::vector<Seg2>> two = {test::rectangle(0, 0, 120, 80, true),
                                              test::circle({20, 20}, 5, false),
                                              test::circle({60, 20}, 5, false)};
  const OffsetResult r = offset_loops(two, 15);  // circles of radius 20, centres 40 apart
  EXPECT_EQ(r.stats.open_fragments, 0u);
  expect_matches_clipper(two, 15);
  const OffsetLevels lv = offset_levels(two, 3, 4);  // level 4 at 15
  EXPECT_EQ(lv.open_fragments, 0u);
}

}  // namespace
}  // namespace ncpath
