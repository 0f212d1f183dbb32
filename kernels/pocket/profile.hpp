#pragma once
// Pocket input: closed profiles of lines, arcs and NURBS curves, grouped into regions (a
// boundary and its islands). Convention used everywhere downstream: boundaries run
// clockwise, islands counter-clockwise, so the material to cut is always on the right of
// the direction of travel.
#include <cstdint>
#include <string>
#include <vector>

#include "kernels/curves/segment.hpp"
#include "kernels/geom/vec.hpp"

namespace ncpath {

// A NURBS curve in the plane: degree p >= 1, clamped knot vector (p+1 equal knots at each
// end), n control points with positive weights, knots.size() == n + p + 1.
struct Nurbs2 {
  int degree = 3;
  std::vector<Vec2> ctrl;       // mm
  std::vector<double> weights;  // > 0; all 1 for a non-rational curve
  std::vector<double> knots;    // non-decreasing, clamped
};

// One piece of a profile: a line or arc (seg), or a NURBS curve (nurbs >= 0 indexes
// Profile::nurbs; seg.a / seg.b then hold its end points and seg.kind is unused).
struct ProfileCurve {
  Seg2 seg;
  std::int32_t nurbs = -1;
};

// A closed, directed chain: curves[i] ends where curves[i+1] starts, the last ends at the
// first's start.
struct Profile {
  std::vector<ProfileCurve> curves;
  std::vector<Nurbs2> nurbs;
};

// A profile of lines and arcs only (a closed chain as above).
inline Profile profile_of(const std::vector<Seg2>& segs) {
  Profile p;
  for (const Seg2& s : segs) p.curves.push_back({s, -1});
  return p;
}

// One pocket: its boundary (clockwise) and the islands inside it (counter-clockwise).
struct Region {
  Profile boundary;
  std::vector<Profile> islands;
};

// Where each input entity came from (for error messages and provenance): Seg2::source
// indexes this table.
struct SourceEntity {
  std::string handle;  // e.g. the DXF handle "2F", or "profile 0 curve 3"
  std::string type;    // e.g. "LINE", "ARC", "LWPOLYLINE", "SPLINE", "line"
};

}  // namespace ncpath
