#pragma once
// Planar curve segments of pocket profiles: lines and circular arcs, exact in double
// precision, millimetres, in the xy plane (right-handed, counter-clockwise = positive).
//
// An arc is given by its end points, centre, radius and turning direction; both end points
// lie on the circle (to rounding). A full circle is two half arcs: a == b is never an arc.
#include <cstdint>
#include <limits>
#include <vector>

#include "kernels/geom/vec.hpp"

namespace ncpath {

enum class SegKind : std::uint8_t { kLine = 0, kArcCcw = 1, kArcCw = 2 };

inline constexpr std::uint32_t kNoSource = std::numeric_limits<std::uint32_t>::max();

struct Seg2 {
  Vec2 a = Vec2::Zero();  // start, mm
  Vec2 b = Vec2::Zero();  // end, mm
  Vec2 c = Vec2::Zero();  // arc centre, mm (arcs only)
  double r = 0;           // arc radius, mm (arcs only)
  SegKind kind = SegKind::kLine;
  std::uint32_t source = kNoSource;  // provenance: index of the input entity it came from

  bool is_arc() const { return kind != SegKind::kLine; }
  // +1 for counter-clockwise arcs, -1 for clockwise ones, 0 for lines.
  int turn() const { return kind == SegKind::kArcCcw ? 1 : (kind == SegKind::kArcCw ? -1 : 0); }
};

Seg2 make_line(const Vec2& a, const Vec2& b, std::uint32_t source = kNoSource);
// Arc from a to b around centre c, turning ccw or cw; radius |a - c|.
Seg2 make_arc(const Vec2& a, const Vec2& b, const Vec2& c, bool ccw,
              std::uint32_t source = kNoSource);
// Arc from a to b with DXF/LWPOLYLINE bulge = tan(sweep / 4) (positive: counter-clockwise);
// a line when bulge == 0.
Seg2 make_bulge_segment(const Vec2& a, const Vec2& b, double bulge,
                        std::uint32_t source = kNoSource);

// Signed sweep angle of an arc, in (-2 pi, 2 pi), radians (0 for lines).
double sweep(const Seg2& s);
double length(const Seg2& s);
// Point at parameter t in [0, 1] (by arc length).
Vec2 point_at(const Seg2& s, double t);
// Unit tangent at parameter t, in the direction of travel.
Vec2 tangent_at(const Seg2& s, double t);
// Twice the signed area swept from the origin: sum over a closed loop = 2 * signed area
// (positive for counter-clockwise loops). Exact for lines and arcs.
double area2_contribution(const Seg2& s);
// Distance from p to the closest point of s.
double distance(const Seg2& s, const Vec2& p);
// Axis-aligned box of the segment (exact for arcs: includes the quadrant points crossed).
void bounds(const Seg2& s, Vec2& lo, Vec2& hi);
// True when the direction of p as seen from the arc's centre lies within its sweep.
bool arc_contains_angle(const Seg2& s, const Vec2& p);
// Points along s from s.a (included) to s.b (excluded) such that the chords stay within
// chordal_tol of the segment (mm); appended to out.
void append_polyline(const Seg2& s, double chordal_tol, std::vector<Vec2>& out);
// A box that contains the segment, cheaper than bounds() for arcs (no angle tests): minor
// arcs get the end points' box grown by their sagitta, others their circle's box.
void loose_bounds(const Seg2& s, Vec2& lo, Vec2& hi);
// Reversed segment (b to a, opposite turn).
Seg2 reversed(const Seg2& s);

}  // namespace ncpath
