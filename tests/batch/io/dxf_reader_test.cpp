#include "batch/io/dxf_reader.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "kernels/curves/nurbs.hpp"
#include "kernels/pocket/chain.hpp"
#include "tests/batch/io/dxf_test_util.hpp"

namespace ncpath::io {
namespace {

using test::dxf_entities;
using test::pairs;
using test::write_temp;

constexpr double kPi = std::numbers::pi;

std::string line_e(const std::string& h, double x1, double y1, double x2, double y2) {
  return pairs({"0", "LINE", "5", h, "8", "0", "10", std::to_string(x1), "20", std::to_string(y1),
                "30", "0", "11", std::to_string(x2), "21", std::to_string(y2), "31", "0"});
}

std::string read_error_of(const std::string& name, const std::string& text) {
  try {
    read_dxf(write_temp(name, text));
  } catch (const ReadError& e) {
    return e.what();
  }
  return "(no error)";
}

// R12 style: no handles, LINE / ARC / CIRCLE.
TEST(DxfReader, R12LineArcCircleGeometry) {
  const std::string text =
      dxf_entities(pairs({"0", "LINE", "8", "0", "10", "1.5", "20", "2", "30", "0", "11", "7", "21",
                          "-3", "31", "0"}) +
                   pairs({"0", "ARC", "8", "0", "10", "10", "20", "20", "30", "0", "40", "5", "50",
                          "30", "51", "120"}) +
                   pairs({"0", "CIRCLE", "8", "0", "10", "-4", "20", "6", "30", "0", "40", "2.5"}));
  const ProfileSoup s = read_dxf(write_temp("r12.dxf", text));
  ASSERT_EQ(s.curves.size(), 4u);
  EXPECT_TRUE(s.warnings.empty());
  EXPECT_EQ(s.zero_length_dropped, 0u);

  const Seg2& line = s.curves[0].seg;
  EXPECT_EQ(line.kind, SegKind::kLine);
  EXPECT_EQ(line.a, Vec2(1.5, 2));
  EXPECT_EQ(line.b, Vec2(7, -3));
  EXPECT_EQ(s.sources[line.source].type, "LINE");
  EXPECT_EQ(s.sources[line.source].handle, "(line 5)");  // no handle: the line of its "0"

  const Seg2& arc = s.curves[1].seg;
  EXPECT_EQ(arc.kind, SegKind::kArcCcw);
  EXPECT_NEAR(arc.a.x(), 10 + 5 * std::sqrt(3.0) / 2, 1e-12);
  EXPECT_NEAR(arc.a.y(), 20 + 2.5, 1e-12);
  EXPECT_NEAR(arc.b.x(), 10 - 2.5, 1e-12);
  EXPECT_NEAR(arc.b.y(), 20 + 5 * std::sqrt(3.0) / 2, 1e-12);
  EXPECT_EQ(arc.c, Vec2(10, 20));
  EXPECT_NEAR(arc.r, 5, 1e-12);
  EXPECT_NEAR(sweep(arc), kPi / 2, 1e-12);
  EXPECT_EQ(s.sources[arc.source].type, "ARC");

  // The circle: two counter-clockwise half arcs through (cx +- r, cy), one source.
  const Seg2& h0 = s.curves[2].seg;
  const Seg2& h1 = s.curves[3].seg;
  EXPECT_EQ(h0.a, Vec2(-1.5, 6));
  EXPECT_EQ(h0.b, Vec2(-6.5, 6));
  EXPECT_EQ(h1.a, h0.b);
  EXPECT_EQ(h1.b, h0.a);
  EXPECT_EQ(h0.kind, SegKind::kArcCcw);
  EXPECT_EQ(h1.kind, SegKind::kArcCcw);
  EXPECT_EQ(h0.source, h1.source);
  EXPECT_EQ(s.sources[h0.source].type, "CIRCLE");
  EXPECT_NEAR(sweep(h0) + sweep(h1), 2 * kPi, 1e-12);
}

TEST(DxfReader, ArcCrossingZeroDegreesAndMirroredExtrusion) {
  const std::string text = dxf_entities(
      pairs({"0", "ARC", "5", "A1", "8", "0", "10", "0", "20", "0", "30", "0", "40", "2", "50",
             "270", "51", "90"}) +
      pairs({"0",  "ARC", "5",  "A2", "8",  "0",  "10",  "10", "20",  "0", "30",  "0",
             "40", "5",   "50", "0",  "51", "90", "210", "0",  "220", "0", "230", "-1"}));
  const ProfileSoup s = read_dxf(write_temp("arcs.dxf", text));
  ASSERT_EQ(s.curves.size(), 2u);
  // 270 -> 90 degrees counter-clockwise passes through 0: the right half circle.
  EXPECT_NEAR(sweep(s.curves[0].seg), kPi, 1e-12);
  EXPECT_NEAR(point_at(s.curves[0].seg, 0.5).x(), 2, 1e-12);
  // Extrusion -Z mirrors x: centre (-10, 0), from (-15, 0) to (-10, 5), clockwise.
  const Seg2& m = s.curves[1].seg;
  EXPECT_EQ(s.sources[m.source].handle, "A2");
  EXPECT_EQ(m.c, Vec2(-10, 0));
  EXPECT_NEAR((m.a - Vec2(-15, 0)).norm(), 0, 1e-12);
  EXPECT_NEAR((m.b - Vec2(-10, 5)).norm(), 0, 1e-12);
  EXPECT_EQ(m.kind, SegKind::kArcCw);
}

std::string lwpolyline(const std::string& h, bool closed) {
  // (0,0) -> (10,0) line, (10,0) -> (10,10) bulge 1 (half circle, ccw), (10,10) -> (0,10).
  return pairs({"0",   "LWPOLYLINE",
                "5",   h,
                "100", "AcDbEntity",
                "8",   "0",
                "100", "AcDbPolyline",
                "90",  "4",
                "70",  closed ? "1" : "0",
                "10",  "0",
                "20",  "0",
                "10",  "10",
                "20",  "0",
                "42",  "1",
                "10",  "10",
                "20",  "10",
                "10",  "0",
                "20",  "10"});
}

TEST(DxfReader, LwpolylineBulgeAndClosedFlag) {
  const ProfileSoup open =
      read_dxf(write_temp("lw_open.dxf", dxf_entities(lwpolyline("2A", false))));
  ASSERT_EQ(open.curves.size(), 3u);
  const ProfileSoup closed =
      read_dxf(write_temp("lw_closed.dxf", dxf_entities(lwpolyline("2A", true))));
  ASSERT_EQ(closed.curves.size(), 4u);
  const Seg2& bulge = closed.curves[1].seg;
  EXPECT_EQ(bulge.kind, SegKind::kArcCcw);
  EXPECT_EQ(bulge.a, Vec2(10, 0));
  EXPECT_EQ(bulge.b, Vec2(10, 10));
  EXPECT_NEAR((bulge.c - Vec2(10, 5)).norm(), 0, 1e-12);
  EXPECT_NEAR(sweep(bulge), kPi, 1e-12);
  EXPECT_EQ(closed.curves[3].seg.a, Vec2(0, 10));  // the closing span
  EXPECT_EQ(closed.curves[3].seg.b, Vec2(0, 0));
  ASSERT_EQ(closed.sources.size(), 1u);
  EXPECT_EQ(closed.sources[0].handle, "2A");
  EXPECT_EQ(closed.sources[0].type, "LWPOLYLINE");
  for (const ProfileCurve& c : closed.curves) EXPECT_EQ(c.seg.source, 0u);
}

TEST(DxfReader, OldStylePolylineWithVertices) {
  const std::string text = dxf_entities(
      pairs({"0", "POLYLINE", "5", "40", "8", "0", "66", "1", "10", "0", "20", "0", "30", "0", "70",
             "1"}) +
      pairs({"0", "VERTEX", "5", "41", "8", "0", "10", "0", "20", "0", "30", "0", "42", "-1"}) +
      pairs({"0", "VERTEX", "5", "42", "8", "0", "10", "4", "20", "0", "30", "0"}) +
      pairs({"0", "VERTEX", "5", "43", "8", "0", "10", "4", "20", "3", "30", "0"}) +
      pairs({"0", "SEQEND", "5", "44", "8", "0"}));
  const ProfileSoup s = read_dxf(write_temp("poly.dxf", text));
  ASSERT_EQ(s.curves.size(), 3u);
  EXPECT_EQ(s.curves[0].seg.kind, SegKind::kArcCw);  // bulge -1: clockwise half circle
  EXPECT_NEAR((s.curves[0].seg.c - Vec2(2, 0)).norm(), 0, 1e-12);
  EXPECT_EQ(s.curves[2].seg.a, Vec2(4, 3));
  EXPECT_EQ(s.curves[2].seg.b, Vec2(0, 0));
  EXPECT_EQ(s.sources[s.curves[0].seg.source].handle, "40");
  EXPECT_EQ(s.sources[s.curves[0].seg.source].type, "POLYLINE");
  EXPECT_TRUE(s.warnings.empty());
}

TEST(DxfReader, SplineControlPointsKnotsWeights) {
  const std::string text = dxf_entities(pairs(
      {"0",  "SPLINE", "5",  "2F", "100", "AcDbEntity", "8",  "0", "100", "AcDbSpline", "70", "12",
       "71", "2",      "72", "6",  "73",  "3",          "74", "0", "40",  "0",          "40", "0",
       "40", "0",      "40", "1",  "40",  "1",          "40", "1", "10",  "0",          "20", "0",
       "30", "0",      "41", "1",  "10",  "5",          "20", "5", "30",  "0",          "41", "0.5",
       "10", "10",     "20", "0",  "30",  "0",          "41", "1"}));
  const ProfileSoup s = read_dxf(write_temp("spline.dxf", text));
  ASSERT_EQ(s.curves.size(), 1u);
  ASSERT_EQ(s.nurbs.size(), 1u);
  EXPECT_EQ(s.curves[0].nurbs, 0);
  const Nurbs2& n = s.nurbs[0];
  EXPECT_EQ(n.degree, 2);
  EXPECT_EQ(n.ctrl, (std::vector<Vec2>{{0, 0}, {5, 5}, {10, 0}}));
  EXPECT_EQ(n.weights, (std::vector<double>{1, 0.5, 1}));
  EXPECT_EQ(n.knots, (std::vector<double>{0, 0, 0, 1, 1, 1}));
  EXPECT_EQ(s.curves[0].seg.a, Vec2(0, 0));
  EXPECT_EQ(s.curves[0].seg.b, Vec2(10, 0));
  EXPECT_EQ(s.sources[0].handle, "2F");  // dxflib alone would say 2 (decimal parse)
  EXPECT_EQ(s.sources[0].type, "SPLINE");
}

TEST(DxfReader, FitPointOnlySplineIsAnErrorNamingTheHandle) {
  const std::string text = dxf_entities(
      line_e("1C", 0, 0, 1, 0) +
      pairs({"0",  "SPLINE", "5",  "2F", "100", "AcDbSpline", "70", "8", "71", "3", "72", "0",
             "73", "0",      "74", "3",  "11",  "0",          "21", "0", "31", "0", "11", "5",
             "21", "5",      "31", "0",  "11",  "10",         "21", "0", "31", "0"}));
  const std::string e = read_error_of("fit.dxf", text);
  EXPECT_NE(e.find("SPLINE 2F has only fit points; ncpath needs control points"), std::string::npos)
      << e;
  // 4 lines of section header + 18 of the LINE: the SPLINE's "0" is line 23.
  EXPECT_NE(e.find("fit.dxf: line 23:"), std::string::npos) << e;
}

TEST(DxfReader, SplineWithMissingControlPointIsAnError) {
  const std::string text = dxf_entities(
      pairs({"0",  "SPLINE", "5",  "30", "70", "8", "71", "1", "72", "4", "73", "2", "74", "0",
             "40", "0",      "40", "0",  "40", "1", "40", "1", "10", "0", "20", "0", "30", "0"}));
  const std::string e = read_error_of("short.dxf", text);
  EXPECT_NE(e.find("SPLINE 30 declares 2 control points (code 73) but lists 1"), std::string::npos)
      << e;
}

TEST(DxfReader, EllipseAsExactNurbs) {
  const std::string text = dxf_entities(pairs({"0",   "ELLIPSE",
                                               "5",   "E1",
                                               "100", "AcDbEllipse",
                                               "8",   "0",
                                               "10",  "3",
                                               "20",  "4",
                                               "30",  "0",
                                               "11",  "6",
                                               "21",  "0",
                                               "31",  "0",
                                               "40",  "0.5",
                                               "41",  "0",
                                               "42",  "6.283185307179586"}));
  const ProfileSoup s = read_dxf(write_temp("ellipse.dxf", text));
  ASSERT_EQ(s.curves.size(), 1u);
  ASSERT_EQ(s.nurbs.size(), 1u);
  const Nurbs2& n = s.nurbs[0];
  EXPECT_EQ(validate(n), "");
  EXPECT_NEAR((s.curves[0].seg.a - Vec2(9, 4)).norm(), 0, 1e-12);
  EXPECT_NEAR((s.curves[0].seg.b - Vec2(9, 4)).norm(), 0, 1e-12);
  // Semi-axes 6 and 3 about (3, 4): every point satisfies the implicit equation.
  for (int k = 0; k <= 16; ++k) {
    const double t = nurbs_t0(n) + (nurbs_t1(n) - nurbs_t0(n)) * k / 16;
    const Vec2 p = nurbs_point(n, t);
    const double f = std::pow((p.x() - 3) / 6, 2) + std::pow((p.y() - 4) / 3, 2);
    EXPECT_NEAR(f, 1, 1e-12) << "t = " << t;
  }
  // Counter-clockwise: a quarter of the way along, the point is near the top (3, 7).
  const Vec2 q = nurbs_point(n, nurbs_t0(n) + 0.25 * (nurbs_t1(n) - nurbs_t0(n)));
  EXPECT_GT(q.y(), 4);
}

TEST(DxfReader, UnsupportedEntitiesWarnZeroLengthCounted) {
  const std::string text = dxf_entities(
      line_e("10", 0, 0, 5, 0) + line_e("11", 2, 2, 2, 2) +
      pairs({"0", "TEXT", "5", "3A", "8", "0", "10", "0", "20", "0", "30", "0", "40", "2", "1",
             "hello"}) +
      pairs({"0", "INSERT", "5", "3B", "8", "0", "2", "BLK", "10", "0", "20", "0", "30", "0"}) +
      pairs({"0", "CIRCLE", "5", "3C", "8", "0", "10", "1", "20", "1", "30", "0", "40", "0"}));
  const ProfileSoup s = read_dxf(write_temp("mixed.dxf", text));
  ASSERT_EQ(s.curves.size(), 1u);
  EXPECT_EQ(s.zero_length_dropped, 2u);
  ASSERT_EQ(s.warnings.size(), 2u);
  EXPECT_EQ(s.warnings[0], "skipped TEXT 3A: not a profile curve");
  EXPECT_EQ(s.warnings[1], "skipped INSERT 3B: not a profile curve");
}

TEST(DxfReader, BlockGeometryIsIgnored) {
  const std::string text = pairs({"0", "SECTION", "2", "BLOCKS", "0", "BLOCK", "8", "0", "2", "BLK",
                                  "70", "0", "10", "0", "20", "0", "30", "0"}) +
                           line_e("20", 0, 0, 9, 9) +
                           pairs({"0", "ENDBLK", "8", "0", "0", "ENDSEC"}) +
                           dxf_entities(line_e("21", 0, 0, 1, 0));
  const ProfileSoup s = read_dxf(write_temp("blocks.dxf", text));
  ASSERT_EQ(s.curves.size(), 1u);
  EXPECT_EQ(s.sources[0].handle, "21");
}

TEST(DxfReader, EmptyAndUselessFilesAreErrors) {
  EXPECT_NE(read_error_of("empty.dxf", "").find("empty.dxf: empty file"), std::string::npos);
  const std::string only_text = dxf_entities(
      pairs({"0", "TEXT", "5", "3A", "8", "0", "10", "0", "20", "0", "30", "0", "1", "x"}));
  const std::string e = read_error_of("text_only.dxf", only_text);
  EXPECT_NE(e.find("no usable profile entity"), std::string::npos) << e;
  EXPECT_NE(e.find("1 skipped"), std::string::npos) << e;
  try {
    read_dxf(std::filesystem::temp_directory_path() / "ncpath_no_such_file.dxf");
    FAIL();
  } catch (const ReadError& err) {
    EXPECT_EQ(err.problem(), "cannot open");
  }
}

// End to end: a square of LINEs in scrambled order and direction with a CIRCLE island.
TEST(DxfReader, ChainsIntoRegion) {
  const std::string text = dxf_entities(
      line_e("A", 100, 0, 100, 100) + line_e("B", 0, 0, 100, 0) + line_e("C", 0, 100, 0, 0) +
      pairs({"0", "CIRCLE", "5", "D", "8", "0", "10", "50", "20", "50", "30", "0", "40", "10"}) +
      line_e("E", 0, 100, 100, 100));
  const ProfileSoup s = read_dxf(write_temp("square.dxf", text));
  const ChainResult r = chain_and_nest(s.curves, s.nurbs, s.sources);
  ASSERT_EQ(r.error, "");
  ASSERT_EQ(r.regions.size(), 1u);
  EXPECT_EQ(r.regions[0].boundary.curves.size(), 4u);
  ASSERT_EQ(r.regions[0].islands.size(), 1u);
  EXPECT_EQ(r.regions[0].islands[0].curves.size(), 2u);
}

}  // namespace
}  // namespace ncpath::io
