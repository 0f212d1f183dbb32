#pragma once
// Local offset of a triangle mesh by a ball radius R (issue 5): the elements whose upper
// envelope is the drop-cutter surface of a ball-end mill, as structure-of-arrays.
//
// The ball centre of a ball-end mill dropped onto a mesh is the highest point at distance R
// from the mesh, i.e. the upper envelope of the R-neighbourhoods of its facets. The
// neighbourhood of one triangle is bounded by
//   - its offset triangle: the triangle translated by R along its unit normal, turned so
//     that n.z >= 0 (the tool comes from +z, so only the upper side can be touched);
//   - a cylinder of radius R around each edge (between the planes through the edge's ends
//     perpendicular to it);
//   - a sphere of radius R around each vertex.
// Choices (documented here because the envelope depends on them):
//   - Every unique edge and every vertex gets its element, convex or concave. Concave edges
//     and vertices lie below the envelope (their neighbouring offset triangles cover them),
//     so keeping them costs a little time and never changes the envelope; deciding
//     convexity robustly on scanned meshes (folds, near-flat edges) is not needed for
//     exactness. EdgeKind is recorded for later stages (junction classification).
//   - Open boundaries and non-manifold edges need nothing special: an edge used by 1 or 3+
//     facets is one edge, one cylinder. Orientation (winding) is never used: facets count
//     as two-sided, like the point drop-cutter (kernels/cutters/drop_cutter.hpp).
//   - Degenerate facets (|e1 x e2| < tol::kDegenerateArea2) contribute nothing, not even
//     their edges and vertices (the point drop-cutter skips them the same way). Unreferenced
//     vertices are ignored.
//   - Vertical facets (|n.z| < tol::kVerticalNormalZ) keep their offset triangle (flagged);
//     slicers skip it: a ball dropped from above touches such a facet first at its top edge
//     or vertex, whose cylinder and sphere give the same height.
//
// Element ids: facets [0, F), edges [F, F + E), vertices [F + E, F + E + V).
//
// Building is split into range kernels (count, fill) so that the engine can run them over
// chunks in parallel and scatter without locks; build_offset_elements() is the sequential
// reference that chains them.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "kernels/geom/tolerance.hpp"
#include "kernels/geom/vec.hpp"
#include "kernels/mesh/triangle_mesh.hpp"

namespace ncpath {

// How the (up to two) facets at an edge meet, as seen by a tool from +z (upward normals).
enum class EdgeKind : std::uint8_t {
  kConvex = 0,       // both facets fall away below each other's plane: a ridge
  kConcave = 1,      // both rise above each other's plane: a valley
  kFlat = 2,         // coplanar within tol::kEdgeFlatSine
  kFold = 3,         // mixed signs: one facet overhangs the other (seen from above)
  kBoundary = 4,     // one facet (open boundary of a scanned mesh)
  kNonManifold = 5,  // three or more facets
};
const char* edge_kind_name(EdgeKind kind);

struct OffsetElements {
  double radius = 0;  // R, mm

  // Positions of the mesh vertices (a copy of mesh.vertices, mm); edges and spheres index it.
  std::vector<Vec3> points;
  // The mesh vertex behind each point when the builder kept only some vertices, in
  // increasing order (engine/offset_elements_build.hpp: one per group of exactly equal
  // vertices); empty when points are the mesh's vertices themselves.
  std::vector<std::uint32_t> point_source;

  // Facets, F of them. facet_normal: the unit normal with n.z >= 0; facet_source: the index
  // into mesh.facets; offset_tri(): the offset triangle's vertices (source + R n, mm),
  // computed when asked (storing them cost 72 bytes per facet).
  std::vector<Vec3> facet_normal;
  std::vector<std::uint32_t> facet_source;
  std::vector<std::array<std::uint32_t, 3>> facet_vertices;  // the source facet's indices
  std::vector<std::uint8_t> facet_vertical;                  // 1 when |n.z| < tol::kVerticalNormalZ

  // Edges, E of them: vertex indices into points (lo < hi), kind and number of facets.
  std::vector<std::array<std::uint32_t, 2>> edge_vertices;
  std::vector<EdgeKind> edge_kind;
  std::vector<std::uint32_t> edge_facet_count;
  // 1 when the ball can touch the edge's interior from above without cutting into one of
  // its two facets (see edge_reachable below); boundary and non-manifold edges always.
  std::vector<std::uint8_t> edge_reachable;
  // Unit directions w1, w2 from the edge into its two facets (perpendicular to it): a ball
  // touching the edge along d (contact to centre) is on the envelope only if d . w1 <= 0 and
  // d . w2 <= 0, so slices keep only that part of the cylinder. Zero when the edge has not
  // two facets (then its whole cylinder is sliced).
  std::vector<std::array<Vec3, 2>> edge_wedge;
  // 1 for an edge kept as nearly flat (tol::kFlatEdgeKeep): its wedge is (almost) empty, so
  // it is trimmed with the slack tol::kFlatTrimSlack instead, to a thin strip around the
  // common normal that covers rounding slivers between the two offset triangles.
  std::vector<std::uint8_t> edge_flat;

  // Spheres, V of them: indices into points. vertex_reachable: 0 when every edge at the
  // vertex is unreachable (its sphere then lies below the envelope too).
  std::vector<std::uint32_t> vertex_source;
  std::vector<std::uint8_t> vertex_reachable;
  // The vertex's 1-ring (indices into points; CSR by vertex slot, V + 1 offsets): a ball
  // touching only the vertex along d is on the envelope only if d . (q - v) <= 0 for every
  // ring point q (else it cuts into a facet there), so slices keep only that part of the
  // sphere. vertex_flat: 1 at a vertex with a nearly flat kept edge (trimmed with
  // tol::kFlatTrimSlack, like the edge).
  std::vector<std::uint32_t> ring_offsets, ring;
  std::vector<std::uint8_t> vertex_flat;

  std::array<Vec3, 3> offset_tri(std::size_t f) const {
    const Vec3 shift = radius * facet_normal[f];
    const auto& v = facet_vertices[f];
    return {points[v[0]] + shift, points[v[1]] + shift, points[v[2]] + shift};
  }

  std::size_t facet_count() const { return facet_normal.size(); }
  std::size_t edge_count() const { return edge_vertices.size(); }
  std::size_t vertex_count() const { return vertex_source.size(); }
  std::size_t element_count() const { return facet_count() + edge_count() + vertex_count(); }
  std::uint32_t edge_id(std::size_t e) const { return std::uint32_t(facet_count() + e); }
  std::uint32_t vertex_id(std::size_t v) const {
    return std::uint32_t(facet_count() + edge_count() + v);
  }
};

// Whether element `id` can be on the upper envelope. Facets: unless vertical. An edge
// shared by two facets: a ball touching its interior along direction d (from the contact to
// the centre, perpendicular to the edge) cuts into a facet unless d . w <= 0 for the
// in-plane directions w1, w2 pointing from the edge into both facets; those d form a wedge,
// and the edge is reachable only if the wedge holds an upward direction (d.z > 0). At a
// concave edge it does not: there the neighbouring offset triangles cross above the
// cylinder, which therefore never shows (unreachable elements are skipped by the scan; the
// drop-cutter comparisons in the tests cover this). Edges bent less than tol::kFlatEdgeKeep
// are kept: their cylinder fills rounding slivers between the two offset triangles, which
// come from different normals. A vertex is unreachable when all its edges are (a pit or a
// valley floor: a ball touching only the vertex would cut into a facet around it).
bool element_reachable(const OffsetElements& el, std::uint32_t id);

// The y extent [lo, hi] of the part of element `id` that can be on the envelope (mm): an
// offset triangle's y range; for a cylinder, its edge's y range grown by R times the
// extreme y components of the contact directions in its wedge (or in the whole circle
// perpendicular to the edge); for a sphere, the vertex's y grown likewise over its ring cone
// (the extremes of a linear function over a polyhedral cone on the unit sphere lie at its
// centre direction, on one face or on an edge of the cone, so a few candidates decide it).
// Drive planes y = v outside [lo, hi] get no piece from the trimmed element. False when the
// element can give no piece at all (unreachable, vertical, empty cone).
bool element_y_reach(const OffsetElements& el, std::uint32_t id, double& lo, double& hi);

// The wedge test above for the edge from a along unit direction e, with w1 and w2 pointing
// from it into the two facets (any lengths).
bool edge_wedge_reachable(const Vec3& e, const Vec3& w1, const Vec3& w2);

// Unit normal of triangle (a, b, c) turned to n.z >= 0. False when degenerate.
bool upward_unit_normal(const Vec3& a, const Vec3& b, const Vec3& c, Vec3& n);

// Number of non-degenerate facets among mesh.facets[begin, end).
std::uint32_t count_offset_facets(const TriangleMesh& mesh, std::uint32_t begin, std::uint32_t end);

// Writes the non-degenerate facets of mesh.facets[begin, end), in order, into slots
// first_slot, first_slot + 1, ... of out's facet arrays (already sized by the caller to the
// total count) and also writes their half-edge keys into keys[3 * slot + k]: (lo << 32 | hi)
// vertex indices of edge k. Offset triangles come from out.radius (offset_tri()).
void fill_offset_facets(const TriangleMesh& mesh, std::uint32_t begin,
                        std::uint32_t end, std::uint32_t first_slot, OffsetElements& out,
                        std::span<std::uint64_t> keys);

// Classifies unique edges [begin, end). sorted_keys holds all half-edge keys sorted, paired
// with the facet slot that owns each (key_facet[i]); edge_start[e] is the first index in
// sorted_keys of unique edge e (edge_start has E + 1 entries, the last = keys.size()). Writes
// edge_vertices, edge_kind and edge_facet_count [begin, end) (sized by the caller).
void classify_edges(std::span<const std::uint64_t> sorted_keys,
                    std::span<const std::uint32_t> key_facet,
                    std::span<const std::uint32_t> edge_start, std::uint32_t begin,
                    std::uint32_t end, OffsetElements& out, double flat_sine = tol::kEdgeFlatSine);

// Coplanar regions: facets joined through flat edges of exactly two facets (continuing
// across the edge, not folded) whose normals are within tol::kCoplanarSine of the region's
// first facet (lowest slot) take that facet's normal, and their offset triangles are
// recomputed with it, so that they tile the offset plane exactly (the slicer computes a
// shared edge's crossing the same way for both facets); the edges inside a region of two or
// more facets become unreachable (their cylinder's contact cone is the normal direction,
// covered by the offset triangles), and collect_vertices() then drops the vertices inside
// (all edges unreachable). Vertical facets form regions of their own (normals compared up to
// sign, offset triangles untouched: they are never sliced): inside such a region every
// point has a point of the region's boundary straight above it, whose elements are higher.
// vertical_only: only regions of vertical facets (Coplanar::kVertical). key_facet /
// edge_start as for classify_edges, run after it over all edges. Returns the number of edges
// dropped. Deterministic (regions grown in slot order).
std::size_t share_coplanar_offsets(std::span<const std::uint32_t> key_facet,
                                   std::span<const std::uint32_t> edge_start, OffsetElements& el,
                                   bool vertical_only = false);

// A vertex inside a straight edge line (two ring points opposite within
// tol::kCoplanarSine, e.g. a midpoint of a subdivided or CAD mesh) becomes unreachable: its
// cone lies in the plane perpendicular to the line and within the wedge of the edge to
// either neighbour (the opposite vertices of that edge's facets are ring points), so its
// sphere shows nothing the two cylinders do not (the slicer pushes cylinder caps out by
// tol::kTrimExtend so that they overlap there). Run after collect_vertices().
void drop_straight_vertices(OffsetElements& el);

// vertex_source, vertex_reachable and the rings from facet_vertices, edge_vertices,
// edge_reachable and edge_wedge.
void collect_vertices(OffsetElements& el);

// Whether the builders merge coplanar regions (share_coplanar_offsets; vertical_only: only
// regions of vertical facets). The drive-plane scan merges all (kMerge). The z-level kernel
// merges only vertical ones (kVertical): its facet regions are unioned with the flat edges'
// strips filling the rounding slivers between them, but vertical facets have no region, and
// an inner edge of a vertical region has its capsule inside the capsules of the region's
// boundary straight above it (same xy, higher) — the walls' stacked edges all project onto
// the wall's line. kKeep keeps every element.
enum class Coplanar : std::uint8_t { kMerge, kVertical, kKeep };

// Sequential reference build: facets, then unique edges (sorted by their vertex pair), then
// referenced vertices (ascending index).
OffsetElements build_offset_elements(const TriangleMesh& mesh, double radius,
                                     Coplanar coplanar = Coplanar::kMerge);

}  // namespace ncpath
