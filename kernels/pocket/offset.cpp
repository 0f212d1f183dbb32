#include "kernels/pocket/offset.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <unordered_map>

#include "kernels/curves/intersect.hpp"
#include "kernels/geom/tolerance.hpp"
#include "kernels/pocket/offset_crude.hpp"
#include "kernels/pocket/seg_grid.hpp"

namespace ncpath {

namespace {

inline double cross(const Vec2& u, const Vec2& v) { return u.x() * v.y() - u.y() * v.x(); }

using pocket_detail::Box;
using pocket_detail::crude_loop;
using pocket_detail::RawSeg;
using pocket_detail::SegGrid;

// Consecutive segments `first` and `second` share the joint first.b == second.a. False
// when they cannot meet anywhere else, decided without computing intersections: two lines
// only meet again when they fold back on each other; a line and a circle through the joint
// meet at one more point, the reflection of the joint along the line; two circles through
// the joint meet at its mirror image across the line of centres.
inline bool adjacent_may_cross(const Seg2& first, const Seg2& second) {
  const Vec2& p = first.b;
  if (!first.is_arc() && !second.is_arc()) return (first.b - first.a).dot(second.b - second.a) < 0;
  Vec2 q;
  if (first.is_arc() != second.is_arc()) {
    const Seg2& arc = first.is_arc() ? first : second;
    const Seg2& line = first.is_arc() ? second : first;
    const Vec2 d = line.b - line.a;
    const double l2 = d.squaredNorm();
    if (l2 == 0) return false;
    // Second point of the line through p on the circle: p + s d, s = -2 (p - c).d / |d|^2;
    // on the line segment only for s in [-1, 0] (p is its end) or [0, 1] (p its start).
    const double sp = -2 * (p - arc.c).dot(d) / l2;
    const double slack = tol::kOffsetJoint / std::sqrt(l2);
    if (first.is_arc() ? (sp < -slack || sp > 1 + slack) : (sp < -1 - slack || sp > slack))
      return false;
    q = p + sp * d;
  } else {
    const Vec2 u = second.c - first.c;
    const double l2 = u.squaredNorm();
    if (l2 == 0) return true;  // concentric through one point: the same circle, let it be
    const Vec2 w = p - first.c;
    q = first.c + (2 * w.dot(u) / l2) * u - w;  // mirror of p across the centre line
  }
  if ((q - p).norm() <= tol::kOffsetJoint) return false;
  return distance(first, q) <= tol::kOffsetJoint && distance(second, q) <= tol::kOffsetJoint;
}

struct SplitPoint {
  double t;
  Vec2 p;
};

}  // namespace

bool raw_offset(const Seg2& s, double d, Seg2& out, bool* inverted) {
  out = s;
  if (!s.is_arc()) {
    const Vec2 dir = s.b - s.a;
    const double l = dir.norm();
    if (l == 0) return false;
    const Vec2 right(dir.y() / l, -dir.x() / l);
    out.a = s.a + d * right;
    out.b = s.b + d * right;
    return true;
  }
  // Counter-clockwise arcs have their centre on the left: moving right grows the radius.
  // An arc whose radius is smaller than d on the side it is offset to turns inside out: its
  // offset points lie past the centre (radius d - r, same turning direction). Kept, so that
  // the crude loop stays continuous through the swallowtail, where validation removes it;
  // the joins to its neighbours are then the arcs of radius d around its end points.
  const double r = s.r + (s.kind == SegKind::kArcCcw ? d : -d);
  if (std::abs(r) <= tol::kOffsetPoint) return false;
  const Vec2 ua = (s.a - s.c) / (s.a - s.c).norm();
  const Vec2 ub = (s.b - s.c) / (s.b - s.c).norm();
  out.a = s.c + r * ua;
  out.b = s.c + r * ub;
  out.r = std::abs(r);
  if (inverted && r < 0) *inverted = true;
  return true;
}

double loop_area2(const std::vector<Seg2>& loop) {
  double a = 0;
  for (const Seg2& s : loop) a += area2_contribution(s);
  return a;
}

double loop_length(const std::vector<Seg2>& loop) {
  double l = 0;
  for (const Seg2& s : loop) l += length(s);
  return l;
}

int winding_number(const std::vector<Seg2>& loop, const Vec2& q) {
  // A horizontal ray to +x; a tiny fixed nudge keeps it off vertices at exactly q.y.
  const Vec2 p(q.x(), q.y() + 1.2345678e-11);
  int w = 0;
  for (const Seg2& s : loop) {
    if (!s.is_arc()) {
      if (s.a.y() <= p.y() && s.b.y() > p.y()) {
        if (cross(s.b - s.a, p - s.a) > 0) ++w;
      } else if (s.b.y() <= p.y() && s.a.y() > p.y()) {
        if (cross(s.b - s.a, p - s.a) < 0) --w;
      }
      continue;
    }
    const double dy = p.y() - s.c.y();
    if (std::abs(dy) >= s.r) continue;
    const double dx = std::sqrt(s.r * s.r - dy * dy);
    for (double x : {s.c.x() - dx, s.c.x() + dx}) {
      if (x <= p.x()) continue;
      const Vec2 hit(x, p.y());
      if (!arc_contains_angle(s, hit)) continue;
      // Direction of travel in y at the hit: ccw arcs go up on the right of the centre.
      const double up = (x - s.c.x()) * s.turn();
      w += up > 0 ? 1 : -1;
    }
  }
  return w;
}

namespace {

// Two curves that touch without crossing (offsets of two islands exactly 2d apart, at the
// level where they meet): one tangent contact, or two hits closer than kOffsetJoint. Such
// a contact is no crossing: both loops stay as they are (touching), instead of being
// split at an ill-conditioned point that stitching cannot follow.
bool touch_only(const Seg2& s0, const Seg2& s1, const SegHit* hits, int h) {
  if (h == 2 && (hits[0].p - hits[1].p).norm() > tol::kOffsetJoint) return false;
  const Vec2 t0 = tangent_at(s0, parameter_of(s0, hits[0].p));
  const Vec2 t1 = tangent_at(s1, parameter_of(s1, hits[0].p));
  return std::abs(t0.x() * t1.y() - t0.y() * t1.x()) <= tol::kTangentCross;
}

}  // namespace

OffsetResult offset_loops(const std::vector<std::vector<Seg2>>& loops, double d,
                          const std::vector<double>* area2) {
  std::vector<OffsetRuns> runs(loops.size());
  for (std::size_t l = 0; l < loops.size(); ++l) {
    runs[l].segs.reserve(loops[l].size());
    for (const Seg2& s : loops[l]) {
      Seg2 o;
      if (raw_offset(s, d, o, &runs[l].inverted)) runs[l].add(s.a, &o, 1);
    }
  }
  return offset_prepared(std::move(runs), loops, d, area2);
}

OffsetResult offset_prepared(std::vector<OffsetRuns> runs,
                             const std::vector<std::vector<Seg2>>& loops, double d,
                             const std::vector<double>* area2, double slack) {
  OffsetResult res;
  const double eps = tol::kOffsetPoint;
  std::vector<RawSeg> raw;
  std::size_t expected = 0;
  for (const OffsetRuns& r : runs) expected += r.segs.size() + r.runs();
  raw.reserve(expected + expected / 4);
  for (std::size_t l = 0; l < runs.size(); ++l)
    crude_loop(runs[l], static_cast<std::uint32_t>(l), d, raw);
  res.stats.raw_segments = raw.size();
  const std::size_t n = raw.size();
  if (n == 0) return res;

  // Dissection: all intersections, by a sweep over x.
  std::vector<Box> box(n);
  for (std::size_t i = 0; i < n; ++i) {
    loose_bounds(raw[i].s, box[i].lo, box[i].hi);
    box[i].lo.array() -= eps;
    box[i].hi.array() += eps;
  }
  // Sweep order: by left edge (key and index side by side: a cache-friendly sort).
  std::vector<std::pair<double, std::uint32_t>> keyed(n);
  for (std::uint32_t i = 0; i < n; ++i) keyed[i] = {box[i].lo.x(), i};
  std::sort(keyed.begin(), keyed.end());
  std::vector<std::uint32_t> order(n);
  for (std::uint32_t i = 0; i < n; ++i) order[i] = keyed[i].second;
  std::vector<std::vector<SplitPoint>> splits(n);
  std::vector<std::uint8_t> crossed(loops.size());  // the crude loop meets itself or another
  std::vector<std::uint32_t> active;
  for (const std::uint32_t i : order) {
    std::size_t keep = 0;
    for (const std::uint32_t j : active)
      if (box[j].hi.x() >= box[i].lo.x()) active[keep++] = j;
    active.resize(keep);
    for (const std::uint32_t j : active) {
      if (box[j].lo.y() > box[i].hi.y() || box[j].hi.y() < box[i].lo.y()) continue;
      if (raw[i].next == j && !adjacent_may_cross(raw[i].s, raw[j].s)) continue;
      if (raw[i].prev == j && !adjacent_may_cross(raw[j].s, raw[i].s)) continue;
      SegHit hits[2];
      const int h = intersect(raw[i].s, raw[j].s, hits, eps, false);
      if (h > 0 && raw[i].next != j && raw[i].prev != j && touch_only(raw[i].s, raw[j].s, hits, h))
        continue;
      for (int k = 0; k < h; ++k) {
        const Vec2& p = hits[k].p;
        // The joint shared with a neighbour is not a crossing.
        if (raw[i].next == j && (p - raw[i].s.b).norm() <= tol::kOffsetJoint) continue;
        if (raw[i].prev == j && (p - raw[i].s.a).norm() <= tol::kOffsetJoint) continue;
        splits[i].push_back({parameter_of(raw[i].s, p), p});
        splits[j].push_back({parameter_of(raw[j].s, p), p});
        crossed[raw[i].loop] = crossed[raw[j].loop] = 1;
        ++res.stats.intersections;
      }
    }
    active.push_back(i);
  }

  // Split into pieces.
  // A piece starts a new run where its validity may change: after a crossing, and at
  // either end of a connector (connectors are validated on their own).
  struct Piece {
    Seg2 s;
    std::uint32_t loop;
    bool run_start;
    bool connector;
    bool at_crossing;  // starts at a crossing (where another piece may continue instead)
  };
  std::vector<Piece> pieces;
  pieces.reserve(n + 2 * res.stats.intersections + 1);
  std::vector<std::uint8_t> cut_at_start(n, 0);  // a crossing sits on the raw joint
  for (std::size_t i = 0; i < n; ++i)
    for (const SplitPoint& q : splits[i]) {
      if ((q.p - raw[i].s.a).norm() <= eps) cut_at_start[i] = 1;
      if ((q.p - raw[i].s.b).norm() <= eps) cut_at_start[raw[i].next] = 1;
    }
  for (std::size_t i = 0; i < n; ++i) {
    const Seg2& s = raw[i].s;
    std::vector<SplitPoint>& sp = splits[i];
    std::sort(sp.begin(), sp.end(),
              [](const SplitPoint& a, const SplitPoint& b) { return a.t < b.t; });
    const bool conn = raw[i].connector;
    bool start = cut_at_start[i] || conn || raw[raw[i].prev].connector;
    bool crossing = cut_at_start[i];
    Vec2 from = s.a;
    for (const SplitPoint& q : sp) {
      if ((q.p - from).norm() <= eps || (q.p - s.b).norm() <= eps) continue;
      pieces.push_back({sub_segment(s, from, q.p), raw[i].loop, start, conn, crossing});
      start = crossing = true;
      from = q.p;
    }
    pieces.push_back({sub_segment(s, from, s.b), raw[i].loop, start, conn, crossing});
  }
  res.stats.pieces = pieces.size();

  // Validation. A crude loop that crosses nothing (neither itself nor another loop) is a
  // simple closed curve parallel to its input: it is the true offset when it runs the same
  // way round as its input, and an inverted remnant (a loop offset past its own width)
  // otherwise - no distance test needed. Pieces of loops that cross something are tested
  // against the input curves.
  std::vector<double> crude_area2(loops.size(), 0.0);
  for (const RawSeg& r : raw)
    if (!crossed[r.loop]) crude_area2[r.loop] += area2_contribution(r.s);
  std::vector<std::uint8_t> same_way(loops.size());
  for (std::size_t l = 0; l < loops.size(); ++l)
    if (!crossed[l])
      same_way[l] = (crude_area2[l] < 0) == ((area2 ? (*area2)[l] : loop_area2(loops[l])) < 0);
  std::vector<Seg2> input;  // all input curves, gathered only when a distance is needed
  std::optional<SegGrid> grid;
  std::vector<std::uint8_t> keep(pieces.size());
  auto valid = [&](const Seg2& sg) {
    if (!grid) {
      for (const auto& l : loops) input.insert(input.end(), l.begin(), l.end());
      grid.emplace(input, d);
    }
    return !grid->any_closer(sg, d - std::max(slack, tol::kOffsetValid));
  };
  // Pieces of one loop are contiguous (raw loops are, and pieces follow raw order).
  for (std::size_t b = 0; b < pieces.size();) {
    const std::uint32_t l = pieces[b].loop;
    std::size_t e = b;
    while (e < pieces.size() && pieces[e].loop == l) ++e;
    if (!crossed[l]) {
      // Validity cannot change along a crude loop that crosses nothing. With a single input
      // loop its orientation tells the true offset from an inverted remnant; with several,
      // it may also lie wholly within d of another input loop (a band thinner than 2d), so
      // one piece is tested by distance.
      // A loop with an inside-out arc is the offset of a stretch narrower than 2d: its
      // inverted part comes closer than d to the arc it came from, and with no crossing
      // the whole loop goes with it.
      std::uint8_t ok = same_way[l] && !runs[l].inverted;
      if (ok && loops.size() > 1) {
        std::size_t best = b;
        for (std::size_t k = b + 1; k < e; ++k)
          if ((pieces[k].s.b - pieces[k].s.a).squaredNorm() >
              (pieces[best].s.b - pieces[best].s.a).squaredNorm())
            best = k;
        ok = valid(pieces[best].s) ? 1 : 0;
      }
      for (std::size_t k = b; k < e; ++k) keep[k] = ok;
    } else {
      // Every run (cyclic) is valid or invalid as a whole: test its longest piece.
      const std::size_t m = e - b;
      std::size_t first = 0;
      while (first < m && !pieces[b + first].run_start) ++first;
      if (first == m) first = 0;
      for (std::size_t r = 0; r < m;) {
        std::size_t len = 1;
        while (len < m && !pieces[b + (first + r + len) % m].run_start) ++len;
        std::size_t best = b + (first + r) % m;
        for (std::size_t q = 1; q < len; ++q) {
          const std::size_t k = b + (first + r + q) % m;
          if ((pieces[k].s.b - pieces[k].s.a).squaredNorm() >
              (pieces[best].s.b - pieces[best].s.a).squaredNorm())
            best = k;
        }
        const std::uint8_t ok = valid(pieces[best].s) ? 1 : 0;
        for (std::size_t q = 0; q < len; ++q) keep[b + (first + r + q) % m] = ok;
        r += len;
      }
    }
    b = e;
  }
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    if ((pieces[k].s.b - pieces[k].s.a).norm() <= eps && !pieces[k].s.is_arc()) keep[k] = 0;
    res.stats.pieces_kept += keep[k];
  }

  // Regrouping: stitch kept pieces end to end.
  auto key = [](const Vec2& p) {
    const double q = 1e-6;  // mm: bucket size for end-point lookup (matches are within eps)
    return (static_cast<std::uint64_t>(static_cast<std::int64_t>(std::floor(p.x() / q))) *
            0x9E3779B97F4A7C15ull) ^
           static_cast<std::uint64_t>(static_cast<std::int64_t>(std::floor(p.y() / q)));
  };
  // Away from crossings a piece continues into the next piece of its own crude loop;
  // only pieces starting at crossings are looked up by position.
  std::vector<std::uint32_t> succ(pieces.size());
  for (std::size_t b = 0; b < pieces.size();) {
    std::size_t e = b;
    while (e < pieces.size() && pieces[e].loop == pieces[b].loop) ++e;
    for (std::size_t k = b; k < e; ++k) succ[k] = static_cast<std::uint32_t>(k + 1 < e ? k + 1 : b);
    b = e;
  }
  std::unordered_multimap<std::uint64_t, std::uint32_t> starts;
  for (std::uint32_t k = 0; k < pieces.size(); ++k)
    if (keep[k] && pieces[k].at_crossing) starts.emplace(key(pieces[k].s.a), k);
  auto find_at_crossing = [&](const Vec2& p, const Vec2& incoming) -> std::int64_t {
    std::int64_t best = -1;
    double best_turn = 1e300;
    const double q = 1e-6;
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy) {
        auto range = starts.equal_range(key(p + Vec2(dx * q, dy * q)));
        for (auto it = range.first; it != range.second; ++it) {
          const std::uint32_t k = it->second;
          if (!keep[k] || (pieces[k].s.a - p).norm() > 10 * eps) continue;
          const Vec2 t = tangent_at(pieces[k].s, 0);
          const double turn = std::atan2(cross(incoming, t), incoming.dot(t));
          if (best < 0 || turn < best_turn) {
            best = k;
            best_turn = turn;
          }
        }
      }
    return best;
  };
  for (std::uint32_t k0 = 0; k0 < pieces.size(); ++k0) {
    if (!keep[k0]) continue;
    OffsetLoop loop;
    std::vector<std::uint32_t> used;
    std::uint32_t k = k0;
    bool closed = false;
    for (std::size_t guard = 0; guard <= pieces.size(); ++guard) {
      keep[k] = 0;
      used.push_back(k);
      loop.segs.push_back(pieces[k].s);
      loop.parents.push_back(pieces[k].loop);
      const Vec2 end = pieces[k].s.b;
      if ((end - pieces[k0].s.a).norm() <= 10 * eps) {
        closed = true;
        break;
      }
      const std::uint32_t sk = succ[k];
      std::int64_t nk;
      if (!pieces[sk].at_crossing && (pieces[sk].s.a - end).norm() <= 10 * eps)
        nk = keep[sk] ? std::int64_t{sk} : -1;
      else
        nk = find_at_crossing(end, tangent_at(pieces[k].s, 1));
      if (nk < 0) break;
      k = static_cast<std::uint32_t>(nk);
    }
    if (!closed) {
      res.stats.open_fragments += used.size();
      continue;
    }
    // Drop slivers by joining their neighbours, then make the joints exact.
    std::vector<Seg2> kept_segs;
    for (const Seg2& sg : loop.segs)
      if ((sg.b - sg.a).norm() > tol::kOffsetSliver ||
          (sg.is_arc() && length(sg) > tol::kOffsetSliver))
        kept_segs.push_back(sg);
    if (kept_segs.size() < 2) continue;
    loop.segs = std::move(kept_segs);
    for (std::size_t s = 0; s < loop.segs.size(); ++s)
      loop.segs[(s + 1) % loop.segs.size()].a = loop.segs[s].b;
    loop.area2 = loop_area2(loop.segs);
    if (std::abs(loop.area2) <= eps) continue;  // a sliver with no area
    std::sort(loop.parents.begin(), loop.parents.end());
    loop.parents.erase(std::unique(loop.parents.begin(), loop.parents.end()), loop.parents.end());
    res.loops.push_back(std::move(loop));
  }
  // Orientation check: offsetting a bounded pocket (its largest loop is a clockwise
  // boundary) can only leave holes inside boundaries. A counter-clockwise loop outside every
  // clockwise one is what is left of islands after the boundary closed over them. (An
  // unbounded region - the complement of a pocket, offset to dilate it - has no such rule.)
  double largest = 0;
  bool pocket = false;
  for (std::size_t l = 0; l < loops.size(); ++l) {
    const double a = area2 ? (*area2)[l] : loop_area2(loops[l]);
    if (std::abs(a) > largest) {
      largest = std::abs(a);
      pocket = a < 0;
    }
  }
  if (pocket) {
    std::vector<std::uint8_t> ok(res.loops.size());
    for (std::size_t i = 0; i < res.loops.size(); ++i) {
      ok[i] = res.loops[i].area2 < 0;
      for (const OffsetLoop& o : res.loops)
        if (!ok[i] && o.area2 < 0 && winding_number(o.segs, res.loops[i].segs.front().a) != 0)
          ok[i] = 1;
    }
    std::vector<OffsetLoop> valid;
    for (std::size_t i = 0; i < res.loops.size(); ++i) {
      if (ok[i])
        valid.push_back(std::move(res.loops[i]));
      else
        ++res.stats.dropped_holes;
    }
    res.loops = std::move(valid);
  }
  return res;
}

}  // namespace ncpath
