// The planar map of the z-level contour pieces, its faces and where they decide (see
// kernels/scan/zlevel_map.hpp).
#include "kernels/scan/zlevel_map.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <tuple>
#include <utility>

namespace ncpath::zlevel_detail {

namespace {

constexpr double kPi = std::numbers::pi;

// Counter-clockwise order of the ends around a vertex by their angles (place_ends); angles
// closer than tol::kZLevelTangentTie (pieces leaving the very same point tangentially and
// bending alike) by turn, then end index.
struct EndOrder {
  std::vector<double> angle, turn;

  bool tied(std::uint32_t a, std::uint32_t b) const {
    const double d = std::abs(angle[a] - angle[b]);
    return std::min(d, 2 * kPi - d) <= tol::kZLevelTangentTie;
  }
  void sort(std::vector<std::uint32_t>::iterator first,
            std::vector<std::uint32_t>::iterator last) const {
    std::sort(first, last, [&](std::uint32_t a, std::uint32_t b) {
      return angle[a] != angle[b] ? angle[a] < angle[b] : a < b;
    });
    const std::ptrdiff_t deg = last - first;
    // Start after a gap so that no run of ties wraps around -pi = pi.
    std::ptrdiff_t s = 0;
    while (s < deg && tied(first[(s + deg - 1) % deg], first[s])) ++s;
    if (s == deg) s = 0;
    std::rotate(first, first + s, last);
    for (auto r = first; r != last;) {
      auto e = r + 1;
      while (e != last && tied(*(e - 1), *e)) ++e;
      std::sort(r, e, [&](std::uint32_t a, std::uint32_t b) {
        return turn[a] != turn[b] ? turn[a] < turn[b] : a < b;
      });
      r = e;
    }
  }
};

}  // namespace

PieceMap::PieceMap(const std::vector<Curve>& curves, const std::vector<Piece>& pieces,
                   const std::vector<std::uint8_t>& keep, bool rotations)
    : curves_(curves), pieces_(pieces) {
  cluster_ends();
  for (std::size_t k = 0; k < pieces_.size(); ++k) dead_[k] |= keep[k] == kInterior;
  drop_duplicates(keep);
  if (rotations) sort_rotations();
}

std::vector<std::uint32_t> PieceMap::degrees() const {
  std::vector<std::uint32_t> deg(vertices_, 0);
  for (std::uint32_t e = 0; e < vertex_.size(); ++e)
    if (!dead_[e / 2]) ++deg[vertex_[e]];
  return deg;
}

std::uint32_t PieceMap::turn_from(std::uint32_t e, int step) const {
  const std::uint32_t v = vertex_[e];
  const std::uint32_t deg = rot_start_[v + 1] - rot_start_[v];
  return rot_[rot_start_[v] + (pos_[e] + std::uint32_t(int(deg) + step)) % deg];
}

// Ends within tol::kZLevelLink are one vertex; pieces whose two ends are one vertex are
// slivers and left out.
void PieceMap::cluster_ends() {
  const std::size_t n = 2 * pieces_.size();
  std::vector<Vec2> pts(n);
  for (std::size_t k = 0; k < pieces_.size(); ++k) {
    pts[2 * k] = pieces_[k].a;
    pts[2 * k + 1] = pieces_[k].b;
  }
  // By x, then by end index (the keys sorted by value: no indirection in the comparisons).
  std::vector<std::pair<double, std::uint32_t>> order(n);
  for (std::uint32_t e = 0; e < n; ++e) order[e] = {pts[e].x(), e};
  std::sort(order.begin(), order.end());
  Dsu dsu(n);
  const double link = tol::kZLevelLink;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n && order[j].first - order[i].first <= link; ++j)
      if ((pts[order[j].second] - pts[order[i].second]).norm() <= link)
        dsu.unite(order[i].second, order[j].second);
  std::vector<std::uint32_t> id(n, kNone);
  vertex_.resize(n);
  vertices_ = 0;
  for (std::uint32_t e = 0; e < n; ++e) {
    const std::uint32_t r = dsu.find(e);
    if (id[r] == kNone) id[r] = vertices_++;
    vertex_[e] = id[r];
  }
  dead_.resize(pieces_.size());
  for (std::size_t k = 0; k < pieces_.size(); ++k) dead_[k] = vertex_[2 * k] == vertex_[2 * k + 1];
  all_start_.assign(vertices_ + 1, 0);
  for (std::uint32_t e = 0; e < n; ++e) ++all_start_[vertex_[e] + 1];
  for (std::uint32_t v = 0; v < vertices_; ++v) all_start_[v + 1] += all_start_[v];
  all_.resize(n);
  std::vector<std::uint32_t> fill(all_start_.begin(), all_start_.end() - 1);
  for (std::uint32_t e = 0; e < n; ++e) all_[fill[vertex_[e]]++] = e;
}

// Pieces joining the same two vertices, one's midpoint within tol::kZLevelDuplicate of the
// other, are one edge (nearly coincident curves of different elements, e.g. the clip lines of
// nearly coplanar facets): one the classification keeps stays (the others lie inside U), of
// those the lowest element id's. Two such pieces would bound a face too thin to decide, and
// two straight pieces through the same two points cannot be ordered consistently around both.
void PieceMap::drop_duplicates(const std::vector<std::uint8_t>& keep) {
  std::vector<std::uint32_t> live;
  for (std::uint32_t k = 0; k < pieces_.size(); ++k)
    if (!dead_[k]) live.push_back(k);
  auto key = [&](std::uint32_t k) {
    const std::uint32_t u = vertex_[2 * k], v = vertex_[2 * k + 1];
    return std::pair(std::min(u, v), std::max(u, v));
  };
  auto rank = [&](std::uint32_t k) {
    return std::tuple(keep[k] != kKept, curves_[pieces_[k].curve].element, k);
  };
  std::sort(live.begin(), live.end(), [&](std::uint32_t a, std::uint32_t b) {
    return key(a) != key(b) ? key(a) < key(b) : rank(a) < rank(b);
  });
  for (std::size_t i = 0; i < live.size();) {
    std::size_t j = i + 1;
    while (j < live.size() && key(live[j]) == key(live[i])) ++j;
    for (std::size_t q = i + 1; q < j; ++q)
      for (std::size_t r = i; r < q; ++r)
        if (!dead_[live[r]] && beside(live[q], live[r])) {
          dead_[live[q]] = 1;
          break;
        }
    i = j;
  }
}

// Whether piece q's midpoint lies within tol::kZLevelDuplicate of piece r's curve.
bool PieceMap::beside(std::uint32_t q, std::uint32_t r) const {
  const Curve& c = curves_[pieces_[r].curve];
  const Vec2 m = midpoint(q);
  const double s = std::clamp(curve_param(c, m), pieces_[r].s0, pieces_[r].s1);
  return (curve_point(c, s) - m).norm() <= tol::kZLevelDuplicate;
}

Vec2 PieceMap::midpoint(std::uint32_t k) const {
  const Piece& p = pieces_[k];
  return curve_point(curves_[p.curve], 0.5 * (p.s0 + p.s1));
}

// Each vertex's ends counter-clockwise (EndOrder): by where the pieces cross a circle around
// the vertex (their ends spread over it; where several run side by side, their places there,
// not their directions, tell their order, the same at both ends of a piece), ties by turn.
void PieceMap::sort_rotations() {
  const std::size_t n = 2 * pieces_.size();
  EndOrder ord;
  ord.angle.resize(n);
  ord.turn.resize(n);
  rot_start_.assign(vertices_ + 1, 0);
  for (std::uint32_t e = 0; e < n; ++e)
    if (!dead_[e / 2]) ++rot_start_[vertex_[e] + 1];
  for (std::uint32_t v = 0; v < vertices_; ++v) rot_start_[v + 1] += rot_start_[v];
  rot_.resize(rot_start_.back());
  pos_.assign(n, kNone);
  std::vector<std::uint32_t> fill(rot_start_.begin(), rot_start_.end() - 1);
  for (std::uint32_t e = 0; e < n; ++e)
    if (!dead_[e / 2]) rot_[fill[vertex_[e]]++] = e;
  for (std::uint32_t v = 0; v < vertices_; ++v) {
    const auto first = rot_.begin() + rot_start_[v], last = rot_.begin() + rot_start_[v + 1];
    if (last - first > 2) {
      place_ends({&*first, std::size_t(last - first)}, ord.angle, ord.turn);
      ord.sort(first, last);
    }
    for (auto it = first; it != last; ++it) pos_[*it] = std::uint32_t(it - first);
  }
}

// Angle (about the vertex's first end) of the point where each end's piece leaves the circle
// of radius max(4 spread, tol::kZLevelOrderRadius) (its far end if it stays inside), and the
// piece's turn at the end (its curvature leaving the vertex).
void PieceMap::place_ends(std::span<const std::uint32_t> ends, std::vector<double>& angle,
                          std::vector<double>& turn) const {
  const Vec2 c = end_point(ends[0]);
  double spread = 0;
  for (std::uint32_t e : ends) spread = std::max(spread, (end_point(e) - c).norm());
  const double r = std::max(4 * spread, tol::kZLevelOrderRadius);
  for (std::uint32_t e : ends) {
    const Piece& p = pieces_[e / 2];
    const Curve& cv = curves_[p.curve];
    const bool at_end = e & 1;
    const double from = at_end ? p.s1 : p.s0, to = at_end ? p.s0 : p.s1;
    const double k = curve_curvature(cv, from);
    turn[e] = at_end ? -k : k;
    // The first of 8 samples beyond r, then bisection back to the circle.
    double lo = from, hi = to;
    Vec2 x = end_point(e ^ 1);
    for (int j = 1; j <= 8; ++j) {
      const double s = from + (to - from) * j / 8;
      if ((curve_point(cv, s) - c).norm() > r) {
        hi = s;
        for (int it2 = 0; it2 < 60; ++it2) {
          const double m = 0.5 * (lo + hi);
          ((curve_point(cv, m) - c).norm() > r ? hi : lo) = m;
        }
        x = curve_point(cv, hi);
        break;
      }
      lo = s;
    }
    angle[e] = std::atan2(x.y() - c.y(), x.x() - c.x());
  }
}

Faces decide_faces(const PieceMap& map, const std::vector<Piece>& pieces,
                   const std::vector<std::uint8_t>& keep) {
  Faces f;
  f.face.assign(map.half_edges(), kNone);
  std::vector<std::uint32_t> cycle;
  for (std::uint32_t h0 = 0; h0 < map.half_edges(); ++h0) {
    if (f.face[h0] != kNone || map.dead(h0 / 2)) continue;
    const auto id = std::uint32_t(f.inside.size());
    cycle.clear();
    for (std::uint32_t h = h0; f.face[h] == kNone; h = map.next(h)) {
      f.face[h] = id;
      cycle.push_back(h);
    }
    double in = 0, out = 0;
    for (std::uint32_t h : cycle) {
      if (f.face[h ^ 1] == id) continue;
      const Piece& p = pieces[h / 2];
      const double len = (p.b - p.a).norm();
      if (!(h & 1)) {
        in += len;
        continue;
      }
      (keep[h / 2] == kKept ? out : in) += len;
    }
    f.inside.push_back(in >= out);
  }
  return f;
}

std::vector<std::uint8_t> sound_pieces(const PieceMap& map, const Faces& faces,
                                       const std::vector<Piece>& pieces,
                                       const std::vector<std::uint8_t>& keep) {
  const auto n = std::uint32_t(pieces.size());
  Dsu dsu(map.vertex_count());
  for (std::uint32_t k = 0; k < n; ++k)
    if (!map.dead(k)) dsu.unite(map.start_vertex(k), map.end_vertex(k));
  const std::uint32_t nv = map.vertex_count();
  std::vector<std::int64_t> euler(nv, 0);  // per root: V - E + F
  std::vector<std::uint8_t> vseen(nv, 0), fseen(faces.inside.size(), 0), bad(nv, 0);
  for (std::uint32_t k = 0; k < n; ++k) {
    if (map.dead(k)) continue;
    const std::uint32_t r = dsu.find(map.start_vertex(k));
    for (std::uint32_t v : {map.start_vertex(k), map.end_vertex(k)})
      if (!vseen[v]) {
        vseen[v] = 1;
        ++euler[r];
      }
    --euler[r];
    for (std::uint32_t h : {2 * k, 2 * k + 1})
      if (!fseen[faces.face[h]]) {
        fseen[faces.face[h]] = 1;
        ++euler[r];
      }
    if (keep[k] == kKept && faces.face[2 * k] == faces.face[2 * k + 1]) bad[r] = 1;
  }
  std::vector<std::uint8_t> sound(n, 0);
  for (std::uint32_t k = 0; k < n; ++k) {
    const std::uint32_t r = dsu.find(map.start_vertex(k));
    sound[k] = !bad[r] && euler[r] == 2;
  }
  return sound;
}

void attach_loose_ends(const std::vector<Curve>& curves, std::vector<Piece>& pieces,
                       std::vector<std::uint8_t>& keep) {
  const PieceMap map(curves, pieces, keep, false);
  const std::vector<std::uint32_t> deg = map.degrees();
  const auto n = std::uint32_t(pieces.size());
  std::vector<std::uint32_t> by_x;  // live pieces by their box's low x
  std::vector<std::array<double, 4>> box(n);
  double widest = 0;
  for (std::uint32_t k = 0; k < n; ++k) {
    if (map.dead(k)) continue;
    const Curve& c = curves[pieces[k].curve];
    box[k] = {INFINITY, INFINITY, -INFINITY, -INFINITY};
    for (int j = 0; j <= 4; ++j) {  // arcs span at most pi / 2: their chord box grown by half
      const Vec2 q = curve_point(c, pieces[k].s0 + (pieces[k].s1 - pieces[k].s0) * j / 4);
      box[k] = {std::min(box[k][0], q.x()), std::min(box[k][1], q.y()),
                std::max(box[k][2], q.x()), std::max(box[k][3], q.y())};
    }
    const double grow = 0.5 * std::max(box[k][2] - box[k][0], box[k][3] - box[k][1]);
    if (c.kind != CurveKind::kLine)
      box[k] = {box[k][0] - grow, box[k][1] - grow, box[k][2] + grow, box[k][3] + grow};
    widest = std::max(widest, box[k][2] - box[k][0]);
    by_x.push_back(k);
  }
  std::sort(by_x.begin(), by_x.end(), [&](std::uint32_t a, std::uint32_t b) {
    return box[a][0] != box[b][0] ? box[a][0] < box[b][0] : a < b;
  });
  const double r = tol::kZLevelLink;
  struct Cut {
    std::uint32_t piece;
    double s;
    Vec2 at;
  };
  std::vector<Cut> cuts;
  for (std::uint32_t e = 0; e < 2 * n; ++e) {
    if (map.dead(e / 2) || deg[map.vertex_of(e)] != 1) continue;
    const Vec2 x = (e & 1) ? pieces[e / 2].b : pieces[e / 2].a;
    auto it = std::lower_bound(by_x.begin(), by_x.end(), x.x() - r - widest,
                               [&](std::uint32_t k, double v) { return box[k][0] < v; });
    double best = r;
    Cut cut{kNone, 0, x};
    for (; it != by_x.end() && box[*it][0] <= x.x() + r; ++it) {
      const std::uint32_t k = *it;
      if (k == e / 2 || x.x() > box[k][2] + r || x.y() < box[k][1] - r || x.y() > box[k][3] + r)
        continue;
      const Curve& c = curves[pieces[k].curve];
      const double sp = curve_param(c, x);
      if (!(sp > pieces[k].s0 && sp < pieces[k].s1)) continue;
      const double d = (curve_point(c, sp) - x).norm();
      if (d < best) {
        best = d;
        cut = {k, sp, x};
      }
    }
    if (cut.piece != kNone) cuts.push_back(cut);
  }
  std::sort(cuts.begin(), cuts.end(), [](const Cut& a, const Cut& b) {
    return a.piece != b.piece ? a.piece < b.piece : a.s < b.s;
  });
  for (std::size_t i = 0; i < cuts.size(); ++i) {
    const Cut& c = cuts[i];
    Piece& p = pieces[c.piece];
    if (!(c.s > p.s0 && c.s < p.s1)) continue;  // an earlier cut of the piece passed it
    // The part before the cut stays in place, the rest is appended (later cuts of this piece
    // lie in the rest, sorted by s).
    Piece rest = p;
    rest.s0 = c.s;
    rest.a = c.at;
    p.s1 = c.s;
    p.b = c.at;
    pieces.push_back(rest);
    keep.push_back(keep[c.piece]);
    for (std::size_t j = i + 1; j < cuts.size() && cuts[j].piece == c.piece; ++j)
      cuts[j].piece = std::uint32_t(pieces.size() - 1);
  }
}

}  // namespace ncpath::zlevel_detail
