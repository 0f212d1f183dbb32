#pragma once
// Planar NURBS curves (any degree, rational, clamped knot vectors): evaluation, knot
// insertion, splitting, reversal, polylines and conversion to arcs for the exact line/arc
// offset machinery (pockets offset the arcs, never the NURBS itself). Pure math: no I/O, no threads. Lengths in mm.
#include <string>
#include <vector>

#include "kernels/curves/segment.hpp"
#include "kernels/pocket/profile.hpp"  // Nurbs2

namespace ncpath {

// "" when usable, else what is wrong: degree < 1, knots.size() != ctrl.size() + degree + 1,
// knots decreasing or not clamped, weights not > 0 or count mismatch, non-finite values.
std::string validate(const Nurbs2& curve);

// Clamped uniform knot vector on [0, 1] for n control points of degree p (n > p).
std::vector<double> clamped_uniform_knots(std::size_t n, int p);

double nurbs_t0(const Nurbs2& curve);  // first knot
double nurbs_t1(const Nurbs2& curve);  // last knot

Vec2 nurbs_point(const Nurbs2& curve, double t);
// Point and first two derivatives with respect to t.
void nurbs_derivatives(const Nurbs2& curve, double t, Vec2& d0, Vec2& d1, Vec2& d2);
// Signed curvature at t (positive when the curve turns left / counter-clockwise).
double nurbs_curvature(const Nurbs2& curve, double t);

// The same curve, traversed backwards.
Nurbs2 nurbs_reversed(const Nurbs2& curve);
// Boehm knot insertion of t, `times` times (the curve is unchanged).
Nurbs2 nurbs_insert_knot(const Nurbs2& curve, double t, int times = 1);
// Splits at t0 < t < t1 into two clamped curves.
void nurbs_split(const Nurbs2& curve, double t, Nurbs2& left, Nurbs2& right);

// Polyline through curve points whose chords deviate from the curve by <= chordal_tol.
std::vector<Vec2> nurbs_polyline(const Nurbs2& curve, double chordal_tol);

// Lines and arcs (biarcs) within tol of the curve, joined end to end, G1 where the curve is;
// `source` is copied into every segment.
std::vector<Seg2> nurbs_to_arcs(const Nurbs2& curve, double tol, std::uint32_t source);

// Exact rational quadratic NURBS of an ellipse arc (DXF ELLIPSE): centre, major-axis vector
// (from the centre to the end of the major axis), minor/major ratio, parameters start and
// end in radians (end > start; end - start = 2 pi for a full ellipse), counter-clockwise.
Nurbs2 nurbs_ellipse(const Vec2& centre, const Vec2& major_axis, double ratio, double start,
                     double end);

}  // namespace ncpath
