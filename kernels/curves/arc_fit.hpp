#pragma once
// Fitting G-code moves to a CL polyline: lines and circular arcs in the xy plane (G17), with z
// varying linearly along each move (helical arcs when z changes), within a chordal tolerance.
//
// Input: one path of n points, `xyz` = 3 doubles per point (tool tip, mm). Output: moves whose
// chain starts at point 0 (not stored) and whose ends are input points, in order; the last move
// ends exactly at point n - 1. Every input point and every input chord lies within `tol` of
// the moves (3-D distance: radial/perpendicular error combined with the z error), and the
// moves advance monotonically along the input (no back-tracking), so the fitted path and the
// polyline are the same path to the tolerance.
//
// Greedy: from the current start point the move is extended through as many consecutive
// points as a line or an arc can take (arc = circle through the start, middle and end points
// of the run); lines win over arcs when both fit. A corner sharper than the tolerance
// allows can never be inside a move, so moves end at it.
#include <cstdint>
#include <numbers>
#include <span>
#include <vector>

#include "kernels/curves/segment.hpp"  // SegKind
#include "kernels/geom/vec.hpp"

namespace ncpath {

struct ArcFitParams {
  double tol = 0.005;  // mm, chordal tolerance (> 0)
  // mm. An arc of larger radius is not used (the run is split into lines instead): G-code
  // arcs of huge radius are ill-conditioned (centre far away, radius rounding on controllers).
  double max_radius = 1000;
  // Radians. Largest |sweep| of one arc. Kept well below 2 pi so that no arc's end point can
  // round onto its start point, which controllers read as a full circle.
  double max_sweep = 1.5 * std::numbers::pi;
  bool allow_arcs = true;  // false: lines only
};

// One fitted move. Its start is the previous move's end (point 0 for the first move).
struct FitMove {
  SegKind kind = SegKind::kLine;  // kLine (G1), kArcCw (G2), kArcCcw (G3)
  Vec3 end = Vec3::Zero();        // mm, == the input point end_index exactly
  Vec2 centre = Vec2::Zero();     // mm, arcs only (xy)
  std::uint32_t end_index = 0;    // index of the input point the move ends at
};

// Appends the moves of the path `xyz` (3 doubles per point, n = xyz.size() / 3) to `out`.
// n < 2 appends nothing. Consecutive duplicate points are absorbed into moves. Cost
// O(n log n) distance tests (galloping search for each move's end). Precondition: tol > 0,
// coordinates finite.
void fit_arcs(std::span<const double> xyz, const ArcFitParams& params, std::vector<FitMove>& out);

}  // namespace ncpath
