// Z-level contours (kernels/scan/zlevel.hpp): a level whose U is the known inside region's U
// (below an overhang or the top of a wall) takes that region's contours. Declarations:
// zlevel_detail.hpp.
#include <algorithm>
#include <cmath>

#include "kernels/scan/zlevel_detail.hpp"

namespace ncpath::zlevel_detail {

namespace {

// Whether a region of the candidates `cand` (facets, edges and their end vertices, vertices)
// may make U at level lv differ from the known inside region's U (ZLevelInside). The others
// are empty, lie wholly above the region's level (strictly; such a region is the same there,
// inside U) or inside its polygon (by its margin; the polygon is inscribed in the region).
// U only grows going down: with none, U is the region's U.
bool any_changed_region(const OffsetElements& el, const std::vector<std::uint32_t>& cand,
                        const ZLevelInside& q, const Level& lv, bool reach) {
  const double zc_known = q.tip_z + lv.R;
  const auto nf = std::uint32_t(el.facet_count()), ne = std::uint32_t(el.edge_count());
  // Whether the region of element id, of lowest point `low`, may change U.
  auto changes = [&](std::uint32_t id, double low) {
    if (low > zc_known) return false;
    Region g;
    return build_region(el, id, lv, reach, g) && !region_in_known(el, q, g, q.margin);
  };
  auto vertex_changes = [&](std::uint32_t point) {
    const auto it = std::lower_bound(el.vertex_source.begin(), el.vertex_source.end(), point);
    if (it == el.vertex_source.end() || *it != point) return false;  // not a vertex element
    return changes(el.vertex_id(std::size_t(it - el.vertex_source.begin())), el.points[point].z());
  };
  for (const std::uint32_t id : cand) {
    if (id < nf) {
      double low = INFINITY;
      for (const Vec3& v : el.offset_tri(id)) low = std::min(low, v.z());
      if (changes(id, low)) return true;
    } else if (id < nf + ne) {
      const auto& ev = el.edge_vertices[id - nf];
      const double low = std::min(el.points[ev[0]].z(), el.points[ev[1]].z());
      if (changes(id, low) || vertex_changes(ev[0]) || vertex_changes(ev[1])) return true;
    } else if (vertex_changes(el.vertex_source[id - nf - ne])) {
      return true;
    }
  }
  return false;
}

}  // namespace

bool contours_from_known(const OffsetElements& el, const std::vector<std::uint32_t>& cand,
                         const ZLevelInside& q, const Level& lv, double tip_z,
                         const ZLevelParams& params, ZLevelResult& result) {
  if (q.contours.empty() || any_changed_region(el, cand, q, lv, params.skip_unreachable))
    return false;
  result.contours = q.contours;
  for (ZContour& c : result.contours)
    for (ZJunction& j : c.junctions) j.position.z() = tip_z;
  result.stats.unchanged = 1;
  return true;
}

}  // namespace ncpath::zlevel_detail
