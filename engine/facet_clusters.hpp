#pragma once
// Facets grouped into small spatial clusters, with the bounds the raster walk uses to
// dismiss a cluster, or a facet, without running the kernel.
//
// Facets are ordered along a Morton (Z-order) curve of their xy centroids and cut into
// runs of at most `group` facets; each run is a cluster with its xy box and top z. Inside a
// cluster the facets are sorted by top z, highest first. Built once per (mesh, cutter).
#include <cstdint>
#include <vector>

#include "engine/facet_table.hpp"
#include "kernels/cutters/cutter.hpp"
#include "kernels/cutters/drop_cutter.hpp"

namespace ncpath {

// One facet's bounds for a given cutter: no contact with the facet is above top_z, none
// exists farther than R from its xy box, and none is above the tangent-plane tip
// plane_a x + plane_b y + plane_c (linear in the tool position; +inf for vertical facets).
struct FacetBound {
  double top_z;
  double x_lo, x_hi, y_lo, y_hi;
  double plane_a, plane_b, plane_c;
  std::uint32_t facet;  // index into FacetTable::facets
};

struct ClusterBound {
  double top_z;
  double x_lo, x_hi, y_lo, y_hi;
  std::uint32_t first, count;  // ClusteredFacets::facets[first, first + count)
};

struct ClusteredFacets {
  std::vector<FacetBound> facets;  // grouped by cluster
  std::vector<ClusterBound> clusters;
};

ClusteredFacets cluster_facets(const FacetTable& table, const Cutter& cutter, unsigned group = 16);

// The bound of one facet for one cutter (exposed for tests).
FacetBound facet_bound(const PreparedFacet& f, const Cutter& cutter, std::uint32_t id);

}  // namespace ncpath
