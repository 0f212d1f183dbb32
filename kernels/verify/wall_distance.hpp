#pragma once
// The verifier's own distances to the walls of a 2.5-D pocket: the input's lines, arcs and
// NURBS curves, exact (lines, arcs) or bounded from below to a resolution (NURBS, by
// subdividing rational Bézier pieces until their control polygons lie within `resolution`
// of their chords: the convex hull property bounds the curve). Nothing here uses the pocket
// planner's offsets, arcs or grids: only the input curves and low-level primitives
// (segment.hpp's arc angle test, nurbs.hpp's knot insertion), tested on their own.
//
// Units mm. A query answers min(distance, cap): walls farther than `cap` are not looked at.
#include <cstdint>
#include <vector>

#include "kernels/curves/segment.hpp"
#include "kernels/geom/segment2.hpp"
#include "kernels/geom/vec.hpp"
#include "kernels/pocket/profile.hpp"
#include "kernels/verify/plan_grid.hpp"

namespace ncpath {

// Exact distances in the plane (mm); point to segment: kernels/geom/segment2.hpp.
double segment_segment_gap(const Vec2& p0, const Vec2& p1, const Vec2& q0, const Vec2& q1);
// Segment [p0, p1] to a line or arc.
double segment_curve_gap(const Vec2& p0, const Vec2& p1, const Seg2& s);

// A rational Bézier piece in homogeneous form (w x, w y, w), degree = size - 1.
struct BezierPiece {
  std::vector<Eigen::Vector3d> ctrl;
  Vec2 lo = Vec2::Zero(), hi = Vec2::Zero();  // box of the control points, mm
};

// The walls of every region: lines and arcs as they are, NURBS as Bézier pieces; a grid over
// their boxes for the queries.
class WallSet {
 public:
  // cap: the largest distance a query needs (mm), e.g. tool radius + stock + 1.
  WallSet(const std::vector<Region>& regions, double cap);

  // min(distance from the segment [p0, p1] to the nearest wall, cap), a lower bound within
  // `resolution` of the truth for NURBS walls (exact to rounding for lines and arcs).
  double distance(const Vec2& p0, const Vec2& p1, double resolution) const;

  std::size_t curve_count() const { return segs_.size() + pieces_.size(); }
  double cap() const { return cap_; }

 private:
  double cap_;
  std::vector<Seg2> segs_;           // grid items [0, segs_.size())
  std::vector<BezierPiece> pieces_;  // grid items from segs_.size() on
  PlanGrid grid_;
};

// Rational Bézier pieces of a NURBS curve (knot insertion to full multiplicity).
std::vector<BezierPiece> bezier_pieces(const Nurbs2& curve);

// Lower bound within `resolution` of the distance from [p0, p1] to a Bézier piece, or `cap`
// when the piece is at least cap away.
double segment_bezier_gap(const Vec2& p0, const Vec2& p1, const BezierPiece& piece, double cap,
                          double resolution);

}  // namespace ncpath
