#pragma once
// Internals of the z-level contour kernel (kernels/scan/zlevel.hpp), shared by its .cpp files
// only: the region of one offset element at one level, its candidate boundary curves, the
// membership test and curve-curve intersection, the pruning grid, the cover and piece
// classification, and loop building. The files:
//   zlevel.cpp            top-level flow (zlevel_contours): regions, active curves,
//                         crossings, splits
//   zlevel_grid.cpp       the pruning grid: candidates that reach the level, interior cells
//   zlevel_regions.cpp    regions of offset elements and their candidate curves
//   zlevel_intersect.cpp  curve evaluation and curve-curve crossings
//   zlevel_cover.cpp      uncovered runs, tangent joints, piece classification
//   zlevel_loops.cpp      linking kept pieces into loops, junctions, canonical output
//   zlevel_inside.cpp     the known inside region of a higher level (ZLevelInside): polygon
//                         index, containment and depth tests, the deep-element filter
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "kernels/geom/tolerance.hpp"
#include "kernels/geom/vec.hpp"
#include "kernels/mesh/offset_elements.hpp"
#include "kernels/scan/zlevel.hpp"

namespace ncpath::zlevel_detail {

inline constexpr std::uint32_t kNone = 0xffffffffu;

inline double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }
inline Vec2 perp(const Vec2& a) { return Vec2(-a.y(), a.x()); }

struct Level {
  double zc = 0;  // ball-centre height, mm
  double R = 0;   // ball radius, mm
};

enum class RegionKind : std::uint8_t { kFacet = 0, kEdge = 1, kVertex = 2 };

// Half-plane n . x <= c, n a unit vector pointing out.
struct HalfPlane {
  Vec2 n = Vec2::Zero();
  double c = 0;
};

// The region of one element at the level (see zlevel.hpp), with its exact bounding box.
struct Region {
  RegionKind kind = RegionKind::kFacet;
  std::uint8_t nhp = 0;
  std::uint32_t element = 0;
  std::uint32_t index = 0;  // facet, edge or vertex index within its kind
  std::uint32_t curve_begin = 0, curve_end = 0;
  double box[4] = {0, 0, 0, 0};             // x0, y0, x1, y1, mm
  std::array<HalfPlane, 4> hp;              // facet: triangle sides and the clip line
  Vec3 a = Vec3::Zero(), d = Vec3::Zero();  // edge: lower end A and B - A (d.z >= 0)
  double dd = 0, dxy2 = 0;                  // edge: |d|^2, |d_xy|^2
  Vec2 c = Vec2::Zero();                    // vertex: centre
  double r = 0, vz = 0;                     // vertex: disc radius, height
  bool known_inside = false;  // wholly above the known inside region's level (inside it)
};

// Builds the region of element `id`; false when it is empty, has no area, or is not needed
// (vertical facet, vertical edge, edge or vertex unreachable by OffsetElements' flags).
bool build_region(const OffsetElements& el, std::uint32_t id, const Level& lv, Region& out);

// Signed membership value at x: < 0 inside, > 0 outside, 0 on the boundary. Exact distance
// for facets and vertex discs; for capsules (g - R^2) / (2 R) with g the squared distance
// to the nearest generating disc, which is at most the distance in magnitude near the
// boundary. `outward` (if given) receives an outward direction (not normalised) and
// `contact` the contact parameter (edges: t on AB).
double region_phi(const Region& g, const Vec2& x, const Level& lv, Vec2* outward = nullptr,
                  double* contact = nullptr);

// The x-interval of {y = const} strictly inside the region by `margin` (an inner subset is
// fine); false if empty. Used to mark interior grid cells.
bool region_row(const Region& g, double y, double margin, const Level& lv, double& x0, double& x1);

enum class CurveKind : std::uint8_t { kLine = 0, kCircle = 1, kEllipse = 2 };

// A candidate boundary curve, running with its region on the left, parameter s in [0, len]:
//   line:  p(s) = a + s dir                              (len = length)
//   conic: p(s) = a + (cos s - 1) e1 + sin s e2           (len = sweep, at most pi / 2)
// The conic form is the arc's own frame (e1 = a - centre, e2 = tangent at a), so it stays
// accurate for very flat ellipses whose centre is far away.
struct Curve {
  CurveKind kind = CurveKind::kLine;
  bool shadow = false;
  std::uint32_t region = 0, element = 0;
  Vec2 a = Vec2::Zero(), b = Vec2::Zero();
  double len = 0;
  Vec2 dir = Vec2::Zero();
  Vec2 e1 = Vec2::Zero(), e2 = Vec2::Zero();
  // Output geometry of conics (zlevel.hpp ContourSeg) with t0 the angle at a.
  Vec2 centre = Vec2::Zero();
  double r1 = 0, r2 = 0, t0 = 0;
  Vec2 axis = Vec2(1, 0);
  // Implicit equation: circle |x - centre|^2 - r1^2; ellipse |(X - ax_p) x ax_d|^2 - R^2
  // with X = (x, y, zc) (the cylinder around the edge's line).
  Vec3 ax_p = Vec3::Zero(), ax_d = Vec3::Zero();
  double box[4] = {0, 0, 0, 0};
};

// A point that must split a curve of element `target` (tangent joints, see zlevel.hpp);
// when no curve of target passes through it, the curves of alt[0], alt[1] are tried.
struct Joint {
  Vec2 p = Vec2::Zero();
  std::uint32_t target = kNone;
  std::uint32_t alt[2] = {kNone, kNone};
};

// Appends the candidate boundary curves of region `g` (index gi) and the joints they make.
void region_curves(const OffsetElements& el, const Region& g, std::uint32_t gi, const Level& lv,
                   std::vector<Curve>& curves, std::vector<Joint>& joints);

// ---- curve geometry (zlevel_intersect.cpp) ----
Vec2 curve_point(const Curve& c, double s);
Vec2 curve_tangent(const Curve& c, double s);  // dp/ds
double curve_speed(const Curve& c);            // bound of |dp/ds| and |d2p/ds2|
// Signed curvature at s, 1/mm: 0 on lines, > 0 on arcs (they turn towards their region).
double curve_curvature(const Curve& c, double s);
// Parameter of a point on or next to the curve (unclamped).
double curve_param(const Curve& c, const Vec2& x);
// Implicit function of the curve's full line / circle / ellipse at x, and its gradient.
double curve_implicit(const Curve& c, const Vec2& x, double zc, Vec2* grad = nullptr);
void finish_box(Curve& c);
// The part [s0, s1] of curve c as a curve of its own (same geometry, ends shared).
Curve sub_curve(const Curve& c, double s0, double s1);

struct Hit {
  Vec2 p;
  double sc, sd;       // parameters on C and on D
  bool touch = false;  // an end of one line on the other (a T-junction), not a crossing
};
// Crossings of C and D within both parameter ranges (inclusive, slightly widened).
// `coincident` is set when the curves lie on the same line / circle / ellipse; then their
// end points inside each other's range are returned as hits instead.
void intersect_curves(const Curve& C, const Curve& D, const Level& lv, std::vector<Hit>& out,
                      bool& coincident);

// When C and D lie on the same line or circle (as intersect_curves decides) and overlap:
// the overlap as the parameter interval [d0, d1] on D. Ellipses are not compared (false).
bool coincident_overlap(const Curve& C, const Curve& D, double& d0, double& d1);

// ---- pruning grid (built in zlevel.cpp) ----

// Uniform grid over the candidates' boxes. A cell is interior when it lies (by
// tol::kZLevelCellMargin) inside one region: it is in the interior of U, no piece of the
// boundary passes through it. `sum` counts the other (open) cells for box queries.
struct Grid {
  double x0 = 0, y0 = 0, cell = 1;
  int nx = 1, ny = 1;
  std::vector<std::uint8_t> interior;
  std::vector<std::uint32_t> sum;  // (nx + 1) x (ny + 1): open cells in [0, i) x [0, j)

  int ix(double x) const { return std::clamp(int(std::floor((x - x0) / cell)), 0, nx - 1); }
  int iy(double y) const { return std::clamp(int(std::floor((y - y0) / cell)), 0, ny - 1); }
  double gx(int i) const { return x0 + i * cell; }
  double gy(int j) const { return y0 + j * cell; }
  int at(const Vec2& p) const { return iy(p.y()) * nx + ix(p.x()); }
  Vec2 centre(int c) const { return Vec2(gx(c % nx) + 0.5 * cell, gy(c / nx) + 0.5 * cell); }
  void range(const double* b, int& i0, int& j0, int& i1, int& j1) const {
    i0 = ix(b[0]);
    j0 = iy(b[1]);
    i1 = ix(b[2]);
    j1 = iy(b[3]);
  }
  bool any_open(const double* b) const {
    if (!(b[0] <= b[2]) || !(b[1] <= b[3])) return false;
    int i0, j0, i1, j1;
    range(b, i0, j0, i1, j1);
    const int w = nx + 1;
    return sum[(j1 + 1) * w + i1 + 1] - sum[j0 * w + i1 + 1] - sum[(j1 + 1) * w + i0] +
               sum[j0 * w + i0] >
           0;
  }
};

// Compressed lists of items per cell of an nx x ny grid (count, scan, fill): item k goes to
// the cells (i, j) of the range range(k, i0, j0, i1, j1) sets (false: none) for which keep(cell)
// holds. start has nx ny + 1 entries; ids[start[c], start[c + 1]) are cell c's items.
template <class Range, class Keep>
void cell_lists(int nx, int ny, std::size_t n, Range&& range, Keep&& keep,
                std::vector<std::uint32_t>& start, std::vector<std::uint32_t>& ids) {
  const std::size_t cells = std::size_t(nx) * ny;
  start.assign(cells + 1, 0);
  for (int pass = 0; pass < 2; ++pass) {
    for (std::size_t k = 0; k < n; ++k) {
      int i0, j0, i1, j1;
      if (!range(k, i0, j0, i1, j1)) continue;
      for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) {
          const std::size_t c = std::size_t(j) * nx + i;
          if (!keep(c)) continue;
          if (pass == 0)
            ++start[c + 1];
          else
            ids[start[c]++] = std::uint32_t(k);
        }
    }
    if (pass == 0) {
      for (std::size_t c = 1; c <= cells; ++c) start[c] += start[c - 1];
      ids.resize(start.back());
    } else {
      for (std::size_t c = cells; c > 0; --c) start[c] = start[c - 1];
      start[0] = 0;
    }
  }
}

// Compressed lists of ids per open cell (count, scan, fill).
struct CellLists {
  std::vector<std::uint32_t> start, ids;
  // Region lists only (sort_by_depth in zlevel.cpp): each region's membership value at the
  // cell's centre, ascending within a cell.
  std::vector<double> depth;
};

// A region whose membership value at a point c is at least this holds no point within
// distance d of c where its value is below `above` (>= -R): the value is the signed distance
// for facets and discs (1-Lipschitz), and (s^2 - R^2) / (2 R) for capsules with s a
// distance, so it grows from c by at most d + d^2 / (2 R) (plus rounding).
inline double depth_cutoff(double d, double R, double above) {
  return above + d * (1 + tol::kZLevelSlack) + d * d / (2 * R) + tol::kZLevelSlack;
}

// Box (x0, y0, x1, y1) of the points p[0, n).
inline void points_box(const Vec2* p, int n, double* b) {
  b[0] = b[1] = INFINITY;
  b[2] = b[3] = -INFINITY;
  for (int k = 0; k < n; ++k) {
    b[0] = std::min(b[0], p[k].x());
    b[1] = std::min(b[1], p[k].y());
    b[2] = std::max(b[2], p[k].x());
    b[3] = std::max(b[3], p[k].y());
  }
}

using Box4f = std::array<float, 4>;

// Box rounded outwards to floats (compact copies for scans over many regions).
inline Box4f outward_box(const double* b) {
  return {std::nextafter(float(b[0]), -INFINITY), std::nextafter(float(b[1]), -INFINITY),
          std::nextafter(float(b[2]), INFINITY), std::nextafter(float(b[3]), INFINITY)};
}

// ---- cover and classification (zlevel_cover.cpp) ----

// A point splitting act[curve] at parameter s (a curve's end, a tangent joint, a crossing).
// At a crossing of two lines, `other` is the other line (its index in act) and `enter` +1
// when the curve runs into its region's side past p, -1 when out of it (exact signs: the
// lines are not parallel); kNone and 0 elsewhere.
struct Split {
  std::uint32_t curve;
  double s;
  Vec2 p;
  std::uint32_t other = kNone;
  std::int8_t enter = 0;
};

// A piece of act[curve] between consecutive splits, parameters s0 < s1, ends a and b.
struct Piece {
  std::uint32_t curve;
  double s0, s1;
  Vec2 a, b;
};

// Tangent joints are split explicitly; crossings between a facet's clip line and its own
// edges' and vertices' curves, or a capsule side and its own end circles, are only those.
// True for such a pair of regions: their curves are not intersected.
bool structural_pair(const OffsetElements& el, const Region& p, const Region& q);

// Appends to `runs` the parameter intervals of curve c that are not certified inside U: c is
// cut into sub-pieces of about a cell; one is certified when it lies in interior cells or its
// hull (ends and, for arcs, the tangents' crossing) lies strictly inside one region other
// than c's own, or (with a known inside region) tol::kZLevelInsideMargin deep inside that;
// sub-pieces that may hold points tol::kZLevelInsideDepth deep inside it are halved until
// they are certified or shown not to. Crossings in certified parts cannot be on the boundary
// of U. `cells` lists the regions per open cell, `rbox` their boxes as outward_box.
void uncovered_runs(const Curve& c, const Grid& grid, const CellLists& cells,
                    const std::vector<Region>& regions, const std::vector<Box4f>& rbox,
                    const Level& lv, const ZLevelInside* inside,
                    std::vector<std::pair<double, double>>& runs);

// Appends the tangent joints as splits: each on the nearest active curve (within 1e-6 mm,
// parameter in range) of the joint's target element, else of alt[0], alt[1]; a vertex
// without one there lends the joint to the circles coincident with its own (which the
// coincident trimming kept in its place). act_begin[g] is region g's first active curve (act
// is in region order).
void joint_splits(const std::vector<Joint>& joints, const std::vector<Region>& regions,
                  const std::vector<Curve>& act, const std::vector<std::uint32_t>& act_begin,
                  std::vector<Split>& splits);

// The pieces between consecutive splits (sorted by curve, s), in that order. Counts
// st.pieces.
std::vector<Piece> split_pieces(const std::vector<Split>& splits, ZLevelStats& st);

// Classification of a piece: strictly inside another region or an interior cell (0), on the
// boundary of U (1), or left out by one of the decisions on another region's boundary below (2).
inline constexpr std::uint8_t kInterior = 0, kKept = 1, kTied = 2;

// Per piece of split_pieces (in its order): kKept when it lies on the boundary of U, by its
// midpoint: it lies strictly inside no other region (`curves` are the untrimmed candidate
// curves, G.curve_begin..curve_end, `region_cells` the regions per open cell). On another
// region's boundary (within tol::kZLevelOnBoundary) its quarter points, the orientation of a
// line crossing it at its ends, the curvatures of a tangent departure, and last the lower
// element id decide (zlevel.hpp, step 7).
void classify_pieces(const std::vector<Split>& splits, const std::vector<Curve>& act,
                     const std::vector<Curve>& curves, const std::vector<Region>& regions,
                     const std::vector<Box4f>& rbox, const Grid& grid,
                     const CellLists& region_cells, const Level& lv,
                     std::vector<std::uint8_t>& keep);

// ContourSeg::clearance of arc `s` (a contour segment) up to `cap` mm: the regions other than
// those of the elements `skip` (its own and its neighbours' in the contour) are looked up at
// the polygon's vertices in the open cells' region lists.
double arc_clearance(const ContourSeg& s, const std::array<std::uint32_t, 3>& skip, double cap,
                     const Grid& grid, const CellLists& region_cells,
                     const std::vector<Region>& regions, const std::vector<Box4f>& rbox,
                     const Level& lv);


// ---- the known inside region (zlevel_inside.cpp, ZLevelInside in zlevel.hpp) ----

// Whether the shape conv(poly[0, n)) grown by r (n <= 4: a disc, a capsule, a triangle or a
// quadrilateral) lies `margin` deep inside q's polygon: its first point is inside and no
// polygon edge (nor blocked cell) comes within r + margin of the hull.
bool inside_contains(const ZLevelInside& q, const Vec2* poly, int n, double r, double margin);

// Whether region g lies `depth` deep inside q's polygon, tested through a hull that holds it:
// the projected offset triangle, the capsule of radius R around the edge's shadow, the disc.
bool region_in_known(const OffsetElements& el, const ZLevelInside& q, const Region& g,
                     double depth);

// Whether x lies within tol of a polygon edge that is on the contour exactly (q.exact).
bool on_exact_edge(const ZLevelInside& q, const Vec2& x, double tol);

// An upper bound of the depth inside q's polygon (the distance to its boundary; none outside)
// of the points of conv(hull[0, n)): the smallest over the polygon edges near it of the
// largest distance of a hull corner to the edge, capped at `limit`.
double inside_depth_bound(const ZLevelInside& q, const Vec2* hull, int n, double limit);

// ---- loops (zlevel_loops.cpp) ----

// The contours from the pieces (zlevel.hpp, step 8): the pieces form a planar map (ends
// within tol::kZLevelLink are one vertex, the pieces around a vertex in the order of their
// tangents, then curvatures); each face is inside U when it lies on the region side of one of
// its pieces, else as `inside_u` says at points tol::kZLevelFaceProbe beside its pieces
// (their lengths vote); the contours are the boundaries of the faces outside U, split into
// simple loops where they pass a vertex twice, merged into runs of one element's curve, with
// their junctions, in canonical order.
void build_loops(const OffsetElements& el, const Level& lv, const std::vector<Region>& regions,
                 const std::vector<Curve>& curves, std::vector<Piece> pieces,
                 std::vector<std::uint8_t> keep, ZLevelResult& out);

// Signed area enclosed by a loop of segments, mm^2 (exact for the typed segments).
double contour_area(const std::vector<ContourSeg>& segs);
// In output order: by the first segment's start (x, then y), then its element.
void sort_contours(std::vector<ZContour>& contours);


// ---- the pruning grid (zlevel_grid.cpp) ----

}  // namespace ncpath::zlevel_detail

namespace ncpath {

// The per-level buffers (ZLevelWorkspace): about 55 MB after a level of a 1.2 M-facet mesh.
struct ZLevelWorkspace::Buffers {
  std::vector<std::uint64_t> bits, pbits, vbits;
  std::vector<std::uint32_t> cand, stamp;
  std::vector<zlevel_detail::Box4f> cand_box, rbox;
  std::vector<zlevel_detail::Region> regions;
  std::vector<zlevel_detail::Curve> curves, act, rest, tmp;
  std::vector<zlevel_detail::Joint> joints;
  zlevel_detail::CellLists region_cells, curve_cells;
  std::vector<zlevel_detail::Split> splits;
};

}  // namespace ncpath

namespace ncpath::zlevel_detail {

using Workspace = ZLevelWorkspace::Buffers;

// The candidates that reach the level, in id order (ws.cand) with their boxes, floats rounded
// outwards (ws.cand_box), and the mesh points at the ends of candidate edges and vertices
// (ws.pbits: their discs mark interior cells); ext becomes their boxes' union. The given ids
// become a bitmap first: sorted, without repeats, independent of their order.
void gather_candidates(const OffsetElements& el, std::span<const std::uint32_t> candidates,
                       const Level& lv, const ZLevelParams& params, Workspace& ws,
                       ZLevelStats& st, double ext[4]);

// The grid over ext (cells of params.cell, else R / 2; at most 4e6 of them), its interior
// cells marked and the prefix sums of its open cells.
Grid level_grid(const OffsetElements& el, const Workspace& ws, const Level& lv,
                const ZLevelInside* inside, const ZLevelParams& params, const double ext[4],
                ZLevelStats& st);

}  // namespace ncpath::zlevel_detail
