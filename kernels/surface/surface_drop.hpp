#pragma once
// Drop of a ball-end mill onto a NURBS height-field surface (issue 7): the lowest tool-tip
// height at plan position (x, y) such that the ball (radius R, axis +z) does not penetrate
// the surface, with the contact (CC) point and the surface normal there.
//
// The ball centre stands at c_z = max f over surface points S within R of (x, y) in plan,
//   f = S_z + sqrt(R^2 - |S_xy - (x, y)|^2),
// and tip_z = c_z - R. The maximum is global (to ~1e-9 mm in practice; the exactness tests
// compare with a brute-force oracle to 1e-6 mm and see ~1e-13 mm) and may lie on the
// surface's border (the ball hanging over an edge) or on a crease between patches.
//
// Method: branch and bound over the surface's rational Bezier patches. A (sub-)patch's upper
// bound of f is the smaller of (control box top + sqrt(R^2 - plan distance to the box^2))
// and the largest value over its control points of a tangent plane of the concave function
// z + sqrt(R^2 - |xy - q|^2); (sub-)patches whose bound does not exceed the best contact so
// far (+ tol::kBoundTie) are dropped, the others split at their middle across the longer plan
// side. Sub-patches over which f has a single maximum (concave: z bends upwards much less
// than the ball; or small against R and z's bending) are searched by projected Newton on f
// within their parent Bezier patch (its border and creases are bounds of that search),
// switching to Newton on the offset condition (S + R n)_xy = (x, y) for steep contacts.
// Thread-safe: drop() is const and uses only locals; those live on the stack except for
// patches of more than 16 control points and more than 64 patches within reach of one drop
// (heap fallbacks).
#include <vector>

#include "kernels/surface/nurbs_surface.hpp"

namespace ncpath {

struct SurfaceContact {
  bool found = false;      // false: no surface point within R of (x, y) in plan
  double tip_z = 0;        // tool tip z (ball centre z - R), mm
  Vec3 cc = Vec3::Zero();  // contact point on the surface
  // (ball centre - cc) / R: the upward unit surface normal at cc for a contact inside the
  // surface; on a border or crease contact the ball's normal there. centre = cc + R normal.
  Vec3 normal = Vec3::Zero();
  double u = 0, v = 0;  // parameters of cc
};

class SurfaceDrop {
 public:
  // Converts the surface to Bezier patches and a bounding-box tree over them. An invalid
  // surface (validate(s) != "") touches nothing: every drop returns found = false.
  explicit SurfaceDrop(const NurbsSurface& s);
  // Tool axis at plan position xy (mm), ball radius > 0 (mm). found = false for a radius
  // <= 0 or a non-finite xy too.
  SurfaceContact drop(const Vec2& xy, double radius) const;
  const NurbsSurface& surface() const { return surface_; }

 private:
  // Bounding-volume tree over the patches' control boxes: a node covers patches
  // order_[first, first + count) and has children left, right (-1 at leaves).
  struct BvhNode {
    Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();
    int left = -1, right = -1;
    int first = 0, count = 0;
  };
  int build_bvh(int first, int count);

  NurbsSurface surface_;
  std::vector<BezierPatch> patches_;
  bool rational_ = false;  // some weight != 1
  std::vector<BvhNode> bvh_;
  std::vector<int> order_;
};

}  // namespace ncpath
