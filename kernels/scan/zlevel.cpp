// Z-level contours (kernels/scan/zlevel.hpp): pruning grid, candidate curves, splitting at
// crossings and classification of the pieces. Linking and output: zlevel_loops.cpp.
#include "kernels/scan/zlevel.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>

#include "kernels/scan/zlevel_detail.hpp"

namespace ncpath {

using namespace zlevel_detail;

namespace {

// Uniform grid over the candidates' boxes. A cell is interior when it lies (by
// tol::kZLevelCellMargin) inside one region: it is in the interior of U, no piece of the
// boundary passes through it. `sum` counts the other (open) cells for box queries.
struct Grid {
  double x0 = 0, y0 = 0, cell = 1;
  int nx = 1, ny = 1;
  std::vector<std::uint8_t> interior;
  std::vector<std::uint32_t> sum;  // (nx + 1) x (ny + 1): open cells in [0, i) x [0, j)

  int ix(double x) const { return std::clamp(int(std::floor((x - x0) / cell)), 0, nx - 1); }
  int iy(double y) const { return std::clamp(int(std::floor((y - y0) / cell)), 0, ny - 1); }
  double gx(int i) const { return x0 + i * cell; }
  double gy(int j) const { return y0 + j * cell; }
  int at(const Vec2& p) const { return iy(p.y()) * nx + ix(p.x()); }
  void range(const double* b, int& i0, int& j0, int& i1, int& j1) const {
    i0 = ix(b[0]);
    j0 = iy(b[1]);
    i1 = ix(b[2]);
    j1 = iy(b[3]);
  }
  bool any_open(const double* b) const {
    if (!(b[0] <= b[2]) || !(b[1] <= b[3])) return false;
    int i0, j0, i1, j1;
    range(b, i0, j0, i1, j1);
    const int w = nx + 1;
    return sum[(j1 + 1) * w + i1 + 1] - sum[j0 * w + i1 + 1] - sum[(j1 + 1) * w + i0] +
               sum[j0 * w + i0] >
           0;
  }
};

// Box of the element's region at any level at or below its top (conservative), false when
// the region is empty at this level.
bool candidate_box(const OffsetElements& el, std::uint32_t id, const Level& lv, double* b) {
  const auto nf = el.facet_count(), ne = el.edge_count();
  auto put = [&](const Vec3& p) {
    b[0] = std::min(b[0], p.x());
    b[1] = std::min(b[1], p.y());
    b[2] = std::max(b[2], p.x());
    b[3] = std::max(b[3], p.y());
  };
  b[0] = b[1] = INFINITY;
  b[2] = b[3] = -INFINITY;
  if (id < nf) {
    if (el.facet_vertical[id]) return false;
    const auto& t = el.facet_tri[id];
    if (std::max({t[0].z(), t[1].z(), t[2].z()}) < lv.zc) return false;
    for (const Vec3& p : t) put(p);
    return true;
  }
  double pad = lv.R;
  if (id < nf + ne) {
    const auto& ev = el.edge_vertices[id - nf];
    const Vec3 &p = el.points[ev[0]], &q = el.points[ev[1]];
    if (!(std::max(p.z(), q.z()) + lv.R > lv.zc)) return false;
    put(p);
    put(q);
  } else {
    const Vec3& p = el.points[el.vertex_source[id - nf - ne]];
    if (!(p.z() + lv.R > lv.zc)) return false;
    put(p);
  }
  b[0] -= pad;
  b[1] -= pad;
  b[2] += pad;
  b[3] += pad;
  return true;
}

void mark_interior(const Region& g, const Level& lv, Grid& grid) {
  const double m = tol::kZLevelCellMargin;
  int j0 = int(std::ceil((g.box[1] - grid.y0) / grid.cell));
  int j1 = int(std::floor((g.box[3] - grid.y0) / grid.cell));
  j0 = std::max(j0, 0);
  j1 = std::min(j1, grid.ny);
  if (j1 - j0 < 1) return;
  double lo_prev = 0, hi_prev = 0;
  bool ok_prev = region_row(g, grid.gy(j0), m, lv, lo_prev, hi_prev);
  for (int j = j0; j < j1; ++j) {
    double lo, hi;
    const bool ok = region_row(g, grid.gy(j + 1), m, lv, lo, hi);
    if (ok && ok_prev) {
      const double a = std::max(lo, lo_prev), b = std::min(hi, hi_prev);
      int i0 = std::max(0, int(std::ceil((a - grid.x0) / grid.cell)));
      int i1 = std::min(grid.nx, int(std::floor((b - grid.x0) / grid.cell)));
      while (i0 < i1 && grid.gx(i0) < a) ++i0;
      while (i1 > i0 && grid.gx(i1) > b) --i1;
      for (int i = i0; i < i1; ++i) grid.interior[std::size_t(j) * grid.nx + i] = 1;
    }
    lo_prev = lo;
    hi_prev = hi;
    ok_prev = ok;
  }
}

// Compressed lists of ids per open cell (count, scan, fill).
struct CellLists {
  std::vector<std::uint32_t> start, ids;
};

template <class BoxOf>
void fill_lists(const Grid& grid, std::size_t n, BoxOf box_of, CellLists& out) {
  out.start.assign(std::size_t(grid.nx) * grid.ny + 1, 0);
  for (int pass = 0; pass < 2; ++pass) {
    for (std::size_t k = 0; k < n; ++k) {
      const double* b = box_of(k);
      if (!(b[0] <= b[2])) continue;
      int i0, j0, i1, j1;
      grid.range(b, i0, j0, i1, j1);
      for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) {
          const std::size_t c = std::size_t(j) * grid.nx + i;
          if (grid.interior[c]) continue;
          if (pass == 0)
            ++out.start[c + 1];
          else
            out.ids[out.start[c]++] = std::uint32_t(k);
        }
    }
    if (pass == 0) {
      for (std::size_t c = 1; c < out.start.size(); ++c) out.start[c] += out.start[c - 1];
      out.ids.resize(out.start.back());
    } else {
      for (std::size_t c = out.start.size() - 1; c > 0; --c) out.start[c] = out.start[c - 1];
      out.start[0] = 0;
    }
  }
}

bool boxes_overlap(const double* a, const double* b) {
  const double s = 1e-9;
  return a[0] <= b[2] + s && b[0] <= a[2] + s && a[1] <= b[3] + s && b[1] <= a[3] + s;
}

// Tangent joints are split explicitly; crossings between a facet's clip line and its own
// edges' and vertices' curves, or a capsule side and its own end circles, are only those.
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

// Appends to `runs` the parameter intervals of curve c that are not certified inside U: c is
// cut into sub-pieces of about a cell; one is certified when it lies in interior cells or its
// hull (ends and, for arcs, the tangents' crossing) lies strictly inside one region other
// than c's own. Crossings in certified parts cannot be on the boundary of U.
using Box4f = std::array<float, 4>;

// Box rounded outwards to floats (compact copies for scans over many regions).
Box4f outward_box(const double* b) {
  return {std::nextafter(float(b[0]), -INFINITY), std::nextafter(float(b[1]), -INFINITY),
          std::nextafter(float(b[2]), INFINITY), std::nextafter(float(b[3]), INFINITY)};
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

// The part [s0, s1] of curve c as a curve of its own (same geometry, ends shared).
Curve sub_curve(const Curve& c, double s0, double s1) {
  if (s0 == 0 && s1 == c.len) return c;
  Curve r = c;
  r.a = s0 == 0 ? c.a : curve_point(c, s0);
  r.b = s1 == c.len ? c.b : curve_point(c, s1);
  r.len = s1 - s0;
  if (c.kind != CurveKind::kLine) {
    const double sn = std::sin(s0), cs = std::cos(s0);
    r.e1 = cs * c.e1 + sn * c.e2;
    r.e2 = -sn * c.e1 + cs * c.e2;
    r.t0 = c.t0 + s0;
  }
  finish_box(r);
  return r;
}

// A point splitting act[curve] at parameter s. At a crossing of two lines, `other` is the
// other line's region and `enter` +1 when the curve runs into it past p, -1 when out of it
// (exact signs: the lines are not parallel); kNone and 0 elsewhere.
struct Split {
  std::uint32_t curve;
  double s;
  Vec2 p;
  std::uint32_t other = kNone;
  std::int8_t enter = 0;
};

}  // namespace

const char* contour_seg_kind_name(ContourSegKind kind) {
  switch (kind) {
    case ContourSegKind::kLine:
      return "line";
    case ContourSegKind::kCircleArc:
      return "circle-arc";
    case ContourSegKind::kEllipseArc:
      return "ellipse-arc";
  }
  return "?";
}

ZLevelResult zlevel_contours(const OffsetElements& el, std::span<const std::uint32_t> candidates,
                             double tip_z, const ZLevelParams& params) {
  ZLevelResult result;
  result.tip_z = tip_z;
  ZLevelStats& st = result.stats;
  const Level lv{tip_z + el.radius, el.radius};
  const auto n_el = std::uint32_t(el.element_count());
  const auto nf = std::uint32_t(el.facet_count()), ne = std::uint32_t(el.edge_count());
  if (!(lv.R > 0)) return result;

  // Candidate set as a bitmap: sorted, without repeats, independent of the given order.
  std::vector<std::uint64_t> bits((n_el + 63) / 64, 0);
  for (std::uint32_t id : candidates)
    if (id < n_el) bits[id >> 6] |= std::uint64_t(1) << (id & 63);
  auto for_each_id = [&](auto&& fn) {
    for (std::size_t w = 0; w < bits.size(); ++w)
      for (std::uint64_t m = bits[w]; m; m &= m - 1)
        fn(std::uint32_t(w * 64 + std::countr_zero(m)));
  };

  // Non-empty candidates with their boxes (floats rounded outwards), the grid's extent and
  // the mesh points at the ends of candidate edges (their discs mark interior cells).
  std::vector<std::uint32_t> cand;
  std::vector<Box4f> cand_box;
  cand.reserve(candidates.size());
  cand_box.reserve(candidates.size());
  std::vector<std::uint64_t> pbits((el.points.size() + 63) / 64, 0);
  auto mark_point = [&](std::uint32_t p) { pbits[p >> 6] |= std::uint64_t(1) << (p & 63); };
  double ext[4] = {INFINITY, INFINITY, -INFINITY, -INFINITY};
  for_each_id([&](std::uint32_t id) {
    ++st.candidates;
    double b[4];
    if (!candidate_box(el, id, lv, b)) return;
    cand.push_back(id);
    cand_box.push_back(outward_box(b));
    ext[0] = std::min(ext[0], b[0]);
    ext[1] = std::min(ext[1], b[1]);
    ext[2] = std::max(ext[2], b[2]);
    ext[3] = std::max(ext[3], b[3]);
    if (id >= nf + ne) {
      mark_point(el.vertex_source[id - nf - ne]);
    } else if (id >= nf) {
      mark_point(el.edge_vertices[id - nf][0]);
      mark_point(el.edge_vertices[id - nf][1]);
    }
  });
  if (!(ext[0] <= ext[2])) return result;
  Grid grid;
  grid.cell = params.cell > 0 ? params.cell : 0.5 * lv.R;
  const double wx = ext[2] - ext[0], wy = ext[3] - ext[1];
  const double max_cells = 4e6;
  if ((wx / grid.cell + 1) * (wy / grid.cell + 1) > max_cells)
    grid.cell = std::sqrt((wx + grid.cell) * (wy + grid.cell) / max_cells);
  grid.cell = std::max(grid.cell, 1e-9 * (1 + std::max(wx, wy)));
  grid.x0 = ext[0];
  grid.y0 = ext[1];
  grid.nx = std::max(1, int(wx / grid.cell) + 1);
  grid.ny = std::max(1, int(wy / grid.cell) + 1);
  grid.interior.assign(std::size_t(grid.nx) * grid.ny, 0);
  st.cells = grid.interior.size();

  // Interior cells: the discs of the mesh points (each inside U: the sphere belongs to a facet's
  // neighbourhood), which cover U's inside up to about the vertex spacing, and the regions of
  // the facets and edges large enough to hold cells beyond their vertices' discs.
  {
    Region g;
    g.kind = RegionKind::kVertex;
    for (std::size_t w = 0; w < pbits.size(); ++w)
      for (std::uint64_t m = pbits[w]; m; m &= m - 1) {
        const Vec3& p = el.points[w * 64 + std::countr_zero(m)];
        const double h = std::max(0.0, lv.zc - p.z());
        if (!(h < lv.R)) continue;
        g.r = std::sqrt((lv.R - h) * (lv.R + h));
        if (g.r < 0.7 * grid.cell) continue;
        g.c = Vec2(p.x(), p.y());
        g.box[0] = g.c.x() - g.r;
        g.box[1] = g.c.y() - g.r;
        g.box[2] = g.c.x() + g.r;
        g.box[3] = g.c.y() + g.r;
        mark_interior(g, lv, grid);
      }
    for (std::size_t k = 0; k < cand.size(); ++k) {
      const std::uint32_t id = cand[k];
      if (id >= nf + ne) continue;
      const auto& b = cand_box[k];
      const double big = id < nf ? grid.cell : 2 * lv.R + 2 * grid.cell;
      if (b[2] - b[0] < big && b[3] - b[1] < big) continue;
      if (id < nf && (b[2] - b[0] < grid.cell || b[3] - b[1] < grid.cell)) continue;
      if (build_region(el, id, lv, params.skip_unreachable, g)) mark_interior(g, lv, grid);
    }
  }
  grid.sum.assign(std::size_t(grid.nx + 1) * (grid.ny + 1), 0);
  for (int j = 0; j < grid.ny; ++j)
    for (int i = 0; i < grid.nx; ++i) {
      const std::size_t w = grid.nx + 1;
      const std::uint32_t open = grid.interior[std::size_t(j) * grid.nx + i] ? 0 : 1;
      grid.sum[(j + 1) * w + i + 1] =
          grid.sum[j * w + i + 1] + grid.sum[(j + 1) * w + i] - grid.sum[j * w + i] + open;
      st.interior_cells += 1 - open;
    }

  // Regions that reach an open cell, in element id order (facets, edges, vertices); vertices
  // come from those edges (and from vertex candidates).
  std::vector<Region> regions;
  std::vector<std::uint64_t> vbits((el.vertex_count() + 63) / 64, 0);
  auto mark_vertex_point = [&](std::uint32_t point) {
    const auto it = std::lower_bound(el.vertex_source.begin(), el.vertex_source.end(), point);
    if (it == el.vertex_source.end() || *it != point) return;
    const auto v = std::size_t(it - el.vertex_source.begin());
    vbits[v >> 6] |= std::uint64_t(1) << (v & 63);
  };
  for (std::size_t k = 0; k < cand.size(); ++k) {
    const std::uint32_t id = cand[k];
    const double b[4] = {cand_box[k][0], cand_box[k][1], cand_box[k][2], cand_box[k][3]};
    if (!grid.any_open(b)) continue;
    if (id >= nf + ne) {
      const std::uint32_t v = id - nf - ne;
      vbits[v >> 6] |= std::uint64_t(1) << (v & 63);
      continue;
    }
    if (id >= nf) {
      const auto& ev = el.edge_vertices[id - nf];
      mark_vertex_point(ev[0]);
      mark_vertex_point(ev[1]);
    }
    Region g;
    if (build_region(el, id, lv, params.skip_unreachable, g) && grid.any_open(g.box))
      regions.push_back(g);
  }
  for (std::size_t w = 0; w < vbits.size(); ++w)
    for (std::uint64_t m = vbits[w]; m; m &= m - 1) {
      const auto v = std::uint32_t(w * 64 + std::countr_zero(m));
      Region g;
      if (build_region(el, el.vertex_id(v), lv, params.skip_unreachable, g) && grid.any_open(g.box))
        regions.push_back(g);
    }
  st.regions = regions.size();

  // Candidate curves that reach an open cell.
  std::vector<Curve> curves;
  std::vector<Joint> joints;
  {
    std::vector<Curve> tmp;
    for (std::size_t gi = 0; gi < regions.size(); ++gi) {
      tmp.clear();
      region_curves(el, regions[gi], std::uint32_t(gi), lv, tmp, joints);
      regions[gi].curve_begin = std::uint32_t(curves.size());
      for (const Curve& c : tmp)
        if (c.len > 0 && grid.any_open(c.box)) curves.push_back(c);
      regions[gi].curve_end = std::uint32_t(curves.size());
    }
  }
  st.curves = curves.size();

  CellLists region_cells, curve_cells;
  fill_lists(
      grid, regions.size(), [&](std::size_t k) { return regions[k].box; }, region_cells);
  std::vector<Box4f> rbox(regions.size());
  for (std::size_t k = 0; k < regions.size(); ++k) rbox[k] = outward_box(regions[k].box);

  // The parts of the curves not certified inside U (piecewise by single regions or interior
  // cells): the active curves, in region order; act_begin[g] is region g's first.
  std::vector<Curve> act;
  std::vector<std::uint32_t> act_begin(regions.size() + 1, 0);
  {
    std::vector<std::pair<double, double>> runs;
    for (std::size_t gi = 0; gi < regions.size(); ++gi) {
      act_begin[gi] = std::uint32_t(act.size());
      for (std::uint32_t c = regions[gi].curve_begin; c < regions[gi].curve_end; ++c) {
        runs.clear();
        uncovered_runs(curves[c], grid, region_cells, regions, rbox, lv, runs);
        for (const auto& r : runs) act.push_back(sub_curve(curves[c], r.first, r.second));
      }
    }
    act_begin[regions.size()] = std::uint32_t(act.size());
  }
  fill_lists(
      grid, act.size(), [&](std::size_t k) { return act[k].box; }, curve_cells);

  // Active curve pairs i < j whose boxes overlap, once each, other than a region's own
  // curves and the structural pairs.
  std::vector<std::uint32_t> stamp;
  auto for_each_pair = [&](auto&& fn) {
    stamp.assign(act.size(), kNone);
    for (std::uint32_t i = 0; i < act.size(); ++i) {
      const Curve& C = act[i];
      int i0, j0, i1, j1;
      grid.range(C.box, i0, j0, i1, j1);
      for (int cj = j0; cj <= j1; ++cj)
        for (int ci = i0; ci <= i1; ++ci) {
          const std::size_t cell = std::size_t(cj) * grid.nx + ci;
          for (std::uint32_t k = curve_cells.start[cell]; k < curve_cells.start[cell + 1]; ++k) {
            const std::uint32_t j = curve_cells.ids[k];
            if (j <= i || stamp[j] == i) continue;
            stamp[j] = i;
            const Curve& D = act[j];
            if (C.region == D.region || !boxes_overlap(C.box, D.box)) continue;
            if (structural_pair(el, regions[C.region], regions[D.region])) continue;
            fn(i, j);
          }
        }
    }
  };

  // Coincident curves (the shadows of a wall's stacked edges and vertices lie on the same
  // lines and circles): where a curve runs along one of a lower element id, the
  // classification below drops it (the lower id keeps a shared piece; regions on both sides
  // drop both). Trimmed here instead, so that k coincident curves do not make k^2 pieces;
  // the lowest stays and still splits the curves that cross there.
  {
    struct Cut {
      std::uint32_t curve;
      double s0, s1;
    };
    std::vector<Cut> cuts;
    for_each_pair([&](std::uint32_t i, std::uint32_t j) {
      double d0, d1;  // act is in element order: act[i]'s is the lower id
      if (coincident_overlap(act[i], act[j], d0, d1)) cuts.push_back({j, d0, d1});
    });
    if (!cuts.empty()) {
      std::sort(cuts.begin(), cuts.end(), [](const Cut& a, const Cut& b) {
        return a.curve != b.curve ? a.curve < b.curve : a.s0 < b.s0;
      });
      std::vector<Curve> rest;
      std::vector<std::uint32_t> rest_begin(regions.size() + 1, 0);
      std::size_t q = 0;
      for (std::size_t gi = 0; gi < regions.size(); ++gi) {
        rest_begin[gi] = std::uint32_t(rest.size());
        for (std::uint32_t c = act_begin[gi]; c < act_begin[gi + 1]; ++c) {
          double from = 0;
          for (; q < cuts.size() && cuts[q].curve == c; ++q) {
            if (cuts[q].s0 > from) rest.push_back(sub_curve(act[c], from, cuts[q].s0));
            from = std::max(from, cuts[q].s1);
          }
          if (from < act[c].len) rest.push_back(sub_curve(act[c], from, act[c].len));
        }
      }
      rest_begin[regions.size()] = std::uint32_t(rest.size());
      act.swap(rest);
      act_begin.swap(rest_begin);
      fill_lists(
          grid, act.size(), [&](std::size_t k) { return act[k].box; }, curve_cells);
    }
  }
  st.active_curves = act.size();

  auto region_of_element = [&](std::uint32_t id) -> std::uint32_t {
    const auto it =
        std::lower_bound(regions.begin(), regions.end(), id,
                         [](const Region& g, std::uint32_t e) { return g.element < e; });
    return it != regions.end() && it->element == id ? std::uint32_t(it - regions.begin()) : kNone;
  };

  // Splits: every curve's ends, the tangent joints, the crossings.
  std::vector<Split> splits;
  splits.reserve(curves.size() * 4);
  for (std::uint32_t i = 0; i < act.size(); ++i) {
    splits.push_back({i, 0.0, act[i].a});
    splits.push_back({i, act[i].len, act[i].b});
  }
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
  {
    std::vector<Hit> hits;
    for_each_pair([&](std::uint32_t i, std::uint32_t j) {
      const Curve &C = act[i], &D = act[j];
      ++st.pairs;
      hits.clear();
      bool coincident;
      intersect_curves(C, D, lv, hits, coincident);
      const bool lines = !coincident && C.kind == CurveKind::kLine && D.kind == CurveKind::kLine &&
                         cross2(D.dir, C.dir) != 0;
      const std::int8_t enter = !lines ? 0 : cross2(D.dir, C.dir) > 0 ? 1 : -1;
      for (const Hit& h : hits) {
        splits.push_back({i, h.sc, h.p, lines ? D.region : kNone, enter});
        splits.push_back({j, h.sd, h.p, lines ? C.region : kNone, std::int8_t(-enter)});
      }
      st.crossings += hits.size();
    });
  }
  std::sort(splits.begin(), splits.end(), [](const Split& a, const Split& b) {
    if (a.curve != b.curve) return a.curve < b.curve;
    if (a.s != b.s) return a.s < b.s;
    if (a.p.x() != b.p.x()) return a.p.x() < b.p.x();
    return a.p.y() < b.p.y();
  });

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
  std::vector<KeptPiece> kept;
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
  st.kept = kept.size();
  build_loops(el, lv, regions, act, kept, params.link, result);
  return result;
}

}  // namespace ncpath
