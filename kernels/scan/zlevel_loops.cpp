// Z-level contours: linking kept pieces into loops, merging, junctions, canonical output
// (kernels/scan/zlevel.hpp); segment evaluation and discretisation.
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <numeric>
#include <span>

#include "kernels/scan/zlevel_map.hpp"

namespace ncpath {

namespace zlevel_detail {

namespace {

constexpr double kPi = std::numbers::pi;

Vec2 unit(const Vec2& v) {
  const double n = v.norm();
  return n > 0 ? Vec2(v / n) : Vec2(0, 0);
}

// Clockwise angle from direction f to direction g, in (0, 2 pi].
double cw_angle(const Vec2& f, const Vec2& g) {
  double a = -std::atan2(cross2(f, g), f.dot(g));
  if (a <= 0) a += 2 * kPi;
  return a;
}

struct RawSeg {
  ContourSeg seg;
  Vec2 tin, tout;  // unit tangents at a and at b
};

// The segment of piece k run forwards, or backwards (`reversed`: an arc then runs
// clockwise, t1 < t0).
RawSeg raw_seg(const Curve& c, const Piece& k, bool reversed) {
  RawSeg r;
  ContourSeg& s = r.seg;
  const double s0 = reversed ? k.s1 : k.s0, s1 = reversed ? k.s0 : k.s1;
  s.element = c.element;
  s.shadow = c.shadow;
  s.a = reversed ? k.b : k.a;
  s.b = reversed ? k.a : k.b;
  if (c.kind != CurveKind::kLine) {
    s.kind =
        c.kind == CurveKind::kCircle ? ContourSegKind::kCircleArc : ContourSegKind::kEllipseArc;
    s.centre = c.centre;
    s.r1 = c.r1;
    s.r2 = c.r2;
    s.axis = c.axis;
    s.t0 = c.t0 + s0;
    s.t1 = c.t0 + s1;
  }
  const double sign = reversed ? -1 : 1;
  r.tin = sign * unit(curve_tangent(c, s0));
  r.tout = sign * unit(curve_tangent(c, s1));
  return r;
}

bool mergeable(const RawSeg& p, const RawSeg& q) {
  const ContourSeg &a = p.seg, &b = q.seg;
  if (a.element != b.element || a.kind != b.kind || a.shadow != b.shadow) return false;
  if (a.kind == ContourSegKind::kLine)
    return std::abs(cross2(p.tout, q.tin)) < tol::kZLevelSameDirection && p.tout.dot(q.tin) > 0;
  return a.centre == b.centre && a.r1 == b.r1 && a.r2 == b.r2 && a.axis == b.axis &&
         (a.t1 > a.t0) == (b.t1 > b.t0);
}

Vec3 contact_vector(const OffsetElements& el, const Region& g, const Vec2& x, const Level& lv) {
  const Vec3 c(x.x(), x.y(), lv.zc);
  Vec3 p = c;
  switch (g.kind) {
    case RegionKind::kFacet:
      return el.facet_normal[g.index];
    case RegionKind::kEdge: {
      double t = 0;
      region_phi(g, x, lv, nullptr, &t);
      p = g.a + t * g.d;
      break;
    }
    case RegionKind::kVertex:
      p = Vec3(g.c.x(), g.c.y(), g.vz);
      break;
  }
  p.z() = std::min(p.z(), lv.zc);  // shadow: the vertical below the element, at the level
  const Vec3 d = c - p;
  const double n = d.norm();
  return n > 0 ? Vec3(d / n) : Vec3(0, 0, 1);
}

const Region& region_of(const std::vector<Region>& regions, std::uint32_t element) {
  const auto it = std::lower_bound(regions.begin(), regions.end(), element,
                                   [](const Region& g, std::uint32_t e) { return g.element < e; });
  return *it;
}

// Emits one closed loop of kept pieces as a contour into out.
void emit_loop(const OffsetElements& el, const Level& lv, const std::vector<Region>& regions,
               const std::vector<Curve>& curves, const std::vector<Piece>& loop,
               const std::vector<std::uint8_t>& reversed, ZLevelResult& out) {
  std::vector<RawSeg> raw;
  raw.reserve(loop.size());
  for (std::size_t i = 0; i < loop.size(); ++i)
    if (loop[i].s0 < loop[i].s1) raw.push_back(raw_seg(curves[loop[i].curve], loop[i], reversed[i]));
  if (raw.empty()) return;
  // Merge runs of one element's curve, cyclically.
  const std::size_t n = raw.size();
  std::size_t first = 0;
  while (first < n && mergeable(raw[(first + n - 1) % n], raw[first])) ++first;
  std::vector<RawSeg> segs;
  if (first == n) first = 0;  // one closed curve (a full circle)
  for (std::size_t i = 0; i < n; ++i) {
    const RawSeg& r = raw[(first + i) % n];
    if (!segs.empty() && mergeable(segs.back(), r) && !(i == 0)) {
      RawSeg& m = segs.back();
      m.seg.b = r.seg.b;
      m.seg.t1 += r.seg.t1 - r.seg.t0;
      m.tout = r.tout;
    } else {
      segs.push_back(r);
    }
  }
  // Elliptic arcs within tol::kZLevelFlatArc of their chord become lines.
  for (RawSeg& r : segs) {
    ContourSeg& s = r.seg;
    if (s.kind != ContourSegKind::kEllipseArc) continue;
    const Vec2 ch = s.b - s.a;
    const double len = ch.norm();
    if (len > 0 && std::abs(cross2(ch, seg_point(s, 0.5) - s.a)) < tol::kZLevelFlatArc * len &&
        std::abs(s.t1 - s.t0) < kPi / 2) {
      s.kind = ContourSegKind::kLine;
      s.centre = Vec2::Zero();
      s.r1 = s.r2 = s.t0 = s.t1 = 0;
      s.axis = Vec2(1, 0);
    }
  }
  // Canonical start: the lowest start point (x, then y), then the lowest element.
  std::size_t start = 0;
  for (std::size_t i = 1; i < segs.size(); ++i) {
    const ContourSeg &a = segs[i].seg, &b = segs[start].seg;
    if (a.a.x() < b.a.x() || (a.a.x() == b.a.x() &&
                              (a.a.y() < b.a.y() || (a.a.y() == b.a.y() && a.element < b.element))))
      start = i;
  }
  std::rotate(segs.begin(), segs.begin() + std::ptrdiff_t(start), segs.end());
  ZContour c;
  const std::size_t m = segs.size();
  for (std::size_t i = 0; i < m; ++i) {
    const RawSeg &prev = segs[(i + m - 1) % m], &cur = segs[i];
    c.segs.push_back(cur.seg);
    if (prev.seg.element == cur.seg.element) continue;
    ZJunction j;
    j.seg = std::uint32_t(i);
    j.position = Vec3(cur.seg.a.x(), cur.seg.a.y(), out.tip_z);
    j.e1 = prev.seg.element;
    j.e2 = cur.seg.element;
    const double ang = std::atan2(cross2(prev.tout, cur.tin), prev.tout.dot(cur.tin));
    if (std::abs(ang) <= tol::kJunctionTangentAngle) {
      j.kind = JunctionKind::kTangent;
    } else if (ang < 0) {
      j.kind = JunctionKind::kSharpConcave;
    } else {
      j.kind = JunctionKind::kConvex;
      ++out.stats.convex_junctions;
    }
    j.b1 = contact_vector(el, region_of(regions, j.e1), cur.seg.a, lv);
    j.b2 = contact_vector(el, region_of(regions, j.e2), cur.seg.a, lv);
    c.junctions.push_back(j);
  }
  c.area = contour_area(c.segs);
  c.hole = c.area < 0;
  out.contours.push_back(std::move(c));
}

// Where a contour runs from piece p (ending at vertex V by end `exit`) into piece q whose end
// at V is another point of V (ends within tol::kZLevelLink are one vertex), both are moved to
// one point: on one curve, p's end; on two curves, a point of V on both (their crossing or
// joint, recorded for both curves with the same coordinates), the one nearest p's end. A
// chord between two points of V would cut across the corner there.
void snap_junction(const PieceMap& map, const std::vector<Piece>& pieces, std::uint32_t exit,
                   Piece& p, bool p_rev, Piece& q, bool q_rev) {
  Vec2& pe = p_rev ? p.a : p.b;
  Vec2& qe = q_rev ? q.b : q.a;
  if (pe == qe) return;
  double& ps = p_rev ? p.s0 : p.s1;
  double& qs = q_rev ? q.s1 : q.s0;
  if (p.curve == q.curve) {
    qe = pe;
    qs = ps;
    return;
  }
  const auto ends = map.ends_at(map.vertex_of(exit));
  double best = INFINITY;
  Vec2 at = pe;
  for (std::uint32_t e : ends) {
    const Piece& a = pieces[e / 2];
    if (a.curve != p.curve) continue;
    const Vec2& x = (e & 1) ? a.b : a.a;
    for (std::uint32_t f : ends) {
      const Piece& b = pieces[f / 2];
      if (b.curve != q.curve || ((f & 1) ? b.b : b.a) != x) continue;
      const double d = (x - pe).norm();
      if (d < best) {
        best = d;
        at = x;
        ps = (e & 1) ? a.s1 : a.s0;
        qs = (f & 1) ? b.s1 : b.s0;
      }
    }
  }
  pe = qe = at;
}

// The kept pieces linked end to end (ends within tol::kZLevelLink; where several loops touch,
// each leaves along the first piece clockwise from the way back; an end left without a
// successor linked to the nearest free start within tol::kZLevelRepair), closed loops emitted,
// open chains counted and left out.
void link_kept(const OffsetElements& el, const Level& lv, const std::vector<Region>& regions,
               const std::vector<Curve>& curves, const std::vector<Piece>& kept,
               ZLevelResult& out) {
  const auto n = std::uint32_t(kept.size());
  // Cluster the ends within tol::kZLevelLink.
  std::vector<Vec2> pts(2 * std::size_t(n));
  for (std::uint32_t k = 0; k < n; ++k) {
    pts[2 * k] = kept[k].a;
    pts[2 * k + 1] = kept[k].b;
  }
  std::vector<std::uint32_t> order(pts.size());
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return pts[a].x() != pts[b].x() ? pts[a].x() < pts[b].x() : a < b;
  });
  Dsu dsu(pts.size());
  const double link = tol::kZLevelLink;
  for (std::size_t i = 0; i < order.size(); ++i)
    for (std::size_t j = i + 1; j < order.size() && pts[order[j]].x() - pts[order[i]].x() <= link;
         ++j)
      if ((pts[order[j]] - pts[order[i]]).norm() <= link) dsu.unite(order[i], order[j]);
  std::vector<std::uint32_t> cl(pts.size());
  for (std::uint32_t i = 0; i < pts.size(); ++i) cl[i] = dsu.find(i);
  // Pieces whose ends fall together are slivers (shorter than tol::kZLevelLink).
  std::vector<std::uint8_t> dead(n, 0);
  for (std::uint32_t k = 0; k < n; ++k) dead[k] = cl[2 * k] == cl[2 * k + 1];
  // Per cluster: pieces ending there (in) and starting there (out).
  std::vector<std::uint32_t> ins_start(pts.size() + 1, 0), outs_start(pts.size() + 1, 0);
  for (std::uint32_t k = 0; k < n; ++k)
    if (!dead[k]) {
      ++ins_start[cl[2 * k + 1] + 1];
      ++outs_start[cl[2 * k] + 1];
    }
  for (std::size_t i = 1; i < ins_start.size(); ++i) {
    ins_start[i] += ins_start[i - 1];
    outs_start[i] += outs_start[i - 1];
  }
  std::vector<std::uint32_t> ins(ins_start.back()), outs(outs_start.back());
  {
    auto fi = ins_start, fo = outs_start;
    for (std::uint32_t k = 0; k < n; ++k)
      if (!dead[k]) {
        ins[fi[cl[2 * k + 1]]++] = k;
        outs[fo[cl[2 * k]]++] = k;
      }
  }
  std::vector<std::uint32_t> next(n, kNone);
  std::vector<std::uint8_t> claimed(n, 0);
  for (std::size_t c = 0; c < pts.size(); ++c) {
    const std::uint32_t i0 = ins_start[c], i1 = ins_start[c + 1];
    const std::uint32_t o0 = outs_start[c], o1 = outs_start[c + 1];
    if (i1 - i0 == 1 && o1 - o0 == 1) {
      next[ins[i0]] = outs[o0];
      continue;
    }
    // Several loops touch here: leave along the first edge clockwise from the way back, so
    // that each loop keeps U on its left without crossing another.
    for (std::uint32_t a = i0; a < i1; ++a) {
      const Piece& pin = kept[ins[a]];
      const Vec2 back = -unit(curve_tangent(curves[pin.curve], pin.s1));
      std::uint32_t best = kNone;
      double best_a = INFINITY;
      for (std::uint32_t b = o0; b < o1; ++b) {
        if (claimed[outs[b]]) continue;
        const Piece& po = kept[outs[b]];
        const double ang = cw_angle(back, unit(curve_tangent(curves[po.curve], po.s0)));
        if (ang < best_a) {
          best_a = ang;
          best = outs[b];
        }
      }
      if (best != kNone) {
        claimed[best] = 1;
        next[ins[a]] = best;
      }
    }
  }
  // Repair: a piece whose end no piece leaves, with a piece that nothing enters starting
  // within tol::kZLevelRepair. Nearly coincident tangents make these: stacked wall edges whose
  // directions differ by ~1e-5 rad (a CAD wall in float coordinates) touch one vertex circle
  // ~R 1e-5 apart; the short arc between their tangent points is not placed consistently
  // with the lines next to it. Nearest start first, in piece order.
  {
    std::vector<std::uint8_t> has_prev(n, 0);
    for (std::uint32_t k = 0; k < n; ++k)
      if (!dead[k] && next[k] != kNone) has_prev[next[k]] = 1;
    std::vector<std::uint32_t> orphan;
    for (std::uint32_t k = 0; k < n; ++k)
      if (!dead[k] && !has_prev[k]) orphan.push_back(k);
    std::sort(orphan.begin(), orphan.end(), [&](std::uint32_t a, std::uint32_t b) {
      return kept[a].a.x() != kept[b].a.x() ? kept[a].a.x() < kept[b].a.x() : a < b;
    });
    std::vector<std::uint8_t> taken(orphan.size(), 0);
    const double r = tol::kZLevelRepair;
    for (std::uint32_t k = 0; k < n && !orphan.empty(); ++k) {
      if (dead[k] || next[k] != kNone) continue;
      const Vec2 e = kept[k].b;
      auto it = std::lower_bound(orphan.begin(), orphan.end(), e.x() - r,
                                 [&](std::uint32_t o, double x) { return kept[o].a.x() < x; });
      std::size_t best = orphan.size();
      double best_d = r;
      for (auto i = std::size_t(it - orphan.begin());
           i < orphan.size() && kept[orphan[i]].a.x() <= e.x() + r; ++i) {
        const double d = (kept[orphan[i]].a - e).norm();
        if (!taken[i] && (d < best_d || (d == best_d && best < orphan.size() &&
                                         orphan[i] < orphan[best]))) {
          best_d = d;
          best = i;
        }
      }
      if (best == orphan.size()) continue;
      taken[best] = 1;
      next[k] = orphan[best];
    }
  }
  // Trace.
  std::vector<std::uint8_t> visited(n, 0);
  std::vector<std::uint32_t> seq;
  for (std::uint32_t k = 0; k < n; ++k) {
    if (dead[k] || visited[k]) continue;
    seq.clear();
    std::uint32_t cur = k;
    bool closed = false;
    while (true) {
      visited[cur] = 1;
      seq.push_back(cur);
      const std::uint32_t nx = next[cur];
      if (nx == k) {
        closed = true;
        break;
      }
      if (nx == kNone || visited[nx]) break;
      cur = nx;
    }
    if (!closed) {
      ++out.stats.open_chains;
      continue;
    }
    std::vector<Piece> loop;
    for (std::uint32_t q : seq) loop.push_back(kept[q]);
    emit_loop(el, lv, regions, curves, loop, std::vector<std::uint8_t>(loop.size(), 0), out);
  }
}

}  // namespace

void build_loops(const OffsetElements& el, const Level& lv, const std::vector<Region>& regions,
                 const std::vector<Curve>& curves, std::vector<Piece> pieces,
                 std::vector<std::uint8_t> keep, ZLevelResult& out) {
  attach_loose_ends(curves, pieces, keep);
  const PieceMap map(curves, pieces, keep);
  const Faces faces = decide_faces(map, pieces, keep);

  // Contour pieces: faces of different status on their two sides. Each runs with U on its
  // left: forwards when its region side is inside, else backwards. lead[e] for an end e by
  // which a contour leaves a vertex.
  const std::size_t n = pieces.size();
  auto status = [&](std::uint32_t h) { return faces.inside[faces.face[h]]; };
  std::vector<std::uint8_t> contour(n, 0), backwards(n, 0);
  const std::vector<std::uint8_t> sound = sound_pieces(map, faces, pieces, keep);
  for (std::uint32_t k = 0; k < n; ++k) {
    if (map.dead(k)) continue;
    if (!sound[k]) continue;
    if (status(2 * k) == status(2 * k + 1)) continue;
    contour[k] = 1;
    backwards[k] = !status(2 * k);
  }
  auto leaves = [&](std::uint32_t e) { return contour[e / 2] && (e & 1) == backwards[e / 2]; };
  // At a vertex, the contour arriving by end a leaves by the first contour end
  // counter-clockwise from a: the faces between them lie outside U, and going round the
  // vertex the faces' status changes at each contour end, so that end leaves; every leaving
  // end follows exactly one arriving end. The successors form closed loops.
  std::vector<std::uint8_t> done(n, 0), reversed;
  std::vector<std::uint32_t> seq;
  std::vector<Piece> loop;
  for (std::uint32_t k0 = 0; k0 < n; ++k0) {
    if (!contour[k0] || done[k0]) continue;
    seq.clear();
    const std::uint32_t first = 2 * k0 + backwards[k0];  // the end it leaves by
    std::uint32_t e = first;
    while (e != kNone && !done[e / 2]) {
      done[e / 2] = 1;
      seq.push_back(e);
      const std::uint32_t a = e ^ 1;
      std::uint32_t b = map.turn_from(a, 1);
      while (b != a && !leaves(b)) b = map.turn_from(b, 1);
      e = b != a ? b : kNone;
    }
    if (e != first) {  // only where the classification decides; counted, never emitted open
      ++out.stats.open_chains;
      continue;
    }
    out.stats.kept += seq.size();
    loop.clear();
    reversed.clear();
    for (std::uint32_t e : seq) {
      loop.push_back(pieces[e / 2]);
      reversed.push_back(e & 1);
    }
    for (std::size_t i = 0; i < seq.size(); ++i) {
      const std::size_t j = (i + 1) % seq.size();
      snap_junction(map, pieces, seq[i] ^ 1, loop[i], reversed[i], loop[j], reversed[j]);
    }
    emit_loop(el, lv, regions, curves, loop, reversed, out);
  }
  std::vector<Piece> unsound;
  for (std::uint32_t k = 0; k < n; ++k)
    if (!sound[k] && keep[k] == kKept) unsound.push_back(pieces[k]);
  link_kept(el, lv, regions, curves, unsound, out);
  sort_contours(out.contours);
}

double contour_area(const std::vector<ContourSeg>& segs) {
  // The polygon of the end points (with the link gaps between segments, up to
  // tol::kZLevelLink) plus each arc's cap r1 r2 (dt - sin dt) / 2.
  const std::size_t m = segs.size();
  if (m == 0) return 0;
  const Vec2 o = segs[0].a;
  double area = 0;
  for (std::size_t i = 0; i < m; ++i) {
    const ContourSeg& s = segs[i];
    area += 0.5 * (cross2(s.a - o, s.b - o) + cross2(s.b - o, segs[(i + 1) % m].a - o));
    if (s.kind != ContourSegKind::kLine) {
      const double dt = s.t1 - s.t0;
      area += 0.5 * s.r1 * s.r2 * (dt - std::sin(dt));
    }
  }
  return area;
}

void sort_contours(std::vector<ZContour>& contours) {
  std::sort(contours.begin(), contours.end(), [](const ZContour& a, const ZContour& b) {
    const Vec2 &p = a.segs[0].a, &q = b.segs[0].a;
    if (p.x() != q.x()) return p.x() < q.x();
    if (p.y() != q.y()) return p.y() < q.y();
    return a.segs[0].element < b.segs[0].element;
  });
}

}  // namespace zlevel_detail

Vec2 seg_point(const ContourSeg& s, double f) {
  if (f <= 0) return s.a;
  if (f >= 1) return s.b;
  if (s.kind == ContourSegKind::kLine) return s.a + f * (s.b - s.a);
  // From a, with differences of cos and sin as products (no far-away centre).
  const double d = f * (s.t1 - s.t0), h = std::sin(0.5 * d), tm = s.t0 + 0.5 * d;
  const Vec2 pa(-s.axis.y(), s.axis.x());
  return s.a + (-2 * std::sin(tm) * h * s.r1) * s.axis + (2 * std::cos(tm) * h * s.r2) * pa;
}

void circumscribed(const ContourSeg& s, double tol, std::vector<Vec2>& out) {
  out.push_back(s.a);
  if (s.kind == ContourSegKind::kLine) return;
  const double span = s.t1 - s.t0;
  const double r = std::max(s.r1, s.r2);
  // k = 1 / cos(dt / 2) - 1 <= tol / r.
  const double max_dt = 2 * std::acos(1 / (1 + tol / r));
  const int n = std::max(1, int(std::ceil(std::abs(span) / max_dt - tol::kCountSlack)));
  if (n > 100000) return;  // a near-line (huge ellipse): its chord is within rounding
  const double dt = span / n, k = 1 / std::cos(dt / 2);
  const Vec2 perp(-s.axis.y(), s.axis.x());
  for (int j = 1; j <= n; ++j) {
    const double t = s.t0 + (j - 0.5) * dt;
    out.push_back(s.centre + k * (s.r1 * std::cos(t) * s.axis + s.r2 * std::sin(t) * perp));
  }
}

void discretise(const ContourSeg& s, double chord_tol, std::vector<Vec2>& out) {
  out.push_back(s.a);
  if (s.kind == ContourSegKind::kLine) return;
  const double rmax = std::max(s.r1, s.r2), sweep = std::abs(s.t1 - s.t0);
  if (!(rmax > chord_tol) || !(chord_tol > 0)) return;
  const double step = 2 * std::acos(1 - chord_tol / rmax);
  const int n = int(std::min(1e6, std::ceil(sweep / step)));
  for (int i = 1; i < n; ++i) out.push_back(seg_point(s, double(i) / n));
}

}  // namespace ncpath
