#pragma once
// Shared by the scan kernel tests: brute-force geometry oracles (no kernel code), the
// point drop-cutter over all facets, random meshes (soups, terrains with a hole and a
// non-manifold edge) and analytic ones (a V-groove, a box pocket, a hemisphere), which the
// engine's clean-up tests use too.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "kernels/cutters/drop_cutter.hpp"
#include "kernels/mesh/offset_elements.hpp"
#include "kernels/scan/plane_slice.hpp"

namespace ncpath::scan_test {

inline constexpr double kDistTol = 1e-9;  // mm: piece point vs exact distance definition
inline constexpr double kDropTol = 1e-7;  // mm: envelope vs point drop-cutter (issue 5)

// ---- oracles (brute-force geometry, no kernel code) ----

inline double point_segment_distance(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 d = b - a;
  const double t = std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return (p - (a + t * d)).norm();
}

// Distance to a triangle: to its plane when the projection is inside (barycentric signs),
// otherwise to the nearest of its three sides.
inline double point_triangle_distance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 n = (b - a).cross(c - a);
  const Vec3 proj = p - n * ((p - a).dot(n) / n.squaredNorm());
  const double s0 = (b - a).cross(proj - a).dot(n), s1 = (c - b).cross(proj - b).dot(n);
  const double s2 = (a - c).cross(proj - c).dot(n);
  if ((s0 >= 0 && s1 >= 0 && s2 >= 0) || (s0 <= 0 && s1 <= 0 && s2 <= 0)) return (p - proj).norm();
  return std::min({point_segment_distance(p, a, b), point_segment_distance(p, b, c),
                   point_segment_distance(p, c, a)});
}

// Distance from p to the element `id` of el, from the mesh data only.
inline double element_distance(const OffsetElements& el, const TriangleMesh& mesh, std::uint32_t id,
                        const Vec3& p) {
  if (id < el.facet_count()) {
    const auto& f = mesh.facets[el.facet_source[id]];
    return point_triangle_distance(p, mesh.vertices[f[0]], mesh.vertices[f[1]],
                                   mesh.vertices[f[2]]);
  }
  id -= std::uint32_t(el.facet_count());
  if (id < el.edge_count()) {
    const auto& e = el.edge_vertices[id];
    return point_segment_distance(p, mesh.vertices[e[0]], mesh.vertices[e[1]]);
  }
  id -= std::uint32_t(el.edge_count());
  return (p - mesh.vertices[el.vertex_source[id]]).norm();
}

// Brute-force point drop-cutter with a ball over all facets.
inline double drop_all(const Cutter& cutter, const std::vector<PreparedFacet>& facets, double x,
                double y) {
  CutterContact best;
  for (std::uint32_t i = 0; i < facets.size(); ++i) drop_facet(cutter, facets[i], x, y, i, best);
  return best.tip_z;
}

inline std::vector<PreparedFacet> prepare_all(const TriangleMesh& mesh) {
  std::vector<PreparedFacet> out;
  for (const auto& f : mesh.facets) {
    PreparedFacet pf;
    if (prepare_facet(mesh.vertices[f[0]], mesh.vertices[f[1]], mesh.vertices[f[2]], pf))
      out.push_back(pf);
  }
  return out;
}

// All pieces of all elements in the plane y0 (trimmed to their cones, or whole).
inline std::vector<SlicePiece> slice_all(const OffsetElements& el, double y0, bool trim = false) {
  std::vector<SlicePiece> pieces;
  slice_elements(el, y0, 0, std::uint32_t(el.element_count()), pieces, trim);
  return pieces;
}

inline double envelope_tip(const std::vector<SlicePiece>& pieces, double x) {
  double best = -std::numeric_limits<double>::infinity();
  for (const SlicePiece& pc : pieces)
    if (x >= pc.x0 && x <= pc.x1) best = std::max(best, tip_z(pc, x));
  return best;
}

// ---- random meshes ----

// A soup of random triangles (every edge a boundary edge), some steep, some overhanging.
inline TriangleMesh random_soup(std::mt19937_64& rng, int count) {
  std::uniform_real_distribution<double> pos(0, 20), off(-3, 3), zc(0, 4);
  TriangleMesh m;
  for (int i = 0; i < count; ++i) {
    const Vec3 c(pos(rng), pos(rng), zc(rng));
    const auto base = std::uint32_t(m.vertices.size());
    for (int k = 0; k < 3; ++k) m.vertices.push_back(c + Vec3(off(rng), off(rng), off(rng)));
    m.facets.push_back({base, base + 1, base + 2});
  }
  return m;
}

// A random height field on an n x n grid (shared edges, convex and concave), with one
// facet deleted (a hole: boundary edges inside) and one extra facet on an existing edge
// (a non-manifold edge).
inline TriangleMesh random_terrain(std::mt19937_64& rng, int n) {
  std::uniform_real_distribution<double> h(0, 3), jitter(-0.3, 0.3);
  TriangleMesh m;
  const double step = 20.0 / (n - 1);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      m.vertices.emplace_back(i * step + jitter(rng), j * step + jitter(rng), h(rng));
  auto id = [n](int i, int j) { return std::uint32_t(j * n + i); };
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      m.facets.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.facets.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  m.facets.erase(m.facets.begin() + std::ptrdiff_t(m.facets.size() / 2));
  m.vertices.emplace_back(5.0, 5.0, 6.0);
  m.facets.push_back({id(2, 2), id(3, 3), std::uint32_t(m.vertices.size() - 1)});
  return m;
}

// ---- analytic meshes ----

// Two half-planes z = a |x| (a groove along y), 20 x 20 mm.
inline TriangleMesh v_groove(double a) {
  TriangleMesh m;
  m.vertices = {{-10, -10, 10 * a}, {0, -10, 0}, {10, -10, 10 * a},
                {-10, 10, 10 * a},  {0, 10, 0},  {10, 10, 10 * a}};
  m.facets = {{0, 1, 4}, {0, 4, 3}, {1, 2, 5}, {1, 5, 4}};
  return m;
}

// A 20 x 20 plate, top z = 3, with a 10 x 10 pocket of floor z = 0 and vertical walls.
inline TriangleMesh box_pocket() {
  TriangleMesh m;
  const double o = 10, i = 5, top = 3;
  m.vertices = {{-o, -o, top}, {o, -o, top}, {o, o, top}, {-o, o, top},  // 0-3 outer
                {-i, -i, top}, {i, -i, top}, {i, i, top}, {-i, i, top},  // 4-7 rim
                {-i, -i, 0},   {i, -i, 0},   {i, i, 0},   {-i, i, 0}};   // 8-11 floor
  m.facets = {{0, 1, 5},  {0, 5, 4},   {1, 2, 6},  {1, 6, 5},
              {2, 3, 7},  {2, 7, 6},   {3, 0, 4},  {3, 4, 7},  // top ring
              {8, 9, 10}, {8, 10, 11},                         // floor
              {4, 5, 9},  {4, 9, 8},   {5, 6, 10}, {5, 10, 9},
              {6, 7, 11}, {6, 11, 10}, {7, 4, 8},  {7, 8, 11}};  // walls
  return m;
}

// A UV sphere of radius rho (vertices on the sphere), upper half, centred at c; rings from
// the pole to the equator, sectors around.
inline TriangleMesh uv_hemisphere(double rho, int rings, int sectors, const Vec3& c) {
  TriangleMesh m;
  m.vertices.push_back(c + Vec3(0, 0, rho));  // pole
  for (int i = 1; i <= rings; ++i) {
    const double th = 0.5 * M_PI * i / rings;
    for (int j = 0; j < sectors; ++j) {
      const double ph = 2 * M_PI * j / sectors;
      m.vertices.push_back(c + rho * Vec3(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph),
                                          std::cos(th)));
    }
  }
  auto id = [&](int i, int j) { return std::uint32_t(1 + (i - 1) * sectors + (j % sectors)); };
  for (int j = 0; j < sectors; ++j) m.facets.push_back({0, id(1, j), id(1, j + 1)});
  for (int i = 1; i < rings; ++i)
    for (int j = 0; j < sectors; ++j) {
      m.facets.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.facets.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return m;
}

}  // namespace ncpath::scan_test
