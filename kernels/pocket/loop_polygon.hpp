#pragma once
// Internal to kernels/pocket/chain.cpp: closed polygons that stand in for profile loops when
// testing containment and intersections. Pure geometry.
#include <cstdint>
#include <vector>

#include "kernels/geom/vec.hpp"

namespace ncpath::detail {

// A closed polygon: edge k runs from pts[k] to pts[(k + 1) % size]; curve[k] is the index of
// the input curve that edge approximates (for messages). The first point is not repeated.
struct LoopPolygon {
  std::vector<Vec2> pts;   // mm
  std::vector<int> curve;  // same size as pts
  Vec2 lo = Vec2::Zero();  // bounding box, mm
  Vec2 hi = Vec2::Zero();
};

// Fills lo / hi from pts.
void update_bounds(LoopPolygon& poly);

// Crossing-number test; p must not lie on the polygon (callers use a vertex of a loop that is
// known not to touch this one).
bool point_in_polygon(const LoopPolygon& poly, const Vec2& p);

// First intersection found between edges of the polygons: two edges of different loops that
// touch or cross, two non-adjacent edges of one loop that touch or cross, or two adjacent
// edges that fold back onto each other. Sweep over edges sorted by their lowest x; only edges
// whose x ranges overlap are compared.
struct PolygonCrossing {
  bool found = false;
  int loop_a = -1, loop_b = -1;    // indexes into the polygons (equal: self-intersection)
  int curve_a = -1, curve_b = -1;  // LoopPolygon::curve of the two edges
  Vec2 at = Vec2::Zero();          // a point of the intersection, mm
};
PolygonCrossing find_crossing(const std::vector<LoopPolygon>& loops);

}  // namespace ncpath::detail
