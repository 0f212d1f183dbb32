#pragma once
// An indexed triangle mesh as the readers produce it. Owned by the caller; kernels see it
// through spans. Coordinates in mm (after the job's transform).
#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "kernels/geom/vec.hpp"

namespace ncpath {

struct TriangleMesh {
  std::vector<Vec3> vertices;                     // mm
  std::vector<std::array<std::uint32_t, 3>> facets;  // indices into vertices, any winding
};

struct Aabb3 {
  Vec3 lo{Vec3::Constant(std::numeric_limits<double>::infinity())};
  Vec3 hi{Vec3::Constant(-std::numeric_limits<double>::infinity())};
  void add(const Vec3& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  bool empty() const { return !(lo.x() <= hi.x()); }
};

// Bounding box of the vertices referenced by facets (unreferenced vertices are ignored).
Aabb3 bounding_box(const TriangleMesh& mesh);

// The facets at each vertex (CSR over facet corners, in facet order): those of vertex v are
// ids[start[v], start[v + 1]).
struct FacetsAround {
  std::vector<std::uint32_t> start, ids;
};
FacetsAround facets_around(const TriangleMesh& mesh);

}  // namespace ncpath
