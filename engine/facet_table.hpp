#pragma once
// The mesh as the drop-cutter kernels want it: one PreparedFacet per non-degenerate
// triangle, built once per mesh in parallel and shared read-only by every query.
#include <cstdint>
#include <vector>

#include "kernels/cutters/drop_cutter.hpp"
#include "kernels/mesh/triangle_mesh.hpp"

namespace ncpath {

struct FacetTable {
  std::vector<PreparedFacet> facets;
  std::vector<std::uint32_t> source_index;  // facets[i] came from mesh.facets[source_index[i]]
  std::uint64_t degenerate = 0;             // triangles skipped (no normal)
  Aabb3 box;                                // of the kept facets, mm
};

// swap_xy mirrors the mesh in the plane x = y (drop heights are invariant under that
// isometry); the raster uses it to scan along y with the code that scans along x.
FacetTable build_facet_table(const TriangleMesh& mesh, bool swap_xy = false);

}  // namespace ncpath
