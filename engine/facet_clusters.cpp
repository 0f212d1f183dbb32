#include "engine/facet_clusters.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/parallel.hpp"

namespace ncpath {

namespace {

// Interleaves the bits of two 16-bit cell coordinates.
std::uint32_t morton2(std::uint32_t x, std::uint32_t y) {
  auto spread = [](std::uint32_t v) {
    v &= 0xFFFFu;
    v = (v | (v << 8)) & 0x00FF00FFu;
    v = (v | (v << 4)) & 0x0F0F0F0Fu;
    v = (v | (v << 2)) & 0x33333333u;
    v = (v | (v << 1)) & 0x55555555u;
    return v;
  };
  return spread(x) | (spread(y) << 1);
}

}  // namespace

FacetBound facet_bound(const PreparedFacet& f, const Cutter& c, std::uint32_t id) {
  const PlaneTip t = plane_tip(c, f);
  return {f.max_z, f.min_x, f.max_x, f.min_y, f.max_y, t.a, t.b, t.c, id};
}

ClusteredFacets cluster_facets(const FacetTable& table, const Cutter& cutter, unsigned group) {
  const std::size_t n = table.facets.size();
  ClusteredFacets out;
  if (n == 0) return out;
  const Aabb3& box = table.box;
  const double sx = 65535.0 / std::max(1e-300, box.hi.x() - box.lo.x());
  const double sy = 65535.0 / std::max(1e-300, box.hi.y() - box.lo.y());
  std::vector<std::uint64_t> keys(n);
  par::for_each(n, 8192, [&](std::size_t i) {
    const PreparedFacet& f = table.facets[i];
    const double cx = (f.p[0].x() + f.p[1].x() + f.p[2].x()) / 3;
    const double cy = (f.p[0].y() + f.p[1].y() + f.p[2].y()) / 3;
    const auto qx = static_cast<std::uint32_t>(std::clamp((cx - box.lo.x()) * sx, 0.0, 65535.0));
    const auto qy = static_cast<std::uint32_t>(std::clamp((cy - box.lo.y()) * sy, 0.0, 65535.0));
    keys[i] = (std::uint64_t{morton2(qx, qy)} << 32) | i;  // unique: ties broken by index
  });
  par::sort(keys.begin(), keys.end(), std::less<>());

  const std::size_t clusters = (n + group - 1) / group;
  out.facets.resize(n);
  out.clusters.resize(clusters);
  par::for_each(clusters, 256, [&](std::size_t c) {
    const std::size_t first = c * group, last = std::min(n, first + group);
    ClusterBound cb{
        -std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
        -std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
        -std::numeric_limits<double>::infinity(), static_cast<std::uint32_t>(first),
        static_cast<std::uint32_t>(last - first)};
    for (std::size_t k = first; k < last; ++k) {
      const auto id = static_cast<std::uint32_t>(keys[k] & 0xFFFFFFFFu);
      const FacetBound b = facet_bound(table.facets[id], cutter, id);
      out.facets[k] = b;
      cb.top_z = std::max(cb.top_z, b.top_z);
      cb.x_lo = std::min(cb.x_lo, b.x_lo);
      cb.x_hi = std::max(cb.x_hi, b.x_hi);
      cb.y_lo = std::min(cb.y_lo, b.y_lo);
      cb.y_hi = std::max(cb.y_hi, b.y_hi);
    }
    std::sort(out.facets.begin() + first, out.facets.begin() + last,
              [](const FacetBound& a, const FacetBound& b) {
                return a.top_z > b.top_z || (a.top_z == b.top_z && a.facet < b.facet);
              });
    out.clusters[c] = cb;
  });
  return out;
}

}  // namespace ncpath
