#include "engine/facet_table.hpp"

#include "engine/parallel.hpp"

namespace ncpath {

namespace {

void corners(const TriangleMesh& mesh, std::size_t i, bool swap_xy, Vec3 (&p)[3]) {
  for (int k = 0; k < 3; ++k) {
    p[k] = mesh.vertices[mesh.facets[i][k]];
    if (swap_xy) std::swap(p[k].x(), p[k].y());
  }
}

}  // namespace

FacetTable build_facet_table(const TriangleMesh& mesh, bool swap_xy) {
  const std::size_t n = mesh.facets.size();
  // Count (which facets are usable), scan (their slots), fill (in place, no second copy of
  // the table: it is the largest structure of a big job).
  std::vector<std::uint32_t> slot(n + 1, 0);
  par::for_each(n, 4096, [&](std::size_t i) {
    Vec3 p[3];
    corners(mesh, i, swap_xy, p);
    PreparedFacet f;
    slot[i + 1] = prepare_facet(p[0], p[1], p[2], f) ? 1 : 0;
  });
  for (std::size_t i = 0; i < n; ++i) slot[i + 1] += slot[i];
  FacetTable t;
  t.facets.resize(slot[n]);
  t.source_index.resize(slot[n]);
  t.degenerate = n - slot[n];
  par::for_each(n, 4096, [&](std::size_t i) {
    if (slot[i + 1] == slot[i]) return;
    Vec3 p[3];
    corners(mesh, i, swap_xy, p);
    prepare_facet(p[0], p[1], p[2], t.facets[slot[i]]);
    t.source_index[slot[i]] = static_cast<std::uint32_t>(i);
  });
  for (const PreparedFacet& f : t.facets)
    for (const Vec3& p : f.p) t.box.add(p);
  return t;
}

}  // namespace ncpath
