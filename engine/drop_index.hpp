#pragma once
// Random-access exact drop-cutter over a whole mesh, accelerated by an Embree 3 BVH.
//
// Each facet is an Embree user primitive whose box is the facet's box grown by the cutter
// radius in x and y and down to the lowest tip height it can produce. A query is one ray
// shot down (-Z) through the tool axis; Embree visits boxes nearest-first and culls any box
// whose top lies below the best tip found so far. The intersection callback runs the
// double-precision kernel (drop_facet), so the answer equals a brute-force scan over all
// facets; Embree's float boxes are padded so rounding can only add candidates.
//
// Facets are prepared (prepare_facet) either once and kept in the index (288 bytes a facet),
// or when a box meets the query (the index keeps 4 bytes a facet beside Embree's BVH, and
// each thread a cache of the 4096 slots' recently prepared facets, 1.2 MB: queries along a
// path meet mostly the same facets; a query far from the last costs about 1.8 times as
// much). Preparing is deterministic: both give the same bits. kAuto keeps them while the table takes at most kPreparedTableBytes: small meshes
// keep their speed, and on a dense scan the pencil and fillet, whose largest structure the
// table was, fit 20 M facets in 24 GB (docs/performance.md "Memory per facet").
//
// Built once per (mesh, cutter radius) and shared read-only: query() is thread-safe.
#include <cstdint>
#include <memory>

#include "engine/facet_table.hpp"
#include "kernels/cutters/cutter.hpp"
#include "kernels/cutters/drop_cutter.hpp"

namespace ncpath {

class DropIndex {
 public:
  enum class Facets { kAuto, kOnDemand, kPrepared };
  static constexpr std::uint64_t kPreparedTableBytes = std::uint64_t{64} << 20;
  // The mesh must outlive the index. Degenerate facets (prepare_facet false) are left out.
  DropIndex(const TriangleMesh& mesh, const Cutter& cutter, Facets facets = Facets::kAuto);
  ~DropIndex();
  DropIndex(const DropIndex&) = delete;
  DropIndex& operator=(const DropIndex&) = delete;

  // Highest contact of the cutter at (x, y); kind kNone when the tool touches nothing.
  // Its facet is an index into mesh.facets.
  CutterContact query(double x, double y) const;

  std::uint64_t facet_count() const;  // facets in the index (not degenerate)
  std::uint64_t degenerate() const;   // facets left out

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The reference answer: every facet tested, in index order (ties keep the lowest index; the
// contact's facet is an index into table.facets).
CutterContact drop_brute_force(const FacetTable& table, const Cutter& cutter, double x, double y);

}  // namespace ncpath
