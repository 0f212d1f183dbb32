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
// Built once per (mesh, cutter radius) and shared read-only: query() is thread-safe.
#include <memory>

#include "engine/facet_table.hpp"
#include "kernels/cutters/cutter.hpp"
#include "kernels/cutters/drop_cutter.hpp"

namespace ncpath {

class DropIndex {
 public:
  DropIndex(const FacetTable& table, const Cutter& cutter);  // table must outlive the index
  ~DropIndex();
  DropIndex(const DropIndex&) = delete;
  DropIndex& operator=(const DropIndex&) = delete;

  // Highest contact of the cutter at (x, y); kind kNone when the tool touches nothing.
  CutterContact query(double x, double y) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The reference answer: every facet tested, in index order (ties keep the lowest index).
CutterContact drop_brute_force(const FacetTable& table, const Cutter& cutter, double x, double y);

}  // namespace ncpath
