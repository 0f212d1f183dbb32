#pragma once
// Exact offsetting of closed line/arc loops with offset-loop dissection (ODM).
//
// Input: closed loops with the material on their right (pocket boundaries clockwise,
// islands counter-clockwise). Each loop is offset by d to its right:
//  1. raw offset: every line shifted by d, every arc's radius changed by d (an arc whose
//     radius would become negative turns inside out, past its centre; it is cut away by
//     validation, its neighbours meet it with arcs of radius d around its end points);
//  2. joining (crude loop): where consecutive offsets leave a gap (convex corner) they are
//     joined by an arc of radius d around the original vertex - the true offset; where they
//     overlap (concave corner) both are trimmed at their intersection (local
//     self-intersection); where they miss each other a line joins them;
//  3. dissection: all intersections among all raw loops (self and mutual: islands meeting
//     the boundary, islands meeting each other) are found with a sweep over x (no pair
//     loop), every segment is split there;
//  4. validation: a piece is kept when no input curve comes closer to it than d (exact
//     segment-segment distances, grid-indexed);
//  5. regrouping: kept pieces are stitched end to end into closed loops (simple loops);
//     at a point where several continue, the one turning most to the right is taken;
//     segments shorter than tol::kOffsetSliver are merged into their neighbours;
//  6. orientation: when the input has a clockwise boundary, counter-clockwise loops
//     (holes) must lie inside a clockwise result loop; others are dropped.
// The result's loops have the material on their right again, so the result can be offset
// once more: offsetting by d1 then d2 equals offsetting by d1 + d2 (erosion composes), which
// is how multi-level offsets are built without drift.
#include <cstdint>
#include <vector>

#include "kernels/curves/segment.hpp"

namespace ncpath {

struct OffsetLoop {
  std::vector<Seg2> segs;              // closed: segs[i].b == segs[i+1].a, last.b == first.a
  double area2 = 0;                    // twice the signed area (< 0: clockwise)
  std::vector<std::uint32_t> parents;  // input loops whose offsets it is made of (sorted)
};

struct OffsetStats {
  std::uint64_t raw_segments = 0;    // after joining
  std::uint64_t intersections = 0;   // between raw segments
  std::uint64_t pieces = 0;          // after splitting
  std::uint64_t pieces_kept = 0;     // after validation
  std::uint64_t open_fragments = 0;  // kept pieces that did not close into a loop (dropped)
  std::uint64_t dropped_holes = 0;   // counter-clockwise loops outside every boundary
};

struct OffsetResult {
  std::vector<OffsetLoop> loops;
  OffsetStats stats;
};

// Offsets the loops (material on the right) by d > 0 into the material. area2, when given,
// holds loop_area2 of each input loop (saves recomputing it).
OffsetResult offset_loops(const std::vector<std::vector<Seg2>>& loops, double d,
                          const std::vector<double>* area2 = nullptr);

// The raw offset of one segment by d to its right (an arc of radius < d on that side turns
// inside out: radius d - r past its centre); false only when an arc collapses to its centre.
bool raw_offset(const Seg2& s, double d, Seg2& out, bool* inverted = nullptr);

// Twice the signed area of a closed loop (> 0: counter-clockwise).
double loop_area2(const std::vector<Seg2>& loop);
double loop_length(const std::vector<Seg2>& loop);
// Winding number of the closed loop around p (p not on the loop): +1 inside a
// counter-clockwise loop, -1 inside a clockwise one, 0 outside.
int winding_number(const std::vector<Seg2>& loop, const Vec2& p);

}  // namespace ncpath
