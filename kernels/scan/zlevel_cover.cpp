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
                    const Level& lv, std::vector<std::pair<double, double>>& runs) {
  const double m = tol::kZLevelCellMargin;
  const bool arc = c.kind != CurveKind::kLine;
  const double speed = arc ? std::sqrt(c.e1.squaredNorm() + c.e2.squaredNorm()) : 1.0;
  double step = grid.cell / speed;
  if (arc) step = std::min(step, std::numbers::pi / 4);
  const int n = std::max(1, int(std::ceil(c.len / step)));
  std::uint32_t last = kNone;
  Vec2 h[3];
  Vec2 prev = c.a;
  for (int k = 0; k < n; ++k) {
    const double s0 = c.len * k / n, s1 = k + 1 == n ? c.len : c.len * (k + 1) / n;
    int nh = 2;
    h[0] = prev;
    h[1] = k + 1 == n ? c.b : curve_point(c, s1);
    prev = h[1];
    if (arc) h[nh++] = h[0] + std::tan(0.5 * (s1 - s0)) * curve_tangent(c, s0);
    double b[4] = {INFINITY, INFINITY, -INFINITY, -INFINITY};
    for (int q = 0; q < nh; ++q) {
      b[0] = std::min(b[0], h[q].x());
      b[1] = std::min(b[1], h[q].y());
      b[2] = std::max(b[2], h[q].x());
      b[3] = std::max(b[3], h[q].y());
    }
    bool found = !grid.any_open(b);
    auto inside = [&](std::uint32_t gi) {
      const Box4f& gb = rbox[gi];
      if (gi == c.region || b[0] < gb[0] || b[1] < gb[1] || b[2] > gb[2] || b[3] > gb[3])
        return false;
      const Region& g = regions[gi];
      for (int q = 0; q < nh; ++q)
        if (!(region_phi(g, h[q], lv) < -m)) return false;
      return true;
    };
    if (!found && last != kNone && inside(last)) found = true;
    if (!found) {
      const int cell = grid.at(0.5 * (h[0] + h[1]));
      for (std::uint32_t q = cells.start[cell]; !found && q < cells.start[cell + 1]; ++q)
        if (inside(cells.ids[q])) {
          last = cells.ids[q];
          found = true;
        }
    }
    if (found) continue;
    if (!runs.empty() && runs.back().second == s0)
      runs.back().second = s1;
    else
      runs.emplace_back(s0, s1);
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

  for (const Joint& j : joints) {
    for (std::uint32_t target : {j.target, j.alt[0], j.alt[1]}) {
      if (target == kNone) continue;
      const std::uint32_t gi = region_of_element(target);
      if (gi == kNone) continue;
      std::uint32_t best = kNone;
      double best_d = 1e-6, best_s = 0;
      for (std::uint32_t c = act_begin[gi]; c < act_begin[gi + 1]; ++c) {
        double s = curve_param(act[c], j.p);
        if (s < 0 || s > act[c].len) continue;
        const double d = (curve_point(act[c], s) - j.p).norm();
        if (d < best_d) {
          best_d = d;
          best = c;
          best_s = s;
        }
      }
      if (best != kNone) {
        splits.push_back({best, best_s, j.p});
        break;
      }
    }
  }
}

void classify_pieces(const std::vector<Split>& splits, const std::vector<Curve>& act,
                     const std::vector<Curve>& curves, const std::vector<Region>& regions,
                     const std::vector<Box4f>& rbox, const Grid& grid,
                     const CellLists& region_cells, const Level& lv, const ZLevelParams& params,
                     ZLevelStats& st, std::vector<KeptPiece>& kept) {
  auto emits_at = [&](const Region& G, const Vec2& m) {
    for (std::uint32_t c = G.curve_begin; c < G.curve_end; ++c) {
      const double s = curve_param(curves[c], m);
      if (s >= -1e-9 && s <= curves[c].len + 1e-9 &&
          (curve_point(curves[c], std::clamp(s, 0.0, curves[c].len)) - m).norm() <=
              params.on_boundary)
        return true;
    }
    return false;
  };

  // The side of region gj on which the piece from splits[k] to splits[k + 1] lies, from the
  // orientation of line crossings with gj at its ends: -1 inside, 1 outside, 0 unknown.
  auto crossing_side = [&](std::size_t k, std::uint32_t gj) {
    const std::uint32_t c = splits[k].curve;
    int side = 0;
    auto vote = [&](int v) { side = side == 0 || side == v ? v : 2; };
    for (std::size_t q = k + 1; q-- > 0 && splits[q].curve == c && splits[q].s == splits[k].s;)
      if (splits[q].other == gj && splits[q].enter != 0) vote(-splits[q].enter);
    for (std::size_t q = k + 1;
         q < splits.size() && splits[q].curve == c && splits[q].s == splits[k + 1].s; ++q)
      if (splits[q].other == gj && splits[q].enter != 0) vote(splits[q].enter);
    return side == 2 ? 0 : side;
  };

  // Pieces between consecutive splits; keep those on the boundary of U.
  const double on = params.on_boundary;
  for (std::size_t k = 0; k + 1 < splits.size(); ++k) {
    const Split &s0 = splits[k], &s1 = splits[k + 1];
    if (s0.curve != s1.curve || !(s1.s > s0.s)) continue;
    const Curve& C = act[s0.curve];
    ++st.pieces;
    const Vec2 m = curve_point(C, 0.5 * (s0.s + s1.s));
    const int cell = grid.at(m);
    if (grid.interior[cell]) continue;
    bool keep = true;
    for (std::uint32_t q = region_cells.start[cell]; keep && q < region_cells.start[cell + 1];
         ++q) {
      const std::uint32_t gj = region_cells.ids[q];
      const Box4f& gb = rbox[gj];
      if (gj == C.region || m.x() < gb[0] || m.x() > gb[2] || m.y() < gb[1] || m.y() > gb[3])
        continue;
      const Region& G = regions[gj];
      Vec2 gout;
      const double phi = region_phi(G, m, lv, &gout);
      if (phi < -on) {
        keep = false;
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
        if (in > 0 && out == 0) keep = false;
        if (in == 0 && out == 0) {
          // Along G's boundary. Next to a crossing with one of G's lines the crossing's
          // orientation tells the side: clip lines of nearly coplanar facets cross at a
          // grazing angle theta and stay within `on` of each other over on / theta.
          const int side = crossing_side(k, gj);
          if (side < 0) keep = false;
          // Regions on both sides: inside U. Same side: the lower element id keeps the shared
          // piece, provided it has a curve there (a capsule's end caps are its vertices').
          if (side == 0) {
            const Vec2 t = curve_tangent(C, 0.5 * (s0.s + s1.s));
            if (gout.dot(Vec2(t.y(), -t.x())) < 0 || (G.element < C.element && emits_at(G, m)))
              keep = false;
          }
        }
      }
    }
    if (keep) kept.push_back({s0.curve, s0.s, s1.s, s0.p, s1.p});
  }
}

}  // namespace ncpath::zlevel_detail
