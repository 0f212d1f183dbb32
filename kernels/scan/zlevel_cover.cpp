// Z-level contours (kernels/scan/zlevel.hpp): which parts of the candidate curves can lie on
// the boundary of U. Uncovered runs (the curves' parts not certified inside U), tangent
// joints (split explicitly; the structural pairs that make only those are not intersected)
// and the classification of the pieces between splits. Declarations: zlevel_detail.hpp.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "kernels/geom/tolerance.hpp"
#include "kernels/scan/zlevel_detail.hpp"

namespace ncpath::zlevel_detail {

namespace {

// Which side of curve D the piece [s0, s1] of curve C lies on when it stays within `on` of D
// (both with their regions on the left) because it leaves D at a tangent joint: 1 left
// (inside D's region), -1 right; 0 when that does not decide. The piece's offset from D at its
// midpoint is as small as its rounding there; from the piece's end nearer D, taken to be on D,
// it is sin(theta) x + dk x^2 / 2 (x the midpoint's distance from that end, theta the angle
// between the tangents, dk the curvatures' difference). Where the second-order term dominates,
// the curve that turns more towards its region lies inside the other's, whichever piece of
// the pair is asked: sign(dk). 0 where the curvatures agree (within `on` over a length R: the
// curves coincide) or the first-order term dominates (a grazing crossing, whose place is
// rounding there, or no joint at all).
int tangent_departure_side(const Curve& C, double s0, double s1, const Curve& D, const Level& lv,
                           double on) {
  auto offset = [&](const Vec2& p) {
    if (D.kind == CurveKind::kLine) return std::abs(cross2(D.dir, p - D.a));
    Vec2 g;
    const double f = curve_implicit(D, p, lv.zc, &g), gn = g.norm();
    return gn > 0 ? std::abs(f) / gn : 0.0;
  };
  const Vec2 p0 = curve_point(C, s0), p1 = curve_point(C, s1);
  const bool from0 = offset(p0) <= offset(p1);
  const double se = from0 ? s0 : s1;
  const Vec2& e = from0 ? p0 : p1;
  const double sd = curve_param(D, e);
  const double dk = curve_curvature(C, se) - curve_curvature(D, sd);
  if (0.5 * std::abs(dk) * lv.R * lv.R <= on) return 0;
  const Vec2 tc = curve_tangent(C, se).normalized(), td = curve_tangent(D, sd).normalized();
  const double x = (curve_point(C, 0.5 * (s0 + s1)) - e).norm();
  if (!(0.5 * std::abs(dk) * x > std::abs(cross2(td, tc)))) return 0;
  return dk > 0 ? 1 : -1;
}

}  // namespace

bool structural_pair(const OffsetElements& el, const Region& p, const Region& q) {
  const Region& a = p.kind < q.kind ? p : q;
  const Region& b = p.kind < q.kind ? q : p;
  auto vertex_point = [&](const Region& r) { return el.vertex_source[r.index]; };
  if (a.kind == RegionKind::kFacet) {
    const auto& fv = el.facet_vertices[a.index];
    auto has = [&](std::uint32_t v) { return v == fv[0] || v == fv[1] || v == fv[2]; };
    if (b.kind == RegionKind::kEdge)
      return has(el.edge_vertices[b.index][0]) && has(el.edge_vertices[b.index][1]);
    if (b.kind == RegionKind::kVertex) return has(vertex_point(b));
    return false;
  }
  if (a.kind == RegionKind::kEdge && b.kind == RegionKind::kVertex) {
    const auto& ev = el.edge_vertices[a.index];
    return vertex_point(b) == ev[0] || vertex_point(b) == ev[1];
  }
  return false;
}

void uncovered_runs(const Curve& c, const Grid& grid, const CellLists& cells,
                    const std::vector<Region>& regions, const std::vector<Box4f>& rbox,
                    const Level& lv, const ZLevelInside* inside,
                    std::vector<std::pair<double, double>>& runs) {
  const double m = tol::kZLevelCellMargin;
  const bool arc = c.kind != CurveKind::kLine;
  const double speed = arc ? std::sqrt(c.e1.squaredNorm() + c.e2.squaredNorm()) : 1.0;
  double step = grid.cell / speed;
  if (arc) step = std::min(step, std::numbers::pi / 4);
  const int n = std::max(1, int(std::ceil(c.len / step)));
  std::uint32_t last = kNone;
  // The hull of the sub-piece: its ends and, for arcs, the tangents' crossing.
  auto hull = [&](double s0, double s1, const Vec2& p0, const Vec2& p1, Vec2* h) {
    h[0] = p0;
    h[1] = p1;
    if (!arc) return 2;
    h[2] = p0 + std::tan(0.5 * (s1 - s0)) * curve_tangent(c, s0);
    return 3;
  };
  // Certified: in interior cells, or its hull inside the known inside region or strictly
  // inside one region other than c's own.
  auto certified = [&](double s0, double s1, const Vec2& p0, const Vec2& p1) {
    Vec2 h[3];
    const int nh = hull(s0, s1, p0, p1, h);
    double b[4];
    points_box(h, nh, b);
    if (!grid.any_open(b)) return true;
    // An end on the known region's boundary (within tol::kZLevelOnExactEdge of an exact edge,
    // the contour to ~1e-11 mm) lies less than m deep in it, so neither it nor a region inside
    // it holds the hull.
    const bool on_known = inside && (on_exact_edge(*inside, h[0], tol::kZLevelOnExactEdge) ||
                                     on_exact_edge(*inside, h[1], tol::kZLevelOnExactEdge));
    if (inside && !on_known && inside_contains(*inside, h, nh, 0, inside->margin)) return true;
    auto in_region = [&](std::uint32_t gi) {
      const Box4f& gb = rbox[gi];
      if (gi == c.region || b[0] < gb[0] || b[1] < gb[1] || b[2] > gb[2] || b[3] > gb[3])
        return false;
      if (on_known && regions[gi].known_inside) return false;
      const Region& g = regions[gi];
      for (int q = 0; q < nh; ++q)
        if (!(region_phi(g, h[q], lv) < -m)) return false;
      return true;
    };
    if (last != kNone && in_region(last)) return true;
    // A region holding the hull has its value below -m at every point of it (values are
    // convex), the chord's midpoint too: at the centre below the cutoff from the nearest.
    const Vec2 mid = 0.5 * (p0 + p1);
    const int cell = grid.at(mid);
    const Vec2 centre = grid.centre(cell);
    double d = (mid - centre).norm();
    for (int q = 0; q < nh; ++q) d = std::min(d, (h[q] - centre).norm());
    const double cutoff = depth_cutoff(d, lv.R, -m);
    for (std::uint32_t q = cells.start[cell]; q < cells.start[cell + 1]; ++q) {
      if (cells.depth[q] >= cutoff) break;
      if (in_region(cells.ids[q])) {
        last = cells.ids[q];
        return true;
      }
    }
    return false;
  };
  auto add_run = [&](double s0, double s1) {
    if (!runs.empty() && runs.back().second == s0)
      runs.back().second = s1;
    else
      runs.emplace_back(s0, s1);
  };
  // A step that is not certified is halved, and its halves once more: the curves of a
  // finely sampled wall (its vertices' circles and edges' shadow lines a fraction of R apart,
  // nearly coincident on a CAD wall stored in floats) are each covered by a neighbour except
  // near their tangent joints, but over a whole step only by several regions together; left
  // whole, every pair of them would be intersected and its pieces classified.
  // With a known inside region the stacked regions are mostly dropped: once is enough.
  const int kHalvings = inside ? 1 : 2;
  // With a known inside region, regions half tol::kZLevelInsideDepth (or more) deep inside it
  // may have been dropped: a sub-piece left uncertified is halved while it may still hold a
  // point that deep, so that every such point ends in a certified half (a half shorter than a
  // quarter of that depth around one is within the margin of nothing).
  const double deep = 0.5 * tol::kZLevelInsideDepth;
  auto refine = [&](auto&& self, double s0, double s1, const Vec2& p0, const Vec2& p1) -> void {
    Vec2 h[3];
    const int nh = hull(s0, s1, p0, p1, h);
    double rho = 0;
    for (int q = 1; q < nh; ++q) rho = std::max(rho, (h[q] - h[0]).norm());
    if (rho < deep / 4 || inside_depth_bound(*inside, h, nh, deep) < deep) return add_run(s0, s1);
    const double sm = 0.5 * (s0 + s1);
    const Vec2 pm = curve_point(c, sm);
    for (int half = 0; half < 2; ++half) {
      const double a = half ? sm : s0, b = half ? s1 : sm;
      const Vec2 &pa = half ? pm : p0, &pb = half ? p1 : pm;
      const int n2 = hull(a, b, pa, pb, h);
      if (!inside_contains(*inside, h, n2, 0, inside->margin)) self(self, a, b, pa, pb);
    }
  };
  auto visit = [&](auto&& self, double s0, double s1, const Vec2& p0, const Vec2& p1,
                   int depth) -> void {
    if (certified(s0, s1, p0, p1)) return;
    if (depth == kHalvings) return inside ? refine(refine, s0, s1, p0, p1) : add_run(s0, s1);
    const double sm = 0.5 * (s0 + s1);
    const Vec2 pm = curve_point(c, sm);
    self(self, s0, sm, p0, pm, depth + 1);
    self(self, sm, s1, pm, p1, depth + 1);
  };
  Vec2 prev = c.a;
  for (int k = 0; k < n; ++k) {
    const double s0 = c.len * k / n, s1 = k + 1 == n ? c.len : c.len * (k + 1) / n;
    const Vec2 p1 = k + 1 == n ? c.b : curve_point(c, s1);
    visit(visit, s0, s1, prev, p1, 0);
    prev = p1;
  }
}

void joint_splits(const std::vector<Joint>& joints, const std::vector<Region>& regions,
                  const std::vector<Curve>& act, const std::vector<std::uint32_t>& act_begin,
                  std::vector<Split>& splits) {
  auto region_of_element = [&](std::uint32_t id) -> std::uint32_t {
    const auto it =
        std::lower_bound(regions.begin(), regions.end(), id,
                         [](const Region& g, std::uint32_t e) { return g.element < e; });
    return it != regions.end() && it->element == id ? std::uint32_t(it - regions.begin()) : kNone;
  };
  // A joint whose target vertex has no active curve through it may lie on a part of its
  // circle that the coincident trimming (zlevel.cpp) left to the circle of another vertex with
  // the same centre and radius, of a lower id: the stacked vertices of a wall, each with its
  // own edges. That circle is split there instead. Otherwise the joint is lost: a wall's
  // stacked edges whose directions differ by an angle a (1e-5 rad on a CAD wall stored in
  // floats) leave the corner's circle at tangent points R a apart, and the kept arc runs on
  // unsplit past the tangent point of a capsule side whose shadow line is the boundary from
  // there (the arc beyond lies inside that capsule by ~(R a)^2 / R), leaving a gap of ~R a
  // in the contour. Vertex regions sorted by centre x find the coincident circles (the test
  // of coincident_overlap: centres and radii within tol::kZLevelOnBoundary).
  std::vector<std::uint32_t> vtx;
  for (std::uint32_t gi = 0; gi < regions.size(); ++gi)
    if (regions[gi].kind == RegionKind::kVertex) vtx.push_back(gi);
  std::sort(vtx.begin(), vtx.end(), [&](std::uint32_t a, std::uint32_t b) {
    return regions[a].c.x() != regions[b].c.x() ? regions[a].c.x() < regions[b].c.x() : a < b;
  });
  const double on = tol::kZLevelOnBoundary;

  std::uint32_t best = kNone;
  double best_d = 0, best_s = 0;
  auto nearest = [&](std::uint32_t gi, const Vec2& p) {
    for (std::uint32_t c = act_begin[gi]; c < act_begin[gi + 1]; ++c) {
      double s = curve_param(act[c], p);
      if (s < 0 || s > act[c].len) continue;
      const double d = (curve_point(act[c], s) - p).norm();
      if (d < best_d) {
        best_d = d;
        best = c;
        best_s = s;
      }
    }
  };
  for (const Joint& j : joints) {
    for (std::uint32_t target : {j.target, j.alt[0], j.alt[1]}) {
      if (target == kNone) continue;
      const std::uint32_t gi = region_of_element(target);
      if (gi == kNone) continue;
      best = kNone;
      best_d = tol::kZLevelJointSnap;
      nearest(gi, j.p);
      const Region& g = regions[gi];
      if (best == kNone && g.kind == RegionKind::kVertex) {
        auto it = std::lower_bound(vtx.begin(), vtx.end(), g.c.x() - on,
                                   [&](std::uint32_t h, double x) { return regions[h].c.x() < x; });
        for (; it != vtx.end() && regions[*it].c.x() <= g.c.x() + on; ++it) {
          const Region& h = regions[*it];
          if (*it != gi && (h.c - g.c).norm() <= on && std::abs(h.r - g.r) <= on) nearest(*it, j.p);
        }
      }
      if (best != kNone) {
        splits.push_back({best, best_s, j.p});
        break;
      }
    }
  }
}

std::vector<Piece> split_pieces(const std::vector<Split>& splits, ZLevelStats& st) {
  std::vector<Piece> pieces;
  for (std::size_t k = 0; k + 1 < splits.size(); ++k) {
    const Split &s0 = splits[k], &s1 = splits[k + 1];
    if (s0.curve != s1.curve || !(s1.s > s0.s)) continue;
    pieces.push_back({s0.curve, s0.s, s1.s, s0.p, s1.p});
  }
  st.pieces = pieces.size();
  return pieces;
}

double arc_clearance(const ContourSeg& s, const std::array<std::uint32_t, 3>& skip, double cap,
                     const Grid& grid, const CellLists& region_cells,
                     const std::vector<Region>& regions, const std::vector<Box4f>& rbox,
                     const Level& lv) {
  // Whether x lies strictly inside a region other than those skipped (regions from x's cell,
  // deepest at its centre first, up to the depth that cannot matter).
  auto entered = [&](const Vec2& x) {
    const int cell = grid.at(x);
    if (grid.interior[cell]) return true;
    const double cutoff = depth_cutoff((x - grid.centre(cell)).norm(), lv.R, 0);
    for (std::uint32_t q = region_cells.start[cell]; q < region_cells.start[cell + 1]; ++q) {
      if (region_cells.depth[q] >= cutoff) break;
      const Region& g = regions[region_cells.ids[q]];
      if (g.element == skip[0] || g.element == skip[1] || g.element == skip[2]) continue;
      const Box4f& gb = rbox[region_cells.ids[q]];
      if (x.x() < gb[0] || x.x() > gb[2] || x.y() < gb[1] || x.y() > gb[3]) continue;
      if (region_phi(g, x, lv) < 0) return true;
    }
    return false;
  };
  std::vector<Vec2> poly;
  for (double tol = cap; tol >= cap * tol::kZLevelMinBulge; tol *= 0.25) {
    poly.clear();
    circumscribed(s, tol, poly);
    bool ok = true;
    for (std::size_t j = 1; j < poly.size() && ok; ++j) ok = !entered(poly[j]);
    if (ok) return tol;
  }
  return cap * tol::kZLevelMinBulge;
}





void classify_pieces(const std::vector<Split>& splits, const std::vector<Curve>& act,
                     const std::vector<Curve>& curves, const std::vector<Region>& regions,
                     const std::vector<Box4f>& rbox, const Grid& grid,
                     const CellLists& region_cells, const Level& lv,
                     std::vector<std::uint8_t>& keep) {
  // G's candidate curve passing nearest to m, within tol::kZLevelOnBoundary (kNone if none).
  auto emits_at = [&](const Region& G, const Vec2& m) {
    std::uint32_t best = kNone;
    double best_d = tol::kZLevelOnBoundary;
    for (std::uint32_t c = G.curve_begin; c < G.curve_end; ++c) {
      const double s = curve_param(curves[c], m);
      if (!(s >= -tol::kZLevelSlack && s <= curves[c].len + tol::kZLevelSlack)) continue;
      const double d = (curve_point(curves[c], std::clamp(s, 0.0, curves[c].len)) - m).norm();
      if (d <= best_d) {
        best_d = d;
        best = c;
      }
    }
    return best;
  };

  // The side of region gj on which the piece from splits[k] to splits[k + 1] lies, from the
  // orientation of line crossings with gj at its ends: -1 inside, 1 outside, 0 unknown. A
  // crossing tells the side of gj only where its line is gj's boundary beside the piece: at
  // the piece's quarter point next to the crossing. A line that ends at the crossing and lies
  // behind it (a capsule's chord ending at its shadow line, which the piece runs along) does
  // not tell.
  auto crossing_side = [&](std::size_t k, std::uint32_t gj) {
    const std::uint32_t c = splits[k].curve;
    const Curve& C = act[c];
    int side = 0;
    auto vote = [&](const Split& sp, double f, int v) {
      if (sp.other == kNone || sp.enter == 0 || act[sp.other].region != gj) return;
      const Curve& D = act[sp.other];
      const double sd =
          curve_param(D, curve_point(C, splits[k].s + f * (splits[k + 1].s - splits[k].s)));
      if (!(sd >= 0 && sd <= D.len)) return;
      side = side == 0 || side == v ? v : 2;
    };
    for (std::size_t q = k + 1; q-- > 0 && splits[q].curve == c && splits[q].s == splits[k].s;)
      vote(splits[q], 0.25, -splits[q].enter);
    for (std::size_t q = k + 1;
         q < splits.size() && splits[q].curve == c && splits[q].s == splits[k + 1].s; ++q)
      vote(splits[q], 0.75, splits[q].enter);
    return side == 2 ? 0 : side;
  };

  // Pieces between consecutive splits; keep those on the boundary of U.
  const double on = tol::kZLevelOnBoundary;
  for (std::size_t k = 0; k + 1 < splits.size(); ++k) {
    const Split &s0 = splits[k], &s1 = splits[k + 1];
    if (s0.curve != s1.curve || !(s1.s > s0.s)) continue;
    const Curve& C = act[s0.curve];
    keep.push_back(0);
    const Vec2 m = curve_point(C, 0.5 * (s0.s + s1.s));
    const int cell = grid.at(m);
    if (grid.interior[cell]) continue;
    bool kept = true, clear = false;
    // Regions whose value at m exceeds `on` do not decide anything (depth_cutoff).
    const double cutoff = depth_cutoff((m - grid.centre(cell)).norm(), lv.R, on);
    for (std::uint32_t q = region_cells.start[cell]; kept && q < region_cells.start[cell + 1];
         ++q) {
      if (region_cells.depth[q] >= cutoff) break;
      const std::uint32_t gj = region_cells.ids[q];
      const Box4f& gb = rbox[gj];
      if (gj == C.region || m.x() < gb[0] || m.x() > gb[2] || m.y() < gb[1] || m.y() > gb[3])
        continue;
      const Region& G = regions[gj];
      Vec2 gout;
      const double phi = region_phi(G, m, lv, &gout);
      if (phi < -on) {
        kept = false;
        clear = true;
      } else if (phi <= on) {
        // The midpoint is on G's boundary. The piece does not cross it (crossings split the
        // curves), so a quarter point clearly inside or outside G decides the side: next to
        // a tangent joint the piece leaves the curve it touches only quadratically, within
        // `on` over sqrt(2 on rho), and rho is up to R / sin^2(slope) on a flat edge's
        // ellipse (a clip line ending on it). Coincident when both quarter points are on it.
        int in = 0, out = 0;
        for (double f : {0.25, 0.75}) {
          const double pf = region_phi(G, curve_point(C, s0.s + f * (s1.s - s0.s)), lv);
          in += pf < -on;
          out += pf > on;
        }
        if (in > 0 && out == 0) kept = false;
        if (in == 0 && out == 0) {
          // Along G's boundary. Next to a crossing with one of G's lines the crossing's
          // orientation tells the side: clip lines of nearly coplanar facets cross at a
          // grazing angle theta and stay within `on` of each other over on / theta.
          const int side = crossing_side(k, gj);
          if (side < 0) kept = false;
          // Regions on both sides: inside U. Same side, along G's curve D: a piece leaving a
          // tangent joint with D stays within `on` of it over sqrt(2 on / dk), dk the
          // curvatures' difference (where a sloping edge's shadow line on a wall turns into its
          // ellipse while the next edge's shadow runs on): the curvatures tell its side.
          // Otherwise (C and D coincide, or cross at a grazing angle) the lower element id
          // keeps the shared piece. Without a curve of G there (a capsule's end caps are its
          // vertices'): keep.
          if (side == 0) {
            const Vec2 t = curve_tangent(C, 0.5 * (s0.s + s1.s));
            if (gout.dot(Vec2(t.y(), -t.x())) < 0) {
              kept = false;
            } else if (const std::uint32_t d = emits_at(G, m); d != kNone) {
              const int dep = tangent_departure_side(C, s0.s, s1.s, curves[d], lv, on);
              if (dep == 0 ? G.element < C.element : dep > 0) kept = false;
            }
          }
        }
      }
    }
    keep.back() = kept ? kKept : clear ? kInterior : kTied;
  }
}

}  // namespace ncpath::zlevel_detail
