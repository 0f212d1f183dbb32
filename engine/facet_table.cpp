#include "engine/facet_table.hpp"

#include "engine/parallel.hpp"

namespace ncpath {

FacetTable build_facet_table(const TriangleMesh& mesh, bool swap_xy) {
  const std::size_t n = mesh.facets.size();
  std::vector<PreparedFacet> all(n);
  std::vector<std::uint8_t> ok(n);
  par::for_each(n, 4096, [&](std::size_t i) {
    Vec3 p[3];
    for (int k = 0; k < 3; ++k) {
      p[k] = mesh.vertices[mesh.facets[i][k]];
      if (swap_xy) std::swap(p[k].x(), p[k].y());
    }
    ok[i] = prepare_facet(p[0], p[1], p[2], all[i]) ? 1 : 0;
  });
  FacetTable t;
  t.facets.reserve(n);
  t.source_index.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (!ok[i]) {
      ++t.degenerate;
      continue;
    }
    t.facets.push_back(all[i]);
    t.source_index.push_back(static_cast<std::uint32_t>(i));
    for (const Vec3& p : all[i].p) t.box.add(p);
  }
  return t;
}

}  // namespace ncpath
