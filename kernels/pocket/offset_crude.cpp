#include "kernels/pocket/offset_crude.hpp"

#include <cmath>

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

// Joins `prev` (its end) to `next` (its start) around the original vertex v; may trim
// both, and may append a joining segment to out.
void join(Seg2& prev, Seg2& next, const Vec2& v, std::vector<Seg2>& out) {
  // Ends that (nearly) meet are made to meet: a joining piece shorter than kOffsetJoint
  // would only be a rounding artefact, and would turn back on itself one level later.
  const double eps = tol::kOffsetPoint;
  if ((prev.b - next.a).norm() <= tol::kOffsetJoint) {
    move_end(next, prev.b, false);
    return;
  }
  const Vec2 te = tangent_at(prev, 1), ts = tangent_at(next, 0);
  const double c = cross(te, ts);
  if (c > 0 || (std::abs(c) <= 1e-15 && te.dot(ts) < 0)) {
    // Left turn: the material side opens; the true offset is the arc around v.
    out.push_back(make_arc(prev.b, next.a, v, true, prev.source));
    out.back().r = (prev.b - v).norm();
    return;
  }
  // Right turn: the offsets overlap; trim both at their intersection nearest to v.
  SegHit hits[2];
  const int n = intersect(prev, next, hits, eps);
  if (n > 0) {
    int best = 0;
    if (n == 2 && (hits[1].p - v).norm() < (hits[0].p - v).norm()) best = 1;
    move_end(prev, hits[best].p, true);
    move_end(next, hits[best].p, false);
    return;
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
    return;
  }
  out.push_back(make_line(prev.b, next.a, prev.source));
}

}  // namespace

// The crude offset loop of one input loop, appended to raw.
// The crude offset loop of one input loop (its curves' raw offsets, in order), appended to
// raw.
void crude_loop(OffsetRuns& runs, std::uint32_t loop_id, std::vector<RawSeg>& raw) {
  const std::size_t n = runs.runs();
  if (n == 0) return;
  // Join each consecutive pair of runs; a run is emitted once both its ends are settled.
  // The last join (back to the first run) may still move the first run's start: the
  // emitted copy is patched afterwards.
  const auto base = static_cast<std::uint32_t>(raw.size());
  std::vector<Seg2> joins;
  for (std::size_t k = 0; k < n; ++k) {
    joins.clear();
    const std::size_t k1 = (k + 1) % n;
    join(runs.segs[runs.start[k + 1] - 1], runs.segs[runs.start[k1]], runs.vertex[k1], joins);
    for (std::uint32_t q = runs.start[k]; q < runs.start[k + 1]; ++q)
      raw.push_back({runs.segs[q], loop_id, 0, 0, false});
    for (const Seg2& js : joins) raw.push_back({js, loop_id, 0, 0, !js.is_arc()});
  }
  raw[base].s = runs.segs[0];
  const auto m = static_cast<std::uint32_t>(raw.size() - base);
  for (std::uint32_t k = 0; k < m; ++k) {
    raw[base + k].prev = base + (k + m - 1) % m;
    raw[base + k].next = base + (k + 1) % m;
  }
}

}  // namespace ncpath::pocket_detail
