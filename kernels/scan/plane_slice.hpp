#pragma once
// Exact slicing of offset elements (kernels/mesh/offset_elements.hpp) by a drive plane
// y = y0: every element that reaches the plane yields curve pieces in the plane, each the
// upper boundary of that element's section, parameterised by x.
//
// Heights: a piece gives the ball-centre height centre_z(x) (a point of the offset surface)
// and the tool-tip height tip_z(x) = centre_z(x) - R, the CL point. The upper envelope of
// all pieces of a plane is the drop-cutter CL curve on it.
//
// Pieces by element:
//   offset triangle  -> kFacetLine: a segment of the offset plane, z linear in x;
//   sphere           -> kSphereArc: upper arc of the circle of radius sqrt(R^2 - d^2),
//                       d = |vertex.y - y0|;
//   cylinder         -> its upper boundary between the planes through the edge's ends
//                       perpendicular to it (the end caps are inside the vertex spheres):
//                       kCylinderEllipse (edge oblique to the plane), kCylinderLine (edge
//                       parallel to the plane, u.y == 0: the upper of the two section lines,
//                       at sqrt(R^2 - d^2) from the axis), kCylinderCircle (edge along y).
//                       One cylinder gives up to two pieces: the edge's parameter along the
//                       upper arc is unimodal, so clipping it to [0, 1] can leave two x
//                       intervals.
// Vertical facets and vertical edges give no piece (see offset_elements.hpp and
// tol::kVerticalEdge): their highest points are those of their top edges / vertices.
//
// All pieces of a cylinder are evaluated by one closed form (the upper root of the
// quadratic in z of "distance to the axis = R"), which is the ellipse, the line or the
// circle according to the edge direction; the kind tag and ellipse_of() give the explicit
// geometry for later stages.
#include <cstdint>
#include <vector>

#include "kernels/geom/vec.hpp"
#include "kernels/mesh/offset_elements.hpp"

namespace ncpath {

enum class PieceKind : std::uint8_t {
  kFacetLine = 0,
  kSphereArc = 1,
  kCylinderEllipse = 2,
  kCylinderLine = 3,
  kCylinderCircle = 4,
  kFloor = 5,  // the floor plane (no element): the tool touches nothing higher
};
const char* piece_kind_name(PieceKind kind);

// One curve piece in the plane y = y0, valid for x in [x0, x1] (mm).
//   kFacetLine: point = a point of the offset plane, dir = its unit normal (n.z > 0).
//   kSphereArc: point = sphere centre (the mesh vertex), dir unused (zero).
//   kCylinder*: point = edge start A, dir = unit axis u (A -> B), length = |B - A|.
//   kFloor:     point = (0, 0, floor + R), dir = (0, 0, 1), element = kNoElement.
struct SlicePiece {
  PieceKind kind = PieceKind::kFacetLine;
  std::uint32_t element = 0;  // id in the OffsetElements element space
  double x0 = 0, x1 = 0;      // x range, mm, x0 <= x1
  double y0 = 0;              // the drive plane, mm
  double radius = 0;          // ball radius R, mm
  Vec3 point = Vec3::Zero();
  Vec3 dir = Vec3::Zero();
  double length = 0;  // cylinders: edge length, mm
};

inline constexpr std::uint32_t kNoElement = 0xffffffffu;

// The floor as a piece over [x0, x1] of the plane y = y0: tool tip at floor_z.
SlicePiece floor_piece(double floor_z, double radius, double y0, double x0, double x1);

// True for pieces whose height is linear in x (facet lines, cylinder lines, the floor).
bool is_linear(const SlicePiece& piece);

// Ball-centre height of the piece at x (mm); x is clamped to [x0, x1].
double centre_z(const SlicePiece& piece, double x);

// dz/dx of the piece at x (clamped to [x0, x1]); +-infinity where the arc is vertical.
double slope(const SlicePiece& piece, double x);

// Every piece is concave in x. Returns the x in [a, b] (within [x0, x1]) that maximises
// centre_z(x) - m x: exact, from the point of the circle, ellipse or line whose tangent has
// slope m (the end of [a, b] nearer to it when it lies outside).
double argmax_tilted(const SlicePiece& piece, double m, double a, double b);
// Tool-tip (CL) height: centre_z - R.
inline double tip_z(const SlicePiece& piece, double x) { return centre_z(piece, x) - piece.radius; }

// Contact point on the part at x and the unit normal from it to the ball centre (the
// bi-contact vector of this element at x).
struct PieceContact {
  Vec3 centre;  // ball centre (x, y0, centre_z), mm
  Vec3 cc;      // contact point on the mesh, mm
  Vec3 normal;  // (centre - cc) / R
};
PieceContact piece_contact(const SlicePiece& piece, double x);

// Explicit ellipse of a cylinder section (any cylinder piece whose edge is not parallel to
// the plane): centre (x, z) where the axis crosses the plane, semi-axes and the unit
// direction (x, z) of the major axis. The circle case has major == minor == R.
struct SectionEllipse {
  Vec2 centre;      // (x, z), mm
  double major;     // R / |u.y|, mm
  double minor;     // R, mm
  Vec2 major_axis;  // unit (x, z) direction of the major axis
};
bool ellipse_of(const SlicePiece& piece, SectionEllipse& out);

// Line pieces (kFacetLine, kCylinderLine): centre_z = slope * x + intercept.
bool line_of(const SlicePiece& piece, double& slope, double& intercept);

// Appends to `out` the pieces of the given elements (ids in [begin, end) of the element
// space) in the plane y = y0, in id order. Pieces of zero x length are dropped.
// trim: keep only the part of a cylinder or sphere where the ball touching it would not cut
// into a facet around the edge or vertex (OffsetElements::edge_wedge, ring): elsewhere the
// piece lies below the envelope. The envelope is the same either way; trimmed pieces are
// far shorter (on a smooth mesh a convex edge's piece spans about R times its bend angle).
void slice_elements(const OffsetElements& el, double y0, std::uint32_t begin, std::uint32_t end,
                    std::vector<SlicePiece>& out, bool trim = true);

}  // namespace ncpath
