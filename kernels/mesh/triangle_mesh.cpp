#include "kernels/mesh/triangle_mesh.hpp"

namespace ncpath {

Aabb3 bounding_box(const TriangleMesh& mesh) {
  Aabb3 box;
  for (const auto& f : mesh.facets)
    for (std::uint32_t v : f) box.add(mesh.vertices[v]);
  return box;
}

FacetsAround facets_around(const TriangleMesh& mesh) {
  FacetsAround a;
  a.start.assign(mesh.vertices.size() + 1, 0);
  for (const auto& f : mesh.facets)
    for (std::uint32_t v : f) ++a.start[v + 1];
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) a.start[v + 1] += a.start[v];
  a.ids.resize(a.start.back());
  std::vector<std::uint32_t> fill(a.start.begin(), a.start.end() - 1);
  for (std::uint32_t f = 0; f < mesh.facets.size(); ++f)
    for (std::uint32_t v : mesh.facets[f]) a.ids[fill[v]++] = f;
  return a;
}

}  // namespace ncpath
