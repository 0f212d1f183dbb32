#pragma once
// The verifier's own queries on a sculptured pocket bottom (a NURBS height field): the
// distance from a segment of ball centres to the surface (does the ball cut into the bottom?)
// and the bottom's height over a plan point (how much material a path leaves: the scallop).
//
// Method: the surface is cut into rational Bézier pieces no larger than `piece` mm (boxes of
// their control points bound them: convex hull property); pieces whose box is out of reach
// are skipped, and on each piece in reach a damped Newton iteration on the exact surface
// (nurbs_surface.hpp's evaluation) finds the local minimum. The pieces are small against the
// bottom's radius of curvature (the planner's own check keeps it a height field), so each
// piece's distance function has one minimum; the answer is exact to ~1e-10 mm where it
// converges. It does not use the planner's drops (kernels/surface/surface_drop.*).
#include <cstdint>
#include <vector>

#include "kernels/geom/vec.hpp"
#include "kernels/surface/nurbs_surface.hpp"
#include "kernels/verify/plan_grid.hpp"

namespace ncpath {

class SurfaceProbe {
 public:
  // piece: largest extent of a piece's box in x, y and z (mm), e.g. a quarter of the radius.
  SurfaceProbe(const NurbsSurface& surface, double piece);

  // min(distance from the segment [a, b] to the surface, cap), mm.
  double segment_distance(const Vec3& a, const Vec3& b, double cap) const;

  // The surface's z over plan point (x, y); false when no piece lies over it.
  bool height_at(const Vec2& xy, double& z) const;

  std::size_t pieces() const { return pieces_.size(); }

 private:
  double piece_distance(const BezierPatch& p, const Vec3& a, const Vec3& b) const;
  const NurbsSurface& surface_;
  std::vector<BezierPatch> pieces_;
  PlanGrid grid_;  // over the pieces' plan boxes
};

}  // namespace ncpath
