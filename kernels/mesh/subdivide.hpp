#pragma once
// Midpoint (1-to-4) subdivision of an indexed triangle mesh, and Loop's smoothing variant.
// Midpoint subdivision does not smooth, so the refined mesh covers exactly the same surface
// as the input: large CAD-like benchmark meshes (datasets/make-large-mesh.sh). Loop's moves
// every vertex: dense scan-like meshes with no coplanar facets (datasets/make-dense-scans.sh).
#include <cstddef>

#include "kernels/mesh/triangle_mesh.hpp"

namespace ncpath {

// Splits every facet (a, b, c) into four by the midpoints m_ab, m_bc, m_ca of its edges:
//   4i+0 = (a, m_ab, m_ca), 4i+1 = (m_ab, b, m_bc), 4i+2 = (m_ca, m_bc, c),
//   4i+3 = (m_ab, m_bc, m_ca)
// so children keep their parent's winding and sit at 4i..4i+3 for parent i.
//
// Output vertices: all input vertices at their input indices (unreferenced ones included),
// then one midpoint per distinct undirected edge {u, v}, numbered in order of the edge's
// first appearance in facet order (facet i, edges ab, bc, ca). An edge shared by several
// facets (manifold or not) gets one midpoint, so a closed mesh stays closed and
// V' = V + E, F' = 4F. The midpoint is 0.5 * (p_min(u,v) + p_max(u,v)), independent of
// facet order. The result depends only on the input: same input, same bytes.
//
// Preconditions (debug-asserted): every facet index < mesh.vertices.size(), and
// mesh.vertices.size() + 3 * mesh.facets.size() and 4 * mesh.facets.size() fit in
// uint32_t (see subdivide_midpoint_fits). Cost: O(F log F) time, O(V + F) memory, no
// per-element allocation.
TriangleMesh subdivide_midpoint(const TriangleMesh& mesh);

// Loop's subdivision (C. Loop, 1987): the midpoint subdivision's facets (same order, same
// vertex numbering), with smoothed positions, so a coarse scan becomes a dense one with no
// two facets coplanar. An edge shared by exactly two facets gets 3/8 (a + b) + 1/8 (c + d)
// (c, d: the corners opposite it); any other edge (boundary, non-manifold) is a crease and
// gets its midpoint. A vertex with only two-facet edges and valence n >= 3 moves to
// (1 - n beta) v + beta (sum of its neighbours), beta = (5/8 - (3/8 + cos(2 pi / n) / 4)^2)
// / n; a vertex on exactly two crease edges to 3/4 v + 1/8 (their far ends); any other
// vertex (a corner of creases, isolated) stays. Sums run in edge order: the same input gives
// the same bytes. Same preconditions and cost as subdivide_midpoint.
TriangleMesh subdivide_loop(const TriangleMesh& mesh);

// True when one more round of subdivide_midpoint on a mesh of this size cannot overflow
// the uint32_t vertex or facet indices (conservative: assumes every edge distinct).
bool subdivide_midpoint_fits(std::size_t num_vertices, std::size_t num_facets);

}  // namespace ncpath
