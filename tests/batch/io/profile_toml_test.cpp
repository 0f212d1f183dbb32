#include "batch/io/profile_toml.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "kernels/pocket/chain.hpp"
#include "tests/batch/io/dxf_test_util.hpp"

namespace ncpath::io {
namespace {

std::string error_of(const std::string& text) {
  try {
    parse_profile_toml(text, "p.toml");
  } catch (const ReadError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(ProfileToml, LoopSegmentsExactGeometry) {
  const ProfileSoup s = parse_profile_toml(R"(
[[loop]]
segments = [
  { line = [[0, 0], [100, 0]] },
  { arc = { to = [100, 50], center = [100, 25], dir = "ccw" } },
  { line_to = [0, 50] },
  { arc = { to = [0, 0], bulge = -1 } },
]
)",
                                           "p.toml");
  ASSERT_EQ(s.curves.size(), 4u);
  EXPECT_EQ(s.curves[0].seg.a, Vec2(0, 0));
  EXPECT_EQ(s.curves[0].seg.b, Vec2(100, 0));
  const Seg2& arc = s.curves[1].seg;
  EXPECT_EQ(arc.kind, SegKind::kArcCcw);
  EXPECT_EQ(arc.a, Vec2(100, 0));  // starts where the previous segment ended
  EXPECT_EQ(arc.c, Vec2(100, 25));
  EXPECT_EQ(arc.r, 25);
  EXPECT_NEAR(sweep(arc), std::numbers::pi, 1e-12);
  EXPECT_EQ(s.curves[2].seg.a, Vec2(100, 50));
  EXPECT_EQ(s.curves[2].seg.b, Vec2(0, 50));
  const Seg2& bulge = s.curves[3].seg;  // bulge -1: clockwise half circle about (0, 25)
  EXPECT_EQ(bulge.kind, SegKind::kArcCw);
  EXPECT_NEAR((bulge.c - Vec2(0, 25)).norm(), 0, 1e-12);
  EXPECT_EQ(s.sources[arc.source].handle, "in loop 0 segment 1");
  EXPECT_EQ(s.sources[arc.source].type, "arc");
  EXPECT_EQ(s.sources[s.curves[2].seg.source].type, "line");
}

TEST(ProfileToml, FirstSegmentStartsWhereTheLastEnds) {
  const ProfileSoup s = parse_profile_toml(R"(
[[loop]]
segments = [{ line_to = [10, 0] }, { line_to = [10, 10] }, { line_to = [0, 0] }]
)",
                                           "p.toml");
  ASSERT_EQ(s.curves.size(), 3u);
  EXPECT_EQ(s.curves[0].seg.a, Vec2(0, 0));
}

TEST(ProfileToml, CirclePolylineNurbs) {
  const ProfileSoup s = parse_profile_toml(R"(
[[circle]]
center = [50, 25]
radius = 5

[[polyline]]
points = [[0, 0], [10, 0, 1], [10, 10]]
closed = true

[[loop]]
segments = [
  { nurbs = { degree = 2, ctrl = [[0, 0], [5, 5], [10, 0]], weights = [1, 0.5, 1] } },
  { line_to = [0, 0] },
]
)",
                                           "p.toml");
  // Delivered loops first, then circles, then polylines.
  ASSERT_EQ(s.curves.size(), 2u + 2u + 3u);
  ASSERT_EQ(s.nurbs.size(), 1u);
  EXPECT_EQ(s.curves[0].nurbs, 0);
  EXPECT_EQ(s.nurbs[0].knots, (std::vector<double>{0, 0, 0, 1, 1, 1}));  // default: clamped
  EXPECT_EQ(s.nurbs[0].weights, (std::vector<double>{1, 0.5, 1}));
  EXPECT_EQ(s.curves[0].seg.a, Vec2(0, 0));
  EXPECT_EQ(s.curves[1].seg.a, Vec2(10, 0));
  EXPECT_EQ(s.curves[1].seg.b, Vec2(0, 0));
  EXPECT_EQ(s.curves[2].seg.a, Vec2(55, 25));
  EXPECT_EQ(s.curves[2].seg.b, Vec2(45, 25));
  EXPECT_EQ(s.curves[3].seg.b, Vec2(55, 25));
  EXPECT_EQ(s.sources[s.curves[2].seg.source].type, "circle");
  const Seg2& b = s.curves[5].seg;
  EXPECT_EQ(b.kind, SegKind::kArcCcw);
  EXPECT_NEAR((b.c - Vec2(10, 5)).norm(), 0, 1e-12);
  EXPECT_EQ(s.curves[6].seg.b, Vec2(0, 0));  // closed
  EXPECT_EQ(s.sources[s.curves[6].seg.source].handle, "0 segment 2");
  EXPECT_EQ(s.sources[s.curves[6].seg.source].type, "polyline");
  EXPECT_EQ(s.sources[s.curves[2].seg.source].handle, "0");  // "circle 0"
}

TEST(ProfileToml, ZeroLengthCounted) {
  const ProfileSoup s = parse_profile_toml(R"(
[[polyline]]
points = [[0, 0], [0, 0], [10, 0]]
[[circle]]
center = [0, 0]
radius = 0
)",
                                           "p.toml");
  EXPECT_EQ(s.curves.size(), 1u);
  EXPECT_EQ(s.zero_length_dropped, 2u);
  EXPECT_EQ(s.sources.size(), 1u);
}

TEST(ProfileToml, ErrorsNameItemKeyAndLine) {
  EXPECT_EQ(
      error_of(
          "[[loop]]\nsegments = [\n  { line_to = [1, 0] },\n  { arc = { center = [0, 0] } },\n]\n"),
      "p.toml: line 4: loop 0 segment 1: arc: missing key 'to'");
  EXPECT_EQ(error_of("[[circle]]\ncentre = [0, 0]\nradius = 1\nradus = 2\n"),
            "p.toml: line 4: circle 0: unknown key 'radus' (expected center, centre, radius)");
  EXPECT_EQ(error_of("[[loop]]\nsegments = [{ line_to = [1, 0] }, { line_to = [0, \"a\"] }]\n"),
            "p.toml: line 2: loop 0 segment 1: line_to: 'line_to' must be a finite number");
  EXPECT_EQ(error_of("[[loop]]\nsegments = [{ line_to = [1, 0] }, { arc = { to = [0, 0], center = "
                     "[5, 5] } }]\n")
                .find("p.toml: line 2: loop 0 segment 1: arc: start and end are not equally far"),
            0u);
  EXPECT_EQ(error_of("[[loop]]\nsegments = [{ spline = [1, 0] }]\n")
                .find("p.toml: line 2: loop 0 segment 0: unknown segment 'spline'"),
            0u);
  const std::string syntax = error_of("[[loop]]\nsegments = [\n{ line_to = [1, 0] \n");
  EXPECT_EQ(syntax.find("p.toml: line "), 0u) << syntax;
  EXPECT_NE(syntax.find("TOML syntax"), std::string::npos) << syntax;
  EXPECT_EQ(error_of("units = \"mm\"\n"),
            "p.toml: no profile curves (add [[loop]], [[circle]] or [[polyline]])");
  EXPECT_EQ(error_of("[loop]\nsegments = []\n"),
            "p.toml: line 1: loop: must be an array of tables: write [[loop]]");
}

TEST(ProfileToml, FileToRegions) {
  const auto path = test::write_temp("pocket.toml", R"(
# A 100 x 50 pocket with a round island, written clockwise or not: nesting decides.
[[loop]]
segments = [
  { line = [[0, 0], [100, 0]] },
  { line_to = [100, 50] },
  { line_to = [0, 50] },
  { line_to = [0, 0] },
]
[[circle]]
center = [50, 25]
radius = 5
)");
  const ProfileSoup s = read_profile_toml(path);
  const ChainResult r = chain_and_nest(s.curves, s.nurbs, s.sources);
  ASSERT_EQ(r.error, "");
  ASSERT_EQ(r.regions.size(), 1u);
  EXPECT_EQ(r.regions[0].boundary.curves.size(), 4u);
  EXPECT_EQ(r.regions[0].islands.size(), 1u);
  EXPECT_THROW(read_profile_toml(path.parent_path() / "no_such.toml"), ReadError);
}

}  // namespace
}  // namespace ncpath::io
