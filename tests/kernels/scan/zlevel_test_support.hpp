#pragma once
// Oracles of the z-level contour tests (tests/kernels/scan/zlevel_*test.cpp): brute force from
// the mesh, no kernel code (point drop-cutter, distances to facets, edges and vertices), the
// checks of a result against them, and small meshes.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "kernels/cutters/drop_cutter.hpp"
#include "kernels/mesh/offset_elements.hpp"
#include "kernels/scan/zlevel.hpp"
#include "tests/kernels/scan/scan_test_support.hpp"

namespace ncpath::zlevel_test {


constexpr double kPi = std::numbers::pi;
constexpr double kDropTol = 1e-7;  // mm: contour vs brute-force point drop-cutter

// ---- oracles (brute force from the mesh, no kernel code) ----

using scan_test::prepare_all;

struct Oracle {
  const TriangleMesh& mesh;
  const OffsetElements& el;
  std::vector<PreparedFacet> facets;
  Cutter ball;
  Oracle(const TriangleMesh& m, const OffsetElements& e)
      : mesh(m), el(e), facets(prepare_all(m)), ball(ball_cutter(2 * e.radius)) {}
  double drop(const Vec2& p) const {
    CutterContact best;
    for (std::uint32_t i = 0; i < facets.size(); ++i)
      drop_facet(ball, facets[i], p.x(), p.y(), i, best);
    return best.tip_z;
  }
};

// Brute-force distances to a segment and a triangle: the scan tests' oracles.
inline double seg_dist(const Vec3& p, const Vec3& a, const Vec3& b) {
  return scan_test::point_segment_distance(p, a, b);
}
inline double tri_dist(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  return scan_test::point_triangle_distance(p, a, b, c);
}

// Distance from p to element `id`, from the mesh.
inline double element_distance(const Oracle& o, std::uint32_t id, const Vec3& p) {
  const auto& el = o.el;
  const auto& V = o.mesh.vertices;
  if (id < el.facet_count()) {
    const auto& f = o.mesh.facets[el.facet_source[id]];
    return tri_dist(p, V[f[0]], V[f[1]], V[f[2]]);
  }
  id -= std::uint32_t(el.facet_count());
  if (id < el.edge_count())
    return seg_dist(p, V[el.edge_vertices[id][0]], V[el.edge_vertices[id][1]]);
  id -= std::uint32_t(el.edge_count());
  return (p - V[el.vertex_source[id]]).norm();
}

// Horizontal contact below an element at the level (shadow): q_xy on the element's
// projection with the element at or above the level there.
inline bool shadow_contact_ok(const Oracle& o, std::uint32_t id, const Vec3& q) {
  const auto& el = o.el;
  const auto& V = o.mesh.vertices;
  const std::size_t nf = el.facet_count(), ne = el.edge_count();
  if (id < nf) return false;
  if (id < nf + ne) {
    const Vec3 &a = V[el.edge_vertices[id - nf][0]], &b = V[el.edge_vertices[id - nf][1]];
    const Vec2 a2(a.x(), a.y()), d2(b.x() - a.x(), b.y() - a.y()), q2(q.x(), q.y());
    const double t = std::clamp((q2 - a2).dot(d2) / d2.squaredNorm(), 0.0, 1.0);
    return (a2 + t * d2 - q2).norm() < 1e-7 && a.z() + t * (b.z() - a.z()) >= q.z() - 1e-7;
  }
  const Vec3& v = V[el.vertex_source[id - nf - ne]];
  return std::hypot(v.x() - q.x(), v.y() - q.y()) < 1e-7 && v.z() >= q.z() - 1e-7;
}

inline std::vector<std::uint32_t> all_ids(const OffsetElements& el) {
  std::vector<std::uint32_t> ids(el.element_count());
  for (std::uint32_t i = 0; i < ids.size(); ++i) ids[i] = i;
  return ids;
}

inline ZLevelResult run(const OffsetElements& el, double z, const ZLevelParams& p = {}) {
  const auto ids = all_ids(el);
  return zlevel_contours(el, ids, z, p);
}

inline std::vector<Vec2> polyline(const ZContour& c, double tol = 1e-6) {
  std::vector<Vec2> pts;
  for (const ContourSeg& s : c.segs) discretise(s, tol, pts);
  return pts;
}

inline bool inside_even_odd(const std::vector<std::vector<Vec2>>& loops, const Vec2& p) {
  bool in = false;
  for (const auto& L : loops)
    for (std::size_t i = 0, j = L.size() - 1; i < L.size(); j = i++) {
      const Vec2 &a = L[i], &b = L[j];
      if ((a.y() > p.y()) != (b.y() > p.y()) &&
          p.x() < a.x() + (p.y() - a.y()) / (b.y() - a.y()) * (b.x() - a.x()))
        in = !in;
    }
  return in;
}

inline double dist_to_loops(const std::vector<std::vector<Vec2>>& loops, const Vec2& p) {
  double best = INFINITY;
  for (const auto& L : loops)
    for (std::size_t i = 0, j = L.size() - 1; i < L.size(); j = i++) {
      const Vec2 d = L[i] - L[j];
      const double t =
          d.squaredNorm() > 0 ? std::clamp((p - L[j]).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0;
      best = std::min(best, (L[j] + t * d - p).norm());
    }
  return best;
}

inline double seg_length(const ContourSeg& s) {
  std::vector<Vec2> pts;
  discretise(s, 1e-9, pts);
  pts.push_back(s.b);
  double len = 0;
  for (std::size_t i = 1; i < pts.size(); ++i) len += (pts[i] - pts[i - 1]).norm();
  return len;
}

// Unit tangent of a segment at fraction f (finite difference of seg_point).
inline Vec2 seg_tangent(const ContourSeg& s, double f) {
  const double h = 1e-6;
  const Vec2 d = seg_point(s, std::min(1.0, f + h)) - seg_point(s, std::max(0.0, f - h));
  return d.normalized();
}

// Checks every invariant of a result against the oracle; returns the number of checks.
// allow_convex: flats exactly at the level expose their convex corners (see zlevel.hpp).
inline int check_result(const Oracle& o, const ZLevelResult& r, std::mt19937_64& rng, double x0, double y0,
                 double x1, double y1, int random_points, bool allow_convex = false) {
  const double z = r.tip_z, R = o.el.radius, zc = z + R;
  int checks = 0;
  EXPECT_EQ(r.stats.open_chains, 0u) << "z " << z;
  if (!allow_convex) {
    EXPECT_EQ(r.stats.convex_junctions, 0u) << "z " << z;
  }
  std::uniform_real_distribution<double> u01(0.1, 0.9);
  std::vector<std::vector<Vec2>> loops;
  for (const ZContour& c : r.contours) {
    loops.push_back(polyline(c));
    EXPECT_EQ(c.hole, c.area < 0);
    for (std::size_t i = 0; i < c.segs.size(); ++i) {
      const ContourSeg& s = c.segs[i];
      const ContourSeg& nx = c.segs[(i + 1) % c.segs.size()];
      const ContourSeg& pv = c.segs[(i + c.segs.size() - 1) % c.segs.size()];
      EXPECT_LT((s.b - nx.a).norm(), tol::kZLevelLink) << "loop not closed, z " << z;
      EXPECT_LT((seg_point(s, 1 - 1e-12) - s.b).norm(), 1e-8);
      for (double f : {0.0, 0.5, 1.0, u01(rng)}) {
        const Vec2 p = seg_point(s, f);
        // On the boundary of U: the drop height equals the level, or (where it jumps: shadow
        // segments, their ends, the equator joints of ellipses) the level lies between the
        // heights 1e-9 mm to either side.
        // Outward normal; at an end, the bisector of both segments' normals (it points into
        // the outside wedge of a sharp corner).
        auto right = [](const Vec2& t) { return Vec2(t.y(), -t.x()); };
        Vec2 n = right(seg_tangent(s, f));
        if (f == 0) n = (n + right(seg_tangent(pv, 1))).normalized();
        if (f == 1) n = (n + right(seg_tangent(nx, 0))).normalized();
        const double d = o.drop(p), dp = o.drop(p + 1e-9 * n), dm = o.drop(p - 1e-9 * n);
        const bool level = std::abs(d - z) <= kDropTol;
        const bool jump =
            std::min({d, dp, dm}) <= z + kDropTol && std::max({d, dp, dm}) >= z - kDropTol;
        EXPECT_TRUE(level || (jump && (s.shadow || f == 0 || f == 1 || std::abs(dp - dm) > 1e-6)))
            << contour_seg_kind_name(s.kind) << " element " << s.element << " f " << f << " at "
            << p.transpose() << " drop " << d << " (" << dm << ", " << dp << ") z " << z;
        ++checks;
        if ((f == 0.5 || (f > 0 && f < 1)) && seg_length(s) > 1e-4) {
          // U on the left: just left is in U, just right is not.
          EXPECT_GE(o.drop(p - 1e-6 * n), z - kDropTol)
              << "left of element " << s.element << " at " << p.transpose() << " z " << z;
          EXPECT_LT(o.drop(p + 1e-6 * n), z + kDropTol)
              << "right of element " << s.element << " at " << p.transpose() << " z " << z;
          checks += 2;
        }
      }
    }
    for (const ZJunction& j : c.junctions) {
      EXPECT_EQ(j.position.z(), z);
      EXPECT_NE(j.e1, j.e2);
      EXPECT_LT((Vec2(j.position.x(), j.position.y()) - c.segs[j.seg].a).norm(), 1e-12);
      const Vec3 centre(j.position.x(), j.position.y(), zc);
      for (int k = 0; k < 2; ++k) {
        const Vec3& b = k == 0 ? j.b1 : j.b2;
        const std::uint32_t e = k == 0 ? j.e1 : j.e2;
        EXPECT_NEAR(b.norm(), 1, 1e-12);
        if (std::abs(b.z()) > 1e-9) {
          EXPECT_NEAR(element_distance(o, e, centre), R, kDropTol) << "element " << e;
          EXPECT_NEAR(element_distance(o, e, centre - R * b), 0, kDropTol) << "element " << e;
        } else {
          EXPECT_TRUE(shadow_contact_ok(o, e, centre - R * b)) << "element " << e;
        }
        ++checks;
      }
      if (j.kind == JunctionKind::kTangent && std::abs(j.b1.z()) > 1e-9 &&
          std::abs(j.b2.z()) > 1e-9) {
        EXPECT_LT((j.b1 - j.b2).norm(), 1e-5);
      }
    }
  }
  std::uniform_real_distribution<double> rx(x0, x1), ry(y0, y1);
  for (int k = 0; k < random_points; ++k) {
    const Vec2 p(rx(rng), ry(rng));
    if (dist_to_loops(loops, p) < 1e-4) continue;
    const double d = o.drop(p);
    if (std::abs(d - z) < 1e-6) continue;
    EXPECT_EQ(inside_even_odd(loops, p), d >= z)
        << "point " << p.transpose() << " drop " << d << " level " << z;
    ++checks;
  }
  return checks;
}

inline bool same_result(const ZLevelResult& a, const ZLevelResult& b) {
  if (a.contours.size() != b.contours.size()) return false;
  for (std::size_t i = 0; i < a.contours.size(); ++i) {
    const ZContour &p = a.contours[i], &q = b.contours[i];
    if (p.segs.size() != q.segs.size() || p.junctions.size() != q.junctions.size() ||
        p.hole != q.hole || p.area != q.area)
      return false;
    for (std::size_t k = 0; k < p.segs.size(); ++k) {
      const ContourSeg &s = p.segs[k], &t = q.segs[k];
      if (s.kind != t.kind || s.element != t.element || s.a != t.a || s.b != t.b ||
          s.centre != t.centre || s.r1 != t.r1 || s.r2 != t.r2 || s.axis != t.axis ||
          s.t0 != t.t0 || s.t1 != t.t1 || s.shadow != t.shadow)
        return false;
    }
    for (std::size_t k = 0; k < p.junctions.size(); ++k) {
      const ZJunction &s = p.junctions[k], &t = q.junctions[k];
      if (s.position != t.position || s.kind != t.kind || s.e1 != t.e1 || s.e2 != t.e2 ||
          s.b1 != t.b1 || s.b2 != t.b2 || s.seg != t.seg)
        return false;
    }
  }
  return true;
}

// ---- meshes ----

// Random soups and terrains: the scan tests' (tests/kernels/scan/scan_test_support.hpp).
using scan_test::random_soup;
using scan_test::random_terrain;

inline TriangleMesh one_triangle(const Vec3& a, const Vec3& b, const Vec3& c) {
  return TriangleMesh{{a, b, c}, {{0, 1, 2}}};
}

}  // namespace ncpath::zlevel_test
