#pragma once
// The solid a cutter sweeps along one straight CL move, and how far it is from (or how deep
// it is in) one triangle. Pure double-precision geometry, independent of the drop-cutter.
//
// Model (tool axis +Z, points are tool tips, mm). With R, r, a = R - r from the Cutter and
// L = SweptTool::shank, the tool is the convex body B(r) + C (Minkowski sum), C the vertical
// cylinder of radius a spanning heights [r, r + L] above the tip (a vertical segment when
// a = 0): ball part, torus or flat bottom, and a shank of radius R reaching L above the
// corner's centre. Swept along the move p0 -> p1 it is B(r) + K, K = C + [p0, p1], convex,
// whose support function is that of the cylinder plus that of the segment. Stock s (material
// to leave) grows it to B(r + s) + K. So for a triangle t:
//   gap = dist(t, K) - (r + s)   (negative when the tool grown by stock overlaps t),
// computed by GJK between t and K in double (stops on the support-plane bound, on a relative
// progress test or at an iteration cap; degenerate simplices fall back to their faces).
//
// "Cuts into" means gap < -tol::kVerifyContact: overlaps below a nanometre are touches, so
// exact contacts (a cutter sliding along a wall at exactly its radius, a drop-cutter point)
// cannot flip into gouges through rounding.
//
// The gouge is a vertical lift: the smallest h >= 0 such that the tool raised by h no
// longer cuts into the triangle ("cut in by h mm"). For one convex triangle the heights at
// which the raised tool cuts form an open interval (they are the points of a vertical line
// inside a convex set: triangle minus swept tool grown by the contact distance), and the
// distance along the line is convex in h, so the lift is that interval's upper end, found
// by Newton steps from above, secant lower bounds from below (convexity) and bisection when
// neither progresses. The lift is large against steep walls: a side contact is cleared only
// above the wall's top.
//
// Sharp tools (r + s < tol::kVerifySharpCorner: flat cutters) are the cylinder of radius
// R + s from s below the tip to L + s above it. Their gouge is exact and closed form: the
// largest height of a triangle point above the bottom over the swept disc, a linear function
// maximised over (triangle x [0, 1]) cut by a quadratic constraint, whose candidates are the
// prism's vertices, its edges' crossings of the constraint and two tangent points per face.
// GJK is not used for their decisions: near a touching rim it resolves distances to only
// ~1e-7 mm. A cutting sharp tool's gap is minus the depth of the deepest triangle point below
// its bottom (it has no ball part whose overlap a distance could measure).
#include "kernels/cutters/cutter.hpp"
#include "kernels/geom/tolerance.hpp"
#include "kernels/geom/vec.hpp"

namespace ncpath {

struct SweptTool {
  Cutter cutter;      // R, r (mm)
  double shank = 50;  // L, mm of shank above the corner's centre (>= 0)
  double stock = 0;   // s, mm of material to leave (>= 0)
};

// Gap between the triangle (t0, t1, t2) and the tool grown by stock, swept along p0 -> p1:
// dist(triangle, K) - (r + s), mm, accurate to about tol::kGjkDistance; -(r + s) when the
// triangle meets K. Sharp tools: see above. p0 == p1 is a point move. The triangle may be
// degenerate.
double swept_gap(const SweptTool& tool, const Vec3& p0, const Vec3& p1, const Vec3& t0,
                 const Vec3& t1, const Vec3& t2);

// The gouge of the move into the triangle (mm): 0 when it does not cut into it
// (gap >= -tol::kVerifyContact), else the smallest vertical lift after which it does not,
// reported at most `resolution` (mm) above that lift and never below it (up to GJK
// rounding): conservative.
double swept_gouge(const SweptTool& tool, const Vec3& p0, const Vec3& p1, const Vec3& t0,
                   const Vec3& t1, const Vec3& t2, double resolution = tol::kGougeResolution);

struct SweptGouge {
  double gouge = 0;   // mm; 0 when the gouge is at most the floor asked for
  int gjk_calls = 0;  // GJK distance evaluations used (statistics)
};

// The gouge when it exceeds `floor` (mm, >= 0), else 0: for a caller that keeps the largest
// gouge over many triangles. Costs one GJK call when the tool raised by `floor` does not cut
// into the triangle (the cutting heights form one interval, so then the gouge is at most
// floor, or 0).
SweptGouge swept_gouge_above(const SweptTool& tool, const Vec3& p0, const Vec3& p1, const Vec3& t0,
                             const Vec3& t1, const Vec3& t2, double floor,
                             double resolution = tol::kGougeResolution);

// Whether the gouge exceeds `floor`, without measuring it: gouge 1 when swept_gouge_above()
// would report one (the same decision, from its first one or two GJK calls), else 0.
SweptGouge swept_gouges_above(const SweptTool& tool, const Vec3& p0, const Vec3& p1,
                              const Vec3& t0, const Vec3& t1, const Vec3& t2, double floor);

// ---- Cheap bounds for callers that cull triangles before GJK (exact, conservative) ----

// The lower surface of the verified body (grown by stock) as a cutter whose tip is `stock`
// below the tool tip: radius R + s, corner r + s (sharp tools: corner 0). Over a point at
// horizontal distance rho from the axis the body is no lower than that tip plus
// profile_height(swept_profile(tool), rho).
Cutter swept_profile(const SweptTool& tool);

// A lower bound of swept_gap() from the slab {x : d_lo <= n . x <= d_hi} (n a unit vector)
// that holds the triangle (its plane, thickened by the rounding of its vertices): the
// distance of the swept body from the slab; <= 0 when the body meets it. A triangle whose
// bound is >= 0 is not cut into.
double swept_plane_gap(const SweptTool& tool, const Vec3& p0, const Vec3& p1, const Vec3& n,
                       double d_lo, double d_hi);

}  // namespace ncpath
