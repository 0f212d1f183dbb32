// The known inside region of the z-level kernel (kernels/scan/zlevel.hpp ZLevelInside): a
// higher level's contours as polygons on a uniform grid, with depth queries. Declarations of
// the queries: zlevel_detail.hpp.
#include <algorithm>
#include <cmath>

#include "kernels/geom/segment2.hpp"
#include "kernels/geom/tolerance.hpp"
#include "kernels/scan/zlevel_detail.hpp"

namespace ncpath {

using namespace zlevel_detail;

namespace {

double orient(const Vec2& a, const Vec2& b, const Vec2& c) { return cross2(b - a, c - a); }

double seg_seg(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const double o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a),
               o4 = orient(c, d, b);
  if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0)))
    return 0;
  return std::min({point_segment_distance(a, c, d), point_segment_distance(b, c, d),
                   point_segment_distance(c, a, b), point_segment_distance(d, a, b)});
}

// Whether x lies in the convex polygon poly[0, n) (either orientation; on its boundary too).
bool in_convex(const Vec2& x, const Vec2* poly, int n) {
  bool pos = false, neg = false;
  for (int k = 0; k < n; ++k) {
    const double o = orient(poly[k], poly[(k + 1) % n], x);
    pos |= o > 0;
    neg |= o < 0;
  }
  return !(pos && neg);
}

// Distance from segment ab to the hull of poly[0, n) (n <= 4, the points in hull order).
double seg_hull(const Vec2& a, const Vec2& b, const Vec2* poly, int n) {
  if (n == 1) return point_segment_distance(poly[0], a, b);
  if (n == 2) return seg_seg(a, b, poly[0], poly[1]);
  if (in_convex(a, poly, n) || in_convex(b, poly, n)) return 0;
  double d = INFINITY;
  for (int k = 0; k < n; ++k) d = std::min(d, seg_seg(a, b, poly[k], poly[(k + 1) % n]));
  return d;
}

int cell_of(const ZLevelInside& q, const Vec2& x) {
  const double fx = std::floor((x.x() - q.x0) / q.cell), fy = std::floor((x.y() - q.y0) / q.cell);
  if (!(fx >= 0 && fx < q.nx && fy >= 0 && fy < q.ny)) return -1;
  return int(fy) * q.nx + int(fx);
}

// Cells whose square meets the box [x0, x1] x [y0, y1], clamped to the grid; false if none.
bool cell_range(const ZLevelInside& q, double x0, double y0, double x1, double y1, int& i0, int& j0,
                int& i1, int& j1) {
  const double fx0 = std::floor((x0 - q.x0) / q.cell), fx1 = std::floor((x1 - q.x0) / q.cell);
  const double fy0 = std::floor((y0 - q.y0) / q.cell), fy1 = std::floor((y1 - q.y0) / q.cell);
  if (!(fx1 >= 0 && fy1 >= 0 && fx0 < q.nx && fy0 < q.ny)) return false;
  i0 = int(std::max(0.0, fx0));
  j0 = int(std::max(0.0, fy0));
  i1 = int(std::min(double(q.nx - 1), fx1));
  j1 = int(std::min(double(q.ny - 1), fy1));
  return true;
}

void fill_cells(ZLevelInside& q) {
  cell_lists(
      q.nx, q.ny, q.edges.size(),
      [&](std::size_t e, int& i0, int& j0, int& i1, int& j1) {
        const Vec2 &a = q.edges[e][0], &b = q.edges[e][1];
        return cell_range(q, std::min(a.x(), b.x()), std::min(a.y(), b.y()), std::max(a.x(), b.x()),
                          std::max(a.y(), b.y()), i0, j0, i1, j1);
      },
      [](std::size_t) { return true; }, q.start, q.ids);
}

// Parity of x from the reference point of its cell: the crossings of the segment between
// them with the cell's polygon edges (half-open at the segment's line, so that an edge pair
// meeting on it counts once). Only for x not on an edge (callers check its clearance).
bool parity_inside(const ZLevelInside& q, const Vec2& x) {
  const int c = cell_of(q, x);
  if (c < 0 || q.ref_state[c] == 2) return false;
  const Vec2& r = q.ref[c];
  const Vec2 d = x - r;
  bool in = q.ref_state[c] == 1;
  for (std::uint32_t k = q.start[c]; k < q.start[c + 1]; ++k) {
    const std::uint32_t e = q.ids[k];
    if (e >= q.polygon_edges) continue;
    const Vec2 &p = q.edges[e][0], &s = q.edges[e][1];
    if ((cross2(d, p - r) > 0) == (cross2(d, s - r) > 0)) continue;
    const Vec2 es = s - p;
    const double a = cross2(es, r - p), b = cross2(es, x - p);
    if ((a > 0 && b < 0) || (a < 0 && b > 0)) in = !in;
  }
  return in;
}

// Smallest distance (minus r) from the hull of poly to the edges near it, or `limit` when none
// is nearer; polygon_only skips the sides of blocked cells.
double clearance(const ZLevelInside& q, const Vec2* poly, int n, double r, double limit,
                 bool polygon_only) {
  double b[4];
  points_box(poly, n, b);
  const double g = r + limit;
  int i0, j0, i1, j1;
  if (!cell_range(q, b[0] - g, b[1] - g, b[2] + g, b[3] + g, i0, j0, i1, j1)) return limit;
  double best = limit;
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) {
      const std::size_t c = std::size_t(j) * q.nx + i;
      for (std::uint32_t k = q.start[c]; k < q.start[c + 1]; ++k) {
        const std::uint32_t e = q.ids[k];
        if (polygon_only && e >= q.polygon_edges) continue;
        const Vec2 &a = q.edges[e][0], &z = q.edges[e][1];
        const double gx =
            std::max({0.0, std::min(a.x(), z.x()) - b[2], b[0] - std::max(a.x(), z.x())});
        const double gy =
            std::max({0.0, std::min(a.y(), z.y()) - b[3], b[1] - std::max(a.y(), z.y())});
        if (gx * gx + gy * gy >= (best + r) * (best + r)) continue;
        best = std::min(best, seg_hull(a, z, poly, n) - r);
        if (best < 0) return best;
      }
    }
  return best;
}

}  // namespace

ZLevelInside zlevel_inside(const ZLevelResult& higher, double cell) {
  ZLevelInside q;
  if (higher.contours.empty() || higher.stats.open_chains > 0) return q;
  q.tip_z = higher.tip_z;
  q.margin = tol::kZLevelInsideMargin;
  // Inscribed polygons: the points lie on the segments, a chord of an arc inside its region.
  std::vector<Vec2> pts;
  double ext[4] = {INFINITY, INFINITY, -INFINITY, -INFINITY};
  std::vector<std::uint8_t> line;  // per point: it starts a line segment ending at the next
  for (const ZContour& con : higher.contours) {
    pts.clear();
    line.clear();
    for (std::size_t i = 0; i < con.segs.size(); ++i) {
      const ContourSeg& s = con.segs[i];
      const std::size_t before = pts.size();
      discretise(s, 0.25 * tol::kZLevelInsideDepth, pts);
      line.resize(pts.size(), 0);
      const Vec2& next = con.segs[(i + 1) % con.segs.size()].a;
      line[before] =
          s.kind == ContourSegKind::kLine && (s.b - next).norm() <= tol::kZLevelSharedEnd;
    }
    for (std::size_t k = 0; k < pts.size(); ++k) {
      const Vec2 &a = pts[k], &b = pts[(k + 1) % pts.size()];
      ext[0] = std::min(ext[0], a.x());
      ext[1] = std::min(ext[1], a.y());
      ext[2] = std::max(ext[2], a.x());
      ext[3] = std::max(ext[3], a.y());
      if (a == b) continue;
      q.edges.push_back({a, b});
      q.exact.push_back(line[k]);
    }
  }
  if (q.edges.size() < 3 || !(ext[0] <= ext[2])) return ZLevelInside{};
  q.polygon_edges = std::uint32_t(q.edges.size());
  q.cell = cell > 0 ? cell : 1.0;
  const double wx = ext[2] - ext[0], wy = ext[3] - ext[1];
  const double max_cells = 4e6;
  if ((wx / q.cell + 3) * (wy / q.cell + 3) > max_cells)
    q.cell = std::sqrt((wx + 3 * q.cell) * (wy + 3 * q.cell) / max_cells);
  q.x0 = ext[0] - q.cell;
  q.y0 = ext[1] - q.cell;
  q.nx = int(wx / q.cell) + 3;
  q.ny = int(wy / q.cell) + 3;
  fill_cells(q);

  // Reference points: the cell's centre, else a few other points of the cell, at least
  // tol::kZLevelRefClearance from the cell's edges; their parity by a ray towards +x over the edges
  // of their row (half-open in y, as parity_inside is at its segment's line).
  const std::size_t cells = std::size_t(q.nx) * q.ny;
  q.ref.assign(cells, Vec2::Zero());
  q.ref_state.assign(cells, 2);
  std::vector<std::vector<std::uint32_t>> rows(q.ny);
  for (std::uint32_t e = 0; e < q.polygon_edges; ++e) {
    const double y0 = std::min(q.edges[e][0].y(), q.edges[e][1].y());
    const double y1 = std::max(q.edges[e][0].y(), q.edges[e][1].y());
    const int j0 = std::max(0, int(std::floor((y0 - q.y0) / q.cell)));
    const int j1 = std::min(q.ny - 1, int(std::floor((y1 - q.y0) / q.cell)));
    for (int j = j0; j <= j1; ++j) rows[j].push_back(e);
  }
  static constexpr double kOffsets[][2] = {{0.5, 0.5},   {0.3, 0.6},   {0.7, 0.4},  {0.4, 0.3},
                                           {0.6, 0.7},   {0.2, 0.8},   {0.8, 0.2},  {0.15, 0.35},
                                           {0.85, 0.65}, {0.35, 0.85}, {0.65, 0.15}};
  std::vector<std::uint32_t> blocked;
  std::vector<double> xs;
  for (int j = 0; j < q.ny; ++j) {
    auto crossings_right = [&](const Vec2& r) {
      int n = 0;
      for (std::uint32_t e : rows[j]) {
        const Vec2 &p = q.edges[e][0], &s = q.edges[e][1];
        if ((p.y() > r.y()) == (s.y() > r.y())) continue;
        const double x = p.x() + (r.y() - p.y()) * (s.x() - p.x()) / (s.y() - p.y());
        n += x > r.x();
      }
      return n;
    };
    // Centres share y: their crossings once, sorted.
    const double yc = q.y0 + (j + 0.5) * q.cell;
    xs.clear();
    for (std::uint32_t e : rows[j]) {
      const Vec2 &p = q.edges[e][0], &s = q.edges[e][1];
      if ((p.y() > yc) == (s.y() > yc)) continue;
      xs.push_back(p.x() + (yc - p.y()) * (s.x() - p.x()) / (s.y() - p.y()));
    }
    std::sort(xs.begin(), xs.end());
    for (int i = 0; i < q.nx; ++i) {
      const std::size_t c = std::size_t(j) * q.nx + i;
      for (std::size_t o = 0; o < std::size(kOffsets); ++o) {
        const Vec2 r(q.x0 + (i + kOffsets[o][0]) * q.cell, q.y0 + (j + kOffsets[o][1]) * q.cell);
        bool clear = true;
        for (std::uint32_t k = q.start[c]; k < q.start[c + 1] && clear; ++k)
          clear = point_segment_distance(r, q.edges[q.ids[k]][0], q.edges[q.ids[k]][1]) >=
                  tol::kZLevelRefClearance;
        if (!clear) continue;
        const auto right =
            o == 0 ? std::size_t(xs.end() - std::upper_bound(xs.begin(), xs.end(), r.x()))
                   : std::size_t(crossings_right(r));
        q.ref[c] = r;
        q.ref_state[c] = std::uint8_t(right & 1);
        break;
      }
      if (q.ref_state[c] == 2) blocked.push_back(std::uint32_t(c));
    }
  }
  // A blocked cell (no clear reference point: rounding-close edges everywhere in it) is
  // never known inside: its sides join the edges that queries keep their distance from.
  q.blocked_cells = std::uint32_t(blocked.size());
  if (!blocked.empty()) {
    for (std::uint32_t c : blocked) {
      const double x0 = q.x0 + (c % q.nx) * q.cell, y0 = q.y0 + (c / q.nx) * q.cell;
      const Vec2 p[4] = {Vec2(x0, y0), Vec2(x0 + q.cell, y0), Vec2(x0 + q.cell, y0 + q.cell),
                         Vec2(x0, y0 + q.cell)};
      for (int k = 0; k < 4; ++k) q.edges.push_back({p[k], p[(k + 1) % 4]});
    }
    fill_cells(q);
  }
  // Chebyshev distance in cells to the nearest cell with an edge (breadth-first, 8 neighbours).
  q.far.assign(cells, 255);
  std::vector<std::uint32_t> front, next;
  for (std::uint32_t c = 0; c < cells; ++c)
    if (q.start[c + 1] > q.start[c]) {
      q.far[c] = 0;
      front.push_back(c);
    }
  for (int d = 1; d < 255 && !front.empty(); ++d) {
    next.clear();
    for (std::uint32_t c : front) {
      const int i = int(c % q.nx), j = int(c / q.nx);
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          const int ii = i + di, jj = j + dj;
          if (ii < 0 || jj < 0 || ii >= q.nx || jj >= q.ny) continue;
          const std::size_t n = std::size_t(jj) * q.nx + ii;
          if (q.far[n] != 255) continue;
          q.far[n] = std::uint8_t(d);
          next.push_back(std::uint32_t(n));
        }
    }
    front.swap(next);
  }
  return q;
}

namespace {

// Quick answer from the far field: 1 when the shape (hull within `reach` of poly[0], grown by
// r) lies `margin` deep inside, 0 when it lies wholly outside, -1 when the edges must decide.
int far_answer(const ZLevelInside& q, const Vec2& p, double reach, double margin) {
  const int c = cell_of(q, p);
  if (c < 0) return -1;
  const int k = q.far[c];
  if (k == 0 || q.ref_state[c] == 2) return -1;
  // Edges lie in cells k or more steps away: at least (k - 1) cells from any point of c.
  if ((k - 1) * q.cell < reach + margin) return -1;
  return q.ref_state[c] == 1 ? 1 : 0;
}

}  // namespace

namespace {

// The shape that holds the region of facet or edge `id` at any level: conv(p[0, n)) grown by
// r (the projected offset triangle; the capsule of radius R around the edge's shadow).
int element_hull(const OffsetElements& el, std::uint32_t id, Vec2* p, double& r) {
  int n = 0;
  if (id < el.facet_count()) {
    for (const Vec3& v : el.offset_tri(id)) p[n++] = Vec2(v.x(), v.y());
    r = 0;
  } else {
    for (std::uint32_t v : el.edge_vertices[id - el.facet_count()])
      p[n++] = Vec2(el.points[v].x(), el.points[v].y());
    r = el.radius;
  }
  return n;
}

}  // namespace

void zlevel_filter_deep(const OffsetElements& el, std::span<const std::uint32_t> ids,
                        const ZLevelInside& q, std::vector<std::uint32_t>& out) {
  if (q.empty()) {
    out.insert(out.end(), ids.begin(), ids.end());
    return;
  }
  const double depth = tol::kZLevelInsideDepth;
  for (std::uint32_t id : ids) {
    if (id >= el.facet_count() + el.edge_count()) {
      out.push_back(id);  // vertices: the kernel derives them from edges
      continue;
    }
    Vec2 p[3];
    double r = 0;
    const int n = element_hull(el, id, p, r);
    if (!zlevel_detail::inside_contains(q, p, n, r, depth)) out.push_back(id);
  }
}

namespace zlevel_detail {

bool region_in_known(const OffsetElements& el, const ZLevelInside& q, const Region& g,
                     double depth) {
  if (g.kind == RegionKind::kVertex) return inside_contains(q, &g.c, 1, g.r, depth);
  Vec2 p[3];
  double r = 0;
  const int n = element_hull(el, g.element, p, r);
  return inside_contains(q, p, n, r, depth);
}

bool on_exact_edge(const ZLevelInside& q, const Vec2& x, double tol) {
  if (q.empty()) return false;
  const int c = cell_of(q, x);
  if (c < 0) return false;
  for (std::uint32_t k = q.start[c]; k < q.start[c + 1]; ++k) {
    const std::uint32_t e = q.ids[k];
    if (e < q.polygon_edges && q.exact[e] &&
        point_segment_distance(x, q.edges[e][0], q.edges[e][1]) <= tol)
      return true;
  }
  return false;
}

bool inside_contains(const ZLevelInside& q, const Vec2* poly, int n, double r, double margin) {
  if (q.empty()) return false;
  double reach = 0;
  for (int k = 1; k < n; ++k) reach = std::max(reach, (poly[k] - poly[0]).norm());
  const int quick = far_answer(q, poly[0], reach + r, margin);
  if (quick != -1) return quick == 1;
  return clearance(q, poly, n, r, margin, false) >= margin && parity_inside(q, poly[0]);
}

double inside_depth_bound(const ZLevelInside& q, const Vec2* hull, int n, double limit) {
  if (q.empty()) return 0;
  // The distance to one edge is convex: over the hull it is largest at a corner.
  double b[4];
  points_box(hull, n, b);
  int i0, j0, i1, j1;
  if (!cell_range(q, b[0] - limit, b[1] - limit, b[2] + limit, b[3] + limit, i0, j0, i1, j1))
    return 0;  // no polygon edge near: outside (the grid holds the polygon with a cell's margin)
  double best = limit, nearest = INFINITY;
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) {
      const std::size_t c = std::size_t(j) * q.nx + i;
      for (std::uint32_t k = q.start[c]; k < q.start[c + 1]; ++k) {
        const std::uint32_t e = q.ids[k];
        if (e >= q.polygon_edges) continue;
        const Vec2 &a = q.edges[e][0], &b = q.edges[e][1];
        double far = 0;
        for (int v = 0; v < n && far < best; ++v)
          far = std::max(far, point_segment_distance(hull[v], a, b));
        best = std::min(best, far);
        if (nearest > tol::kZLevelRefClearance)
          nearest = std::min(nearest, seg_hull(a, b, hull, n));
      }
    }
  if (best < limit) return best;
  // An edge crosses or touches the hull (without one edge near all of it): not known.
  if (nearest <= tol::kZLevelRefClearance) return limit;
  // No edge meets the hull: it lies on one side; outside, it has no depth.
  const int c = cell_of(q, hull[0]);
  if (c < 0) return 0;
  return q.ref_state[c] == 2 || parity_inside(q, hull[0]) ? limit : 0;
}

}  // namespace zlevel_detail

}  // namespace ncpath
