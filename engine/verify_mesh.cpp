#include "engine/verify_mesh.hpp"

#include <Eigen/Geometry>  // cross

#include <algorithm>
#include <array>
#include <cmath>

#include "engine/parallel.hpp"
#include "kernels/geom/tolerance.hpp"

namespace ncpath {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// A facet as the checks want it: vertices, plane, xy box and z range, first grid cell.
struct FacetRec {
  Vec3 p[3];
  Vec3 n;             // unit normal; zero for a degenerate facet (no plane bound)
  double d_lo, d_hi;  // the vertices' n . p: the facet lies in this slab (rounding)
  double lo_x, lo_y, hi_x, hi_y, z_lo, z_hi;
  std::int32_t ci = 0, cj = 0;  // grid cell of the box's low corner
  std::uint32_t source;         // index into mesh.facets
};

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }
double orient(const Vec2& a, const Vec2& b, const Vec2& c) { return cross2(b - a, c - a); }

double dist2_point_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double den = ab.squaredNorm();
  const double t = den > 0 ? std::clamp((p - a).dot(ab) / den, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).squaredNorm();
}

// Closed segments ab and cd meet (collinear ones are taken to meet: only a weaker bound).
bool segments_meet(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const double d1 = orient(c, d, a), d2 = orient(c, d, b);
  const double d3 = orient(a, b, c), d4 = orient(a, b, d);
  return d1 * d2 <= 0 && d3 * d4 <= 0;
}

// Distance in xy between the segment ab and the triangle t (0 when they overlap): a lower
// bound of the horizontal distance from the tool axis to any point of the facet.
double xy_distance(const Vec2& a, const Vec2& b, const Vec2 t[3]) {
  const double o0 = orient(t[0], t[1], a), o1 = orient(t[1], t[2], a), o2 = orient(t[2], t[0], a);
  if ((o0 >= 0 && o1 >= 0 && o2 >= 0) || (o0 <= 0 && o1 <= 0 && o2 <= 0)) return 0;
  double d2 = kInf;
  for (int k = 0; k < 3; ++k) {
    const Vec2& c = t[k];
    const Vec2& d = t[(k + 1) % 3];
    if (segments_meet(a, b, c, d)) return 0;
    d2 = std::min({d2, dist2_point_segment(a, c, d), dist2_point_segment(b, c, d),
                   dist2_point_segment(c, a, b)});
  }
  return std::sqrt(d2);
}

// Squared distance in xy between two boxes (0 when they overlap).
double box_distance2(double ax0, double ay0, double ax1, double ay1, double bx0, double by0,
                     double bx1, double by1) {
  const double dx = std::max({0.0, bx0 - ax1, ax0 - bx1});
  const double dy = std::max({0.0, by0 - ay1, ay0 - by1});
  return dx * dx + dy * dy;
}

// What a move (or a group of consecutive moves) asks of the grid: the box of the swept
// body and the bounds that dismiss a tile or a facet. Tips lie in [tip_lo, tip_hi].
struct SweptBox {
  Vec3 tip_lo, tip_hi;
  Vec3 lo, hi;  // the swept body's box (plus the cap)

  SweptBox(const SweptTool& tool, const Vec3& t0, const Vec3& t1, double cap)
      : tip_lo(t0.cwiseMin(t1)), tip_hi(t0.cwiseMax(t1)) {
    update(tool, cap);
  }
  void add(const SweptTool& tool, const Vec3& p, double cap) {
    tip_lo = tip_lo.cwiseMin(p);
    tip_hi = tip_hi.cwiseMax(p);
    update(tool, cap);
  }
  // The body (grown by stock) reaches R + s sideways and up to 2r + shank + s above the
  // highest tip (ball part on top of the shank).
  void update(const SweptTool& tool, double cap) {
    const double s = tool.stock, reach = tool.cutter.radius + s + cap;
    const double top = 2 * tool.cutter.corner_radius + tool.shank + s;
    lo = tip_lo - Vec3(reach, reach, s + cap);
    hi = tip_hi + Vec3(reach, reach, top + cap);
  }
  // Squared xy distance of the box [x0, x1] x [y0, y1] from the tips' box.
  double xy_distance2(double x0, double y0, double x1, double y1) const {
    return box_distance2(x0, y0, x1, y1, tip_lo.x(), tip_lo.y(), tip_hi.x(), tip_hi.y());
  }
  template <class Box>  // FacetRec or Candidate
  bool meets(const Box& f) const {
    return !(f.hi_x < lo.x() || f.lo_x > hi.x() || f.hi_y < lo.y() || f.lo_y > hi.y() ||
             f.z_hi < lo.z() || f.z_lo > hi.z());
  }
};

// Rounded to float outward (down for a low bound, up for a high one).
float float_down(double v) {
  const float f = static_cast<float>(v);
  return f > v ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
}
float float_up(double v) {
  const float f = static_cast<float>(v);
  return f < v ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
}

// A facet gathered for a group of moves: its box rounded outward to float (compact, for the
// first tests of every move of the group) and its index into the verifier's facets.
struct Candidate {
  float lo_x, lo_y, hi_x, hi_y, z_lo, z_hi;
  std::uint32_t facet;
  Candidate(const FacetRec& f, std::uint32_t index)
      : lo_x(float_down(f.lo_x)), lo_y(float_down(f.lo_y)), hi_x(float_up(f.hi_x)),
        hi_y(float_up(f.hi_y)), z_lo(float_down(f.z_lo)), z_hi(float_up(f.z_hi)),
        facet(index) {}
};

}  // namespace

struct MeshVerifier::Impl {
  std::vector<FacetRec> facets;  // ordered by first grid cell (row-major): cache locality
  std::uint64_t skipped = 0;
  double x0 = 0, y0 = 0, cell = 1;
  std::int32_t nx = 0, ny = 0;
  // A facet in one cell, with what the traversal tests before touching the facet: its first
  // cell (visit once) and its top rounded up to float (below the tool's box: skip).
  struct Entry {
    std::uint32_t facet;  // index into facets
    std::uint16_t ci, cj;
    float z_hi;
  };
  // A cell's entries (CSR: cell_start, nx * ny + 1 offsets) come in three runs: the facets
  // whose first cell it is, up to a_end; those whose first cell lies to its left in its row,
  // up to b_end; those whose first cell lies in an earlier row. A query visits each facet at
  // its first cell within the query: the first run everywhere, the second in the query's
  // first column, the third (tested) in its first row only.
  std::vector<std::uint32_t> cell_start, a_end, b_end;
  std::vector<Entry> entries;
  // Tiles of kTile x kTile cells, each bounding every facet registered in its cells (xy box
  // and top): a query dismisses a whole tile when no facet in it can matter.
  static constexpr std::int32_t kTile = 4;
  struct Tile {
    double lo_x = kInf, lo_y = kInf, hi_x = -kInf, hi_y = -kInf, z_hi = -kInf;
  };
  std::int32_t tx = 0;  // tiles a row
  std::vector<Tile> tiles;

  std::int32_t cell_x(double x) const { return clamp_cell((x - x0) / cell, nx); }
  std::int32_t cell_y(double y) const { return clamp_cell((y - y0) / cell, ny); }
  static std::int32_t clamp_cell(double u, std::int32_t n) {
    if (!(u > 0)) return 0;  // also NaN
    return u >= n - 1 ? n - 1 : static_cast<std::int32_t>(u);
  }

  void build(const TriangleMesh& mesh);
  void set_grid(double lx, double ly, double hx, double hy, double mean_extent, std::size_t count);
  void build_grid();
  void build_tiles();
  template <class Matters, class Visit>
  void visit(const Vec3& lo, const Vec3& hi, Matters&& matters, Visit&& visit) const;
  void gather(const SweptTool& tool, const Cutter& profile, const SweptBox& group, double floor,
              double cap, std::vector<Candidate>& out) const;
  template <class Visit>
  void visit_cell(std::int32_t i, std::int32_t j, std::int32_t i0, std::int32_t j0,
                  const Vec3& lo, const Vec3& hi, Visit&& visit) const;
};

namespace {

// The record of mesh facet i (vertices, plane, box; no grid cell yet); false when a vertex
// is not finite.
bool make_record(const TriangleMesh& mesh, std::size_t i, FacetRec& f) {
  for (int k = 0; k < 3; ++k) {
    f.p[k] = mesh.vertices[mesh.facets[i][k]];
    if (!f.p[k].allFinite()) return false;
  }
  const Vec3 n = (f.p[1] - f.p[0]).cross(f.p[2] - f.p[0]);
  const double len = n.norm();
  f.n = len > 0 ? Vec3(n / len) : Vec3::Zero();
  f.d_lo = std::min({f.n.dot(f.p[0]), f.n.dot(f.p[1]), f.n.dot(f.p[2])});
  f.d_hi = std::max({f.n.dot(f.p[0]), f.n.dot(f.p[1]), f.n.dot(f.p[2])});
  f.lo_x = std::min({f.p[0].x(), f.p[1].x(), f.p[2].x()});
  f.hi_x = std::max({f.p[0].x(), f.p[1].x(), f.p[2].x()});
  f.lo_y = std::min({f.p[0].y(), f.p[1].y(), f.p[2].y()});
  f.hi_y = std::max({f.p[0].y(), f.p[1].y(), f.p[2].y()});
  f.z_lo = std::min({f.p[0].z(), f.p[1].z(), f.p[2].z()});
  f.z_hi = std::max({f.p[0].z(), f.p[1].z(), f.p[2].z()});
  f.source = static_cast<std::uint32_t>(i);
  return true;
}

// The xy box of mesh facet i; false when a vertex is not finite.
bool facet_xy_box(const TriangleMesh& mesh, std::size_t i, Vec2& lo, Vec2& hi) {
  lo = Vec2(kInf, kInf);
  hi = Vec2(-kInf, -kInf);
  for (int k = 0; k < 3; ++k) {
    const Vec3& p = mesh.vertices[mesh.facets[i][k]];
    if (!p.allFinite()) return false;
    lo = lo.cwiseMin(p.head<2>());
    hi = hi.cwiseMax(p.head<2>());
  }
  return true;
}

}  // namespace

// Facets in row-major order of their first grid cell (the cell of their box's low corner),
// in mesh order within a cell: the grid comes from one pass over the boxes in mesh order
// (so the cell size has the same bits for any thread count), then (cell, facet) keys are
// sorted and the records built in that order, in parallel.
void MeshVerifier::Impl::build(const TriangleMesh& mesh) {
  const std::size_t n = mesh.facets.size();
  std::vector<std::uint32_t> usable;
  usable.reserve(n);
  double lx = kInf, ly = kInf, hx = -kInf, hy = -kInf, extent = 0;
  for (std::size_t i = 0; i < n; ++i) {
    Vec2 lo, hi;
    if (!facet_xy_box(mesh, i, lo, hi)) {
      ++skipped;
      continue;
    }
    usable.push_back(static_cast<std::uint32_t>(i));
    lx = std::min(lx, lo.x());
    ly = std::min(ly, lo.y());
    hx = std::max(hx, hi.x());
    hy = std::max(hy, hi.y());
    extent += std::max(hi.x() - lo.x(), hi.y() - lo.y());
  }
  if (usable.empty()) return;
  set_grid(lx, ly, hx, hy, extent / static_cast<double>(usable.size()), usable.size());
  std::vector<std::uint64_t> keys(usable.size());
  par::for_each(keys.size(), 4096, [&](std::size_t k) {
    Vec2 lo, hi;
    facet_xy_box(mesh, usable[k], lo, hi);
    const std::uint64_t c = static_cast<std::uint64_t>(cell_y(lo.y())) * nx + cell_x(lo.x());
    keys[k] = c << 32 | usable[k];
  });
  std::vector<std::uint32_t>().swap(usable);
  par::sort(keys.begin(), keys.end(), std::less<>());
  facets.resize(keys.size());
  par::for_each(keys.size(), 4096, [&](std::size_t k) {
    FacetRec& f = facets[k];
    make_record(mesh, keys[k] & 0xffffffffu, f);
    f.ci = cell_x(f.lo_x);
    f.cj = cell_y(f.lo_y);
  });
  build_grid();
}

// Cells about the size of a facet (mean extent) and about as many as facets, at most 4096 a
// side (cell indices fit 16 bits).
void MeshVerifier::Impl::set_grid(double lx, double ly, double hx, double hy, double mean_extent,
                                  std::size_t count) {
  const double w = hx - lx, h = hy - ly, n = static_cast<double>(count);
  cell = std::max({mean_extent, std::sqrt(w * h / n), w / 4096, h / 4096});
  if (!(cell > 0)) cell = 1;
  x0 = lx;
  y0 = ly;
  nx = static_cast<std::int32_t>(w / cell) + 1;
  ny = static_cast<std::int32_t>(h / cell) + 1;
}

// Cell entries (CSR, three runs a cell) and tiles of the sorted facets.
void MeshVerifier::Impl::build_grid() {
  // Count, scan, fill (facets in their order within each run). Run of cell (i, j) for a
  // facet: 0 its first cell, 1 further along its first row, 2 a later row.
  const std::size_t cells = static_cast<std::size_t>(nx) * ny;
  std::vector<std::array<std::uint32_t, 3>> count(cells, {0, 0, 0});
  auto each_cell = [&](const FacetRec& f, auto&& body) {
    const std::int32_t i1 = cell_x(f.hi_x), j1 = cell_y(f.hi_y);
    for (std::int32_t j = f.cj; j <= j1; ++j)
      for (std::int32_t i = f.ci; i <= i1; ++i)
        body(static_cast<std::size_t>(j) * nx + i, j > f.cj ? 2 : i > f.ci ? 1 : 0);
  };
  for (const FacetRec& f : facets) each_cell(f, [&](std::size_t c, int run) { ++count[c][run]; });
  std::vector<std::uint32_t> total(cells);
  for (std::size_t c = 0; c < cells; ++c) total[c] = count[c][0] + count[c][1] + count[c][2];
  cell_start.assign(cells + 1, 0);
  par::exclusive_scan<std::uint32_t, std::uint32_t>(total, cell_start);
  a_end.resize(cells);
  b_end.resize(cells);
  for (std::size_t c = 0; c < cells; ++c) {
    a_end[c] = cell_start[c] + count[c][0];
    b_end[c] = a_end[c] + count[c][1];
  }
  entries.resize(cell_start.back());
  for (std::size_t c = 0; c < cells; ++c) count[c] = {cell_start[c], a_end[c], b_end[c]};
  for (std::size_t k = 0; k < facets.size(); ++k) {
    const FacetRec& f = facets[k];
    const Entry e{static_cast<std::uint32_t>(k), static_cast<std::uint16_t>(f.ci),
                  static_cast<std::uint16_t>(f.cj), float_up(f.z_hi)};
    each_cell(f, [&](std::size_t c, int run) { entries[count[c][run]++] = e; });
  }
  build_tiles();
}

void MeshVerifier::Impl::build_tiles() {
  tx = (nx + kTile - 1) / kTile;
  const std::int32_t ty = (ny + kTile - 1) / kTile;
  tiles.assign(static_cast<std::size_t>(tx) * ty, Tile{});
  par::for_each(static_cast<std::size_t>(ty), 1, [&](std::size_t tj) {
    for (std::int32_t j = static_cast<std::int32_t>(tj) * kTile;
         j < std::min<std::int32_t>(ny, static_cast<std::int32_t>(tj + 1) * kTile); ++j)
      for (std::int32_t i = 0; i < nx; ++i) {
        Tile& t = tiles[tj * tx + i / kTile];
        const std::size_t c = static_cast<std::size_t>(j) * nx + i;
        for (std::uint32_t k = cell_start[c]; k < cell_start[c + 1]; ++k) {
          const FacetRec& f = facets[entries[k].facet];
          t.lo_x = std::min(t.lo_x, f.lo_x);
          t.lo_y = std::min(t.lo_y, f.lo_y);
          t.hi_x = std::max(t.hi_x, f.hi_x);
          t.hi_y = std::max(t.hi_y, f.hi_y);
          t.z_hi = std::max(t.z_hi, f.z_hi);
        }
      }
  });
}

// Calls visit(facet) once for every facet whose box meets [lo, hi] and whose tile matters
// (matters(tile) is false only when no facet registered in the tile can matter), tile by tile
// and in grid order within a tile. A facet is met in every shared cell but visited only in
// the first one (its low corner clamped to the query's cells): a facet whose first cell lies
// in a dismissed tile is dismissed with it.
template <class Matters, class Visit>
void MeshVerifier::Impl::visit(const Vec3& lo, const Vec3& hi, Matters&& matters,
                               Visit&& visit) const {
  if (facets.empty()) return;
  const std::int32_t i0 = cell_x(lo.x()), i1 = cell_x(hi.x());
  const std::int32_t j0 = cell_y(lo.y()), j1 = cell_y(hi.y());
  for (std::int32_t tj = j0 / kTile; tj <= j1 / kTile; ++tj)
    for (std::int32_t ti = i0 / kTile; ti <= i1 / kTile; ++ti) {
      const Tile& t = tiles[static_cast<std::size_t>(tj) * tx + ti];
      if (t.z_hi < lo.z() || t.hi_x < lo.x() || t.lo_x > hi.x() || t.hi_y < lo.y() ||
          t.lo_y > hi.y() || !matters(t))
        continue;
      const std::int32_t ja = std::max(j0, tj * kTile), jb = std::min(j1, tj * kTile + kTile - 1);
      const std::int32_t ia = std::max(i0, ti * kTile), ib = std::min(i1, ti * kTile + kTile - 1);
      for (std::int32_t j = ja; j <= jb; ++j)
        for (std::int32_t i = ia; i <= ib; ++i) visit_cell(i, j, i0, j0, lo, hi, visit);
    }
}

template <class Visit>
void MeshVerifier::Impl::visit_cell(std::int32_t i, std::int32_t j, std::int32_t i0,
                                    std::int32_t j0, const Vec3& lo, const Vec3& hi,
                                    Visit&& visit) const {
  const std::size_t c = static_cast<std::size_t>(j) * nx + i;
  auto consider = [&](const Entry& e) {
    if (e.z_hi < lo.z()) return;  // below the box
    const FacetRec& f = facets[e.facet];
    if (f.hi_x < lo.x() || f.lo_x > hi.x() || f.hi_y < lo.y() || f.lo_y > hi.y() ||
        f.z_hi < lo.z() || f.z_lo > hi.z())
      return;
    visit(f);
  };
  // The facets whose first cell within the query is this one (see cell_start).
  const std::uint32_t end = i == i0 ? b_end[c] : a_end[c];
  for (std::uint32_t k = cell_start[c]; k < end; ++k) consider(entries[k]);
  if (j != j0) return;
  for (std::uint32_t k = b_end[c]; k < cell_start[c + 1]; ++k)
    if (std::max<std::int32_t>(entries[k].ci, i0) == i) consider(entries[k]);
}

MeshVerifier::MeshVerifier(const TriangleMesh& mesh) : impl_(std::make_unique<Impl>()) {
  impl_->build(mesh);
}

MeshVerifier::~MeshVerifier() = default;

std::uint64_t MeshVerifier::facet_count() const { return impl_->facets.size(); }
std::uint64_t MeshVerifier::skipped() const { return impl_->skipped; }

namespace {

// One move's scan over its candidate facets: the gouge (kept as the floor of later facets)
// and, for rapids, the clearance. Each facet is first tested with exact cheap bounds.
struct MoveScan {
  const SweptTool& tool;
  Vec3 p0, p1;
  Vec2 a, b;       // the move in xy
  double foot;     // R + stock: horizontal reach of the body from the axis, mm
  double low_tip;  // lowest tip of the move, mm
  const Cutter& profile;  // lower surface of the body, tip at tip - stock
  double floor0;   // gouges at most this are not reported, mm
  double cap;      // clearance cap (0: no clearance), mm
  bool decide;     // MoveCheckMode::kDecide: stop at the first gouge, do not measure it
  SweptBox box;
  MeshVerifier::MoveCheck out;

  MoveScan(const SweptTool& t, const Vec3& q0, const Vec3& q1, const Cutter& prof,
           double gouge_floor, double clearance_cap, MoveCheckMode mode)
      : tool(t), p0(q0), p1(q1), a(q0.x(), q0.y()), b(q1.x(), q1.y()),
        foot(t.cutter.radius + t.stock), low_tip(std::min(q0.z(), q1.z())), profile(prof),
        floor0(gouge_floor), cap(clearance_cap), decide(mode == MoveCheckMode::kDecide),
        box(t, q0, q1, clearance_cap) {}

  // Nothing left to find: a decided gouge (no clearance asked).
  bool done() const { return decide && out.gouge > 0 && cap == 0; }

  // A candidate of the move's group: dismissed when its box misses the move's, or when
  // its xy box is beyond the body's reach (and the cap), or (no clearance asked) when its
  // top lies under the body raised by the gouge so far over that box distance (a lower
  // bound of the exact xy distance). The float box holds the facet's: these tests are
  // conservative, and the exact box is tested last.
  void candidate(const Candidate& c, const FacetRec* facets) {
    if (!box.meets(c)) return;
    ++out.candidates;
    const double d2 = box.xy_distance2(c.lo_x, c.lo_y, c.hi_x, c.hi_y);
    if (d2 > (foot + cap) * (foot + cap)) return;
    const double rise = c.z_hi - (low_tip + std::max(floor0, out.gouge) - tool.stock);
    if (cap == 0 && profile_height_at_least(profile, d2, rise)) return;
    const FacetRec& f = facets[c.facet];
    if (box.meets(f)) facet(f);
  }

  // Without clearance, the box tests of candidate() stand for the exact xy distance: on a
  // dense scan it dismissed one facet in five of those left, at a cost above the plane and
  // GJK tests it saved (ncpath_bench_verify: checks 1.35x faster without it). Rapids need it
  // for their clearance.
  void facet(const FacetRec& f) {
    if (cap == 0) return gouge(f);
    const Vec2 t[3] = {
        {f.p[0].x(), f.p[0].y()}, {f.p[1].x(), f.p[1].y()}, {f.p[2].x(), f.p[2].y()}};
    const double dxy = xy_distance(a, b, t);
    // Raised by the gouge so far the body is above the facet (its bottom over the facet's
    // footprint is no lower than this): the gouge is at most that.
    const double bottom =
        low_tip + std::max(floor0, out.gouge) - tool.stock + profile_height(profile, dxy);
    if (dxy <= foot && f.z_hi > bottom) gouge(f);
    if (dxy <= foot + cap) clearance(f, dxy);
  }

  void gouge(const FacetRec& f) {
    const double floor = std::max(floor0, out.gouge);
    // Raised by `floor` the body lies beyond the facet's plane: the gouge is at most the floor.
    const Vec3 up(0, 0, floor);
    if (f.n != Vec3::Zero() && swept_plane_gap(tool, p0 + up, p1 + up, f.n, f.d_lo, f.d_hi) >= 0)
      return;
    if (decide && out.gouge > 0) return;
    const SweptGouge g =
        decide ? swept_gouges_above(tool, p0, p1, f.p[0], f.p[1], f.p[2], floor)
               : swept_gouge_above(tool, p0, p1, f.p[0], f.p[1], f.p[2], floor);
    out.gjk_calls += g.gjk_calls;
    if (decide && g.gouge > 0) {
      out.gouge = std::numeric_limits<double>::infinity();
      out.gouge_facet = f.source;
    } else if (g.gouge > out.gouge) {
      out.gouge = g.gouge;
      out.gouge_facet = f.source;
    }
  }

  void clearance(const FacetRec& f, double dxy) {
    double bound = std::max(dxy - foot, low_tip - tool.stock - f.z_hi);
    if (f.n != Vec3::Zero())
      bound = std::max(bound, swept_plane_gap(tool, p0, p1, f.n, f.d_lo, f.d_hi));
    if (bound >= out.clearance || bound >= cap) return;
    ++out.gjk_calls;
    const double gap = swept_gap(tool, p0, p1, f.p[0], f.p[1], f.p[2]);
    if (gap < out.clearance && gap < cap) {
      out.clearance = gap;
      out.clearance_facet = f.source;
    }
  }
};

}  // namespace

// Facets a group of moves may reach: those whose box meets the group's box, in tiles that
// matter for some move of the group (with rapids every tile matters: the clearance), in
// ascending index. A tile matters unless it lies beyond the body's reach from every tip
// box, or below the body's bottom (raised by the floor) at that distance; the profile is
// non-decreasing, so the bound holds for every move of the group.
void MeshVerifier::Impl::gather(const SweptTool& tool, const Cutter& profile, const SweptBox& g,
                                double floor, double cap,
                                std::vector<Candidate>& out) const {
  const double reach = tool.cutter.radius + tool.stock + cap;
  const double base = g.tip_lo.z() + floor - tool.stock;  // the lowest bottom, raised
  // Within reach of the tips' box, and (no clearance asked) not under the body's bottom at
  // that distance: what a box (a tile's, a facet's) must pass to matter to some move.
  auto may_matter = [&](double x0, double y0, double x1, double y1, double top) {
    const double d2 = g.xy_distance2(x0, y0, x1, y1);
    if (d2 > reach * reach) return false;
    return cap > 0 || !profile_height_at_least(profile, d2, top - base);
  };
  out.clear();
  visit(
      g.lo, g.hi,
      [&](const Tile& t) { return may_matter(t.lo_x, t.lo_y, t.hi_x, t.hi_y, t.z_hi); },
      [&](const FacetRec& f) {
        if (may_matter(f.lo_x, f.lo_y, f.hi_x, f.hi_y, f.z_hi))
          out.emplace_back(f, static_cast<std::uint32_t>(&f - facets.data()));
      });
  std::sort(out.begin(), out.end(),
            [](const Candidate& a, const Candidate& b) { return a.facet < b.facet; });
}

void MeshVerifier::check_moves(const SweptTool& tool_in, const Vec3* from, const Vec3* to,
                               std::size_t n, double gouge_floor, double clearance_cap,
                               MoveCheck* out, MoveCheckMode mode) const {
  SweptTool tool = tool_in;
  tool.stock = std::max(0.0, tool.stock);
  tool.shank = std::max(0.0, tool.shank);
  const double floor = std::max(0.0, gouge_floor), cap = std::max(0.0, clearance_cap);
  const Cutter profile = swept_profile(tool);
  const double extent = kGroupExtent * (tool.cutter.radius + tool.stock);
  auto finite = [&](std::size_t k) { return from[k].allFinite() && to[k].allFinite(); };
  std::vector<Candidate> candidates;
  for (std::size_t k = 0; k < n;) {
    if (!finite(k)) {
      out[k++] = MoveCheck{};
      continue;
    }
    // Moves [k, e) form a group: consecutive, their tips within `extent` in x, y and z.
    SweptBox group(tool, from[k], to[k], cap);
    std::size_t e = k + 1;
    for (; e < n && e - k < kMaxGroup && finite(e); ++e) {
      const Vec3 lo = group.tip_lo.cwiseMin(from[e]).cwiseMin(to[e]);
      const Vec3 hi = group.tip_hi.cwiseMax(from[e]).cwiseMax(to[e]);
      if ((hi - lo).maxCoeff() > extent) break;
      group.add(tool, from[e], cap);
      group.add(tool, to[e], cap);
    }
    impl_->gather(tool, profile, group, floor, cap, candidates);
    for (; k < e; ++k) {
      MoveScan scan(tool, from[k], to[k], profile, floor, cap, mode);
      for (std::size_t c = 0; c < candidates.size() && !scan.done(); ++c)
        scan.candidate(candidates[c], impl_->facets.data());
      out[k] = scan.out;
    }
  }
}

void MeshVerifier::check_path(const SweptTool& tool, const Vec3* tips, std::size_t n,
                              double gouge_floor, double clearance_cap, MoveCheck* out,
                              MoveCheckMode mode) const {
  if (n >= 2) check_moves(tool, tips, tips + 1, n - 1, gouge_floor, clearance_cap, out, mode);
}

MeshVerifier::MoveCheck MeshVerifier::check_move(const SweptTool& tool, const Vec3& p0,
                                                 const Vec3& p1, double gouge_floor,
                                                 double clearance_cap) const {
  MoveCheck out;
  check_moves(tool, &p0, &p1, 1, gouge_floor, clearance_cap, &out);
  return out;
}

}  // namespace ncpath
