#include "kernels/mesh/triangle_mesh.hpp"

namespace ncpath {

Aabb3 bounding_box(const TriangleMesh& mesh) {
  Aabb3 box;
  for (const auto& f : mesh.facets)
    for (std::uint32_t v : f) box.add(mesh.vertices[v]);
  return box;
}

}  // namespace ncpath
