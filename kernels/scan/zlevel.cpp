// Z-level contours (kernels/scan/zlevel.hpp): the top-level flow of zlevel_contours. Regions
// and candidate curves, active (uncovered) curves, coincident trimming, splits at tangent
// joints and crossings. The pruning grid: zlevel_grid.cpp; cover and piece classification:
// zlevel_cover.cpp; linking and output: zlevel_loops.cpp; the known inside region:
// zlevel_inside.cpp.
#include "kernels/scan/zlevel.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <optional>

#include "kernels/scan/zlevel_detail.hpp"

namespace ncpath {

using namespace zlevel_detail;

namespace {

template <class BoxOf>
void fill_lists(const Grid& grid, std::size_t n, BoxOf box_of, CellLists& out) {
  cell_lists(
      grid.nx, grid.ny, n,
      [&](std::size_t k, int& i0, int& j0, int& i1, int& j1) {
        const double* b = box_of(k);
        if (!(b[0] <= b[2])) return false;
        grid.range(b, i0, j0, i1, j1);
        return true;
      },
      [&](std::size_t c) { return !grid.interior[c]; }, out.start, out.ids);
}

// Each open cell's regions, deepest at the cell's centre first (ties by index), with that
// depth (lists.depth): the region that holds a curve piece in the cell is then found early in
// uncovered_runs and InsideU, whose scans stop at the first, and scans end where no
// region can matter any more (depth_cutoff).
void sort_by_depth(const Grid& grid, const std::vector<Region>& regions, const Level& lv,
                   CellLists& lists) {
  lists.depth.assign(lists.ids.size(), INFINITY);
  std::vector<std::pair<double, std::uint32_t>> key;
  for (int j = 0; j < grid.ny; ++j)
    for (int i = 0; i < grid.nx; ++i) {
      const std::size_t cell = std::size_t(j) * grid.nx + i;
      const std::uint32_t b0 = lists.start[cell], b1 = lists.start[cell + 1];
      if (b1 == b0) continue;
      const Vec2 centre = grid.centre(int(cell));
      key.clear();
      for (std::uint32_t q = b0; q < b1; ++q) {
        const double phi = region_phi(regions[lists.ids[q]], centre, lv);
        key.emplace_back(std::isnan(phi) ? INFINITY : phi, lists.ids[q]);
      }
      std::sort(key.begin(), key.end());
      for (std::uint32_t q = b0; q < b1; ++q) {
        lists.ids[q] = key[q - b0].second;
        lists.depth[q] = key[q - b0].first;
      }
    }
}

}  // namespace


ZLevelWorkspace::ZLevelWorkspace() : buffers_(std::make_unique<Buffers>()) {}
ZLevelWorkspace::~ZLevelWorkspace() = default;
ZLevelWorkspace::ZLevelWorkspace(ZLevelWorkspace&&) noexcept = default;
ZLevelWorkspace& ZLevelWorkspace::operator=(ZLevelWorkspace&&) noexcept = default;

namespace {

// A part [s0, s1] of active curve `curve` to remove.
struct Cut {
  std::uint32_t curve;
  double s0, s1;
};

// Removes the cuts (any order) from the active curves `act`, each region's curves staying
// together (act_begin[g]: region g's first); `rest` is scratch.
void remove_cuts(std::vector<Cut>& cuts, std::vector<Curve>& act, std::vector<Curve>& rest,
                 std::vector<std::uint32_t>& act_begin) {
  std::sort(cuts.begin(), cuts.end(), [](const Cut& a, const Cut& b) {
    return a.curve != b.curve ? a.curve < b.curve : a.s0 < b.s0;
  });
  const std::size_t regions = act_begin.size() - 1;
  rest.clear();
  std::vector<std::uint32_t> rest_begin(regions + 1, 0);
  std::size_t q = 0;
  for (std::size_t gi = 0; gi < regions; ++gi) {
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
  rest_begin[regions] = std::uint32_t(rest.size());
  act.swap(rest);
  act_begin.swap(rest_begin);
}

bool boxes_overlap(const double* a, const double* b) {
  const double s = tol::kZLevelSlack;
  return a[0] <= b[2] + s && b[0] <= a[2] + s && a[1] <= b[3] + s && b[1] <= a[3] + s;
}

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

namespace {

// The splits where active curves i and j cross or touch (both curves' parameters); line
// crossings carry their orientation, for the classification. Returns the number of hits.
std::size_t crossing_splits(const std::vector<Curve>& act, std::uint32_t i, std::uint32_t j,
                            const Level& lv, std::vector<Hit>& hits, std::vector<Split>& splits,
                            ZLevelStats& st) {
  hits.clear();
  bool coincident;
  const Curve &C = act[i], &D = act[j];
  intersect_curves(C, D, lv, hits, coincident);
  st.coincident_pairs += coincident;
  const bool lines = !coincident && C.kind == CurveKind::kLine && D.kind == CurveKind::kLine &&
                     cross2(D.dir, C.dir) != 0;
  const std::int8_t enter = !lines ? 0 : cross2(D.dir, C.dir) > 0 ? 1 : -1;
  for (const Hit& h : hits) {
    // A T-junction (one line ends on the other) has no orientation: the lines need not
    // cross there.
    const bool cross = lines && !h.touch;
    const std::int8_t e = cross ? enter : 0;
    splits.push_back({i, h.sc, h.p, cross ? j : kNone, e});
    splits.push_back({j, h.sd, h.p, cross ? i : kNone, std::int8_t(-e)});
  }
  return hits.size();
}

// Splits by curve, then parameter, then position (a total order: any input order).
void sort_splits(std::vector<Split>& splits) {
  std::sort(splits.begin(), splits.end(), [](const Split& a, const Split& b) {
    if (a.curve != b.curve) return a.curve < b.curve;
    if (a.s != b.s) return a.s < b.s;
    if (a.p.x() != b.p.x()) return a.p.x() < b.p.x();
    return a.p.y() < b.p.y();
  });
}

// Each arc's clearance (ContourSeg::clearance, arc_clearance): how far its circumscribed
// polygon may bulge, at most `cap`, without entering the regions other than its own and its
// neighbours'.
void set_clearances(double cap, const Grid& grid, const CellLists& region_cells,
                    const std::vector<Region>& regions, const std::vector<Box4f>& rbox,
                    const Level& lv, ZLevelResult& result) {
  for (ZContour& c : result.contours)
    for (std::size_t i = 0; i < c.segs.size(); ++i) {
      ContourSeg& s = c.segs[i];
      if (s.kind == ContourSegKind::kLine) continue;
      const std::size_t m = c.segs.size();
      const std::array<std::uint32_t, 3> skip = {s.element, c.segs[(i + m - 1) % m].element,
                                                 c.segs[(i + 1) % m].element};
      s.clearance = arc_clearance(s, skip, cap, grid, region_cells, regions, rbox, lv);
    }
}

// Regions that reach an open cell, in element id order (facets, edges, vertices; vertices
// come from those edges and from vertex candidates), each marked when wholly above the
// inside region's level (Region::known_inside); a region deep inside it
// (tol::kZLevelInsideDepth) is dropped, its shape tested through a hull that holds it: the
// projected offset triangle, the capsule of radius R around the edge's shadow, the disc.
void collect_regions(const OffsetElements& el, Workspace& ws, const Level& lv,
                     const ZLevelInside* inside, const Grid& grid, ZLevelStats& st) {
  const auto nf = std::uint32_t(el.facet_count()), ne = std::uint32_t(el.edge_count());
  const std::vector<std::uint32_t>& cand = ws.cand;
  const std::vector<Box4f>& cand_box = ws.cand_box;
  const double zc_inside = inside ? inside->tip_z + lv.R : INFINITY;
  auto mark_known = [&](Region& g) {
    double low = INFINITY;
    if (g.kind == RegionKind::kFacet) {
      for (const Vec3& v : el.offset_tri(g.index)) low = std::min(low, v.z());
    } else if (g.kind == RegionKind::kEdge) {
      low = g.a.z();  // the lower end
    } else {
      low = g.vz;
    }
    g.known_inside = low >= zc_inside;
  };
  auto deep_inside = [&](const Region& g) {
    if (!inside) return false;
    const bool deep = region_in_known(el, *inside, g, tol::kZLevelInsideDepth);
    st.inside_regions += deep;
    return deep;
  };
  std::vector<Region>& regions = ws.regions;
  regions.clear();
  std::vector<std::uint64_t>& vbits = ws.vbits;
  vbits.assign((el.vertex_count() + 63) / 64, 0);
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
    if (build_region(el, id, lv, g) && grid.any_open(g.box) && !deep_inside(g)) {
      mark_known(g);
      regions.push_back(g);
    }
  }
  for (std::size_t w = 0; w < vbits.size(); ++w)
    for (std::uint64_t m = vbits[w]; m; m &= m - 1) {
      const auto v = std::uint32_t(w * 64 + std::countr_zero(m));
      Region g;
      if (build_region(el, el.vertex_id(v), lv, g) && grid.any_open(g.box) && !deep_inside(g)) {
        mark_known(g);
        regions.push_back(g);
      }
    }
  st.regions = regions.size();

}

// The regions' curves that reach an open cell (ws.curves, each region's a range of them),
// and their tangent joints (ws.joints).
void collect_curves(const OffsetElements& el, Workspace& ws, const Level& lv, const Grid& grid,
                    ZLevelStats& st) {
  std::vector<Region>& regions = ws.regions;
  std::vector<Curve>& curves = ws.curves;
  std::vector<Joint>& joints = ws.joints;
  curves.clear();
  joints.clear();
  {
    std::vector<Curve>& tmp = ws.tmp;
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

}

// Active curve pairs i < j whose boxes overlap, once each, other than a region's own curves
// and the structural pairs.
template <class Fn>
void for_each_pair(const OffsetElements& el, Workspace& ws, const Grid& grid, Fn&& fn) {
  const std::vector<Curve>& act = ws.act;
  const std::vector<Region>& regions = ws.regions;
  const CellLists& curve_cells = ws.curve_cells;
  std::vector<std::uint32_t>& stamp = ws.stamp;
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
}

// The parts of the curves not certified inside U (piecewise by single regions or interior
// cells): the active curves (ws.act), in region order, with coincident curves trimmed to the
// lowest element id's; the lists of regions and active curves per cell. Returns each
// region's first active curve (and the end).
std::vector<std::uint32_t> active_curves(const OffsetElements& el, Workspace& ws,
                                         const Level& lv, const ZLevelInside* inside,
                                         const Grid& grid, ZLevelStats& st) {
  std::vector<Region>& regions = ws.regions;
  const std::vector<Curve>& curves = ws.curves;
  CellLists &region_cells = ws.region_cells, &curve_cells = ws.curve_cells;
  fill_lists(
      grid, regions.size(), [&](std::size_t k) { return regions[k].box; }, region_cells);
  sort_by_depth(grid, regions, lv, region_cells);
  std::vector<Box4f>& rbox = ws.rbox;
  rbox.resize(regions.size());
  for (std::size_t k = 0; k < regions.size(); ++k) rbox[k] = outward_box(regions[k].box);

  std::vector<Curve>& act = ws.act;
  act.clear();
  std::vector<std::uint32_t> act_begin(regions.size() + 1, 0);
  {
    std::vector<std::pair<double, double>> runs;
    for (std::size_t gi = 0; gi < regions.size(); ++gi) {
      act_begin[gi] = std::uint32_t(act.size());
      for (std::uint32_t c = regions[gi].curve_begin; c < regions[gi].curve_end; ++c) {
        runs.clear();
        uncovered_runs(curves[c], grid, region_cells, regions, rbox, lv, inside, runs);
        for (const auto& r : runs) act.push_back(sub_curve(curves[c], r.first, r.second));
      }
    }
    act_begin[regions.size()] = std::uint32_t(act.size());
  }
  fill_lists(
      grid, act.size(), [&](std::size_t k) { return act[k].box; }, curve_cells);

  // Coincident curves (the shadows of a wall's stacked edges and vertices lie on the same
  // lines and circles): where a curve runs along one of a lower element id, the
  // classification below drops it (the lower id keeps a shared piece; regions on both sides
  // drop both). Trimmed here instead, so that k coincident curves do not make k^2 pieces;
  // the lowest stays and still splits the curves that cross there.
  {
    std::vector<Cut> cuts;
    for_each_pair(el, ws, grid, [&](std::uint32_t i, std::uint32_t j) {
      double d0, d1;  // act is in element order: act[i]'s is the lower id
      if (coincident_overlap(act[i], act[j], d0, d1)) cuts.push_back({j, d0, d1});
    });
    if (!cuts.empty()) {
      remove_cuts(cuts, act, ws.rest, act_begin);
      fill_lists(
          grid, act.size(), [&](std::size_t k) { return act[k].box; }, curve_cells);
    }
  }
  st.active_curves = act.size();

  return act_begin;
}

// Splits of the active curves: every curve's ends, the tangent joints, the crossings; sorted.
void level_splits(Workspace& ws, const std::vector<std::uint32_t>& act_begin,
                  const OffsetElements& el, const Level& lv, const Grid& grid, ZLevelStats& st) {
  const std::vector<Curve>& act = ws.act;
  const std::vector<Curve>& curves = ws.curves;
  const std::vector<Joint>& joints = ws.joints;
  const std::vector<Region>& regions = ws.regions;
  std::vector<Split>& splits = ws.splits;
  splits.clear();
  splits.reserve(curves.size() * 4);
  for (std::uint32_t i = 0; i < act.size(); ++i) {
    splits.push_back({i, 0.0, act[i].a});
    splits.push_back({i, act[i].len, act[i].b});
  }
  joint_splits(joints, regions, act, act_begin, splits);
  {
    std::vector<Hit> hits;
    for_each_pair(el, ws, grid, [&](std::uint32_t i, std::uint32_t j) {
      ++st.pairs;
      st.crossings += crossing_splits(act, i, j, lv, hits, splits, st);
    });
  }
  sort_splits(splits);

}

}  // namespace

ZLevelResult zlevel_contours(const OffsetElements& el, std::span<const std::uint32_t> candidates,
                             double tip_z, const ZLevelParams& params) {
  ZLevelResult result;
  result.tip_z = tip_z;
  ZLevelStats& st = result.stats;
  const Level lv{tip_z + el.radius, el.radius};
  if (!(lv.R > 0)) return result;
  std::optional<ZLevelWorkspace> own;
  if (!params.workspace) own.emplace();
  Workspace& ws = params.workspace ? params.workspace->buffers() : own->buffers();
  double ext[4] = {INFINITY, INFINITY, -INFINITY, -INFINITY};
  gather_candidates(el, candidates, lv, params, ws, st, ext);
  if (!(ext[0] <= ext[2])) return result;
  const ZLevelInside* inside = params.inside && !params.inside->empty() ? params.inside : nullptr;
  const Grid grid = level_grid(el, ws, lv, inside, params, ext, st);
  collect_regions(el, ws, lv, inside, grid, st);
  collect_curves(el, ws, lv, grid, st);
  const std::vector<std::uint32_t> act_begin = active_curves(el, ws, lv, inside, grid, st);
  level_splits(ws, act_begin, el, lv, grid, st);

  // The pieces between consecutive splits; the contours are the boundaries of the faces of
  // their planar map that lie outside U.
  const std::vector<Piece> pieces = split_pieces(ws.splits, st);
  std::vector<std::uint8_t> keep;
  classify_pieces(ws.splits, ws.act, ws.curves, ws.regions, ws.rbox, grid, ws.region_cells, lv,
                  keep);
  build_loops(el, lv, ws.regions, ws.act, pieces, keep, result);
  if (params.clearance_cap > 0)
    set_clearances(params.clearance_cap, grid, ws.region_cells, ws.regions, ws.rbox, lv,
                   result);
  return result;
}

}  // namespace ncpath
