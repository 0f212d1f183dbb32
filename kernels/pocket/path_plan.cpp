#include "kernels/pocket/path_plan.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <memory>
#include <numeric>
#include <tuple>

#include "kernels/curves/intersect.hpp"
#include "kernels/geom/tolerance.hpp"
#include "kernels/pocket/offset.hpp"
#include "kernels/pocket/seg_grid.hpp"

namespace ncpath {

namespace {

using pocket_detail::SegGrid;
constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

// A point of a loop: segment index, parameter on it, the point itself.
struct Pos {
  std::uint32_t seg = 0;
  double t = 0;
  Vec2 p = Vec2::Zero();
};

Pos pos_on(const std::vector<Seg2>& segs, std::uint32_t i, const Vec2& q) {
  const double t = parameter_of(segs[i], q);
  return {i, t, point_at(segs[i], t)};
}

// The same point on the reversed loop (reversed_loop below).
Pos flip(const Pos& q, std::size_t n) {
  return {static_cast<std::uint32_t>(n - 1 - q.seg), 1 - q.t, q.p};
}

std::vector<Seg2> reversed_loop(const std::vector<Seg2>& segs) {
  std::vector<Seg2> r;
  r.reserve(segs.size());
  for (auto it = segs.rbegin(); it != segs.rend(); ++it) r.push_back(reversed(*it));
  return r;
}

// Lazily built segment grids of the loops, for nearest-point queries.
class Grids {
 public:
  Grids(const std::vector<PlanLoop>& loops, double cell)
      : loops_(loops), cell_(cell), grids_(loops.size()) {}
  // The point of loop l nearest to p, if closer than limit.
  bool near(std::uint32_t l, const Vec2& p, double limit, Pos& out) {
    if (!grids_[l]) grids_[l] = std::make_unique<SegGrid>(*loops_[l].segs, cell_);
    std::uint32_t seg = 0;
    double d = 0;
    if (!grids_[l]->nearest_within(p, limit, seg, d)) return false;
    out = pos_on(*loops_[l].segs, seg, p);
    return true;
  }

 private:
  const std::vector<PlanLoop>& loops_;
  double cell_;
  std::vector<std::unique_ptr<SegGrid>> grids_;
};

// The first vertex of `from` (in order) within limit of loop `to`.
bool scan_pair(Grids& grids, const std::vector<Seg2>& from, std::uint32_t to, double limit,
               Pos& on_from, Pos& on_to) {
  for (std::uint32_t i = 0; i < from.size(); ++i) {
    if (grids.near(to, from[i].a, limit, on_to)) {
      on_from = {i, 0, from[i].a};
      return true;
    }
  }
  return false;
}

// The pair of points (a vertex of one loop, its nearest point on the other) at the smallest
// distance found; exact for lines, a close upper bound where two arcs face each other.
double nearest_pair(Grids& grids, const std::vector<PlanLoop>& loops, std::uint32_t a,
                    std::uint32_t b, Pos& on_a, Pos& on_b) {
  double best = std::numeric_limits<double>::infinity();
  for (int side = 0; side < 2; ++side) {
    const std::uint32_t from = side == 0 ? a : b, to = side == 0 ? b : a;
    const std::vector<Seg2>& fs = *loops[from].segs;
    for (std::uint32_t i = 0; i < fs.size(); ++i) {
      double limit = best;
      if (!std::isfinite(limit)) {
        limit = 0;
        for (const Seg2& s : *loops[to].segs) limit = std::max(limit, distance(s, fs[i].a));
        limit += 1;
      }
      Pos hit;
      if (!grids.near(to, fs[i].a, limit, hit)) continue;
      const double d = (hit.p - fs[i].a).norm();
      if (d >= best) continue;
      best = d;
      (side == 0 ? on_a : on_b) = {i, 0, fs[i].a};
      (side == 0 ? on_b : on_a) = hit;
    }
  }
  return best;
}

std::uint32_t find_root(std::vector<std::uint32_t>& up, std::uint32_t x) {
  while (up[x] != x) x = up[x] = up[up[x]];
  return x;
}

}  // namespace

bool segment_inside(const std::vector<const std::vector<Seg2>*>& region, const Vec2& a,
                    const Vec2& b) {
  if ((a - b).norm() <= tol::kLinkSlack) return true;
  const Seg2 line = make_line(a, b);
  Vec2 lo, hi;
  bounds(line, lo, hi);
  int winding = 0;
  const Vec2 mid = 0.5 * (a + b);
  for (const std::vector<Seg2>* loop : region) {
    for (const Seg2& s : *loop) {
      Vec2 slo, shi;
      loose_bounds(s, slo, shi);
      if (slo.x() > hi.x() || shi.x() < lo.x() || slo.y() > hi.y() || shi.y() < lo.y()) continue;
      SegHit hits[2];
      const int n = intersect(line, s, hits, tol::kOffsetPoint, false);
      for (int k = 0; k < n; ++k) {
        if ((hits[k].p - a).norm() > tol::kLinkSlack && (hits[k].p - b).norm() > tol::kLinkSlack)
          return false;
      }
    }
    winding += winding_number(*loop, mid);
  }
  return winding < 0;
}

std::vector<SameLevelEdge> same_level_edges(const std::vector<PlanLoop>& loops) {
  const auto n = static_cast<std::uint32_t>(loops.size());
  std::vector<std::uint32_t> up(n);
  std::iota(up.begin(), up.end(), 0u);
  for (std::uint32_t l = 0; l < n; ++l)
    for (std::uint32_t p : loops[l].parents) up[find_root(up, l)] = find_root(up, p);
  // Groups, deepest level first.
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t x, std::uint32_t y) {
    return std::tie(loops[y].level, loops[x].group) < std::tie(loops[x].level, loops[y].group);
  });
  std::vector<SameLevelEdge> out;
  double cell = 1;
  Grids grids(loops, cell);
  for (std::size_t i = 0; i < order.size();) {
    std::size_t j = i;
    while (j < order.size() && loops[order[j]].group == loops[order[i]].group) ++j;
    const std::vector<std::uint32_t> group(order.begin() + static_cast<std::ptrdiff_t>(i),
                                           order.begin() + static_cast<std::ptrdiff_t>(j));
    i = j;
    if (group.size() < 2) continue;
    std::vector<const std::vector<Seg2>*> region;
    for (std::uint32_t l : group) region.push_back(loops[l].segs);
    // Join every loop to the group's first until all are connected (candidates nearest
    // first; a join must not cross another loop of the group).
    for (std::uint32_t h : group) {
      if (find_root(up, h) == find_root(up, group[0])) continue;
      std::vector<std::tuple<double, std::uint32_t, Pos, Pos>> cands;
      for (std::uint32_t t : group) {
        if (find_root(up, t) == find_root(up, h)) continue;
        Pos ph, pt;
        const double d = nearest_pair(grids, loops, h, t, ph, pt);
        if (std::isfinite(d)) cands.emplace_back(d, t, ph, pt);
      }
      std::stable_sort(cands.begin(), cands.end(), [](const auto& x, const auto& y) {
        return std::get<0>(x) < std::get<0>(y);
      });
      for (const auto& [d, t, ph, pt] : cands) {
        if (!segment_inside(region, ph.p, pt.p)) continue;
        out.push_back({h, t, ph.p, pt.p});
        up[find_root(up, h)] = find_root(up, t);
        break;
      }
    }
  }
  return out;
}

std::vector<std::vector<std::uint32_t>> connected_parts(const std::vector<PlanLoop>& loops,
                                                        const std::vector<SameLevelEdge>& extra) {
  const auto n = static_cast<std::uint32_t>(loops.size());
  std::vector<std::uint32_t> up(n);
  std::iota(up.begin(), up.end(), 0u);
  for (std::uint32_t l = 0; l < n; ++l)
    for (std::uint32_t p : loops[l].parents) up[find_root(up, l)] = find_root(up, p);
  for (const SameLevelEdge& e : extra) up[find_root(up, e.a)] = find_root(up, e.b);
  std::vector<std::vector<std::uint32_t>> parts;
  std::vector<std::uint32_t> part_of(n, kNone);
  for (std::uint32_t l = 0; l < n; ++l) {
    const std::uint32_t r = find_root(up, l);
    if (part_of[r] == kNone) {
      part_of[r] = static_cast<std::uint32_t>(parts.size());
      parts.emplace_back();
    }
    parts[part_of[r]].push_back(l);
  }
  return parts;
}

namespace {

// Plans one part: tree, links, clean-up attachments, then the path by DFS.
class PartPlanner {
 public:
  PartPlanner(const std::vector<PlanLoop>& loops, const std::vector<SameLevelEdge>& extra,
              const std::vector<CleanupLoop>& cleanups, const PlanParams& params)
      : loops_(loops),
        extra_(extra),
        cleanups_(cleanups),
        prm_(params),
        grids_(loops, std::max(params.stepover, params.tool_radius)),
        n_(loops.size()),
        adj_(n_),
        parent_(n_, kNone),
        edge_(n_, kNone),
        children_(n_),
        entry_(n_),
        link_from_(n_),
        direct_(n_, false),
        forward_(n_, true),
        last_(n_, kNone),
        size_(n_, 1),
        pre_(n_, kNone),
        attached_(n_) {
    for (std::uint32_t l = 0; l < n_; ++l)
      for (std::uint32_t p : loops[l].parents) {
        adj_[l].push_back({p, kNone});
        adj_[p].push_back({l, kNone});
      }
    for (std::uint32_t e = 0; e < extra.size(); ++e) {
      adj_[extra[e].a].push_back({extra[e].b, e});
      adj_[extra[e].b].push_back({extra[e].a, e});
    }
    for (auto& a : adj_) std::sort(a.begin(), a.end());
  }

  PlannedPath run(const std::vector<std::uint32_t>& part, std::uint32_t root, const Vec2& start) {
    out_ = {};
    out_.root = root;
    out_.loops = part;
    root_ = root;
    build_tree(root);
    place_links(root, start);
    std::uint32_t counter = 0;
    preorder(root, false, counter);
    attach_cleanups(part);
    emit(root, false);
    out_.start = entry_[root].p;
    // The way back to the start for the next depth pass: straight when that stays inside
    // the part's first level (all of it is cut by then), else the one-way links reversed.
    std::vector<const std::vector<Seg2>*> top;
    for (std::uint32_t l : part)
      if (loops_[l].level == 1) top.push_back(loops_[l].segs);
    const Vec2 end = out_.moves.empty() ? out_.start : out_.moves.back().seg.b;
    if (segment_inside(top, end, out_.start)) {
      if ((end - out_.start).norm() > 0)
        out_.back.push_back({make_line(end, out_.start), MoveKind::kLink});
    } else {
      for (auto it = spine_.rbegin(); it != spine_.rend(); ++it)
        out_.back.push_back({reversed(it->seg), MoveKind::kLink});
    }
    return std::move(out_);
  }

 private:
  struct Adj {
    std::uint32_t to, edge;  // edge: same-level edge index, or kNone for an OGH edge
    bool operator<(const Adj& o) const { return std::tie(to, edge) < std::tie(o.to, o.edge); }
  };
  struct Attach {
    Pos at;  // on the level loop (stored direction)
    std::uint32_t cleanup;
    std::uint32_t vertex;  // of the clean-up loop
  };
  struct Event {
    std::uint32_t off;
    double t;
    Pos at;  // on the oriented loop
    bool child;
    std::uint32_t id;  // child loop or index into attached_[x]
  };

  const std::vector<Seg2>& segs(std::uint32_t l) const { return *loops_[l].segs; }

  void build_tree(std::uint32_t root) {
    std::deque<std::uint32_t> queue{root};
    std::vector<bool> seen(n_, false);
    seen[root] = true;
    while (!queue.empty()) {
      const std::uint32_t x = queue.front();
      queue.pop_front();
      bfs_.push_back(x);
      for (const Adj& a : adj_[x]) {
        if (seen[a.to]) continue;
        seen[a.to] = true;
        parent_[a.to] = x;
        edge_[a.to] = a.edge;
        children_[x].push_back(a.to);
        queue.push_back(a.to);
      }
    }
    for (auto it = bfs_.rbegin(); it != bfs_.rend(); ++it)
      if (parent_[*it] != kNone) size_[parent_[*it]] += size_[*it];
    // Cutting direction (see the header).
    for (std::uint32_t x : bfs_) {
      bool outward;
      if (parent_[x] == kNone)
        outward = prm_.outward;
      else
        outward = loops_[parent_[x]].level > loops_[x].level;
      forward_[x] = outward != prm_.climb;
    }
  }

  void place_links(std::uint32_t root, const Vec2& start) {
    std::uint32_t seg = 0;
    double d = 0;
    SegGrid grid(segs(root), prm_.stepover);
    grid.nearest_within(start, std::numeric_limits<double>::infinity(), seg, d);
    entry_[root] = pos_on(segs(root), seg, start);
    for (std::uint32_t x : bfs_) {
      // The one-way child: the largest subtree (fewest links travelled twice).
      for (std::uint32_t c : children_[x])
        if (last_[x] == kNone || size_[c] > size_[last_[x]]) last_[x] = c;
      for (std::uint32_t c : children_[x]) {
        ++out_.links;
        if (edge_[c] != kNone) {
          const SameLevelEdge& e = extra_[edge_[c]];
          const bool x_is_a = e.a == x;
          link_from_[c] = locate(x, x_is_a ? e.pa : e.pb);
          entry_[c] = locate(c, x_is_a ? e.pb : e.pa);
          continue;
        }
        // Links span one level step: the inner loop's distance from its parents.
        const std::uint32_t deeper = loops_[x].level > loops_[c].level ? x : c;
        const double step = loops_[deeper].step > 0 ? loops_[deeper].step : prm_.stepover;
        const double reach = step + tol::kLinkSlack;
        Pos q;
        if (grids_.near(c, entry_[x].p, reach, q)) {
          link_from_[c] = entry_[x];
          entry_[c] = q;
          direct_[c] = true;
          continue;
        }
        // A vertex of the inner loop within the stepover of the outer one.
        const bool x_inner = loops_[x].level > loops_[c].level;
        const std::uint32_t inner = x_inner ? x : c, outer = x_inner ? c : x;
        Pos on_inner, on_outer;
        if (!scan_pair(grids_, segs(inner), outer, reach, on_inner, on_outer)) {
          ++out_.long_links;
          nearest_pair(grids_, loops_, inner, outer, on_inner, on_outer);
        }
        link_from_[c] = x_inner ? on_inner : on_outer;
        entry_[c] = x_inner ? on_outer : on_inner;
      }
    }
  }

  // The position on loop l of a point known to lie on it.
  Pos locate(std::uint32_t l, const Vec2& p) {
    Pos q;
    grids_.near(l, p, 1, q);
    q.p = p;
    return q;
  }

  // Event key of an oriented position relative to the oriented entry.
  static std::uint32_t offset_of(const Pos& q, const Pos& e, std::size_t n) {
    std::uint32_t off = static_cast<std::uint32_t>((q.seg + n - e.seg) % n);
    if (off == 0 && q.t < e.t) off = static_cast<std::uint32_t>(n);
    return off;
  }
  Pos oriented(std::uint32_t x, const Pos& q) const {
    return forward_[x] ? q : flip(q, segs(x).size());
  }

  // Children and clean-ups of x met along its traversal, sorted; the one-way child is
  // excluded unless x returns.
  std::vector<Event> events(std::uint32_t x, bool returning) const {
    const std::size_t n = segs(x).size();
    const Pos e = oriented(x, entry_[x]);
    std::vector<Event> ev;
    for (std::uint32_t c : children_[x]) {
      if (!returning && c == last_[x]) continue;
      const Pos q = oriented(x, link_from_[c]);
      ev.push_back({offset_of(q, e, n), q.t, q, true, c});
    }
    for (std::uint32_t k = 0; k < attached_[x].size(); ++k) {
      const Pos q = oriented(x, attached_[x][k].at);
      ev.push_back({offset_of(q, e, n), q.t, q, false, k});
    }
    std::sort(ev.begin(), ev.end(), [](const Event& a, const Event& b) {
      return std::tie(a.off, a.t, a.child, a.id) < std::tie(b.off, b.t, b.child, b.id);
    });
    return ev;
  }

  // Recursion only into out-and-back subtrees (the smaller ones); the one-way chain, as
  // long as the deepest branch, is a loop.
  void preorder(std::uint32_t x, bool returning, std::uint32_t& counter) {
    for (; x != kNone; x = returning ? kNone : last_[x]) {
      pre_[x] = counter++;
      for (const Event& e : events(x, returning))
        if (e.child) preorder(e.id, true, counter);
    }
  }

  void attach_cleanups(const std::vector<std::uint32_t>& part) {
    std::vector<bool> in_part(n_, false);
    for (std::uint32_t l : part) in_part[l] = true;
    const double reach = prm_.tool_radius + tol::kLinkSlack;
    for (std::uint32_t u = 0; u < cleanups_.size(); ++u) {
      const CleanupLoop& cu = cleanups_[u];
      if (cu.bounds.empty() || !in_part[cu.bounds[0]]) continue;
      std::vector<std::uint32_t> cand = cu.bounds;
      std::stable_sort(cand.begin(), cand.end(),
                       [&](std::uint32_t a, std::uint32_t b) { return pre_[a] > pre_[b]; });
      bool done = false;
      for (std::uint32_t l : cand) {
        Pos on_u, on_l;
        if (!scan_pair(grids_, cu.segs, l, reach, on_u, on_l)) continue;
        attached_[l].push_back({on_l, u, on_u.seg});
        ++out_.cleanup_curves;
        done = true;
        break;
      }
      if (!done) out_.unattached.push_back(u);
    }
  }

  // Appends the oriented loop `o` from (off1, a) to (off2, b), offsets relative to base.
  static void walk(const std::vector<Seg2>& o, std::uint32_t base, std::uint32_t off1, const Pos& a,
                   std::uint32_t off2, const Pos& b, std::vector<Seg2>& out) {
    const std::size_t n = o.size();
    auto piece = [&](std::size_t k, const Vec2& from, const Vec2& to) {
      if ((from - to).norm() > tol::kOffsetPoint) out.push_back(sub_segment(o[k], from, to));
    };
    if (off1 == off2) {
      if (b.t > a.t) piece((base + off1) % n, a.p, b.p);
      return;
    }
    const std::size_t k1 = (base + off1) % n, k2 = (base + off2) % n;
    piece(k1, a.p, o[k1].b);
    for (std::uint32_t off = off1 + 1; off < off2; ++off) out.push_back(o[(base + off) % n]);
    piece(k2, o[k2].a, b.p);
  }

  void push(const std::vector<Seg2>& segs, MoveKind kind) {
    for (const Seg2& s : segs) out_.moves.push_back({s, kind});
  }
  void link(const Vec2& a, const Vec2& b, MoveKind kind) {
    if ((a - b).norm() <= tol::kOffsetPoint) return;
    out_.moves.push_back({make_line(a, b), kind});
    if (kind == MoveKind::kLink)
      out_.slotting_length += std::max(0.0, (a - b).norm() - prm_.tool_radius);
  }

  void emit(std::uint32_t x, bool returning) {
    while (x != kNone) x = emit_loop(x, returning);
  }

  // Emits loop x with its detours; returns the one-way child to continue with, if any.
  std::uint32_t emit_loop(std::uint32_t x, bool returning) {
    const std::vector<Seg2>& stored = segs(x);
    const std::size_t n = stored.size();
    std::vector<Seg2> rev;
    if (!forward_[x]) rev = reversed_loop(stored);
    const std::vector<Seg2>& o = forward_[x] ? stored : rev;
    const Pos e = oriented(x, entry_[x]);
    std::vector<Seg2> pieces;
    std::uint32_t off = 0;
    Pos cur = e;
    for (const Event& ev : events(x, returning)) {
      pieces.clear();
      walk(o, e.seg, off, cur, ev.off, ev.at, pieces);
      push(pieces, MoveKind::kCut);
      if (x == root_) out_.first_loop.insert(out_.first_loop.end(), pieces.begin(), pieces.end());
      if (ev.child) {
        link(ev.at.p, entry_[ev.id].p, MoveKind::kLink);
        emit(ev.id, true);
        link(entry_[ev.id].p, ev.at.p, MoveKind::kLink);
      } else {
        cleanup(ev.at.p, attached_[x][ev.id]);
      }
      off = ev.off;
      cur = ev.at;
    }
    pieces.clear();
    walk(o, e.seg, off, cur, static_cast<std::uint32_t>(n), e, pieces);
    push(pieces, MoveKind::kCut);
    if (x == root_) {
      out_.first_loop.insert(out_.first_loop.end(), pieces.begin(), pieces.end());
      out_.slotting_length += loop_length(out_.first_loop);
    }
    if (returning || last_[x] == kNone) return kNone;
    // One way into the last child: from the entry, or along the loop (already cut) to the
    // link's foot, the shorter way round.
    const std::uint32_t c = last_[x];
    const std::size_t mark = out_.moves.size();
    if (!direct_[c]) {
      const Pos p = oriented(x, link_from_[c]);
      const std::uint32_t poff = offset_of(p, e, n);
      std::vector<Seg2> ahead, behind;
      walk(o, e.seg, 0, e, poff, p, ahead);
      walk(o, e.seg, poff, p, static_cast<std::uint32_t>(n), e, behind);
      if (loop_length(ahead) <= loop_length(behind)) {
        push(ahead, MoveKind::kLink);
      } else {
        for (auto it = behind.rbegin(); it != behind.rend(); ++it)
          out_.moves.push_back({reversed(*it), MoveKind::kLink});
      }
    }
    link(link_from_[c].p, entry_[c].p, MoveKind::kLink);
    spine_.insert(spine_.end(), out_.moves.begin() + static_cast<std::ptrdiff_t>(mark),
                  out_.moves.end());
    return c;
  }

  // Detour from p on a level loop: link, the whole clean-up loop, link back.
  void cleanup(const Vec2& p, const Attach& a) {
    const std::vector<Seg2>& stored = cleanups_[a.cleanup].segs;
    const std::vector<Seg2> o = prm_.climb ? stored : reversed_loop(stored);
    const std::size_t n = o.size();
    Pos v{a.vertex, 0, stored[a.vertex].a};
    if (!prm_.climb) v = flip({a.vertex, 0, stored[a.vertex].a}, n);
    link(p, v.p, MoveKind::kCleanupLink);
    std::vector<Seg2> pieces;
    walk(o, v.seg, 0, v, static_cast<std::uint32_t>(n), v, pieces);
    push(pieces, MoveKind::kCleanup);
    link(v.p, p, MoveKind::kCleanupLink);
  }

  const std::vector<PlanLoop>& loops_;
  const std::vector<SameLevelEdge>& extra_;
  const std::vector<CleanupLoop>& cleanups_;
  PlanParams prm_;
  Grids grids_;
  std::size_t n_;
  std::vector<std::vector<Adj>> adj_;
  std::vector<std::uint32_t> parent_, edge_;
  std::vector<std::vector<std::uint32_t>> children_;
  std::vector<Pos> entry_, link_from_;
  std::vector<bool> direct_, forward_;
  std::vector<std::uint32_t> last_, size_, pre_;
  std::vector<std::vector<Attach>> attached_;
  std::vector<std::uint32_t> bfs_;
  std::vector<Move2> spine_;
  std::uint32_t root_ = 0;
  PlannedPath out_;
};

}  // namespace

PlannedPath plan_part(const std::vector<PlanLoop>& loops, const std::vector<SameLevelEdge>& extra,
                      const std::vector<CleanupLoop>& cleanups,
                      const std::vector<std::uint32_t>& part, std::uint32_t root, const Vec2& start,
                      const PlanParams& params) {
  PartPlanner planner(loops, extra, cleanups, params);
  return planner.run(part, root, start);
}

}  // namespace ncpath
