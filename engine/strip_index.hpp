#pragma once
// Candidate culling for raster drop-cutting: coherence along scan lines.
//
// Scan lines (along x) are grouped into strips of consecutive lines. Every facet cluster
// (engine/facet_clusters.hpp) is bucketed (count, scan, fill) into the strips whose y-range
// its box, grown by the cutter radius, overlaps. A strip then bins its clusters along x;
// each bin lists the clusters that can reach it, highest top first (the buckets are filled
// in that order, so no bin is ever sorted). A drop at (x, y) walks its bin and stops at the
// first cluster whose top lies at or below the best tip found so far: nothing later can
// beat it, as no tip is above the highest vertex it touches. A cluster, and then each of its
// facets, is also dismissed when it lies farther than R from the axis, when its top lowered
// by the cutter's rise at that distance cannot beat the best, or (facets) when its
// tangent-plane bound cannot. Survivors go to the double-precision kernel, so every answer
// equals the brute-force maximum over all facets.
#include <cstdint>
#include <vector>

#include "engine/facet_clusters.hpp"
#include "engine/facet_table.hpp"
#include "kernels/cutters/cutter.hpp"
#include "kernels/cutters/drop_cutter.hpp"

namespace ncpath {

// Clusters of each strip, CSR: strip s holds cluster ids ids[offsets[s] .. offsets[s+1]),
// highest top first.
struct StripBuckets {
  double y0 = 0, height = 1;  // strip s covers y in [y0 + s*height, y0 + (s+1)*height]
  std::vector<std::uint32_t> offsets;
  std::vector<std::uint32_t> ids;
};

StripBuckets bucket_clusters_by_strip(const ClusteredFacets& clustered, double radius, double y0,
                                      double height, std::size_t strips);

// The x-binned candidate lists of one strip. Built by the task that owns the strip.
class StripBins {
 public:
  // ids: the strip's clusters, highest top first (as bucket_clusters_by_strip leaves them).
  void rebuild(const FacetTable& table, const ClusteredFacets& clustered, const Cutter& cutter,
               const std::uint32_t* ids, std::size_t count, double x0, double x1, double bin_width);

  // Highest contact at (x, y), starting from `seed` (a lower bound on the answer, e.g. the
  // floor or the previous point's contact); x must lie in [x0, x1] of rebuild().
  CutterContact drop(double x, double y, CutterContact seed) const;

 private:
  const FacetTable* table_ = nullptr;
  const ClusteredFacets* clustered_ = nullptr;
  Cutter cutter_;
  double x0_ = 0, inv_width_ = 1;
  std::vector<std::uint32_t> offsets_;
  std::vector<ClusterBound> entries_;            // copies, for locality of the walk
  std::vector<std::uint32_t> lo_, hi_, cursor_;  // scratch for rebuild()
};

}  // namespace ncpath
