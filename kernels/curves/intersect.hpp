#pragma once
// Intersections and distances between line/arc segments, double precision.
#include "kernels/curves/segment.hpp"

namespace ncpath {

struct SegHit {
  Vec2 p;     // the intersection point, mm
  double t0;  // parameter on the first segment, [0, 1] by arc length
  double t1;  // parameter on the second segment
};

// Intersections of two segments: at most 2 points. Overlapping collinear lines or
// co-circular arcs report the end points of their overlap. Points within `eps` (mm) of a
// segment count as on it (end points included). Returns the number written to hits.
// With want_params == false, t0 and t1 are left 0 (callers that filter hits first compute
// parameters only for the hits they keep: it costs trigonometry on arcs).
int intersect(const Seg2& s0, const Seg2& s1, SegHit hits[2], double eps, bool want_params = true);

// Crossings of the unbounded carriers of two segments (infinite lines, full circles): at
// most 2, none for parallel lines or concentric circles. Tangent contacts count once.
int carrier_crossings(const Seg2& s0, const Seg2& s1, Vec2 out[2]);

// Parameter of the point of s closest to p, in [0, 1] by arc length.
double parameter_of(const Seg2& s, const Vec2& p);

// Sub-segment of s between parameters t0 < t1, with the given exact end points (callers
// pass the split points they computed once, so neighbouring pieces share them bitwise).
Seg2 sub_segment(const Seg2& s, const Vec2& from, const Vec2& to);

// Smallest distance between two segments (0 when they intersect).
double distance(const Seg2& s0, const Seg2& s1);

}  // namespace ncpath
