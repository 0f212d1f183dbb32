#pragma once
// Exact z-level contours of a ball-end mill over a triangle mesh: for a tool-tip level z the
// boundary of U = {(x, y) : E(x, y) >= zc}, zc = z + R, where E is the drop-cutter surface
// (upper envelope of the offset elements, kernels/mesh/offset_elements.hpp): the region where
// the ball at that height would touch or cut the part. Closed loops of typed segments (lines,
// circular and elliptic arcs), U on the left, with the element each segment comes from and
// the junctions between elements with their bi-contact vectors.
//
// Regions (their union is U). E is the highest point at distance R from the mesh, the max
// over facets of the top of each facet's R-neighbourhood N_f. The top of N_f above (x, y) is
// reached either at a point with an interior closest point (then it lies on the offset
// triangle, the normal turned up) or with its closest point on the facet's boundary (then it
// lies on an edge's cylinder or a vertex's sphere). Hence {E >= zc} is the union of
//   - facet f (not vertical): the projected offset triangle where the offset plane's height
//     is >= zc (a triangle clipped by one half-plane);
//   - edge AB: the capsule shadow {xy : exists p in AB, |xy - p_xy|^2 + max(0, zc - p_z)^2
//     <= R^2} (cylinder and both end spheres; convex);
//   - vertex v: the disc of radius sqrt(R^2 - max(0, zc - v_z)^2) (the capsule's end disc;
//     kept as a region of its own so that the circle shared by all capsules at v is emitted
//     once, under the vertex's id).
// Vertical facets add nothing beyond their top edges and vertices; vertical edges nothing
// beyond their end discs. With OffsetElements' reachability flags, unreachable edges and
// vertices (below the envelope of their neighbours) are skipped: U does not change.
//
// Boundary candidates. A facet region's sides other than its clip line lie strictly inside
// its edges' capsules (an offset-edge point q = p + R n with q_z > zc has |q_xy - p_xy|^2 +
// (zc - p_z)^2 = R^2 (1 - n_z^2) + (zc - p_z)^2 < R^2), so facets contribute only their clip
// segment (and, in the degenerate case of an offset side at exactly zc, that side). Each
// clip segment ends tangent to the ellipse of the edge it ends on (the offset plane is
// tangent to the edge's cylinder along the offset edge), and each capsule side ends tangent
// to its end vertex's circle: these tangent joints are inserted as split points explicitly
// (on the circle kept in the vertex's place when stacked vertices' circles coincide). A line
// ending within 2 tol::kZLevelOnBoundary of another line splits that one too (a T-junction).
//
// Method: one pipeline per level (zlevel_contours, zlevel.cpp), each step dropping only what
// cannot lie on the boundary of U, so that the last steps see few curves:
//  1. Candidates: the given elements whose region can reach the level (ZLevelElementBoxes);
//     vertices come from the candidate edges.
//  2. Pruning grid (cells of about R / 2): a cell lying (by tol::kZLevelCellMargin) inside
//     one region, mostly the discs of the mesh points, is interior to U; no boundary passes
//     through it. Regions and curves that reach no other cell are never built.
//  3. Regions and their candidate curves, with the tangent joints where the curves end
//     (zlevel_regions.cpp).
//  4. Cover (zlevel_cover.cpp uncovered_runs): each curve is cut into sub-pieces of about a
//     cell, a sub-piece that is not certified halved twice; those lying in interior cells or
//     strictly inside one other region (searched deepest at the cell's centre first) are
//     dropped, and the curve is trimmed to the rest: crossings there cannot be on the boundary.
//  5. Coincident curves (the shadows of a wall's stacked edges and vertices; lines by the
//     distance of their ends, their directions differ by rounding): only the lowest element
//     id's is kept, so that k of them do not make k^2 pieces.
//  6. Splits (zlevel_intersect.cpp): the trimmed curves are split at their exact crossings
//     (closed form when a line is involved or for two circles; certified branch-and-bound
//     root isolation on the arc parameter otherwise) and at the tangent joints.
//  7. Classification (zlevel_cover.cpp classify_pieces): a piece is kept when it lies
//     strictly inside no other region; a piece strictly inside one (by tol::kZLevelOnBoundary)
//     is interior. A piece lies on one side of each region's boundary: its midpoint decides;
//     within tol::kZLevelOnBoundary of the boundary its quarter points do (a piece leaving a
//     tangent joint, where a flat edge's ellipse has a radius of curvature up to
//     R / sin^2(slope)), then the orientation of a line crossing at its ends, where that line
//     runs beside the piece (clip lines of nearly coplanar facets crossing at a grazing angle);
//     else pieces with regions on both sides are dropped; a piece leaving a tangent joint with
//     the region's curve lies inside where it turns more towards its region than that curve;
//     otherwise (coincident curves, grazing crossings) the lower element id keeps a shared
//     piece. These decisions on another region's boundary are one piece at a time; they need
//     not agree with each other, and step 8 does not rely on them alone.
//  8. Loops (zlevel_map.cpp, zlevel_loops.cpp): the pieces that are not interior form a
//     planar map (ends within tol::kZLevelLink one vertex; a curve end on another piece
//     within that distance splits it; pieces joining the same vertices along each other
//     merged; the pieces about a vertex ordered by where they cross a circle of
//     tol::kZLevelOrderRadius or more around it); each face is decided once, inside or outside
//     U, by the length-weighted vote of its pieces' classifications, and the contours are the
//     pieces between faces of different status, linked around each vertex to the next one
//     counter-clockwise: closed by construction (zlevel_map.hpp says why). A connected part of
//     the map that is not planar, or along which a kept piece has one face on both sides (a
//     gap in the map), is linked from the classification instead (kept pieces end to end, an
//     end left over linked to the nearest free start within tol::kZLevelRepair); a chain that
//     still does not close is counted (open_chains) and left out. Runs of one element's curve
//     are merged, junctions classified, and each arc's clearance (ContourSeg::clearance) found.
// The known inside region of a higher level (ZLevelInside below, optional) is one more
// certificate of "inside U" at steps 2 (its cells are interior), 3 (regions lying deep in it
// are dropped before their curves are built; callers may leave such elements out of the
// candidates, zlevel_filter_deep) and 4 (sub-pieces in it are covered). It never changes the
// answer; it makes a level's work scale with the elements near its boundary rather than with
// all those above it.
// Every tolerance is named in kernels/geom/tolerance.hpp (the kZLevel* block).
//
// Contacts. On a capsule side or vertex circle where the element lies above the level
// (ContourSeg::shadow), E jumps there (a wall or an overhang): the ball at the level does not
// touch the element but passes under it; its contact is on the vertical below the element
// (the wall, when the mesh has one), the bi-contact vector is horizontal.
//
// Output is deterministic: it does not depend on the order or repetition of candidates.
#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "kernels/geom/tolerance.hpp"
#include "kernels/geom/vec.hpp"
#include "kernels/mesh/offset_elements.hpp"
#include "kernels/scan/envelope.hpp"  // JunctionKind, shared with the drive-plane curves

namespace ncpath {

enum class ContourSegKind : std::uint8_t { kLine = 0, kCircleArc = 1, kEllipseArc = 2 };
const char* contour_seg_kind_name(ContourSegKind kind);

// One segment of a contour, from a to b (mm), U on its left. Arcs:
//   p(t) = centre + r1 cos(t) axis + r2 sin(t) perp(axis),  t from t0 to t1,
// perp(axis) = axis turned +90 degrees; t1 > t0 is counter-clockwise (always so here: every
// arc bounds its own convex region, which lies on its left). Circles: r1 == r2, axis (1, 0).
// Ellipses (section of an edge's cylinder by the plane z = zc): r2 = R, r1 = R / sin(slope)
// along the edge's horizontal direction `axis`; very flat edges give huge r1 and a far
// centre: evaluate with seg_point(), which works from the end points. Lines: a, b only.
struct ContourSeg {
  ContourSegKind kind = ContourSegKind::kLine;
  bool shadow = false;        // the element lies above the level here (E jumps, see above)
  std::uint32_t element = 0;  // offset element id whose region boundary this is
  Vec2 a = Vec2::Zero(), b = Vec2::Zero();
  Vec2 centre = Vec2::Zero();
  double r1 = 0, r2 = 0;
  Vec2 axis = Vec2(1, 0);
  double t0 = 0, t1 = 0;
  // Arcs: the largest tolerance (mm, ZLevelParams::clearance_cap divided by powers of 4, down
  // to tol::kZLevelMinBulge times it) at which the vertices of circumscribed() lie in no other
  // region than the arc's own and its neighbours' (beside a narrow gap of U's complement the
  // polygon must bulge less than the gap); infinite when not computed.
  double clearance = INFINITY;
};

// Where segment `seg` of a contour starts and the previous one (of a different element) ends.
// position: (x, y, tip level). b1, b2: unit vectors from the contact point of e1 (the
// element before) and of e2 (after) to the ball centre (x, y, zc). The contact point is the
// element's closest point (facet: centre - R n; edge: closest point of the segment; vertex),
// or, for a shadow element, the point of the vertical below it at height zc. A union of
// convex regions has no convex corners, so kConvex does not occur, except at the corners of a
// horizontal facet lying exactly at the level (a floor: its capsules have zero width there).
struct ZJunction {
  Vec3 position = Vec3::Zero();
  JunctionKind kind = JunctionKind::kTangent;
  std::uint32_t seg = 0;
  std::uint32_t e1 = 0, e2 = 0;
  Vec3 b1 = Vec3::Zero(), b2 = Vec3::Zero();
};

// A closed loop: segs[i].b == segs[i + 1].a (within tol::kZLevelLink), the last ends at the
// first's start. Outer boundaries run counter-clockwise (area > 0), holes clockwise.
struct ZContour {
  std::vector<ContourSeg> segs;
  std::vector<ZJunction> junctions;
  bool hole = false;
  double area = 0;  // signed enclosed area, mm^2 (exact for the typed segments)
};

struct ZLevelStats {
  std::uint64_t candidates = 0;        // distinct candidate ids
  std::uint64_t regions = 0;           // regions built (near the boundary)
  std::uint64_t interior_cells = 0;    // grid cells certified inside U
  std::uint64_t cells = 0;             // grid cells
  std::uint64_t curves = 0;            // candidate boundary curves built
  std::uint64_t active_curves = 0;     // trimmed curves (parts not certified inside U)
  std::uint64_t pairs = 0;             // curve pairs intersected
  std::uint64_t crossings = 0;         // crossing points found
  std::uint64_t coincident_pairs = 0;  // pairs taken as one curve (split at each other's ends)
  std::uint64_t pieces = 0;            // pieces classified
  std::uint64_t kept = 0;              // pieces on the boundary
  std::uint64_t open_chains = 0;       // chains that could not be closed (0 in a valid result)
  std::uint64_t convex_junctions = 0;  // convex corners (only at floors exactly at the level)
  std::uint64_t inside_regions = 0;    // regions dropped deep inside ZLevelParams::inside
  std::uint64_t inside_cells = 0;      // interior cells found inside ZLevelParams::inside
};

struct ZLevelResult {
  double tip_z = 0;                // the level, mm
  std::vector<ZContour> contours;  // sorted by their first segment's start (x, then y)
  ZLevelStats stats;
};

// What the candidate filter reads of each element at every level, gathered once for many
// levels (zlevel_element_boxes): its region's box at any level (x0, y0, x1, y1, mm, rounded
// outwards to float) and `reach`, the ball-centre height up to which the region can be
// non-empty (facets: up to and including it; edges and vertices: strictly below it; -inf for
// vertical facets). 24 bytes an element, read in order instead of its geometry.
struct ZLevelElementBoxes {
  std::vector<std::array<float, 4>> box;
  std::vector<double> reach;
};
ZLevelElementBoxes zlevel_element_boxes(const OffsetElements& el);

// A region known to lie inside U (see above) at the levels below the one it was made from:
// U only grows as the level goes down, so a higher level's contours bound a part of U. Its
// loops are polygons inscribed in the contour segments (chords of a convex arc lie inside its
// region), indexed on a uniform grid: per cell the polygon edges that touch it and a reference
// point whose inside/outside parity is known. Build with zlevel_inside; the kernel
// (ZLevelParams::inside) then
//   - marks the grid cells that lie inside it as interior,
//   - drops the regions lying tol::kZLevelInsideDepth deep inside it (their boundary is deep
//     inside U; their curves are never built): the stacked regions of a steep wall above the
//     level, most of those near the boundary,
//   - certifies the curve pieces lying `margin` deep inside it as covered; pieces not
//     certified, halved while they may hold a point half tol::kZLevelInsideDepth deep (down
//     to a quarter of that), hold no point of a dropped region, so the remaining regions
//     decide them exactly as all regions would.
// The caller may leave out of the candidates elements whose region lies half that depth
// inside (zlevel_filter_deep, run against the region of a higher level: a region only grows
// going down, and the polygons lie within a quarter of the depth of the contours).
// The contours are the same as without it (up to rounding where they are split).
struct ZLevelInside {
  double x0 = 0, y0 = 0, cell = 1;
  int nx = 0, ny = 0;
  std::vector<std::array<Vec2, 2>> edges;  // polygon edges, then the sides of blocked cells
  std::uint32_t polygon_edges = 0;         // edges[0, polygon_edges) count for the parity
  std::vector<std::uint32_t> start, ids;   // CSR: the edges whose box meets each cell
  std::vector<Vec2> ref;                   // per cell: the reference point
  std::vector<std::uint8_t> ref_state;     // 0 outside, 1 inside, 2 blocked (no reference)
  std::vector<std::uint8_t> far;  // per cell: cells (Chebyshev, capped) to the nearest with an edge
  // mm: tol::kZLevelInsideMargin.
  double margin = 0;
  std::uint32_t blocked_cells = 0;
  // The level's tip z, and per polygon edge 1 when it lies on the contour exactly (a line
  // segment's, between end points shared to 1e-12 mm): the regions of elements wholly above
  // that level (inside the region) cannot hold a point within 1e-10 mm of such an edge, so the
  // kernel does not try them there.
  double tip_z = 0;
  std::vector<std::uint8_t> exact;
  bool empty() const { return nx == 0; }
};

// The inside region given by the contours of a higher level (empty when it has open chains:
// its loops are then not known to bound U). cell: the index's cell, mm (0: 1 mm).
ZLevelInside zlevel_inside(const ZLevelResult& higher, double cell = 0);

// Appends to `out` the ids (in their order) of facets and edges whose region may not lie
// tol::kZLevelInsideDepth deep inside `inside` at some level (the others the kernel would drop
// anyway: leaving them out of its candidates changes nothing; at lower levels, with the
// region of a level below this one, they still lie half as deep, see ZLevelInside, unless
// that region has blocked cells). A quick test per element: most lie far inside or outside.
void zlevel_filter_deep(const OffsetElements& el, std::span<const std::uint32_t> ids,
                        const ZLevelInside& inside, std::vector<std::uint32_t>& out);

// The kernel's per-level buffers (regions, curves, cell lists, splits: tens of MB a level on
// a dense mesh). Reusing one from level to level spares fresh memory and its page faults; the
// result never depends on what an earlier call left in it. One per thread at a time.
class ZLevelWorkspace {
 public:
  ZLevelWorkspace();
  ~ZLevelWorkspace();
  ZLevelWorkspace(ZLevelWorkspace&&) noexcept;
  ZLevelWorkspace& operator=(ZLevelWorkspace&&) noexcept;
  struct Buffers;
  Buffers& buffers() { return *buffers_; }

 private:
  std::unique_ptr<Buffers> buffers_;
};

struct ZLevelParams {
  double cell = 0;  // pruning grid cell, mm; 0: R / 2 (raised if the grid would be huge)
  // Optional: zlevel_element_boxes(el) of the same elements (the result is the same).
  const ZLevelElementBoxes* boxes = nullptr;
  // Optional: zlevel_inside(r) of the result r of a higher level (the result is the same, up
  // to rounding where curves are split).
  const ZLevelInside* inside = nullptr;
  // Optional: buffers to reuse (the caller's, e.g. one per thread); null: the call's own.
  ZLevelWorkspace* workspace = nullptr;
  // mm; > 0: each arc's ContourSeg::clearance is computed up to this (the output polylines'
  // tolerance): the polyline keeps within it.
  double clearance_cap = 0;
};

// Contours at tool-tip level tip_z. `candidates`: element ids that may reach the level (any
// order, repeats allowed); it must contain every facet and edge whose region is not empty
// (vertices are derived from the edges), except, with params.inside, those whose region lies
// deep inside it (see ZLevelInside); passing all ids is correct.
ZLevelResult zlevel_contours(const OffsetElements& el, std::span<const std::uint32_t> candidates,
                             double tip_z, const ZLevelParams& params = {});

// Point of a segment at fraction f of its parameter (0: a, 1: b), mm.
Vec2 seg_point(const ContourSeg& s, double f);
// Appends the polyline of the segment from a (included) towards b (excluded) that never
// enters the segment's own region: lines exactly; arcs by the polygon circumscribed to them in
// their affine frame (vertices at t0 + (j - 1/2) dt scaled by 1 / cos(dt / 2), so that every
// chord is tangent to the arc), within `tol` (mm, r_max (1 / cos(dt / 2) - 1) <= tol) of it.
// Pass min(tol, seg.clearance) to keep out of the other regions too.
void circumscribed(const ContourSeg& s, double tol, std::vector<Vec2>& out);
// Appends points of the segment from a (included) towards b (excluded), chords within
// chord_tol (mm) of the exact curve.
void discretise(const ContourSeg& s, double chord_tol, std::vector<Vec2>& out);

}  // namespace ncpath
