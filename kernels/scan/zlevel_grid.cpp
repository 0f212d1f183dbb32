// The pruning grid of one z level (kernels/scan/zlevel.hpp, zlevel_detail.hpp): the
// candidates that reach the level and their boxes, the grid over them and its interior cells
// (certainly inside U), which prune regions, curves and pairs in zlevel.cpp.
#include <algorithm>
#include <bit>
#include <cmath>

#include "kernels/scan/zlevel_detail.hpp"

namespace ncpath {

using namespace zlevel_detail;

namespace {

// Box of the element's region at any level (conservative, mm) and its reach (see
// ZLevelElementBoxes); false for a vertical facet (no region at any level).
bool element_box(const OffsetElements& el, std::uint32_t id, double* b, double& reach) {
  const auto nf = el.facet_count(), ne = el.edge_count();
  auto put = [&](const Vec3& p) {
    b[0] = std::min(b[0], p.x());
    b[1] = std::min(b[1], p.y());
    b[2] = std::max(b[2], p.x());
    b[3] = std::max(b[3], p.y());
  };
  b[0] = b[1] = INFINITY;
  b[2] = b[3] = -INFINITY;
  reach = -INFINITY;
  if (id < nf) {
    if (el.facet_vertical[id]) return false;
    const auto t = el.offset_tri(id);
    reach = std::max({t[0].z(), t[1].z(), t[2].z()});
    for (const Vec3& p : t) put(p);
    return true;
  }
  const double pad = el.radius;
  if (id < nf + ne) {
    const auto& ev = el.edge_vertices[id - nf];
    const Vec3 &p = el.points[ev[0]], &q = el.points[ev[1]];
    reach = std::max(p.z(), q.z()) + el.radius;
    put(p);
    put(q);
  } else {
    const Vec3& p = el.points[el.vertex_source[id - nf - ne]];
    reach = p.z() + el.radius;
    put(p);
  }
  b[0] -= pad;
  b[1] -= pad;
  b[2] += pad;
  b[3] += pad;
  return true;
}

// Whether the region of element `id` (facets: ids below nf) can be non-empty at the level.
bool reaches(double reach, bool facet, const Level& lv) {
  return facet ? reach >= lv.zc : reach > lv.zc;
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

// Interior cells: the discs of the mesh points at the ends of candidate edges (each inside U:
// the sphere belongs to a facet's neighbourhood), which cover U's inside up to about the
// vertex spacing, the regions of the facets and edges large enough to hold cells beyond their
// vertices' discs, and the cells inside the known inside region (a higher level's contours).
void mark_interior_cells(const OffsetElements& el, const Workspace& ws, const Level& lv,
                         const ZLevelInside* inside, Grid& grid, ZLevelStats& st) {
  const auto nf = std::uint32_t(el.facet_count()), ne = std::uint32_t(el.edge_count());
  const auto& pbits = ws.pbits;
  const auto& cand = ws.cand;
  const auto& cand_box = ws.cand_box;
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
    if (build_region(el, id, lv, g)) mark_interior(g, lv, grid);
  }
  if (inside)
    for (int j = 0; j < grid.ny; ++j)
      for (int i = 0; i < grid.nx; ++i) {
        const std::size_t c = std::size_t(j) * grid.nx + i;
        if (grid.interior[c]) continue;
        const double x0 = grid.gx(i), y0 = grid.gy(j), x1 = x0 + grid.cell, y1 = y0 + grid.cell;
        const Vec2 sq[4] = {Vec2(x0, y0), Vec2(x1, y0), Vec2(x1, y1), Vec2(x0, y1)};
        if (inside_contains(*inside, sq, 4, 0, inside->margin)) {
          grid.interior[c] = 1;
          ++st.inside_cells;
        }
      }
}

}  // namespace

ZLevelElementBoxes zlevel_element_boxes(const OffsetElements& el) {
  ZLevelElementBoxes out;
  const std::size_t n = el.element_count();
  out.box.resize(n);
  out.reach.resize(n);
  for (std::size_t id = 0; id < n; ++id) {
    double b[4];
    element_box(el, std::uint32_t(id), b, out.reach[id]);  // reach -inf: no region
    out.box[id] = outward_box(b);
  }
  return out;
}

namespace zlevel_detail {

void gather_candidates(const OffsetElements& el, std::span<const std::uint32_t> candidates,
                       const Level& lv, const ZLevelParams& params, Workspace& ws,
                       ZLevelStats& st, double ext[4]) {
  const auto n_el = std::uint32_t(el.element_count());
  const auto nf = std::uint32_t(el.facet_count()), ne = std::uint32_t(el.edge_count());
  std::vector<std::uint64_t>& bits = ws.bits;
  bits.assign((n_el + 63) / 64, 0);
  for (std::uint32_t id : candidates)
    if (id < n_el) bits[id >> 6] |= std::uint64_t(1) << (id & 63);
  auto for_each_id = [&](auto&& fn) {
    for (std::size_t w = 0; w < bits.size(); ++w)
      for (std::uint64_t m = bits[w]; m; m &= m - 1)
        fn(std::uint32_t(w * 64 + std::countr_zero(m)));
  };

  std::vector<std::uint32_t>& cand = ws.cand;
  std::vector<Box4f>& cand_box = ws.cand_box;
  cand.clear();
  cand_box.clear();
  cand.reserve(candidates.size());
  cand_box.reserve(candidates.size());
  std::vector<std::uint64_t>& pbits = ws.pbits;
  pbits.assign((el.points.size() + 63) / 64, 0);
  auto mark_point = [&](std::uint32_t p) { pbits[p >> 6] |= std::uint64_t(1) << (p & 63); };
  const ZLevelElementBoxes* pre = params.boxes;
  for_each_id([&](std::uint32_t id) {
    ++st.candidates;
    Box4f fb;
    if (pre) {
      if (!reaches(pre->reach[id], id < nf, lv)) return;
      fb = pre->box[id];
    } else {
      double b[4], reach;
      if (!element_box(el, id, b, reach) || !reaches(reach, id < nf, lv)) return;
      fb = outward_box(b);
    }
    cand.push_back(id);
    cand_box.push_back(fb);
    ext[0] = std::min(ext[0], double(fb[0]));
    ext[1] = std::min(ext[1], double(fb[1]));
    ext[2] = std::max(ext[2], double(fb[2]));
    ext[3] = std::max(ext[3], double(fb[3]));
    if (id >= nf + ne) {
      mark_point(el.vertex_source[id - nf - ne]);
    } else if (id >= nf) {
      mark_point(el.edge_vertices[id - nf][0]);
      mark_point(el.edge_vertices[id - nf][1]);
    }
  });
}

Grid level_grid(const OffsetElements& el, const Workspace& ws, const Level& lv,
                const ZLevelInside* inside, const ZLevelParams& params, const double ext[4],
                ZLevelStats& st) {
  Grid grid;
  grid.cell = params.cell > 0 ? params.cell : 0.5 * lv.R;
  const double wx = ext[2] - ext[0], wy = ext[3] - ext[1];
  const double max_cells = 4e6;
  if ((wx / grid.cell + 1) * (wy / grid.cell + 1) > max_cells)
    grid.cell = std::sqrt((wx + grid.cell) * (wy + grid.cell) / max_cells);
  grid.cell = std::max(grid.cell, tol::kZLevelMinCell * (1 + std::max(wx, wy)));
  grid.x0 = ext[0];
  grid.y0 = ext[1];
  grid.nx = std::max(1, int(wx / grid.cell) + 1);
  grid.ny = std::max(1, int(wy / grid.cell) + 1);
  grid.interior.assign(std::size_t(grid.nx) * grid.ny, 0);
  st.cells = grid.interior.size();

  mark_interior_cells(el, ws, lv, inside, grid, st);
  grid.sum.assign(std::size_t(grid.nx + 1) * (grid.ny + 1), 0);
  for (int j = 0; j < grid.ny; ++j)
    for (int i = 0; i < grid.nx; ++i) {
      const std::size_t w = grid.nx + 1;
      const std::uint32_t open = grid.interior[std::size_t(j) * grid.nx + i] ? 0 : 1;
      grid.sum[(j + 1) * w + i + 1] =
          grid.sum[j * w + i + 1] + grid.sum[(j + 1) * w + i] - grid.sum[j * w + i] + open;
      st.interior_cells += 1 - open;
    }

  return grid;
}

}  // namespace zlevel_detail

}  // namespace ncpath
