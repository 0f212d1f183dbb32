#pragma once
// NURBS surfaces (rational, any degree, clamped knot vectors): the sculptured bottoms of
// pockets (issue 7). Evaluation with derivatives, normals and normal curvature, conversion
// to rational Bezier patches (for bounds and subdivision), and the checks a bottom must pass
// (valid data, a height field: single-valued in z over the plan). Pure math, mm.
#include <string>
#include <vector>

#include "kernels/geom/vec.hpp"

namespace ncpath {

struct NurbsSurface {
  int degree_u = 3, degree_v = 3;  // >= 1
  int nu = 0, nv = 0;              // control points along u and along v
  std::vector<Vec3> ctrl;          // nu * nv, row-major by u: ctrl[i * nv + j] (i along u)
  std::vector<double> weights;     // nu * nv, > 0 (all 1: non-rational)
  std::vector<double> knots_u;     // nu + degree_u + 1, non-decreasing, clamped
  std::vector<double> knots_v;     // nv + degree_v + 1, non-decreasing, clamped
};

// "" when usable, else what is wrong, naming it: degrees, control-net size vs nu * nv,
// knot counts vs nu + p + 1, knots decreasing or not clamped, weights not > 0 or count
// mismatch, non-finite values.
std::string validate(const NurbsSurface& s);

// A grid of bicubic Bezier patches as one NURBS surface: patches_u x patches_v patches
// sharing edges, ctrl (3 * patches_u + 1) x (3 * patches_v + 1) points, row-major by u;
// knots 0,0,0,0,1,1,1,2,2,2,...,n,n,n,n (interior multiplicity 3). Throws
// std::invalid_argument when the count does not match.
NurbsSurface bezier_grid_surface(int patches_u, int patches_v, const std::vector<Vec3>& ctrl);

// Parameter domain: [u0, u1] x [v0, v1] (first and last knots).
struct SurfaceDomain {
  double u0 = 0, u1 = 1, v0 = 0, v1 = 1;
};
SurfaceDomain domain(const NurbsSurface& s);

// Point and partial derivatives (up to second order) at (u, v).
struct SurfacePoint {
  Vec3 p = Vec3::Zero();
  Vec3 su = Vec3::Zero(), sv = Vec3::Zero();
  Vec3 suu = Vec3::Zero(), suv = Vec3::Zero(), svv = Vec3::Zero();
};
SurfacePoint evaluate(const NurbsSurface& s, double u, double v);
Vec3 surface_point(const NurbsSurface& s, double u, double v);

// Unit normal su x sv turned to point upward (z >= 0: the side a 3-axis tool comes from).
// Where su or sv vanishes (a pole: a whole domain edge meets in one point) it is the limit
// normal, from the mixed derivative suv; (0, 0, 1) when there is no tangent plane at all.
Vec3 upward_normal(const SurfacePoint& sp);

// Normal curvature (1/mm) in the tangent direction T = su du + sv dv, (du, dv) != 0:
//   kappa = -n . (suu du^2 + 2 suv du dv + svv dv^2) / |T|^2,  n = upward_normal(sp),
// i.e. II / I taken against the upward normal and negated: positive where the surface bends
// away from (below) its upward normal, convex seen from above. Upper hemisphere of radius r
// (a dome): +1/r in every direction; lower hemisphere (a bowl seen from above): -1/r; a
// cylinder of radius r lying along x: +-1/r across, 0 along; a plane: 0.
double normal_curvature(const SurfacePoint& sp, double du, double dv);

// The same surface as rational Bezier patches (knot insertion to full multiplicity): patch
// k covers [u0, u1] x [v0, v1] of the original parameters, with homogeneous control points
// (x w, y w, z w, w), (degree_u + 1) x (degree_v + 1), row-major by u, and the bounding box
// of its control points (which contains the patch: convex hull property).
struct BezierPatch {
  int degree_u = 3, degree_v = 3;
  double u0 = 0, u1 = 1, v0 = 0, v1 = 1;
  std::vector<Eigen::Vector4d> ctrl;
  Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();
};
std::vector<BezierPatch> bezier_patches(const NurbsSurface& s);
// Splits a patch at the middle of its longer parameter side (de Casteljau), boxes updated.
void split_patch(const BezierPatch& p, BezierPatch& a, BezierPatch& b);
// Splits at the middle of u (along_u) or of v. a gets the lower half; a or b may alias p.
void split_patch(const BezierPatch& p, bool along_u, BezierPatch& a, BezierPatch& b);
// Point of a patch at local parameters (s, t) in [0, 1]^2.
Vec3 patch_point(const BezierPatch& p, double s, double t);

// Height-field check: the plan map (u, v) -> (x, y) must be one-to-one with a Jacobian
// determinant of one sign over the whole domain (no fold, no vertical tangent plane).
// Returns "" or a message saying where it fails:
//   "... folds over itself in plan (the plan Jacobian changes sign) near (u, v) = (0.4, 0.7),
//    plan (x, y) = (12.3, 45.6)" (a point where the Jacobian crosses zero),
//   "... has a vertical tangent plane ... near (u, v) = ..., plan (x, y) = ..." (|n_z| at most
//    tol::kHeightFieldNz, a degenerate point such as a pole, or a Jacobian that stays
//    within ~1e-6 of zero where the certificate below cannot decide),
//   "... overlaps itself in plan: its border at (u, v) = ... and at (u, v) = ... both lie over
//    plan (x, y) = ..." (one-signed Jacobian but the border's image crosses itself),
//   "invalid surface: ..." (validate() fails).
// The sign is certified per Bezier patch from the Bernstein coefficients of
// det(P, P_u, P_v) = w^3 J (P homogeneous), subdividing where they are mixed; the border
// image is tested for self-intersection on a polygon within tol::kHeightFieldOutline times
// the plan size.
std::string check_height_field(const NurbsSurface& s);

// The outline of the surface's plan projection: the image of the domain's border, as a
// closed polygon (counter-clockwise, the first point not repeated at the end, consecutive
// duplicates removed) whose chords are within `tol` mm of the border curves (tol is raised to
// tol::kNurbsMinTol). Used to check that a pocket lies over the surface. Empty for an invalid
// surface. A degenerate border edge (a pole) adds a single point, a meridian run to a pole
// and back a zero-area spike.
std::vector<Vec2> plan_outline(const NurbsSurface& s, double tol);

}  // namespace ncpath
