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

void fill_offset_facets(const TriangleMesh& mesh, std::uint32_t begin,
                        std::uint32_t end, std::uint32_t first_slot, OffsetElements& out,
                        std::span<std::uint64_t> keys) {
  std::uint32_t slot = first_slot;
  for (std::uint32_t i = begin; i < end; ++i) {
    const auto& f = mesh.facets[i];
    const Vec3 &a = mesh.vertices[f[0]], &b = mesh.vertices[f[1]], &c = mesh.vertices[f[2]];
    Vec3 n;
    if (!upward_unit_normal(a, b, c, n)) continue;
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

namespace {

// Extreme y components of the unit directions d with d . w <= 0 for all w in ws (see
// element_y_reach; at most 32 constraints). False when there is none.
bool cone_y_extent(std::span<const Vec3> ws, double slack, double& dy_min, double& dy_max) {
  const double kIn = std::max(1e-9, 2 * slack);  // on a face counts as inside up to this
  std::array<Vec3, 32> wn;                        // the constraints as unit vectors (or zero)
  const std::size_t n = std::min<std::size_t>(ws.size(), wn.size());
  for (std::size_t i = 0; i < n; ++i) {
    const double len = ws[i].norm();
    wn[i] = len > 0 ? Vec3(ws[i] / len) : Vec3::Zero();
  }
  dy_min = INFINITY;
  dy_max = -INFINITY;
  // The directions d and -d at once: -d normalised and its dot products are d's negated,
  // exactly, so one pass decides both.
  auto consider_both = [&](const Vec3& d) {
    const double len = d.norm();
    if (!(len > tol::kConeDirectionMin)) return;
    const Vec3 u = d / len;
    bool plus = true, minus = true;
    for (std::size_t i = 0; i < n && (plus || minus); ++i) {
      const double s = u.dot(wn[i]);
      plus = plus && !(s > kIn);
      minus = minus && !(-s > kIn);
    }
    if (plus) {
      dy_min = std::min(dy_min, u.y());
      dy_max = std::max(dy_max, u.y());
    }
    if (minus) {
      dy_min = std::min(dy_min, -u.y());
      dy_max = std::max(dy_max, -u.y());
    }
  };
  const Vec3 ey(0, 1, 0);
  consider_both(ey);
  for (std::size_t i = 0; i < n; ++i) consider_both(ey - wn[i] * wn[i].y());
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) consider_both(ws[i].cross(ws[j]));
  return dy_min <= dy_max;
}

}  // namespace

bool element_y_reach(const OffsetElements& el, std::uint32_t id, double& lo, double& hi) {
  if (!element_reachable(el, id)) return false;
  const double R = el.radius;
  const std::size_t nf = el.facet_count(), ne = el.edge_count();
  if (id < nf) {
    const auto t = el.offset_tri(id);
    lo = std::min({t[0].y(), t[1].y(), t[2].y()});
    hi = std::max({t[0].y(), t[1].y(), t[2].y()});
    return true;
  }
  double dy_min = -1, dy_max = 1;
  if (id < nf + ne) {
    const std::size_t e = id - nf;
    const auto& ev = el.edge_vertices[e];
    const Vec3 &a = el.points[ev[0]], &b = el.points[ev[1]];
    const Vec3 d = b - a;
    const double len = d.norm();
    if (!(len > 0) || std::hypot(d.x(), d.y()) < tol::kVerticalEdge * len) return false;
    const Vec3 u = d / len;
    const auto& wedge = el.edge_wedge[e];
    const double slack = el.edge_flat[e] ? tol::kFlatTrimSlack : tol::kTrimSlack;
    if (wedge[0].isZero()) {
      const double s = std::sqrt(std::max(0.0, 1 - u.y() * u.y()));  // the whole circle
      dy_min = -s;
      dy_max = s;
    } else {
      // Directions perpendicular to u: add -u and u as constraints (d . u = 0).
      const std::array<Vec3, 4> ws = {wedge[0], wedge[1], u, -u};
      if (!cone_y_extent(ws, slack, dy_min, dy_max)) return false;
    }
    lo = std::min(a.y(), b.y()) + R * dy_min;
    hi = std::max(a.y(), b.y()) + R * dy_max;
  } else {
    const std::size_t v = id - nf - ne;
    const Vec3& c = el.points[el.vertex_source[v]];
    const std::uint32_t r0 = el.ring_offsets.empty() ? 0 : el.ring_offsets[v];
    const std::uint32_t r1 = el.ring_offsets.empty() ? 0 : el.ring_offsets[v + 1];
    if (r1 > r0) {
      std::array<Vec3, 32> ws;
      const std::uint32_t n = std::min<std::uint32_t>(r1 - r0, 32);
      for (std::uint32_t k = 0; k < n; ++k) ws[k] = el.points[el.ring[r0 + k]] - c;
      const double slack = el.vertex_flat[v] ? tol::kFlatTrimSlack : tol::kTrimSlack;
      if (r1 - r0 <= 32 &&
          !cone_y_extent(std::span<const Vec3>(ws.data(), n), slack, dy_min, dy_max))
        return false;
      if (r1 - r0 > 32) {
        dy_min = -1;
        dy_max = 1;
      }
    }
    lo = c.y() + R * dy_min;
    hi = c.y() + R * dy_max;
  }
  const double pad = tol::kReachPad * R;
  lo -= pad;
  hi += pad;
  return true;
}

void collect_vertices(OffsetElements& el) {
  // used: 1 referenced, 2 reachable (an incident edge is), 4 a flat kept edge.
  std::vector<std::uint8_t> used(el.points.size(), 0);
  for (const auto& fv : el.facet_vertices)
    for (std::uint32_t v : fv) used[v] = 1;
  for (std::size_t e = 0; e < el.edge_count(); ++e) {
    if (!el.edge_reachable[e]) continue;
    for (std::uint32_t v : el.edge_vertices[e]) used[v] |= el.edge_flat[e] ? 6 : 2;
  }
  el.vertex_source.clear();
  el.vertex_reachable.clear();
  el.vertex_flat.clear();
  std::vector<std::uint32_t> slot(el.points.size(), ~0u);
  for (std::uint32_t v = 0; v < used.size(); ++v)
    if (used[v]) {
      slot[v] = std::uint32_t(el.vertex_source.size());
      el.vertex_source.push_back(v);
      el.vertex_reachable.push_back((used[v] & 2) != 0);
      el.vertex_flat.push_back((used[v] & 4) != 0);
    }
  // Rings (count, scan, fill) of reachable vertices.
  const std::size_t nv = el.vertex_source.size();
  auto ringed = [&](std::uint32_t v) { return (used[v] & 2) != 0; };
  el.ring_offsets.assign(nv + 1, 0);
  for (const auto& ev : el.edge_vertices)
    for (int k = 0; k < 2; ++k)
      if (ringed(ev[k])) ++el.ring_offsets[slot[ev[k]] + 1];
  for (std::size_t i = 0; i < nv; ++i) el.ring_offsets[i + 1] += el.ring_offsets[i];
  el.ring.resize(el.ring_offsets[nv]);
  std::vector<std::uint32_t> fill(el.ring_offsets.begin(), el.ring_offsets.end() - 1);
  for (const auto& ev : el.edge_vertices)
    for (int k = 0; k < 2; ++k)
      if (ringed(ev[k])) el.ring[fill[slot[ev[k]]]++] = ev[1 - k];
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
    std::array<Vec3, 2> wedge = {Vec3::Zero(), Vec3::Zero()};
    bool flat_edge = false;
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
        const double n1 = w1.norm(), n2 = w2.norm();
        const bool flat = std::abs(e.dot(w1.cross(w2))) <= tol::kFlatEdgeKeep * n1 * n2;
        if (reachable && n1 > 0 && n2 > 0) wedge = {w1 / n1, w2 / n2};
        flat_edge = flat;
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
    out.edge_wedge[e] = wedge;
    out.edge_flat[e] = flat_edge;
  }
}

void drop_straight_vertices(OffsetElements& el) {
  const std::size_t nv = el.vertex_count();
  // A vertex inside a straight edge line (two ring points exactly opposite, e.g. a midpoint
  // of a subdivided or CAD mesh): its cone lies in the plane perpendicular to the line and
  // within the wedge of the edge to either neighbour (the opposite vertices of that edge's
  // facets are ring points), so its sphere shows nothing the cylinders do not: dropped.
  for (std::size_t i = 0; i < nv; ++i) {
    if (!el.vertex_reachable[i]) continue;
    const Vec3& c = el.points[el.vertex_source[i]];
    const std::uint32_t r0 = el.ring_offsets[i], r1 = el.ring_offsets[i + 1];
    bool straight = false;
    for (std::uint32_t a = r0; a < r1 && !straight; ++a)
      for (std::uint32_t b = a + 1; b < r1 && !straight; ++b) {
        const Vec3 da = el.points[el.ring[a]] - c, db = el.points[el.ring[b]] - c;
        straight = da.dot(db) < 0 &&
                   da.cross(db).norm() <= tol::kCoplanarSine * da.norm() * db.norm();
      }
    if (straight) el.vertex_reachable[i] = 0;
  }
}

// A cylinder is trimmed to its wedge where a facet's offset takes over: the wedge's side
// must be the plane of the edge and that facet's offset normal. An edge of a facet whose
// normal a coplanar region replaced gets its side from the new normal (n x e, on the facet's
// side): from the facet's own plane it differed by up to tol::kCoplanarSine, and with the axis
// nearly in a drive plane that moved the hand-over along it (a relief's base fan, vertex
// noise 1e-11: 0.13 mm where neither cylinder nor facet was kept, a scan cut of 2.3 mm).
template <class PairOf>
void match_wedges_to_normals(OffsetElements& el, const std::vector<std::uint8_t>& renormed,
                             PairOf&& pair_of) {
  for (std::size_t e = 0; e < el.edge_count(); ++e) {
    if (el.edge_facet_count[e] != 2 || el.edge_wedge[e][0].isZero()) continue;
    const auto f = pair_of(e);
    if (!renormed[f[0]] && !renormed[f[1]]) continue;
    const auto& ev = el.edge_vertices[e];
    const Vec3 axis = (el.points[ev[1]] - el.points[ev[0]]).normalized();
    for (int i = 0; i < 2; ++i) {
      if (!renormed[f[i]]) continue;
      Vec3& w = el.edge_wedge[e][i];
      const Vec3 side = el.facet_normal[f[i]].cross(axis).normalized();
      w = side.dot(w) >= 0 ? side : Vec3(-side);
    }
  }
}

std::size_t share_coplanar_offsets(std::span<const std::uint32_t> key_facet,
                                   std::span<const std::uint32_t> edge_start, OffsetElements& el,
                                   bool vertical_only) {
  const std::size_t nf = el.facet_count(), ne = el.edge_count();
  // Facet adjacency through joinable edges (CSR).
  auto pair_of = [&](std::size_t e) {
    return std::array<std::uint32_t, 2>{key_facet[edge_start[e]], key_facet[edge_start[e] + 1]};
  };
  auto joinable = [&](std::size_t e) {
    // Flat and continuing across the edge (w1 and w2 opposite), not folded back onto itself.
    if (el.edge_facet_count[e] != 2 || !el.edge_flat[e] || !el.edge_reachable[e] ||
        !(el.edge_wedge[e][0].dot(el.edge_wedge[e][1]) < -0.5))
      return false;
    const auto f = pair_of(e);
    if (vertical_only && !el.facet_vertical[f[0]]) return false;
    return el.facet_vertical[f[0]] == el.facet_vertical[f[1]];
  };
  std::vector<std::uint32_t> start(nf + 1, 0);
  for (std::size_t e = 0; e < ne; ++e)
    if (joinable(e))
      for (std::uint32_t f : pair_of(e)) ++start[f + 1];
  for (std::size_t f = 0; f < nf; ++f) start[f + 1] += start[f];
  std::vector<std::uint32_t> adj(start[nf]), fill(start.begin(), start.end() - 1);
  for (std::size_t e = 0; e < ne; ++e)
    if (joinable(e)) {
      const auto f = pair_of(e);
      adj[fill[f[0]]++] = f[1];
      adj[fill[f[1]]++] = f[0];
    }
  // Regions grown from the lowest unassigned slot.
  constexpr std::uint32_t kNone = ~0u;
  std::vector<std::uint32_t> region(nf, kNone), stack;
  std::vector<std::uint8_t> renormed(nf, 0);
  for (std::uint32_t seed = 0; seed < nf; ++seed) {
    if (region[seed] != kNone || start[seed] == start[seed + 1]) continue;
    const Vec3 n = el.facet_normal[seed];
    region[seed] = seed;
    stack.assign(1, seed);
    while (!stack.empty()) {
      const std::uint32_t f = stack.back();
      stack.pop_back();
      for (std::uint32_t k = start[f]; k < start[f + 1]; ++k) {
        const std::uint32_t g = adj[k];
        if (region[g] != kNone) continue;
        // Vertical facets (never sliced; their normals' signs are arbitrary) join by the
        // line of their normal and keep their own offset triangle.
        const Vec3& m = el.facet_normal[g];
        const bool vertical = el.facet_vertical[seed];
        if (el.facet_vertical[g] != vertical || !(vertical || m.dot(n) > 0) ||
            !(m.cross(n).norm() <= tol::kCoplanarSine))
          continue;
        region[g] = seed;
        stack.push_back(g);
        if (!vertical && m != n) {
          el.facet_normal[g] = n;  // offset_tri() follows
          renormed[g] = 1;
        }
      }
    }
  }
  match_wedges_to_normals(el, renormed, pair_of);
  std::size_t dropped = 0;
  for (std::size_t e = 0; e < ne; ++e) {
    if (el.edge_facet_count[e] != 2) continue;
    const auto f = pair_of(e);
    if (!joinable(e) || region[f[0]] == kNone || region[f[0]] != region[f[1]]) continue;
    el.edge_reachable[e] = 0;
    el.edge_wedge[e] = {Vec3::Zero(), Vec3::Zero()};
    ++dropped;
  }
  return dropped;
}

OffsetElements build_offset_elements(const TriangleMesh& mesh, double radius,
                                     Coplanar coplanar) {
  OffsetElements el;
  el.radius = radius;
  el.points = mesh.vertices;
  const auto nf_mesh = std::uint32_t(mesh.facets.size());
  const std::uint32_t nf = count_offset_facets(mesh, 0, nf_mesh);
  el.facet_normal.resize(nf);
  el.facet_source.resize(nf);
  el.facet_vertices.resize(nf);
  el.facet_vertical.resize(nf);
  std::vector<std::uint64_t> keys(3 * std::size_t(nf));
  fill_offset_facets(mesh, 0, nf_mesh, 0, el, keys);

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
  el.edge_wedge.resize(ne);
  el.edge_flat.resize(ne);
  classify_edges(sorted, key_facet, edge_start, 0, ne, el);
  if (coplanar != Coplanar::kKeep)
    share_coplanar_offsets(key_facet, edge_start, el, coplanar == Coplanar::kVertical);
  collect_vertices(el);
  if (coplanar == Coplanar::kMerge) drop_straight_vertices(el);
  return el;
}

}  // namespace ncpath
