// Upper envelope of a drive plane and its CL curve (kernels/scan/envelope): the envelope
// equals the brute-force point drop-cutter (raised to a floor) within 1e-7 mm on random
// meshes; junctions carry bi-contact vectors at distance R from both elements; analytic
// V-grooves and a box pocket put sharp-concave points where geometry says they are; the
// discretisation never lies below the exact curve and stays within the tolerance.
#include "kernels/scan/envelope.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "tests/kernels/scan/scan_test_support.hpp"

namespace ncpath {
namespace {

using namespace scan_test;

struct PlaneResult {
  std::vector<SlicePiece> pieces;
  std::vector<EnvelopeSpan> spans;
  PlaneCurve curve;
};

PlaneResult scan_plane(const OffsetElements& el, double y0, double floor_z, double x_lo,
                       double x_hi) {
  PlaneResult r;
  // Only reachable elements, as the engine does: the drop-cutter comparisons check that
  // the skipped ones never show.
  for (std::uint32_t id = 0; id < el.element_count(); ++id)
    if (element_reachable(el, id)) slice_elements(el, y0, id, id + 1, r.pieces);
  std::erase_if(r.pieces, [&](const SlicePiece& p) { return p.x1 <= x_lo || p.x0 >= x_hi; });
  for (SlicePiece& p : r.pieces) {
    p.x0 = std::max(p.x0, x_lo);
    p.x1 = std::min(p.x1, x_hi);
  }
  r.pieces.push_back(floor_piece(floor_z, el.radius, y0, x_lo, x_hi));
  upper_envelope(r.pieces, r.spans);
  plane_curve(r.pieces, r.spans, r.curve);
  return r;
}

// Tip z of the exact curve at x (the span containing x; the higher one at a shared end).
double curve_z(const PlaneResult& r, double x) {
  double best = -INFINITY;
  for (const EnvelopeSpan& s : r.spans)
    if (x >= s.x0 && x <= s.x1) best = std::max(best, tip_z(r.pieces[s.piece], x));
  return best;
}

void check_random(const TriangleMesh& mesh, std::mt19937_64& rng, int planes, int& checks) {
  const double R = 1.25, floor_z = -0.5, x_lo = -1.5, x_hi = 21.5;
  const OffsetElements el = build_offset_elements(mesh, R);
  const auto facets = prepare_all(mesh);
  const Cutter ball = ball_cutter(2 * R);
  std::uniform_real_distribution<double> ry(-1, 21), rx(x_lo, x_hi);
  for (int k = 0; k < planes; ++k) {
    const double y0 = ry(rng);
    const PlaneResult r = scan_plane(el, y0, floor_z, x_lo, x_hi);
    // Spans cover [x_lo, x_hi] without gaps or overlaps, in order.
    ASSERT_FALSE(r.spans.empty());
    EXPECT_EQ(r.spans.front().x0, x_lo);
    EXPECT_EQ(r.spans.back().x1, x_hi);
    for (std::size_t i = 0; i < r.spans.size(); ++i) {
      EXPECT_LT(r.spans[i].x0, r.spans[i].x1);
      if (i > 0) {
        EXPECT_EQ(r.spans[i - 1].x1, r.spans[i].x0);
      }
    }
    EXPECT_EQ(r.curve.run_starts.size(), 1u);
    auto want = [&](double x) { return std::max(floor_z, drop_all(ball, facets, x, y0)); };
    for (int s = 0; s < 200; ++s) {
      const double x = rx(rng);
      ASSERT_NEAR(curve_z(r, x), want(x), kDropTol) << "x " << x << " y " << y0;
      ++checks;
    }
    // Span ends (where pieces change) and span middles.
    for (const EnvelopeSpan& s : r.spans) {
      const double xm = 0.5 * (s.x0 + s.x1);
      ASSERT_NEAR(tip_z(r.pieces[s.piece], xm), want(xm), kDropTol) << "mid x " << xm;
      ++checks;
    }
    // Junctions: both contacts at distance R from the ball centre, unit normals.
    for (const CurveJunction& j : r.curve.junctions) {
      const Vec3 centre(j.x, y0, j.z + R);
      EXPECT_NEAR(j.b1.norm(), 1, 1e-9);
      EXPECT_NEAR(j.b2.norm(), 1, 1e-9);
      // At the low end of a jump (a vertical segment) the upper element is seen from the
      // side: at distance R only for a vertical wall, so it is not checked there.
      const auto& segs = r.curve.segments;
      const bool down_before = j.segment > 0 && segs[j.segment - 1].vertical &&
                               segs[j.segment - 1].z1 < segs[j.segment - 1].z0;
      const bool up_after = segs[j.segment].vertical && segs[j.segment].z1 > segs[j.segment].z0;
      for (int side = 0; side < 2; ++side) {
        const std::uint32_t e = side == 0 ? j.element1 : j.element2;
        if ((side == 0 && down_before) || (side == 1 && up_after)) continue;
        if (e == kNoElement) {
          EXPECT_NEAR(centre.z() - R, floor_z, 1e-9);
        } else {
          EXPECT_NEAR(element_distance(el, mesh, e, centre), R, 1e-7)
              << "element " << e << " of " << j.element1 << "," << j.element2 << " kind "
              << junction_kind_name(j.kind) << " x " << j.x << " seg " << j.segment << " vert "
              << r.curve.segments[j.segment].vertical << " F " << el.facet_count() << " E "
              << el.edge_count();
        }
      }
    }
  }
}

TEST(Envelope, RandomSoupEqualsDropCutter) {
  std::mt19937_64 rng(7);
  int checks = 0;
  for (int m = 0; m < 3; ++m) check_random(random_soup(rng, 300), rng, 10, checks);
  EXPECT_GE(checks, 6000);
}

TEST(Envelope, RandomTerrainEqualsDropCutter) {
  std::mt19937_64 rng(77);
  int checks = 0;
  for (int m = 0; m < 3; ++m) check_random(random_terrain(rng, 13), rng, 10, checks);
  EXPECT_GE(checks, 6000);
}

std::vector<const CurveJunction*> concave(const PlaneCurve& c) {
  std::vector<const CurveJunction*> out;
  for (const CurveJunction& j : c.junctions)
    if (j.kind == JunctionKind::kSharpConcave) out.push_back(&j);
  return out;
}

TEST(Envelope, VGrooveSharpConcavePoint) {
  const double R = 2.5;
  for (double a : {1.0, 0.3, 2.5}) {
    const OffsetElements el = build_offset_elements(v_groove(a), R);
    const PlaneResult r = scan_plane(el, 1.3, -100, -8, 8);
    // The ball sits on both flanks at x = 0: centre R sqrt(1 + a^2), tip R (sqrt(1+a^2) - 1).
    const auto cj = concave(r.curve);
    ASSERT_EQ(cj.size(), 1u) << "a " << a;
    EXPECT_NEAR(cj[0]->x, 0, 1e-9);
    EXPECT_NEAR(cj[0]->z, R * (std::sqrt(1 + a * a) - 1), 1e-9);
    const double n = std::sqrt(1 + a * a);
    EXPECT_LT((cj[0]->b1 - Vec3(a / n, 0, 1 / n)).norm(), 1e-9);  // left flank z = -a x
    EXPECT_LT((cj[0]->b2 - Vec3(-a / n, 0, 1 / n)).norm(), 1e-9);
    // On each flank the curve is the flank raised by R sqrt(1 + a^2) - R.
    for (double x : {-5.0, -1.0, 2.0, 6.0})
      EXPECT_NEAR(curve_z(r, x), a * std::abs(x) + R * (n - 1), 1e-9) << "x " << x;
  }
}

TEST(Envelope, BoxPocketWallFloorCreases) {
  const double R = 1.25;
  const OffsetElements el = build_offset_elements(box_pocket(), R);
  const PlaneResult r = scan_plane(el, 0.7, -50, -9, 9);
  // Left wall x = -5: the ball slides down it at x = -5 + R onto the floor; right wall at
  // x = 5 - R. The creases are sharp concave with b = wall normal and floor normal.
  const auto cj = concave(r.curve);
  ASSERT_EQ(cj.size(), 2u);
  EXPECT_NEAR(cj[0]->x, -5 + R, 1e-12);
  EXPECT_NEAR(cj[0]->z, 0, 1e-12);
  EXPECT_LT((cj[0]->b1 - Vec3(1, 0, 0)).norm(), 1e-9);
  EXPECT_LT((cj[0]->b2 - Vec3(0, 0, 1)).norm(), 1e-9);
  EXPECT_NEAR(cj[1]->x, 5 - R, 1e-12);
  EXPECT_LT((cj[1]->b1 - Vec3(0, 0, 1)).norm(), 1e-9);
  EXPECT_LT((cj[1]->b2 - Vec3(-1, 0, 0)).norm(), 1e-9);
  // Two vertical segments (the walls), from 3 - R down to 0 and back up.
  int vertical = 0;
  for (const CurveSegment& s : r.curve.segments)
    if (s.vertical) {
      ++vertical;
      EXPECT_NEAR(std::max(s.z0, s.z1), 3 - R, 1e-12);
      EXPECT_NEAR(std::min(s.z0, s.z1), 0, 1e-12);
    }
  EXPECT_EQ(vertical, 2);
  // The rim: the edge's quarter circle, tip 3 + sqrt(R^2 - d^2) - R at d from the wall.
  for (double d : {0.2, 0.6, 1.1})
    EXPECT_NEAR(curve_z(r, 5 - d), 3 + std::sqrt(R * R - d * d) - R, 1e-12);
  for (double x : {-8.0, 6.0}) EXPECT_NEAR(curve_z(r, x), 3, 1e-12);
  for (double x : {-3.0, 0.0, 3.5}) EXPECT_NEAR(curve_z(r, x), 0, 1e-12);
}

TEST(Envelope, OpenSingleFacet) {
  // One tilted facet z = 0.2 x over a floor: CL = the offset plane, then the edge arcs
  // down to the floor, where the ball meets the floor: two sharp-concave points.
  const double R = 1.0;
  TriangleMesh m{{{0, -10, 0}, {10, -10, 2}, {0, 10, 0}}, {{0, 1, 2}}};
  const OffsetElements el = build_offset_elements(m, R);
  const PlaneResult r = scan_plane(el, -5, -1, -5, 15);
  const double n = std::sqrt(1 + 0.04);
  for (double x : {1.0, 3.0}) EXPECT_NEAR(curve_z(r, x), 0.2 * x + R * (n - 1), 1e-12);
  const auto cj = concave(r.curve);
  ASSERT_EQ(cj.size(), 2u);
  for (const CurveJunction* j : cj) {
    EXPECT_NEAR(j->z, -1, 1e-12);
    // The ball touches the floor and an edge (the vertical left edge x = 0, or the right
    // edge from (10,-10,2) to (0,10,0)).
    EXPECT_TRUE(j->element1 == kNoElement || j->element2 == kNoElement);
  }
  // Left: the ball at the floor touching the edge x = 0, z = 0: centre (x, -5, 0) at
  // distance R from (0, -5, 0) -> x = -R.
  EXPECT_NEAR(cj[0]->x, -R, 1e-12);
}

// A faceted cylinder of radius rho lying along direction (cos t, sin t) through the origin.
TriangleMesh lying_cylinder(double rho, double t, int sides) {
  TriangleMesh m;
  const Vec3 ax(std::cos(t), std::sin(t), 0), side(-std::sin(t), std::cos(t), 0);
  for (int k = 0; k <= sides; ++k) {
    const double phi = M_PI * k / sides;  // upper half
    const Vec3 r = rho * (std::cos(phi) * side + std::sin(phi) * Vec3(0, 0, 1));
    m.vertices.push_back(-15 * ax + r);
    m.vertices.push_back(15 * ax + r);
  }
  for (int k = 0; k < sides; ++k) {
    const auto a = std::uint32_t(2 * k);
    m.facets.push_back({a, a + 1, a + 3});
    m.facets.push_back({a, a + 3, a + 2});
  }
  return m;
}

TEST(Envelope, LyingCylindersGiveLinesAndEllipses) {
  const double R = 1.5;
  std::mt19937_64 rng(3);
  for (double t : {0.0, M_PI / 4}) {
    const TriangleMesh mesh = lying_cylinder(4, t, 12);
    const OffsetElements el = build_offset_elements(mesh, R);
    const auto facets = prepare_all(mesh);
    const Cutter ball = ball_cutter(2 * R);
    // y0 = 1.4 lies in the contact wedge of the ridge edge at 75 degrees (y in [1.23, 1.61]).
    const double y0 = t == 0 ? 1.4 : 0.9;
    const PlaneResult r = scan_plane(el, y0, -2, -8, 8);
    int ellipses = 0, lines = 0;
    for (const EnvelopeSpan& s : r.spans) {
      const PieceKind k = r.pieces[s.piece].kind;
      ellipses += k == PieceKind::kCylinderEllipse;
      lines += k == PieceKind::kCylinderLine;
    }
    if (t == 0) {  // the ridge edge is parallel to the plane: a line over the whole range
      EXPECT_GT(lines, 0);
      EXPECT_EQ(ellipses, 0);
    } else {
      EXPECT_GT(ellipses, 4);  // every ridge edge crosses the plane obliquely
    }
    std::uniform_real_distribution<double> rx(-8, 8);
    for (int s = 0; s < 300; ++s) {
      const double x = rx(rng);
      EXPECT_NEAR(curve_z(r, x), std::max(-2.0, drop_all(ball, facets, x, y0)), kDropTol);
    }
  }
}

TEST(Envelope, SphereIsSmoothAndBetweenItsBounds) {
  // Over a convex faceted sphere the CL curve has no sharp-concave point above the floor,
  // and the ball centre stays between rho cos(a) + R and rho + R from the sphere's centre
  // (a: the largest angle between a facet's normal and its vertices, so the facets lie
  // between the spheres of radius rho cos(a) and rho).
  const double rho = 10, R = 2.5;
  const TriangleMesh mesh = uv_hemisphere(rho, 24, 64, Vec3(10, 10, 0));
  double cos_a = 1;
  for (const auto& f : mesh.facets) {
    const Vec3 &a = mesh.vertices[f[0]], &b = mesh.vertices[f[1]], &c = mesh.vertices[f[2]];
    const Vec3 n = (b - a).cross(c - a).normalized();
    for (const Vec3& p : {a, b, c})
      cos_a = std::min(cos_a, std::abs(n.dot((p - Vec3(10, 10, 0)).normalized())));
  }
  const OffsetElements el = build_offset_elements(mesh, R);
  for (double y0 : {10.0, 13.7}) {
    const PlaneResult r = scan_plane(el, y0, -R, -5, 25);
    for (const CurveJunction& j : r.curve.junctions)
      if (j.kind == JunctionKind::kSharpConcave) {
        EXPECT_TRUE(j.element1 == kNoElement || j.element2 == kNoElement)
            << "concave point on the sphere at x " << j.x;
      }
    for (double x = 10 - 9; x <= 10 + 9; x += 0.37) {
      const double z = curve_z(r, x) + R;  // ball centre
      const double d = (Vec3(x, y0, z) - Vec3(10, 10, 0)).norm();
      if (z < R) continue;  // on the floor
      EXPECT_LE(d, rho + R + 1e-9) << "x " << x;
      EXPECT_GE(d, rho * cos_a + R - 1e-9) << "x " << x;
    }
  }
}

TEST(Envelope, DiscretisationIsAboveAndWithinTolerance) {
  std::mt19937_64 rng(11);
  const TriangleMesh mesh = random_terrain(rng, 9);
  const double R = 2.0;
  const OffsetElements el = build_offset_elements(mesh, R);
  for (double tol : {0.01, 0.001}) {
    const PlaneResult r = scan_plane(el, 7.3, -1, -1, 21);
    std::vector<Vec2> pts;
    std::vector<double> lift;
    for (const CurveSegment& s : r.curve.segments)
      discretise_segment(r.pieces[s.piece], s, tol, pts, lift);
    const CurveSegment& last = r.curve.segments.back();
    pts.emplace_back(last.x1, last.z1);
    lift.push_back(0);
    // Raise each point by the larger lift of its two chords.
    std::vector<Vec2> out = pts;
    for (std::size_t i = 0; i < pts.size(); ++i)
      out[i].y() += std::max(lift[i], i > 0 ? lift[i - 1] : 0.0);
    int arcs = 0;
    for (std::size_t i = 0; i + 1 < out.size(); ++i) {
      const Vec2 a = out[i], b = out[i + 1];
      if (a.x() == b.x()) continue;  // vertical segment
      for (int s = 1; s < 8; ++s) {
        const double f = s / 8.0, x = a.x() + f * (b.x() - a.x());
        const double zc = a.y() + f * (b.y() - a.y()), ze = curve_z(r, x);
        EXPECT_GE(zc, ze - 1e-12) << "chord below the curve at x " << x;
        // Vertical gap within tol times the chord's slope factor (perpendicular tol).
        const double m = (b.y() - a.y()) / (b.x() - a.x());
        EXPECT_LE(zc - ze, 2 * tol * std::sqrt(1 + m * m) + 1e-12) << "x " << x;
      }
      arcs += lift[i] > 0;
    }
    EXPECT_GT(arcs, 10);
  }
}

TEST(Envelope, PieceOrderDoesNotMatter) {
  std::mt19937_64 rng(21);
  const OffsetElements el = build_offset_elements(random_terrain(rng, 11), 1.0);
  PlaneResult r = scan_plane(el, 9.1, -1, -1, 21);
  std::vector<SlicePiece> shuffled = r.pieces;
  std::shuffle(shuffled.begin(), shuffled.end(), rng);
  std::vector<EnvelopeSpan> spans;
  upper_envelope(shuffled, spans);
  ASSERT_EQ(spans.size(), r.spans.size());
  for (std::size_t i = 0; i < spans.size(); ++i) {
    EXPECT_EQ(shuffled[spans[i].piece].element, r.pieces[r.spans[i].piece].element);
    EXPECT_EQ(spans[i].x0, r.spans[i].x0);
    EXPECT_EQ(spans[i].x1, r.spans[i].x1);
  }
}

}  // namespace
}  // namespace ncpath
