#pragma once
// Input conditioning for the exact slicers (z-levels, drive planes, pencil, fillet): one pass
// that gives every representation of a part the same near-degenerate-free geometry, so that
// the kernels' exact predicates never see "almost coplanar" or "almost vertical" facets.
//
// Why. Exporters write a part's vertices with 6 to 17 significant digits, convert units, or
// compute them in double booleans: faces that are planar in the part become facets whose
// normals differ by 1e-13 to 1e-6. Two such facets cross at a grazing angle; the crossing of
// their offset planes is then known only to rounding / angle (1e-16 * 100 mm / 1e-11 = 1e-3
// mm), and the z-level contours lose or invent pieces there (issue 17). Far from that band the
// configuration is well conditioned (digits 6: the facets clearly bend) or exactly degenerate
// and handled as such (full precision: coplanar to rounding, share_coplanar_offsets).
//
// What. Four steps, one purpose: every face the part has is one exact plane.
//   1. Clusters. Facets are grown, through shared vertices (T-junctions and non-manifold
//      edges do not split a face), into planar clusters: a facet joins when its three
//      vertices lie within tol::kConditionPlane of the plane fitted so far (area-weighted
//      normal and centroid); the cluster is then grown again from its seed against that plane
//      held fixed, so every member lies within kConditionPlane of it.
//   2. Snaps. A cluster's plane becomes an axis plane (x, y or z = const), else vertical
//      (n.z = 0), when every vertex of the cluster stays within kConditionPlane of it.
//   3. One plane per face. Clusters whose planes coincide within kConditionPlane take the
//      earliest one's plane, bit for bit: pieces of a face that share no vertex (a wall
//      interrupted by a fillet) then have edges whose shadows coincide exactly.
//   4. Moves. Each vertex moves by the smallest displacement (least squares: a point on one
//      plane, a line on two, the corner on three) that puts it on the planes of its
//      clusters (two facets or more, or snapped: a lone facet's own plane passes through its
//      vertices) and of the vertical clusters in whose plane one of its edges lies (a ruling
//      of the curved surface beside a wall, the edge of a ledge straight above a wall: their
//      shadows run along the wall's),
//      only when that moves it at most tol::kConditionMove; an axis plane's coordinate is
//      then set exactly (a horizontal face becomes z == c in every bit).
//
// Safety. Vertices move by at most stats.max_move (0 when nothing was near-degenerate, or
// exactly degenerate already). Callers grow the ball by it (stock on the conditioned part),
// so the tool keeps at least zero from the part as given.
//
// Deterministic: clusters are grown from the lowest facet index, the facets around a vertex
// visited in index order.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "kernels/mesh/triangle_mesh.hpp"

namespace ncpath {

struct ConditionStats {
  std::uint64_t planes = 0;          // planar clusters of two or more facets
  std::uint64_t planar_facets = 0;   // facets in them
  std::uint64_t axis_planes = 0;     // cluster planes snapped to an axis plane or to vertical
  std::uint64_t moved_vertices = 0;  // vertices moved onto their planes
  std::uint64_t kept_vertices = 0;   // vertices that would have moved farther than kConditionMove
  double max_move = 0;               // mm, the largest vertex displacement made
};

struct ConditionedMesh {
  TriangleMesh mesh;  // same vertex and facet indices as the input
  ConditionStats stats;
};

// Runs body(begin, end) over ranges covering [0, n), possibly in parallel (the engine passes
// its TBB loop; kernels stay free of threads). Empty: one range, sequentially.
using RangeRunner =
    std::function<void(std::size_t n, const std::function<void(std::size_t, std::size_t)>& body)>;

// The conditioned mesh (see above). The mesh must be welded (shared vertices by index:
// engine/offset_elements_build.hpp condition_for_slicing welds exact duplicates first). The
// per-facet and per-vertex passes go through `ranges`; the result does not depend on it.
ConditionedMesh condition_mesh(const TriangleMesh& mesh, const RangeRunner& ranges = {});

}  // namespace ncpath
