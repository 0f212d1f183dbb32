// Z-level contours (kernels/scan/zlevel): analytic cases (a horizontal facet's rounded
// triangle, an apex circle, a V-groove's sharp-concave point, a box pocket's hole, a tilted
// facet's clip line, short and grazing clip lines, stacked wall edges, a ring ridge's outer
// loop and hole), each also checked by the brute-force oracles of zlevel_test_support.hpp.
// Random meshes, a real part and determinism: zlevel_oracle_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "kernels/scan/zlevel.hpp"
#include "tests/kernels/scan/zlevel_test_support.hpp"

namespace ncpath {
namespace {

using namespace zlevel_test;

// ---- analytic cases ----

// Below a horizontal facet the contour is the triangle dilated by rho = sqrt(R^2 - dz^2):
// three lines at distance rho from the sides, three arcs of radius rho around the corners.
TEST(ZLevel, HorizontalFacetGivesRoundedTriangle) {
  const TriangleMesh mesh = one_triangle({0, 0, 0}, {10, 0, 0}, {0, 10, 0});
  const double R = 2, rho = std::sqrt(3.0);
  const OffsetElements el = build_offset_elements(mesh, R, Coplanar::kKeep);
  const ZLevelResult r = run(el, -1);
  ASSERT_EQ(r.contours.size(), 1u);
  const ZContour& c = r.contours[0];
  EXPECT_FALSE(c.hole);
  const double perim = 20 + 10 * std::sqrt(2.0);
  EXPECT_NEAR(c.area, 50 + perim * rho + kPi * rho * rho, 1e-9);
  int lines = 0, arcs = 0;
  double sweep = 0, line_len = 0;
  const Vec2 corners[3] = {{0, 0}, {10, 0}, {0, 10}};
  for (const ContourSeg& s : c.segs) {
    if (s.kind == ContourSegKind::kLine) {
      ++lines;
      line_len += (s.b - s.a).norm();
      EXPECT_GE(s.element, el.facet_count());
      // At distance rho outside one side.
      for (double f : {0.0, 0.5, 1.0}) {
        const Vec2 p = seg_point(s, f);
        const Vec3 q(p.x(), p.y(), 0);
        const double d =
            std::min({seg_dist(q, {0, 0, 0}, {10, 0, 0}), seg_dist(q, {10, 0, 0}, {0, 10, 0}),
                      seg_dist(q, {0, 10, 0}, {0, 0, 0})});
        EXPECT_NEAR(d, rho, 1e-12);
      }
    } else {
      ASSERT_EQ(s.kind, ContourSegKind::kCircleArc);
      ++arcs;
      EXPECT_NEAR(s.r1, rho, 1e-15);
      double dmin = INFINITY;
      for (const Vec2& q : corners) dmin = std::min(dmin, (s.centre - q).norm());
      EXPECT_EQ(dmin, 0);
      sweep += s.t1 - s.t0;
    }
    EXPECT_FALSE(s.shadow);
  }
  EXPECT_EQ(lines, 3);
  EXPECT_EQ(arcs, 3);
  EXPECT_NEAR(sweep, 2 * kPi, 1e-12);
  EXPECT_NEAR(line_len, perim, 1e-9);
  ASSERT_EQ(c.junctions.size(), 6u);
  for (const ZJunction& j : c.junctions) {
    EXPECT_EQ(j.kind, JunctionKind::kTangent);
    EXPECT_LT((j.b1 - j.b2).norm(), 1e-9);
    EXPECT_NEAR(j.b1.z(), 0.5, 1e-12);  // contact 1 mm below a centre at distance R = 2
  }
  // Above the facet's reach nothing remains.
  EXPECT_TRUE(run(el, 0.5).contours.empty());
}

// A pyramid's apex: just below the top the ball touches only the apex (its tilt rho / R is
// below the ridge and face slopes), the contour is the circle of radius rho.
TEST(ZLevel, ApexGivesCircle) {
  TriangleMesh mesh{{{0, 0, 5}, {20, 20, 0}, {-20, 20, 0}, {-20, -20, 0}, {20, -20, 0}},
                    {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 1}, {1, 2, 3}, {1, 3, 4}}};
  const double R = 2, rho = 0.3, dz = R - std::sqrt(R * R - rho * rho);
  const OffsetElements el = build_offset_elements(mesh, R, Coplanar::kKeep);
  const ZLevelResult r = run(el, 5 - dz);
  ASSERT_EQ(r.contours.size(), 1u);
  const ZContour& c = r.contours[0];
  ASSERT_EQ(c.segs.size(), 1u);
  const ContourSeg& s = c.segs[0];
  EXPECT_EQ(s.kind, ContourSegKind::kCircleArc);
  EXPECT_EQ(s.element, el.vertex_id(0));
  EXPECT_NEAR(s.r1, rho, 1e-12);
  EXPECT_NEAR(s.centre.norm(), 0, 1e-15);
  EXPECT_NEAR(s.t1 - s.t0, 2 * kPi, 1e-12);
  EXPECT_NEAR(c.area, kPi * rho * rho, 1e-12);
  EXPECT_TRUE(c.junctions.empty());
  std::mt19937_64 rng(3);
  Oracle o(mesh, el);
  check_result(o, r, rng, -3, -3, 3, 3, 200);
  // Lower down the ridges and faces join in: still exact against the oracle.
  for (double z : {4.0, 2.5, 0.7}) check_result(o, run(el, z), rng, -25, -25, 25, 25, 300);
}

// A 90-degree V-groove whose floor rises along y (planes z = |x| + y / 2): in the groove the
// offset planes give |x| + y / 2 + R * 1.5 >= zc, two lines meeting at (0, 6) for level 4,
// R = 2, where the ball touches both planes: a sharp-concave junction with b = the normals.
TEST(ZLevel, VGrooveSharpConcavePoint) {
  TriangleMesh mesh{
      {{-10, 0, 10}, {0, 0, 0}, {10, 0, 10}, {-10, 20, 20}, {0, 20, 10}, {10, 20, 20}},
      {{0, 1, 4}, {0, 4, 3}, {1, 2, 5}, {1, 5, 4}}};
  const double R = 2, z = 4;
  const OffsetElements el = build_offset_elements(mesh, R, Coplanar::kKeep);
  const ZLevelResult r = run(el, z);
  ASSERT_EQ(r.contours.size(), 1u);
  const ZContour& c = r.contours[0];
  EXPECT_FALSE(c.hole);
  const Vec3 n_left = Vec3(1, -0.5, 1) / 1.5, n_right = Vec3(-1, -0.5, 1) / 1.5;
  int sharp = 0;
  for (const ZJunction& j : c.junctions) {
    if ((j.position - Vec3(0, 6, z)).norm() < 1e-9) {
      ++sharp;
      EXPECT_EQ(j.kind, JunctionKind::kSharpConcave);
      const bool order1 = (j.b1 - n_left).norm() < 1e-12 && (j.b2 - n_right).norm() < 1e-12;
      const bool order2 = (j.b1 - n_right).norm() < 1e-12 && (j.b2 - n_left).norm() < 1e-12;
      EXPECT_TRUE(order1 || order2) << j.b1.transpose() << " / " << j.b2.transpose();
      EXPECT_LT(j.e1, el.facet_count());
      EXPECT_LT(j.e2, el.facet_count());
    } else {
      EXPECT_NE(j.kind, JunctionKind::kSharpConcave) << j.position.transpose();
    }
  }
  EXPECT_EQ(sharp, 1);
  // The groove's contour lines: |x| + y / 2 = 3 on both sides of the notch.
  double groove_len = 0;
  for (const ContourSeg& s : c.segs) {
    if (s.element >= el.facet_count()) continue;
    ASSERT_EQ(s.kind, ContourSegKind::kLine);
    for (double f : {0.0, 0.5, 1.0}) {
      const Vec2 p = seg_point(s, f);
      EXPECT_NEAR(std::abs(p.x()) + 0.5 * p.y(), 3, 1e-12) << p.transpose();
    }
    groove_len += (s.b - s.a).norm();
  }
  // From y = 6 down to y = -2/3, where the offset faces end (shifted by R n_xy).
  EXPECT_NEAR(groove_len, 2 * (6 + 2.0 / 3) * std::sqrt(1.25), 1e-9);
  std::mt19937_64 rng(4);
  Oracle o(mesh, el);
  check_result(o, r, rng, -14, -4, 14, 24, 400);
}

// A plate with a rectangular pocket (vertical walls): at a level inside the pocket the
// pocket's contour is a clockwise hole R inside the walls (the rims' shadows) with sharp
// corners whose bi-contact vectors are the walls' normals; the plate's outline gives an
// outer loop at R around it with round corners.
TEST(ZLevel, BoxPocketHole) {
  TriangleMesh mesh;
  mesh.vertices = {{-10, -10, 0}, {40, -10, 0}, {40, 30, 0},   {-10, 30, 0},  // outer
                   {0, 0, 0},     {30, 0, 0},   {30, 20, 0},   {0, 20, 0},    // rim
                   {0, 0, -10},   {30, 0, -10}, {30, 20, -10}, {0, 20, -10}};
  for (std::uint32_t k = 0; k < 4; ++k) {
    const std::uint32_t k1 = (k + 1) % 4;
    mesh.facets.push_back({k, k1, 4 + k1});
    mesh.facets.push_back({k, 4 + k1, 4 + k});
    mesh.facets.push_back({4 + k, 4 + k1, 8 + k1});
    mesh.facets.push_back({4 + k, 8 + k1, 8 + k});
  }
  mesh.facets.push_back({8, 9, 10});
  mesh.facets.push_back({8, 10, 11});
  const double R = 2, z = -5;
  const OffsetElements el = build_offset_elements(mesh, R, Coplanar::kKeep);
  const ZLevelResult r = run(el, z);
  ASSERT_EQ(r.contours.size(), 2u);
  const ZContour* outer = r.contours[0].hole ? &r.contours[1] : &r.contours[0];
  const ZContour* hole = r.contours[0].hole ? &r.contours[0] : &r.contours[1];
  ASSERT_TRUE(hole->hole);
  ASSERT_FALSE(outer->hole);
  EXPECT_NEAR(outer->area, 54.0 * 44.0 - (4 - kPi) * R * R, 1e-9);
  EXPECT_NEAR(hole->area, -26.0 * 16.0, 1e-9);
  for (const ContourSeg& s : hole->segs) {
    EXPECT_EQ(s.kind, ContourSegKind::kLine);
    EXPECT_TRUE(s.shadow);
  }
  const Vec2 corners[4] = {{2, 2}, {28, 2}, {28, 18}, {2, 18}};
  const Vec3 normals[4][2] = {{{1, 0, 0}, {0, 1, 0}},
                              {{-1, 0, 0}, {0, 1, 0}},
                              {{-1, 0, 0}, {0, -1, 0}},
                              {{1, 0, 0}, {0, -1, 0}}};
  int found = 0;
  for (const ZJunction& j : hole->junctions) {
    int k = 0;
    while (k < 4 && (Vec2(j.position.x(), j.position.y()) - corners[k]).norm() > 1e-9) ++k;
    if (k == 4) {
      EXPECT_EQ(j.kind, JunctionKind::kTangent);  // coincident wall edges taking turns
      continue;
    }
    ++found;
    EXPECT_EQ(j.kind, JunctionKind::kSharpConcave);
    const bool o1 = (j.b1 - normals[k][0]).norm() < 1e-12 && (j.b2 - normals[k][1]).norm() < 1e-12;
    const bool o2 = (j.b1 - normals[k][1]).norm() < 1e-12 && (j.b2 - normals[k][0]).norm() < 1e-12;
    EXPECT_TRUE(o1 || o2) << j.b1.transpose() << " / " << j.b2.transpose();
  }
  EXPECT_EQ(found, 4);
  int arcs = 0;
  for (const ContourSeg& s : outer->segs)
    if (s.kind == ContourSegKind::kCircleArc) {
      ++arcs;
      EXPECT_NEAR(s.r1, R, 1e-15);
      EXPECT_NEAR(s.t1 - s.t0, kPi / 2, 1e-12);
    }
  EXPECT_EQ(arcs, 4);
  std::mt19937_64 rng(5);
  Oracle o(mesh, el);
  check_result(o, r, rng, -14, -14, 44, 34, 400);
  // At the floor's own height the ball touches the floor everywhere in the pocket: no hole.
  // Just above it the same hole as at -5 (the rims' shadows).
  const ZLevelResult at_floor = run(el, -10);
  ASSERT_EQ(at_floor.contours.size(), 1u);
  EXPECT_NEAR(at_floor.contours[0].area, outer->area, 1e-9);
  check_result(o, at_floor, rng, -14, -14, 44, 34, 400);
  const ZLevelResult above = run(el, -9.999);
  ASSERT_EQ(above.contours.size(), 2u);
  EXPECT_NEAR(above.contours[0].area + above.contours[1].area, outer->area + hole->area, 1e-9);
}

// An open tilted facet: its clip line lies on the offset plane at the level and ends tangent
// to its edges' ellipses (b1 = b2 = the facet normal there).
TEST(ZLevel, TiltedFacetClipLine) {
  const TriangleMesh mesh = one_triangle({0, 0, 0}, {10, 0, 2}, {0, 10, 5});
  const double R = 1.5, z = 2;
  const OffsetElements el = build_offset_elements(mesh, R, Coplanar::kKeep);
  const ZLevelResult r = run(el, z);
  ASSERT_EQ(r.contours.size(), 1u);
  const Vec3 n = Vec3(-2, -5, 10).normalized();
  int clips = 0, tangents = 0;
  for (const ContourSeg& s : r.contours[0].segs)
    if (s.element == 0) {
      ++clips;
      EXPECT_EQ(s.kind, ContourSegKind::kLine);
      for (double f : {0.0, 0.3, 1.0}) {
        const Vec2 p = seg_point(s, f);
        EXPECT_NEAR(n.dot(Vec3(p.x(), p.y(), z + R)), R, 1e-12);
      }
    }
  for (const ZJunction& j : r.contours[0].junctions)
    if (j.e1 == 0 || j.e2 == 0) {
      ++tangents;
      EXPECT_EQ(j.kind, JunctionKind::kTangent);
      EXPECT_LT((j.b1 - n).norm(), 1e-9);
      EXPECT_LT((j.b2 - n).norm(), 1e-9);
    }
  EXPECT_EQ(clips, 1);
  EXPECT_EQ(tangents, 2);
  std::mt19937_64 rng(6);
  Oracle o(mesh, el);
  for (double zz : {z, 0.0, 3.9, -1.2}) check_result(o, run(el, zz), rng, -3, -3, 13, 13, 400);
}

// Just below the top vertex V of a facet whose edges from V are flat (slope 0.05) but run
// nearly along the facet's level lines, the clip line is short (length L) and ends tangent to
// both edges' ellipses on their flat sides (radius of curvature about 90 mm there). The
// ellipses cross each other between the joints; their pieces from the joints to that crossing
// lie inside the facet's region, but for L around 1.5e-4 mm only by about 1e-11 mm at the
// midpoints (regression: such pieces were kept and left open chains, as on the bunny).
TEST(ZLevel, ShortClipLineBetweenFlatEllipses) {
  const double R = 2.5, g = 0.5;  // facet plane z = 1 - g y, V = (0, 0, 1) on top
  const TriangleMesh mesh = one_triangle({0, 0, 1}, {-10, 1, 1 - g}, {10, 1, 1 - g});
  const OffsetElements el = build_offset_elements(mesh, R, Coplanar::kKeep);
  const Vec3 n = Vec3(0, g, 1).normalized();
  Oracle o(mesh, el);
  std::mt19937_64 rng(8);
  int levels = 0;
  for (double L = 3e-5; L < 2e-3; L *= 1.15, ++levels) {
    // The offset vertex V + R n lies at height 1 + R n.z; the clip line's length is 20 dy
    // where the level is g dy below it.
    const double z = 1 + R * n.z() - g * (L / 20) - R;
    const ZLevelResult r = run(el, z);
    EXPECT_EQ(r.stats.open_chains, 0u) << "L " << L;
    ASSERT_EQ(r.contours.size(), 1u) << "L " << L;
    int clips = 0;
    for (const ContourSeg& s : r.contours[0].segs)
      if (s.element == 0) {
        ++clips;
        EXPECT_NEAR((s.b - s.a).norm(), L, 1e-3 * L);
      }
    EXPECT_EQ(clips, 1) << "L " << L;
    if (levels % 8 == 0) check_result(o, r, rng, -14, -5, 14, 5, 200);
  }
}

// Two facets meeting in a valley bent by 3e-6 along a flat edge: their clip lines cross at a
// grazing angle, so each one's stretch past the crossing lies within 1e-11 mm of the other's
// line over more than the link tolerance (regression: the lower facet kept its stretch, as
// if shared, and left open chains; bends of about 1e-6 occur on scanned meshes).
TEST(ZLevel, GrazingClipLineCrossing) {
  const double R = 2.5, k = 0.1, s = 1, bend = 3e-6;
  const TriangleMesh mesh{
      {{0, 0, 0}, {10, 0, 10 * k}, {5, 5, 5 * k + 5 * s}, {5, -5, 5 * k - 5 * (s - bend)}},
      {{0, 1, 2}, {1, 0, 3}}};
  const OffsetElements el = build_offset_elements(mesh, R, Coplanar::kKeep);
  Oracle o(mesh, el);
  std::mt19937_64 rng(9);
  for (int l = 0; l < 40; ++l) {
    const double z = -1.5 + 0.0731 * l;
    const ZLevelResult r = run(el, z);
    EXPECT_EQ(r.stats.open_chains, 0u) << "z " << z;
    EXPECT_EQ(r.contours.size(), 1u) << "z " << z;
    if (l % 5 == 0) check_result(o, r, rng, -3, -8, 13, 8, 200);
  }
}

// A roof whose ridge rises at slopes of 6.5e-5 and 1e-5 and turns by 1.5e-4 rad at its middle
// vertex: the two ridge edges' ellipses are 46 and 300 m long and cross at a grazing angle
// beside the vertex, within a micrometre of each other over millimetres. Regression, found on
// a generated relief (tests/engine/robustness_test.cpp, relief seed 1020): the root search's
// rounding slack was scaled by the ellipse's length squared, kept every interval of that
// stretch open until it gave up, and called the curves coincident; the splits at the other
// curve's ends then cut a piece 4e-5 mm off its curve, and the contour was left open.
TEST(ZLevel, FlatRidgeEllipsesCrossingAtAGrazingAngle) {
  const double R = 3, h = 5, eave = 8;
  const double x[3] = {0, 20, 40}, y[3] = {0, 0.0015, 0};
  const double z[3] = {h, h + 20 * 6.5e-5, h + 20 * 6.5e-5 + 20 * 1e-5};
  TriangleMesh mesh;
  for (int i = 0; i < 3; ++i) {
    mesh.vertices.emplace_back(x[i], y[i], z[i]);       // ridge 3 i
    mesh.vertices.emplace_back(x[i], y[i] - eave, 0);   // eave -y
    mesh.vertices.emplace_back(x[i], y[i] + eave, 0);   // eave +y
  }
  for (std::uint32_t i = 0; i < 2; ++i) {
    const std::uint32_t r0 = 3 * i, r1 = 3 * i + 3;
    mesh.facets.push_back({r0, r0 + 1, r1 + 1});
    mesh.facets.push_back({r0, r1 + 1, r1});
    mesh.facets.push_back({r0, r1, r1 + 2});
    mesh.facets.push_back({r0, r1 + 2, r0 + 2});
  }
  const OffsetElements el = build_offset_elements(mesh, R, Coplanar::kKeep);
  Oracle o(mesh, el);
  std::mt19937_64 rng(10);
  for (double f : {0.2, 0.35, 0.5, 0.65, 0.8}) {
    const ZLevelResult r = run(el, z[1] + f * R - R);
    EXPECT_EQ(r.contours.size(), 1u) << "f " << f;
    EXPECT_EQ(r.stats.coincident_pairs, 0u) << "f " << f;
    check_result(o, r, rng, -4, -12, 44, 12, 300);
  }
}

// A square tower whose walls are cut into 40 bands: below the top every band's edges and
// corners shadow the same lines and circles. The contour is the square dilated by R (area
// exact, with the link gaps at the near-tangent joints), and the stacked coincident curves
// are trimmed to one before crossing (regression: k^2 pairs and pieces).
TEST(ZLevel, StackedWallEdgesShareOneShadow) {
  const int bands = 40;
  const double R = 2, side = 20, height = 30;
  TriangleMesh mesh;
  const Vec2 corner[4] = {{0, 0}, {side, 0}, {side, side}, {0, side}};
  for (int b = 0; b <= bands; ++b)
    for (const Vec2& c : corner) mesh.vertices.emplace_back(c.x(), c.y(), height * b / bands);
  for (std::uint32_t b = 0; b < std::uint32_t(bands); ++b)
    for (std::uint32_t i = 0; i < 4; ++i) {
      const std::uint32_t p = 4 * b + i, q = 4 * b + (i + 1) % 4;
      mesh.facets.push_back({p, q, q + 4});
      mesh.facets.push_back({p, q + 4, p + 4});
    }
  const std::uint32_t top = 4 * bands;
  mesh.facets.push_back({top, top + 1, top + 2});
  mesh.facets.push_back({top, top + 2, top + 3});
  const OffsetElements el = build_offset_elements(mesh, R, Coplanar::kKeep);
  Oracle o(mesh, el);
  std::mt19937_64 rng(10);
  for (double z : {1.0, 10.0, 25.0}) {
    const ZLevelResult r = run(el, z);
    ASSERT_EQ(r.contours.size(), 1u) << "z " << z;
    EXPECT_NEAR(r.contours[0].area, side * side + 4 * side * R + kPi * R * R, 1e-9) << "z " << z;
    EXPECT_LT(r.stats.pieces, 100u) << "z " << z;
    check_result(o, r, rng, -4, -4, side + 4, side + 4, 300);
  }
}

// A ring-shaped ridge: an outer loop and a hole inside it.
TEST(ZLevel, RingRidgeGivesOuterLoopAndHole) {
  TriangleMesh mesh;
  const int n = 33;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double x = -20 + 40.0 * i / (n - 1), y = -20 + 40.0 * j / (n - 1);
      const double rr = std::hypot(x, y);
      mesh.vertices.emplace_back(x, y, 5 * std::exp(-std::pow((rr - 10) / 3, 2)));
    }
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const auto a = std::uint32_t(j * n + i);
      mesh.facets.push_back({a, a + 1, a + std::uint32_t(n) + 1});
      mesh.facets.push_back({a, a + std::uint32_t(n) + 1, a + std::uint32_t(n)});
    }
  const OffsetElements el = build_offset_elements(mesh, 1.5, Coplanar::kKeep);
  const ZLevelResult r = run(el, 2);
  ASSERT_EQ(r.contours.size(), 2u);
  const ZContour* outer = r.contours[0].hole ? &r.contours[1] : &r.contours[0];
  const ZContour* hole = r.contours[0].hole ? &r.contours[0] : &r.contours[1];
  ASSERT_TRUE(hole->hole);
  ASSERT_FALSE(outer->hole);
  EXPECT_TRUE(inside_even_odd({polyline(*outer)}, hole->segs[0].a));
  std::mt19937_64 rng(7);
  Oracle o(mesh, el);
  EXPECT_LT(o.drop(Vec2(0, 0)), 2);
  EXPECT_FALSE(inside_even_odd({polyline(*outer), polyline(*hole)}, Vec2(0, 0)));
  check_result(o, r, rng, -22, -22, 22, 22, 600);
}

}  // namespace
}  // namespace ncpath
