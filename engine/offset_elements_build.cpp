#include "engine/offset_elements_build.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <span>

#include "engine/parallel.hpp"
#include "kernels/geom/tolerance.hpp"

namespace ncpath {

OffsetElements build_offset_elements_parallel(const TriangleMesh& input, double radius,
                                              bool swap_xy) {
  TriangleMesh swapped;
  if (swap_xy) {
    swapped.facets = input.facets;
    swapped.vertices.resize(input.vertices.size());
    par::for_each(input.vertices.size(), 4096, [&](std::size_t i) {
      const Vec3& v = input.vertices[i];
      swapped.vertices[i] = Vec3(v.y(), v.x(), v.z());
    });
  }
  const TriangleMesh& mesh = swap_xy ? swapped : input;
  OffsetElements el;
  el.radius = radius;
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
  el.facet_tri.resize(nf);
  el.facet_normal.resize(nf);
  el.facet_source.resize(nf);
  el.facet_vertices.resize(nf);
  el.facet_vertical.resize(nf);
  std::vector<std::uint64_t> keys(3 * std::size_t(nf));
  par::for_each(chunks, 1, [&](std::size_t c) {
    const auto b = std::uint32_t(c * kChunk), e = std::min(nf_mesh, b + kChunk);
    fill_offset_facets(mesh, radius, b, e, offsets[c], el, keys);
  });

  // Unique edges: half-edges sorted by (key, slot), as the reference does.
  std::vector<std::uint32_t> order(keys.size());
  std::iota(order.begin(), order.end(), 0u);
  par::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return keys[a] != keys[b] ? keys[a] < keys[b] : a < b;
  });
  std::vector<std::uint64_t> sorted(keys.size());
  std::vector<std::uint32_t> key_facet(keys.size());
  par::for_each(order.size(), 65536, [&](std::size_t i) {
    sorted[i] = keys[order[i]];
    key_facet[i] = order[i] / 3;
  });
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
  par::for_ranges(ne, 16384, [&](std::size_t b, std::size_t e) {
    classify_edges(sorted, key_facet, edge_start, std::uint32_t(b), std::uint32_t(e), el);
  });

  collect_vertices(el);
  return el;
}

void PlaneIndex::query(double v, std::vector<std::uint32_t>& out) const {
  const auto first = std::lower_bound(lo.begin(), lo.end(), v - short_extent);
  for (auto k = std::size_t(first - lo.begin()); k < lo.size() && lo[k] <= v; ++k)
    if (hi[k] >= v) out.push_back(ids[k]);
  for (std::size_t k = 0; k < long_ids.size(); ++k)
    if (long_lo[k] <= v && long_hi[k] >= v) out.push_back(long_ids[k]);
}

PlaneIndex build_plane_index(const OffsetElements& el) {
  const double R = el.radius;
  const std::size_t n = el.element_count();
  std::vector<double> lo(n, INFINITY), hi(n, -INFINITY);
  const std::size_t nf = el.facet_count(), ne = el.edge_count();
  par::for_each(n, 16384, [&](std::size_t id) {
    if (!element_reachable(el, std::uint32_t(id))) return;
    if (id < nf) {
      const auto& t = el.facet_tri[id];
      lo[id] = std::min({t[0].y(), t[1].y(), t[2].y()});
      hi[id] = std::max({t[0].y(), t[1].y(), t[2].y()});
    } else if (id < nf + ne) {
      const auto& ev = el.edge_vertices[id - nf];
      const Vec3 &a = el.points[ev[0]], &b = el.points[ev[1]];
      const Vec3 d = b - a;
      const double len = d.norm();
      if (!(len > 0) || std::hypot(d.x(), d.y()) < tol::kVerticalEdge * len) return;
      lo[id] = std::min(a.y(), b.y()) - R;
      hi[id] = std::max(a.y(), b.y()) + R;
    } else {
      const double y = el.points[el.vertex_source[id - nf - ne]].y();
      lo[id] = y - R;
      hi[id] = y + R;
    }
  });
  // Short: at most twice the median extent of the facets plus 2R (edges and vertices reach
  // R beyond their own extent); the rest are long.
  std::vector<double> ext;
  for (std::size_t id = 0; id < nf; id += std::max<std::size_t>(1, nf / 4096))
    if (lo[id] <= hi[id]) ext.push_back(hi[id] - lo[id]);
  double median = 0;
  if (!ext.empty()) {
    std::nth_element(ext.begin(), ext.begin() + std::ptrdiff_t(ext.size() / 2), ext.end());
    median = ext[ext.size() / 2];
  }
  PlaneIndex ix;
  ix.short_extent = 2 * R + 4 * median;
  std::vector<std::uint32_t> order;
  for (std::uint32_t id = 0; id < n; ++id) {
    if (!(lo[id] <= hi[id])) continue;
    if (hi[id] - lo[id] <= ix.short_extent) {
      order.push_back(id);
    } else {
      ix.long_ids.push_back(id);
      ix.long_lo.push_back(lo[id]);
      ix.long_hi.push_back(hi[id]);
    }
  }
  par::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return lo[a] != lo[b] ? lo[a] < lo[b] : a < b;
  });
  ix.ids = order;
  ix.lo.resize(order.size());
  ix.hi.resize(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    ix.lo[k] = lo[order[k]];
    ix.hi[k] = hi[order[k]];
  }
  return ix;
}

}  // namespace ncpath
