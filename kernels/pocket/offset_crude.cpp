#include "kernels/pocket/offset_crude.hpp"

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

// Joins `prev` (its end) to `next` (its start) around the original vertex v; may trim
// both. True when a joining segment is needed: it is written to out.
bool join(Seg2& prev, Seg2& next, const Vec2& v, Seg2& out) {
  // Ends that (nearly) meet are made to meet: a joining piece shorter than kOffsetJoint
  // would only be a rounding artefact, and would turn back on itself one level later.
  const double eps = tol::kOffsetPoint;
  if ((prev.b - next.a).norm() <= tol::kOffsetJoint) {
    move_end(next, prev.b, false);
    return false;
  }
  const Vec2 te = tangent_at(prev, 1), ts = tangent_at(next, 0);
  const double c = cross(te, ts);
  if (c > 0 || (std::abs(c) <= 1e-15 && te.dot(ts) < 0)) {
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

// At a right turn whose end segments do not meet (runs of many short arcs, e.g. a NURBS
// curve's offset, overlap over many segments), the crossing nearest to the vertex among the
// segments within `reach` mm of the run ends. On success the runs are shortened to it:
// last (exclusive end of the previous run) and first (start of the next run) move.
bool trim_overlap(std::vector<Seg2>& segs, std::uint32_t prev_begin, std::uint32_t& last,
                  std::uint32_t& first, std::uint32_t next_end, const Vec2& v, double reach) {
  // Candidate segments: walk back from the previous run's end and forward from the next
  // run's start until `reach` mm of curve are covered, never past each other (one run).
  std::vector<std::uint32_t> back, ahead;
  double len = 0;
  for (std::uint32_t i = last; i > prev_begin && len <= reach;) {
    --i;
    back.push_back(i);
    len += length(segs[i]);
  }
  len = 0;
  for (std::uint32_t j = first; j < next_end && len <= reach; ++j) {
    ahead.push_back(j);
    len += length(segs[j]);
  }
  double best = std::numeric_limits<double>::infinity();
  std::uint32_t bi = 0, bj = 0;
  Vec2 bp = Vec2::Zero();
  std::vector<Vec2> lo(ahead.size()), hi(ahead.size());
  for (std::size_t q = 0; q < ahead.size(); ++q) loose_bounds(segs[ahead[q]], lo[q], hi[q]);
  for (std::uint32_t i : back) {
    Vec2 ilo, ihi;
    loose_bounds(segs[i], ilo, ihi);
    for (std::size_t q = 0; q < ahead.size(); ++q) {
      const std::uint32_t j = ahead[q];
      if (i == j || lo[q].x() > ihi.x() || hi[q].x() < ilo.x() || lo[q].y() > ihi.y() ||
          hi[q].y() < ilo.y())
        continue;
      SegHit hits[2];
      const int n = intersect(segs[i], segs[j], hits, tol::kOffsetPoint, false);
      for (int k = 0; k < n; ++k) {
        const double dv = (hits[k].p - v).norm();
        if (dv < best) {
          best = dv;
          bi = i;
          bj = j;
          bp = hits[k].p;
        }
      }
    }
  }
  if (!std::isfinite(best)) return false;
  move_end(segs[bi], bp, true);
  move_end(segs[bj], bp, false);
  last = bi + 1;
  first = bj;
  return true;
}

}  // namespace

constexpr std::uint32_t kNoJoin = 0xffffffffu;

// The crude offset loop of one input loop (its curves' raw offsets, in order), appended to
// raw. d: the offset distance (bounds the search for overlaps at concave joints).
void crude_loop(OffsetRuns& runs, std::uint32_t loop_id, double d, std::vector<RawSeg>& raw) {
  const std::size_t n = runs.runs();
  if (n == 0) return;
  // Effective ranges of the runs: joins may trim whole segments off their ends.
  std::vector<std::uint32_t> first(runs.start.begin(), runs.start.end() - 1),
      last(runs.start.begin() + 1, runs.start.end());
  // The joining segment after each run (at most one: an arc or a connector line).
  std::vector<Seg2> joins;
  std::vector<std::uint32_t> join_of(n, kNoJoin);  // index into joins, per run
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t k1 = (k + 1) % n;
    Seg2& prev = runs.segs[last[k] - 1];
    Seg2& next = runs.segs[first[k1]];
    Seg2 js;
    if (!join(prev, next, runs.vertex[k1], js)) continue;
    join_of[k] = static_cast<std::uint32_t>(joins.size());
    joins.push_back(js);
    // A connector line at a right turn means the ends missed each other: look further back.
    const bool missed = !js.is_arc();
    if (!missed) continue;
    const Vec2 te = tangent_at(prev, 1), ts = tangent_at(next, 0);
    if (cross(te, ts) > 0) continue;
    // The overlap of two offsets at a corner turning by theta reaches d tan(theta / 2) from
    // the vertex; 20 d covers turns up to ~174 degrees.
    std::uint32_t l = last[k], f = first[k1];
    const std::uint32_t prev_begin = k1 == k ? f + 1 : first[k];
    const std::uint32_t next_end = k1 == k ? l - 1 : last[k1];
    if (prev_begin >= l || f >= next_end) continue;
    if (trim_overlap(runs.segs, prev_begin, l, f, next_end, runs.vertex[k1], 20 * d)) {
      last[k] = l;
      first[k1] = f;
      join_of[k] = kNoJoin;
    }
  }
  const auto base = static_cast<std::uint32_t>(raw.size());
  for (std::size_t k = 0; k < n; ++k) {
    for (std::uint32_t q = first[k]; q < last[k]; ++q)
      raw.push_back({runs.segs[q], loop_id, 0, 0, false});
    if (join_of[k] != kNoJoin) {
      const Seg2& js = joins[join_of[k]];
      raw.push_back({js, loop_id, 0, 0, !js.is_arc()});
    }
  }
  const auto m = static_cast<std::uint32_t>(raw.size() - base);
  if (m == 0) return;
  for (std::uint32_t k = 0; k < m; ++k) {
    raw[base + k].prev = base + k - 1;
    raw[base + k].next = base + k + 1;
  }
  raw[base].prev = base + m - 1;
  raw[base + m - 1].next = base;
}

}  // namespace ncpath::pocket_detail
