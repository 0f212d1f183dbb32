#pragma once
// Parallel build of a mesh's offset elements (kernels/mesh/offset_elements.hpp) and the
// index that finds the elements reaching a drive plane y = v (engine/scan.hpp).
#include <cstdint>
#include <span>
#include <vector>

#include "kernels/mesh/condition.hpp"
#include "kernels/mesh/offset_elements.hpp"
#include "kernels/mesh/triangle_mesh.hpp"

namespace ncpath {

// The mesh element behind an offset element id, for output: kind (0 facet, 1 edge, 2 vertex,
// 3 none: the floor) and mesh indices (facet index, -1; the edge's two vertex indices;
// vertex index, -1; -1, -1).
struct ElementRef {
  std::int64_t kind = 3, a = -1, b = -1;
};
ElementRef element_ref(const OffsetElements& el, std::uint32_t id);

// The drop-cutter contact kind code (ContactKind: facet, edge, vertex; none for the floor).
std::uint8_t contact_code(const OffsetElements& el, std::uint32_t id);

// For every vertex, the lowest index of the vertices with exactly the same coordinates.
std::vector<std::uint32_t> exact_duplicate_map(const std::vector<Vec3>& vertices);

// The mesh welded at exactly equal vertices (facets refer to the lowest index of each group)
// and conditioned for the exact slicers (kernels/mesh/condition.hpp): what z-levels, pencil
// and fillet slice. Vertex and facet indices are the input's.
ConditionedMesh condition_for_slicing(const TriangleMesh& mesh);

// The elements build_offset_elements (the sequential reference) gives for the mesh welded
// at exactly equal vertices (facets refer to the lowest index of each group: an STL soup
// becomes connected, so its edges are classified and its duplicates vanish), built with
// count/scan/fill over chunks of facets, parallel sorts and parallel edge classification.
// Only the kept vertex of each group is a point (an STL soup keeps one in six):
// OffsetElements::point_source names its mesh vertex, and element_ref() reports mesh
// vertices; element ids and their order are those of the welded mesh.
// swap_xy: build them for the mesh with x and y exchanged (the frame of planes x = const);
// element ids are the same either way. coplanar: as for build_offset_elements.
OffsetElements build_offset_elements_parallel(const TriangleMesh& mesh, double radius,
                                              bool swap_xy, Coplanar coplanar = Coplanar::kMerge);

// The same elements with x and y exchanged in every position and direction (a mirror: the
// edge wedges, rings and kinds are unchanged), i.e. the elements of the swapped mesh without
// building them again. Pass an rvalue to mirror in place.
OffsetElements mirror_xy(OffsetElements el);

// The elements of el whose extent along the axis (0 x, 1 y: element_extent, padded like the
// plane index's bound) meets one of the planes at `at` across it, with the points and rings
// they use: what slices those planes, for a family scanned only along its two side planes.
// The kept elements stay in id order (their new ids are increasing), so sorts and ties by id
// order them as before, and element_ref() names the same mesh elements.
OffsetElements elements_near_planes(const OffsetElements& el, int axis,
                                    std::span<const double> at);

// The extent of every element across the planes (y) that its trimmed pieces can reach
// (element_y_reach: an offset triangle's y range; an edge's or vertex's y range grown by R
// times the y reach of its cone). Unreachable and vertical elements are left out (they give
// no piece). Elements up to the 99.9th percentile of the extents (`short_extent`) are sorted
// by their low end; the longer ones are kept apart and checked for every plane.
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

// A cheap range containing everything of element id along axis (0 x, 1 y): the offset
// facet's own range, an edge's or vertex's range grown by R.
void element_extent(const OffsetElements& el, std::uint32_t id, int axis, double& lo,
                    double& hi);

// The index of el's reachable elements by their y reach. With only_at, the index answers
// queries at those plane positions only (with the same elements, in the same order, as the
// full index) and holds just the elements meeting them: a cheap bound (the offset facet's
// range, an edge's or vertex's range grown by R) spares the exact reach of the others.
PlaneIndex build_plane_index(const OffsetElements& el, std::span<const double> only_at = {});

}  // namespace ncpath
