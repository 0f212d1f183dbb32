#pragma once
// Candidate culling for raster drop-cutting: coherence along scan lines.
//
// Scan lines (along x) are grouped into strips of consecutive lines. Every facet is
// bucketed (count, scan, fill) into the strips whose y-range its box, grown by the cutter
// radius, overlaps. A strip then bins its candidates along x; each bin lists the facets that
// can reach it, sorted by their top z, highest first. A drop at (x, y) walks its bin's list
// and stops at the first facet whose top lies below the best tip found so far: no later
// facet can beat it (a tip is never above its facet's highest vertex). The kernel decides
// in double, so every answer equals the brute-force maximum over all facets.
#include <cstdint>
#include <vector>

#include "engine/facet_table.hpp"
#include "kernels/cutters/cutter.hpp"
#include "kernels/cutters/drop_cutter.hpp"

namespace ncpath {

// Facets of each strip, CSR: strip s holds facet ids ids[offsets[s] .. offsets[s+1]).
struct StripBuckets {
  double y0 = 0, height = 1;  // strip s covers y in [y0 + s*height, y0 + (s+1)*height]
  std::vector<std::uint32_t> offsets;
  std::vector<std::uint32_t> ids;
  std::size_t strip_count() const { return offsets.empty() ? 0 : offsets.size() - 1; }
};

StripBuckets bucket_facets_by_strip(const FacetTable& table, double radius, double y0,
                                    double height, std::size_t strips);

// The x-binned candidate lists of one strip. Built by the task that owns the strip and
// reused from strip to strip (rebuild() keeps the allocations).
class StripBins {
 public:
  // ids must be sorted highest top first (as bucket_facets_by_strip leaves them).
  void rebuild(const FacetTable& table, const Cutter& cutter, const std::uint32_t* ids,
               std::size_t count, double x0, double x1, double bin_width);

  // Highest contact at (x, y), starting from `seed` (a lower bound on the answer, e.g. the
  // floor or the previous point's contact); x must lie in [x0, x1] of rebuild().
  CutterContact drop(double x, double y, CutterContact seed) const;

 private:
  // Everything the walk needs to dismiss a facet without touching its PreparedFacet: its
  // top, its box grown by the radius, and the tangent-plane tip, which is linear in (x, y)
  // (plane_a x + plane_b y + plane_c) and bounds every contact with the facet from above.
  struct Entry {
    double top_z;
    double x_lo, x_hi, y_lo, y_hi;
    double plane_a, plane_b, plane_c;
    std::uint32_t facet;
  };
  static Entry make_entry(const PreparedFacet& f, const Cutter& c, std::uint32_t id);
  const FacetTable* table_ = nullptr;
  Cutter cutter_;
  double x0_ = 0, inv_width_ = 1;
  std::vector<std::uint32_t> offsets_;
  std::vector<Entry> entries_;
  std::vector<std::uint32_t> lo_, hi_, cursor_;  // scratch for rebuild()
};

}  // namespace ncpath
