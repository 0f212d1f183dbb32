#include "kernels/pocket/offset_crude.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "kernels/curves/intersect.hpp"
#include "kernels/geom/tolerance.hpp"

namespace ncpath::pocket_detail {

namespace {

inline double cross(const Vec2& u, const Vec2& v) { return u.x() * v.y() - u.y() * v.x(); }

}  // namespace

namespace {

// Moves an end of s to p (end = true: s.b, else s.a). An arc whose new end lands just
// behind its other end would turn the long way round the circle; such a sliver becomes the
// straight piece it really is.
void move_end(Seg2& s, const Vec2& p, bool end) {
  if (!s.is_arc() || arc_contains_angle(s, p)) {  // the common case: no trigonometry
    (end ? s.b : s.a) = p;
    return;
  }
  const double before = std::abs(sweep(s));
  (end ? s.b : s.a) = p;
  if (std::abs(sweep(s)) > before + 1e-6) s.kind = SegKind::kLine;
}

// Crossing of the unbounded carriers of two segments (lines, full circles) nearest to v.
bool extended_crossing(const Seg2& s0, const Seg2& s1, const Vec2& v, Vec2& out) {
  Vec2 cand[2];
  const int n = carrier_crossings(s0, s1, cand);
  if (n == 0) return false;
  out = cand[0];
  if (n == 2 && (cand[1] - v).norm() < (cand[0] - v).norm()) out = cand[1];
  return true;
}

// Whether the input turns left at the vertex v = e1.b = e2.a, given the unit normals n1, n2
// of e1 and e2 there (n1 = (prev.b - v) / d: read from the offsets' ends, because the
// offsets' own tangents run backwards along an arc turned inside out). Within 90 degrees of
// straight on, the normals tell. Near a reversal (the tip of a thin spike, the end of a
// crack) the curves' bending within the offset distance may outweigh the corner's angle:
// a spike's sides may even cross a fraction of a micrometre from its tip. There the turn is
// read at the offset's scale, from the chords to the points s = min(d, lengths) away.
bool left_turn(const Seg2& e1, const Seg2& e2, const Vec2& n1, const Vec2& n2, double d) {
  const double c = cross(n1, n2);
  if (n1.dot(n2) >= 0) return c > 0;
  const double l1 = length(e1), l2 = length(e2);
  const double s = std::min({d, l1, l2});
  const double bend = s * ((e1.is_arc() ? 1 / e1.r : 0) + (e2.is_arc() ? 1 / e2.r : 0));
  if (std::abs(c) > bend) return c > 0;
  const Vec2& v = e2.a;
  const double chords = cross(v - point_at(e1, 1 - s / l1), point_at(e2, s / l2) - v);
  if (chords != 0) return chords > 0;
  return c > 0 || (c == 0 && tangent_at(e1, 1).dot(tangent_at(e2, 0)) < 0);
}

// Joins `prev` (its end) to `next` (its start), the offsets by d of the input curves e1 and
// e2, around their common vertex; may trim both. True when a joining segment is needed: it
// is written to out.
bool join(Seg2& prev, Seg2& next, const Seg2& e1, const Seg2& e2, double d, Seg2& out) {
  // Ends that (nearly) meet are made to meet: a joining piece shorter than kOffsetJoint
  // would only be a rounding artefact, and would turn back on itself one level later.
  const double eps = tol::kOffsetPoint;
  if ((prev.b - next.a).norm() <= tol::kOffsetJoint) {
    move_end(next, prev.b, false);
    return false;
  }
  const Vec2& v = e2.a;
  if (left_turn(e1, e2, (prev.b - v).normalized(), (next.a - v).normalized(), d)) {
    // Left turn: the material side opens; the true offset is the arc around v.
    out = make_arc(prev.b, next.a, v, true, prev.source);
    out.r = (prev.b - v).norm();
    return true;
  }
  // Right turn: the offsets overlap; trim both at their intersection nearest to v.
  SegHit hits[2];
  const int n = intersect(prev, next, hits, eps, false);
  if (n > 0) {
    int best = 0;
    if (n == 2 && (hits[1].p - v).norm() < (hits[0].p - v).norm()) best = 1;
    move_end(prev, hits[best].p, true);
    move_end(next, hits[best].p, false);
    return false;
  }
  // Nearly parallel ends (a corner of a few micro-radians) cross just past an end, where
  // the bounded intersection test cannot see it: meet at the crossing of the extended
  // curves when it is that close.
  Vec2 p;
  const double gap = (prev.b - next.a).norm();
  if (gap <= 1e-3 * (prev.b - v).norm() && extended_crossing(prev, next, v, p) &&
      (p - prev.b).norm() <= 2 * gap + tol::kOffsetJoint) {
    move_end(prev, p, true);
    move_end(next, p, false);
    return false;
  }
  out = make_line(prev.b, next.a, prev.source);
  return true;
}

}  // namespace

RawOffsets raw_offsets(const Seg2* curves, std::size_t count, double d) {
  RawOffsets out;
  out.d = d;
  out.segs.reserve(count);
  out.curves.reserve(count);
  for (std::size_t k = 0; k < count; ++k) {
    Seg2 o;
    if (!raw_offset(curves[k], d, o, &out.inverted)) continue;
    out.segs.push_back(o);
    out.curves.push_back(curves[k]);
  }
  return out;
}

void crude_loop(RawOffsets& offsets, std::uint32_t loop_id, std::vector<RawSeg>& raw) {
  std::vector<Seg2>& segs = offsets.segs;
  const std::size_t n = segs.size();
  if (n == 0) return;
  const auto base = static_cast<std::uint32_t>(raw.size());
  // Join every offset to the next (the last to the first), then emit each offset followed
  // by its joining segment: joins trim the offsets' ends, so all joins come first. (A curve
  // whose offset vanished leaves its neighbours' offsets to be joined at the start of the
  // next curve.)
  std::vector<Seg2> joins(n);
  std::vector<std::uint8_t> joined(n, 0);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t k1 = (k + 1) % n;
    joined[k] = join(segs[k], segs[k1], offsets.curves[k], offsets.curves[k1], offsets.d, joins[k]);
  }
  for (std::size_t k = 0; k < n; ++k) {
    raw.push_back({segs[k], loop_id, 0, 0, false});
    if (joined[k]) raw.push_back({joins[k], loop_id, 0, 0, !joins[k].is_arc()});
  }
  const auto m = static_cast<std::uint32_t>(raw.size() - base);
  for (std::uint32_t k = 0; k < m; ++k) {
    raw[base + k].prev = base + k - 1;
    raw[base + k].next = base + k + 1;
  }
  raw[base].prev = base + m - 1;
  raw[base + m - 1].next = base;
}

}  // namespace ncpath::pocket_detail
