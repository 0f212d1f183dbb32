// Offset-loop dissection proper (kernels/pocket/offset.hpp, steps 3 to 6): crossings of the
// crude loops, splitting, validation in runs, stitching, orientation.
#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "kernels/curves/intersect.hpp"
#include "kernels/geom/tolerance.hpp"
#include "kernels/pocket/offset_crude.hpp"
#include "kernels/pocket/seg_grid.hpp"

namespace ncpath::pocket_detail {

namespace {

inline double cross(const Vec2& u, const Vec2& v) { return u.x() * v.y() - u.y() * v.x(); }

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

struct SplitPoint {
  double t;
  Vec2 p;
};

}  // namespace

OffsetResult dissect(const std::vector<RawSeg>& raw, const std::vector<Chain>& chains,
                     const std::vector<std::uint32_t>* rank, const DissectParams& par,
                     const PieceValid& valid) {
  OffsetResult res;
  res.stats.raw_segments = raw.size();
  const double eps = tol::kOffsetPoint;
  const std::size_t n = raw.size();
  if (n == 0) return res;
  const auto has_next = [&](std::size_t i) { return raw[i].next != kNoRaw; };
  const auto has_prev = [&](std::size_t i) { return raw[i].prev != kNoRaw; };

  // Dissection: all intersections, by a sweep over x.
  std::vector<Box> box(n);
  for (std::size_t i = 0; i < n; ++i) {
    loose_bounds(raw[i].s, box[i].lo, box[i].hi);
    box[i].lo.array() -= eps;
    box[i].hi.array() += eps;
  }
  // Sweep order: by left edge, ties by rank (key and index side by side: a cache-friendly
  // sort). The rank keeps a windowed dissection's pairs in the complete one's order.
  std::vector<std::pair<double, std::uint64_t>> keyed(n);
  for (std::uint32_t i = 0; i < n; ++i)
    keyed[i] = {box[i].lo.x(), rank ? (std::uint64_t{(*rank)[i]} << 32 | i) : i};
  std::sort(keyed.begin(), keyed.end());
  std::vector<std::uint32_t> order(n);
  for (std::uint32_t i = 0; i < n; ++i) order[i] = static_cast<std::uint32_t>(keyed[i].second);
  std::vector<std::vector<SplitPoint>> splits(n);
  std::vector<std::uint8_t> crossed(chains.size());  // the chain meets itself or another
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
  // A piece starts a new run where its validity may change: after a crossing, at either end
  // of a connector (connectors are validated on their own), and at the start of an open
  // chain.
  struct Piece {
    Seg2 s;
    std::uint32_t loop;  // chain
    bool run_start;
    bool connector;
    bool at_crossing;  // starts at a crossing (where another piece may continue instead)
  };
  std::vector<Piece> pieces;
  pieces.reserve(n + 2 * res.stats.intersections + 1);
  std::vector<std::uint32_t> first_piece(n + 1);  // pieces of raw[i]: [first[i], first[i+1])
  std::vector<std::uint8_t> cut_at_start(n, 0);   // a crossing sits on the raw joint
  for (std::size_t i = 0; i < n; ++i)
    for (const SplitPoint& q : splits[i]) {
      if ((q.p - raw[i].s.a).norm() <= eps) cut_at_start[i] = 1;
      if ((q.p - raw[i].s.b).norm() <= eps && has_next(i)) cut_at_start[raw[i].next] = 1;
    }
  for (std::size_t i = 0; i < n; ++i) {
    first_piece[i] = static_cast<std::uint32_t>(pieces.size());
    const Seg2& s = raw[i].s;
    std::vector<SplitPoint>& sp = splits[i];
    std::sort(sp.begin(), sp.end(),
              [](const SplitPoint& a, const SplitPoint& b) { return a.t < b.t; });
    const bool conn = raw[i].connector;
    bool start = cut_at_start[i] || conn || !has_prev(i) || raw[raw[i].prev].connector;
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
  first_piece[n] = static_cast<std::uint32_t>(pieces.size());
  res.stats.pieces = pieces.size();

  // Validation. A closed crude loop that crosses nothing (neither itself nor another loop)
  // is a simple closed curve parallel to its input: it is the true offset when it runs the
  // same way round as its input, and an inverted remnant (a loop offset past its own width)
  // otherwise - no distance test needed. Pieces of chains that cross something, and of open
  // chains, are tested against the input curves.
  std::vector<double> crude_area2(chains.size(), 0.0);
  for (const RawSeg& r : raw)
    if (!crossed[r.loop]) crude_area2[r.loop] += area2_contribution(r.s);
  std::vector<std::uint8_t> keep(pieces.size());
  const auto raw_of = [&](std::size_t piece) {
    return static_cast<std::uint32_t>(
        std::upper_bound(first_piece.begin(), first_piece.end(), piece) - first_piece.begin() - 1);
  };
  // Pieces of one chain are contiguous (chains are, and pieces follow raw order).
  for (std::size_t b = 0; b < pieces.size();) {
    const std::uint32_t l = pieces[b].loop;
    std::size_t e = b;
    while (e < pieces.size() && pieces[e].loop == l) ++e;
    if (!crossed[l] && chains[l].closed) {
      // Validity cannot change along a crude loop that crosses nothing. With a single input
      // loop its orientation tells the true offset from an inverted remnant; with several,
      // it may also lie wholly within d of another input loop (a band thinner than 2d), so
      // one piece is tested by distance.
      // A loop with an inside-out arc is the offset of a stretch narrower than 2d: its
      // inverted part comes closer than d to the arc it came from, and with no crossing
      // the whole loop goes with it.
      const bool same_way = (crude_area2[l] < 0) == (chains[l].input_area2 < 0);
      std::uint8_t ok = same_way && !chains[l].inverted;
      if (ok && par.several_inputs) {
        std::size_t best = b;
        for (std::size_t k = b + 1; k < e; ++k)
          if ((pieces[k].s.b - pieces[k].s.a).squaredNorm() >
              (pieces[best].s.b - pieces[best].s.a).squaredNorm())
            best = k;
        ok = valid(pieces[best].s, raw_of(best), tol::kOffsetValid) ? 1 : 0;
      }
      for (std::size_t k = b; k < e; ++k) keep[k] = ok;
    } else {
      // Every run (cyclic on a closed chain) is valid or invalid as a whole: test its
      // longest piece. A piece that misses by less than kOffsetMarginal may sit where the
      // run's validity changes after all, at the boundary of an input curve's neighbourhood
      // that no crude loop follows (round the far side of a hooked spike's tip): then the
      // run is what most of its length is.
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
        std::uint8_t ok = valid(pieces[best].s, raw_of(best), tol::kOffsetValid) ? 1 : 0;
        if (!ok && len > 1 && valid(pieces[best].s, raw_of(best), tol::kOffsetMarginal)) {
          double in = 0, out = 0;
          for (std::size_t q = 0; q < len; ++q) {
            const std::size_t k = b + (first + r + q) % m;
            (valid(pieces[k].s, raw_of(k), tol::kOffsetValid) ? in : out) += length(pieces[k].s);
          }
          ok = in > out ? 1 : 0;
        }
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
  // Away from crossings a piece continues into the next piece of its own chain (cyclic on a
  // closed one); only pieces starting at crossings are looked up by position.
  constexpr std::uint32_t kNone = 0xffffffffu;
  std::vector<std::uint32_t> succ(pieces.size());
  for (std::size_t b = 0; b < pieces.size();) {
    std::size_t e = b;
    while (e < pieces.size() && pieces[e].loop == pieces[b].loop) ++e;
    const std::uint32_t wrap =
        chains[pieces[b].loop].closed ? static_cast<std::uint32_t>(b) : kNone;
    for (std::size_t k = b; k < e; ++k)
      succ[k] = k + 1 < e ? static_cast<std::uint32_t>(k + 1) : wrap;
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
  // Loops start at their first kept piece in raw order (by rank when given: a windowed
  // dissection then lists the complete one's loops, each from the same piece).
  std::vector<std::uint32_t> by_rank;
  if (rank) {
    by_rank.resize(n);
    for (std::uint32_t i = 0; i < n; ++i) by_rank[i] = i;
    std::sort(by_rank.begin(), by_rank.end(),
              [&](std::uint32_t a, std::uint32_t b) { return (*rank)[a] < (*rank)[b]; });
  }
  for (std::size_t ri = 0; ri < n; ++ri) {
    const std::size_t i = rank ? by_rank[ri] : ri;
    for (std::uint32_t k0 = first_piece[i]; k0 < first_piece[i + 1]; ++k0) {
      if (!keep[k0]) continue;
      OffsetLoop loop;
      std::vector<std::uint32_t> used;
      std::uint32_t k = k0;
      bool closed = false;
      for (std::size_t guard = 0; guard <= pieces.size(); ++guard) {
        keep[k] = 0;
        used.push_back(k);
        loop.segs.push_back(pieces[k].s);
        loop.parents.push_back(chains[pieces[k].loop].input);
        const Vec2 end = pieces[k].s.b;
        if ((end - pieces[k0].s.a).norm() <= 10 * eps) {
          closed = true;
          break;
        }
        const std::uint32_t sk = succ[k];
        std::int64_t nk;
        if (sk != kNone && !pieces[sk].at_crossing && (pieces[sk].s.a - end).norm() <= 10 * eps)
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
  }
  // Orientation check: offsetting a bounded pocket (its largest loop is a clockwise
  // boundary) can only leave holes inside boundaries. A counter-clockwise loop outside every
  // clockwise one is what is left of islands after the boundary closed over them. (An
  // unbounded region - the complement of a pocket, offset to dilate it - has no such rule.)
  if (par.pocket) {
    std::vector<std::uint8_t> ok(res.loops.size());
    for (std::size_t i = 0; i < res.loops.size(); ++i) {
      ok[i] = res.loops[i].area2 < 0;
      for (const OffsetLoop& o : res.loops)
        if (!ok[i] && o.area2 < 0 && winding_number(o.segs, res.loops[i].segs.front().a) != 0)
          ok[i] = 1;
    }
    std::vector<OffsetLoop> kept;
    for (std::size_t i = 0; i < res.loops.size(); ++i) {
      if (ok[i])
        kept.push_back(std::move(res.loops[i]));
      else
        ++res.stats.dropped_holes;
    }
    res.loops = std::move(kept);
  }
  return res;
}

}  // namespace ncpath::pocket_detail
