#include "kernels/mesh/offset_elements.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cassert>
#include <cmath>
#include <numeric>

namespace ncpath {

const char* edge_kind_name(EdgeKind kind) {
  switch (kind) {
    case EdgeKind::kConvex:
      return "convex";
    case EdgeKind::kConcave:
      return "concave";
    case EdgeKind::kFlat:
      return "flat";
    case EdgeKind::kFold:
      return "fold";
    case EdgeKind::kBoundary:
      return "boundary";
    case EdgeKind::kNonManifold:
      return "non-manifold";
  }
  return "?";
}

bool upward_unit_normal(const Vec3& a, const Vec3& b, const Vec3& c, Vec3& n) {
  // Same normal and degeneracy test as prepare_facet (drop_cutter.cpp), so that both agree
  // on which facets exist.
  n = (b - a).cross(c - a);
  const double len = n.norm();
  if (!(len >= tol::kDegenerateArea2)) return false;
  n /= len;
  if (n.z() < 0) n = -n;
  return true;
}

std::uint32_t count_offset_facets(const TriangleMesh& mesh, std::uint32_t begin,
                                  std::uint32_t end) {
  std::uint32_t count = 0;
  Vec3 n;
  for (std::uint32_t i = begin; i < end; ++i) {
    const auto& f = mesh.facets[i];
    count += upward_unit_normal(mesh.vertices[f[0]], mesh.vertices[f[1]], mesh.vertices[f[2]], n);
  }
  return count;
}

void fill_offset_facets(const TriangleMesh& mesh, double radius, std::uint32_t begin,
                        std::uint32_t end, std::uint32_t first_slot, OffsetElements& out,
                        std::span<std::uint64_t> keys) {
  std::uint32_t slot = first_slot;
  for (std::uint32_t i = begin; i < end; ++i) {
    const auto& f = mesh.facets[i];
    const Vec3 &a = mesh.vertices[f[0]], &b = mesh.vertices[f[1]], &c = mesh.vertices[f[2]];
    Vec3 n;
    if (!upward_unit_normal(a, b, c, n)) continue;
    const Vec3 shift = radius * n;
    out.facet_tri[slot] = {a + shift, b + shift, c + shift};
    out.facet_normal[slot] = n;
    out.facet_source[slot] = i;
    out.facet_vertices[slot] = f;
    out.facet_vertical[slot] = std::abs(n.z()) < tol::kVerticalNormalZ;
    for (int k = 0; k < 3; ++k) {
      const std::uint64_t p = f[k], q = f[(k + 1) % 3];
      keys[3 * std::size_t(slot) + k] = (std::min(p, q) << 32) | std::max(p, q);
    }
    ++slot;
  }
}

namespace {

std::uint32_t opposite_vertex(const OffsetElements& el, std::uint32_t facet, std::uint32_t lo,
                              std::uint32_t hi) {
  const auto& fv = el.facet_vertices[facet];
  std::uint32_t opp = fv[0];
  for (std::uint32_t v : fv)
    if (v != lo && v != hi) opp = v;
  return opp;
}

// Sine-like signed height of the facet's vertex opposite to the edge (lo, hi) over the other
// facet's plane, relative to its distance from the edge's start.
double opposite_height(const OffsetElements& el, std::uint32_t plane_facet,
                       std::uint32_t other_facet, std::uint32_t lo, std::uint32_t hi) {
  const Vec3 d = el.points[opposite_vertex(el, other_facet, lo, hi)] - el.points[lo];
  const double len = d.norm();
  return len > 0 ? el.facet_normal[plane_facet].dot(d) / len : 0.0;
}

}  // namespace

bool edge_wedge_reachable(const Vec3& e, const Vec3& w1, const Vec3& w2) {
  const double s = e.dot(w1.cross(w2));
  // Flat (or nearly): kept. Its cylinder only ties with the two offset triangles, but those
  // are computed from different normals, so rounding can leave a sliver between them that
  // the cylinder fills. Folded onto itself (w1 along w2): the edge is a boundary.
  if (std::abs(s) <= tol::kFlatEdgeKeep * w1.norm() * w2.norm()) return true;
  // Rays of the wedge: r1 perpendicular to w1 with r1 . w2 < 0, r2 likewise.
  const double sign = s > 0 ? 1.0 : -1.0;
  const Vec3 r1 = -sign * e.cross(w1), r2 = sign * e.cross(w2);
  return r1.z() > 0 || r2.z() > 0;
}

bool element_reachable(const OffsetElements& el, std::uint32_t id) {
  const std::size_t nf = el.facet_count(), ne = el.edge_count();
  if (id < nf) return !el.facet_vertical[id];
  if (id < nf + ne) return el.edge_reachable[id - nf] != 0;
  return el.vertex_reachable[id - nf - ne] != 0;
}

void collect_vertices(OffsetElements& el) {
  std::vector<std::uint8_t> used(el.points.size(), 0);
  for (const auto& fv : el.facet_vertices)
    for (std::uint32_t v : fv) used[v] = 1;
  for (std::size_t e = 0; e < el.edge_count(); ++e)
    if (el.edge_reachable[e])
      for (std::uint32_t v : el.edge_vertices[e]) used[v] = 2;
  el.vertex_source.clear();
  el.vertex_reachable.clear();
  for (std::uint32_t v = 0; v < used.size(); ++v)
    if (used[v]) {
      el.vertex_source.push_back(v);
      el.vertex_reachable.push_back(used[v] == 2);
    }
}

void classify_edges(std::span<const std::uint64_t> sorted_keys,
                    std::span<const std::uint32_t> key_facet,
                    std::span<const std::uint32_t> edge_start, std::uint32_t begin,
                    std::uint32_t end, OffsetElements& out, double flat_sine) {
  for (std::uint32_t e = begin; e < end; ++e) {
    const std::uint32_t i0 = edge_start[e], i1 = edge_start[e + 1];
    const std::uint64_t key = sorted_keys[i0];
    const auto lo = std::uint32_t(key >> 32), hi = std::uint32_t(key & 0xffffffffu);
    out.edge_vertices[e] = {lo, hi};
    out.edge_facet_count[e] = i1 - i0;
    EdgeKind kind;
    bool reachable = true;
    if (i1 - i0 == 1) {
      kind = EdgeKind::kBoundary;
    } else if (i1 - i0 > 2) {
      kind = EdgeKind::kNonManifold;
    } else {
      const std::uint32_t f1 = key_facet[i0], f2 = key_facet[i0 + 1];
      const Vec3 a = out.points[lo], d = out.points[hi] - a;
      const double len = d.norm();
      if (len > 0) {
        const Vec3 e = d / len;
        Vec3 w1 = out.points[opposite_vertex(out, f1, lo, hi)] - a;
        Vec3 w2 = out.points[opposite_vertex(out, f2, lo, hi)] - a;
        w1 -= e * e.dot(w1);
        w2 -= e * e.dot(w2);
        reachable = edge_wedge_reachable(e, w1, w2);
      }
      const double s1 = opposite_height(out, f1, f2, lo, hi);
      const double s2 = opposite_height(out, f2, f1, lo, hi);
      if (std::abs(s1) <= flat_sine && std::abs(s2) <= flat_sine)
        kind = EdgeKind::kFlat;
      else if (s1 < -flat_sine && s2 < -flat_sine)
        kind = EdgeKind::kConvex;
      else if (s1 > flat_sine && s2 > flat_sine)
        kind = EdgeKind::kConcave;
      else
        kind = EdgeKind::kFold;
    }
    out.edge_kind[e] = kind;
    out.edge_reachable[e] = reachable;
  }
}

OffsetElements build_offset_elements(const TriangleMesh& mesh, double radius) {
  OffsetElements el;
  el.radius = radius;
  el.points = mesh.vertices;
  const auto nf_mesh = std::uint32_t(mesh.facets.size());
  const std::uint32_t nf = count_offset_facets(mesh, 0, nf_mesh);
  el.facet_tri.resize(nf);
  el.facet_normal.resize(nf);
  el.facet_source.resize(nf);
  el.facet_vertices.resize(nf);
  el.facet_vertical.resize(nf);
  std::vector<std::uint64_t> keys(3 * std::size_t(nf));
  fill_offset_facets(mesh, radius, 0, nf_mesh, 0, el, keys);

  // Sort half-edges by (vertex pair, facet slot): ties keep slot order, so the result is
  // independent of how the engine chunks the sort.
  std::vector<std::uint32_t> order(keys.size());
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return keys[a] != keys[b] ? keys[a] < keys[b] : a < b;
  });
  std::vector<std::uint64_t> sorted(keys.size());
  std::vector<std::uint32_t> key_facet(keys.size());
  std::vector<std::uint32_t> edge_start;
  for (std::size_t i = 0; i < order.size(); ++i) {
    sorted[i] = keys[order[i]];
    key_facet[i] = order[i] / 3;
    if (i == 0 || sorted[i] != sorted[i - 1]) edge_start.push_back(std::uint32_t(i));
  }
  const auto ne = std::uint32_t(edge_start.size());
  edge_start.push_back(std::uint32_t(sorted.size()));
  el.edge_vertices.resize(ne);
  el.edge_kind.resize(ne);
  el.edge_facet_count.resize(ne);
  el.edge_reachable.resize(ne);
  classify_edges(sorted, key_facet, edge_start, 0, ne, el);
  collect_vertices(el);
  return el;
}

}  // namespace ncpath
