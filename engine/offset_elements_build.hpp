#pragma once
// Parallel build of a mesh's offset elements (kernels/mesh/offset_elements.hpp) and the
// index that finds the elements reaching a drive plane y = v (engine/scan.hpp).
#include <cstdint>
#include <vector>

#include "kernels/mesh/offset_elements.hpp"
#include "kernels/mesh/triangle_mesh.hpp"

namespace ncpath {

// Same elements, in the same order, as build_offset_elements (the sequential reference),
// built with count/scan/fill over chunks of facets, a parallel sort of the half-edge keys
// and parallel edge classification. swap_xy: build them for the mesh with x and y exchanged
// (the frame of planes x = const); element ids are the same either way.
OffsetElements build_offset_elements_parallel(const TriangleMesh& mesh, double radius,
                                              bool swap_xy);

// The extent of every element across the planes (y): an offset triangle's y range, an
// edge's y range grown by R, a vertex's y +- R. Vertical facets and vertical edges are left
// out (they give no piece). Elements no longer than `short_extent` are sorted by their low
// end; the longer ones are kept apart and checked for every plane.
struct PlaneIndex {
  std::vector<double> lo, hi;          // short elements, sorted by (lo, id)
  std::vector<std::uint32_t> ids;
  std::vector<double> long_lo, long_hi;  // long elements, by id
  std::vector<std::uint32_t> long_ids;
  double short_extent = 0;  // mm

  // Appends the ids of elements whose extent contains v: short ones by increasing low end,
  // then long ones by id.
  void query(double v, std::vector<std::uint32_t>& out) const;
};

PlaneIndex build_plane_index(const OffsetElements& el);

}  // namespace ncpath
