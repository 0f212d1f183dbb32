#include "engine/offset_elements_build.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <span>

#include "engine/parallel.hpp"
#include "kernels/cutters/drop_cutter.hpp"
#include "kernels/geom/tolerance.hpp"

namespace ncpath {

std::vector<std::uint32_t> exact_duplicate_map(const std::vector<Vec3>& v) {
  // Sorted as contiguous (x, y, z, index) records: the sort reads no other memory.
  struct Key {
    double x, y, z;
    std::uint32_t i;
  };
  std::vector<Key> order(v.size());
  par::for_each(v.size(), 65536, [&](std::size_t i) {
    order[i] = {v[i].x(), v[i].y(), v[i].z(), std::uint32_t(i)};
  });
  par::sort(order.begin(), order.end(), [](const Key& p, const Key& q) {
    if (p.x != q.x) return p.x < q.x;
    if (p.y != q.y) return p.y < q.y;
    if (p.z != q.z) return p.z < q.z;
    return p.i < q.i;
  });
  std::vector<std::uint32_t> rep(v.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    const Key& a = order[k];
    const bool same = k > 0 && a.x == order[k - 1].x && a.y == order[k - 1].y &&
                      a.z == order[k - 1].z;
    rep[a.i] = same ? rep[order[k - 1].i] : a.i;
  }
  return rep;
}

namespace {

// The mesh welded at exactly equal vertices and compacted: one vertex per group (the group's
// lowest input index, in increasing order: source[k] is the input index of vertex k), facets
// remapped; x and y swapped when asked. The order of the kept vertices is the input's, so
// anything sorted by vertex index sorts the same as over the welded input.
TriangleMesh welded_compact(const TriangleMesh& input, bool swap_xy,
                            std::vector<std::uint32_t>& source) {
  const std::vector<std::uint32_t> rep = exact_duplicate_map(input.vertices);
  std::vector<std::uint32_t> slot(rep.size());
  source.clear();
  for (std::uint32_t i = 0; i < rep.size(); ++i)
    if (rep[i] == i) {
      slot[i] = std::uint32_t(source.size());
      source.push_back(i);
    }
  TriangleMesh mesh;
  mesh.vertices.resize(source.size());
  par::for_each(source.size(), 4096, [&](std::size_t k) {
    const Vec3& v = input.vertices[source[k]];
    mesh.vertices[k] = swap_xy ? Vec3(v.y(), v.x(), v.z()) : v;
  });
  mesh.facets.resize(input.facets.size());
  par::for_each(input.facets.size(), 16384, [&](std::size_t i) {
    const auto& f = input.facets[i];
    mesh.facets[i] = {slot[rep[f[0]]], slot[rep[f[1]]], slot[rep[f[2]]]};
  });
  return mesh;
}

}  // namespace

ConditionedMesh condition_for_slicing(const TriangleMesh& input) {
  TriangleMesh mesh;
  mesh.vertices = input.vertices;
  const std::vector<std::uint32_t> rep = exact_duplicate_map(input.vertices);
  mesh.facets.resize(input.facets.size());
  par::for_each(input.facets.size(), 16384, [&](std::size_t i) {
    const auto& f = input.facets[i];
    mesh.facets[i] = {rep[f[0]], rep[f[1]], rep[f[2]]};
  });
  return condition_mesh(mesh, [](std::size_t n,
                                 const std::function<void(std::size_t, std::size_t)>& body) {
    par::for_ranges(n, 4096, body);
  });
}

OffsetElements build_offset_elements_parallel(const TriangleMesh& input, double radius,
                                              bool swap_xy, Coplanar coplanar) {
  OffsetElements el;
  el.radius = radius;
  const TriangleMesh mesh = welded_compact(input, swap_xy, el.point_source);
  el.points = mesh.vertices;

  // Facets: count per chunk, scan, fill.
  const auto nf_mesh = std::uint32_t(mesh.facets.size());
  constexpr std::uint32_t kChunk = 16384;
  const std::size_t chunks = (nf_mesh + kChunk - 1) / kChunk;
  std::vector<std::uint32_t> counts(chunks), offsets(chunks + 1);
  par::for_each(chunks, 1, [&](std::size_t c) {
    const auto b = std::uint32_t(c * kChunk), e = std::min(nf_mesh, b + kChunk);
    counts[c] = count_offset_facets(mesh, b, e);
  });
  par::exclusive_scan(std::span<const std::uint32_t>(counts), std::span<std::uint32_t>(offsets));
  const std::uint32_t nf = offsets[chunks];
  el.facet_normal.resize(nf);
  el.facet_source.resize(nf);
  el.facet_vertices.resize(nf);
  el.facet_vertical.resize(nf);
  std::vector<std::uint64_t> keys(3 * std::size_t(nf));
  par::for_each(chunks, 1, [&](std::size_t c) {
    const auto b = std::uint32_t(c * kChunk), e = std::min(nf_mesh, b + kChunk);
    fill_offset_facets(mesh, b, e, offsets[c], el, keys);
  });

  // Unique edges: half-edges sorted by (key, slot), as the reference does, as contiguous
  // pairs (the sort reads no other memory).
  std::vector<std::pair<std::uint64_t, std::uint32_t>> order(keys.size());
  par::for_each(keys.size(), 65536,
                [&](std::size_t i) { order[i] = {keys[i], std::uint32_t(i)}; });
  std::vector<std::uint64_t>().swap(keys);
  par::sort(order.begin(), order.end(), [](const auto& a, const auto& b) { return a < b; });
  std::vector<std::uint64_t> sorted(order.size());
  std::vector<std::uint32_t> key_facet(order.size());
  par::for_each(order.size(), 65536, [&](std::size_t i) {
    sorted[i] = order[i].first;
    key_facet[i] = order[i].second / 3;
  });
  decltype(order)().swap(order);
  std::vector<std::uint32_t> edge_start;
  edge_start.reserve(sorted.size() / 2 + 1);
  for (std::size_t i = 0; i < sorted.size(); ++i)
    if (i == 0 || sorted[i] != sorted[i - 1]) edge_start.push_back(std::uint32_t(i));
  const auto ne = std::uint32_t(edge_start.size());
  edge_start.push_back(std::uint32_t(sorted.size()));
  el.edge_vertices.resize(ne);
  el.edge_kind.resize(ne);
  el.edge_facet_count.resize(ne);
  el.edge_reachable.resize(ne);
  el.edge_wedge.resize(ne);
  el.edge_flat.resize(ne);
  par::for_ranges(ne, 16384, [&](std::size_t b, std::size_t e) {
    classify_edges(sorted, key_facet, edge_start, std::uint32_t(b), std::uint32_t(e), el);
  });
  if (coplanar != Coplanar::kKeep)
    share_coplanar_offsets(key_facet, edge_start, el, coplanar == Coplanar::kVertical);

  collect_vertices(el);
  if (coplanar == Coplanar::kMerge) drop_straight_vertices(el);
  return el;
}

ElementRef element_ref(const OffsetElements& el, std::uint32_t e) {
  ElementRef r;
  if (e >= el.element_count()) return r;  // kNoElement: the floor
  auto mesh_vertex = [&](std::uint32_t point) {
    return el.point_source.empty() ? point : el.point_source[point];
  };
  if (e < el.facet_count()) return {0, el.facet_source[e], -1};
  e -= std::uint32_t(el.facet_count());
  if (e < el.edge_count())
    return {1, mesh_vertex(el.edge_vertices[e][0]), mesh_vertex(el.edge_vertices[e][1])};
  e -= std::uint32_t(el.edge_count());
  return {2, mesh_vertex(el.vertex_source[e]), -1};
}

std::uint8_t contact_code(const OffsetElements& el, std::uint32_t e) {
  ContactKind k = ContactKind::kVertex;
  if (e >= el.element_count())
    k = ContactKind::kNone;
  else if (e < el.facet_count())
    k = ContactKind::kFacet;
  else if (e < el.facet_count() + el.edge_count())
    k = ContactKind::kEdge;
  return std::uint8_t(k);
}

OffsetElements mirror_xy(OffsetElements el) {
  auto swap = [](Vec3& v) { v = Vec3(v.y(), v.x(), v.z()); };
  par::for_each(el.points.size(), 16384, [&](std::size_t i) { swap(el.points[i]); });
  par::for_each(el.facet_normal.size(), 16384, [&](std::size_t i) { swap(el.facet_normal[i]); });
  par::for_each(el.edge_wedge.size(), 16384, [&](std::size_t i) {
    for (Vec3& w : el.edge_wedge[i]) swap(w);
  });
  return el;
}

void PlaneIndex::query(double v, std::vector<std::uint32_t>& out) const {
  const auto first = std::lower_bound(lo.begin(), lo.end(), v - short_extent);
  for (auto k = std::size_t(first - lo.begin()); k < lo.size() && lo[k] <= v; ++k)
    if (hi[k] >= v) out.push_back(ids[k]);
  for (std::size_t k = 0; k < long_ids.size(); ++k)
    if (long_lo[k] <= v && long_hi[k] >= v) out.push_back(long_ids[k]);
}

void element_extent(const OffsetElements& el, std::uint32_t id, int axis, double& lo,
                    double& hi) {
  const std::size_t nf = el.facet_count(), ne = el.edge_count();
  if (id < nf) {
    const auto t = el.offset_tri(id);
    lo = std::min({t[0][axis], t[1][axis], t[2][axis]});
    hi = std::max({t[0][axis], t[1][axis], t[2][axis]});
  } else if (id < nf + ne) {
    const auto& ev = el.edge_vertices[id - nf];
    lo = std::min(el.points[ev[0]][axis], el.points[ev[1]][axis]) - el.radius;
    hi = std::max(el.points[ev[0]][axis], el.points[ev[1]][axis]) + el.radius;
  } else {
    const double c = el.points[el.vertex_source[id - nf - ne]][axis];
    lo = c - el.radius;
    hi = c + el.radius;
  }
}

namespace {

// element_extent, padded over element_y_reach's own rounding: contains the reach along the
// axis (what element_y_reach gives for y).
void reach_bound(const OffsetElements& el, std::uint32_t id, int axis, double& lo, double& hi) {
  element_extent(el, id, axis, lo, hi);
  const double pad = 2 * tol::kReachPad * el.radius;
  lo -= pad;
  hi += pad;
}

bool meets_any(double lo, double hi, std::span<const double> at) {
  for (const double v : at)
    if (lo <= v && v <= hi) return true;
  return false;
}

// Appends src[i] for the kept i in [0, n) (an array the build left empty stays empty).
template <class T>
void append_kept(std::vector<T>& dst, const std::vector<T>& src, const std::uint8_t* keep,
                 std::size_t n) {
  if (src.size() != n) return;
  for (std::size_t i = 0; i < n; ++i)
    if (keep[i]) dst.push_back(src[i]);
}

}  // namespace

OffsetElements elements_near_planes(const OffsetElements& el, int axis,
                                    std::span<const double> at) {
  const std::size_t nf = el.facet_count(), ne = el.edge_count(), nv = el.vertex_count();
  std::vector<std::uint8_t> keep(el.element_count());
  par::for_each(keep.size(), 16384, [&](std::size_t id) {
    double lo, hi;
    reach_bound(el, std::uint32_t(id), axis, lo, hi);
    keep[id] = meets_any(lo, hi, at);
  });
  OffsetElements out;
  out.radius = el.radius;
  out.points = el.points;
  out.point_source = el.point_source;
  const std::uint8_t *kf = keep.data(), *ke = kf + nf, *kv = ke + ne;
  append_kept(out.facet_normal, el.facet_normal, kf, nf);
  append_kept(out.facet_source, el.facet_source, kf, nf);
  append_kept(out.facet_vertices, el.facet_vertices, kf, nf);
  append_kept(out.facet_vertical, el.facet_vertical, kf, nf);
  append_kept(out.edge_vertices, el.edge_vertices, ke, ne);
  append_kept(out.edge_kind, el.edge_kind, ke, ne);
  append_kept(out.edge_facet_count, el.edge_facet_count, ke, ne);
  append_kept(out.edge_reachable, el.edge_reachable, ke, ne);
  append_kept(out.edge_wedge, el.edge_wedge, ke, ne);
  append_kept(out.edge_flat, el.edge_flat, ke, ne);
  append_kept(out.vertex_source, el.vertex_source, kv, nv);
  append_kept(out.vertex_reachable, el.vertex_reachable, kv, nv);
  append_kept(out.vertex_flat, el.vertex_flat, kv, nv);
  if (el.ring_offsets.size() == nv + 1) {
    out.ring_offsets.push_back(0);
    for (std::size_t v = 0; v < nv; ++v) {
      if (!kv[v]) continue;
      out.ring.insert(out.ring.end(), el.ring.begin() + el.ring_offsets[v],
                      el.ring.begin() + el.ring_offsets[v + 1]);
      out.ring_offsets.push_back(std::uint32_t(out.ring.size()));
    }
  }
  return out;
}

PlaneIndex build_plane_index(const OffsetElements& el, std::span<const double> only_at) {
  const std::size_t n = el.element_count();
  const std::size_t sample = std::max<std::size_t>(1, n / 65536);
  std::vector<double> lo(n, INFINITY), hi(n, -INFINITY);
  par::for_each(n, 16384, [&](std::size_t id) {
    double l, h;
    if (!only_at.empty() && id % sample != 0) {
      reach_bound(el, std::uint32_t(id), 1, l, h);
      if (!meets_any(l, h, only_at)) return;
    }
    if (element_y_reach(el, std::uint32_t(id), l, h)) {
      lo[id] = l;
      hi[id] = h;
    }
  });
  // Short: up to the 99.9th percentile of the extents (sampled over all elements); the
  // longest 0.1 % (big facets, untrimmed cylinders) are long and checked for every plane.
  std::vector<double> ext;
  for (std::size_t id = 0; id < n; id += sample)
    if (lo[id] <= hi[id]) ext.push_back(hi[id] - lo[id]);
  double limit = 0;
  if (!ext.empty()) {
    const auto k = std::ptrdiff_t(std::min(ext.size() - 1, ext.size() * 999 / 1000));
    std::nth_element(ext.begin(), ext.begin() + k, ext.end());
    limit = ext[std::size_t(k)];
  }
  if (!only_at.empty()) {  // the sampled elements meeting no plane: out
    for (std::size_t id = 0; id < n; id += sample)
      if (!meets_any(lo[id], hi[id], only_at)) lo[id] = INFINITY;
  }
  PlaneIndex ix;
  ix.short_extent = limit;
  // Sorted by (lo, id) as contiguous pairs: the sort reads no other memory.
  struct Key {
    double lo;
    std::uint32_t id;
  };
  std::vector<Key> order;
  for (std::uint32_t id = 0; id < n; ++id) {
    if (!(lo[id] <= hi[id])) continue;
    if (hi[id] - lo[id] <= ix.short_extent) {
      order.push_back({lo[id], id});
    } else {
      ix.long_ids.push_back(id);
      ix.long_lo.push_back(lo[id]);
      ix.long_hi.push_back(hi[id]);
    }
  }
  par::sort(order.begin(), order.end(), [](const Key& a, const Key& b) {
    return a.lo != b.lo ? a.lo < b.lo : a.id < b.id;
  });
  ix.ids.resize(order.size());
  ix.lo.resize(order.size());
  ix.hi.resize(order.size());
  par::for_each(order.size(), 65536, [&](std::size_t k) {
    ix.ids[k] = order[k].id;
    ix.lo[k] = order[k].lo;
    ix.hi[k] = hi[order[k].id];
  });
  return ix;
}

}  // namespace ncpath
