#pragma once
// Every tolerance of ncpath, in one place: name, unit and purpose (STYLE.md habit 5).
// Kernels take these as defaulted parameters; nothing else hard-codes an epsilon.

namespace ncpath::tol {

// mm. Two drop-cutter heights closer than this are "the same" height. The exactness
// contract (accelerated result == brute force) is stated with this tolerance.
inline constexpr double kExactZ = 1e-9;

// mm. Convergence target of numeric contact solvers (bull-nose edge contact): the returned
// tip height is within this of the true maximum.
inline constexpr double kContactSolve = 1e-10;

// mm^2. A facet whose doubled xyz area (|e1 x e2|) is below this is degenerate: it has no
// normal, is skipped by the readers and counted in the statistics.
inline constexpr double kDegenerateArea2 = 1e-18;

// Dimensionless. A facet whose unit normal has |n_z| below this is treated as vertical: it
// has no facet contact with a tool dropped along -Z; its edges and vertices still do.
inline constexpr double kVerticalNormalZ = 1e-12;

// Dimensionless. Relative padding added to float boxes handed to Embree so that float
// rounding can never drop a candidate that double precision would keep.
inline constexpr double kFloatBoxPad = 1e-5;

// mm. Default chordal tolerance of adaptive sampling along a scan line: the straight move
// between two CL points deviates from the sampled CL curve by at most this.
inline constexpr double kDefaultChordal = 0.01;

// Dimensionless, relative to the polygon's size (longest side of its bounding box). A polygon
// edge shorter than this fraction of the size has zero length: the polygon is rejected as
// not strictly convex (the OFF reader's polygon check).
inline constexpr double kPolygonZeroEdge = 1e-12;

// Dimensionless. A polygon vertex whose turn has |sin(angle)| below this, and that keeps
// going forward, is straight (collinear with its neighbours): it is not a corner, so it is
// neither a turn of the wrong sign nor the apex of a zero-area fan triangle. Likewise a
// polygon whose doubled Newell area is below this times size^2 has no plane (degenerate).
inline constexpr double kPolygonStraightTurn = 1e-12;

}  // namespace ncpath::tol
