#include "engine/concave_zone.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <numbers>
#include <optional>
#include <span>

#include <Eigen/Geometry>

#include "engine/parallel.hpp"
#include "engine/run_control.hpp"
#include "kernels/geom/tolerance.hpp"

namespace ncpath {

namespace {

constexpr double kKeepCellPerRadius = 0.25;  // the kept region's cell edge, in R
constexpr double kLookupCellPerRadius = 1;     // holds()'s cell edge, in R
constexpr std::int64_t kMaxCells = std::int64_t(1) << 25;

// A uniform grid over a box; cells grow until there are at most max_cells.
struct Grid {
  Vec3 lo;
  double h = 1;
  std::array<std::int64_t, 3> n{1, 1, 1};

  Grid(const Vec3& lo_, double h_, std::array<std::int64_t, 3> n_) : lo(lo_), h(h_), n(n_) {}
  Grid(const Aabb3& box, double cell, std::int64_t max_cells = kMaxCells) : lo(box.lo), h(cell) {
    for (;; h *= 1.5) {
      for (int a = 0; a < 3; ++a) n[a] = std::int64_t((box.hi[a] - box.lo[a]) / h) + 1;
      if (n[0] * n[1] * n[2] <= max_cells) break;
    }
  }
  std::int64_t coord(double v, int a) const {
    return std::clamp(std::int64_t(std::floor((v - lo[a]) / h)), std::int64_t(0), n[a] - 1);
  }
  std::int64_t index(std::int64_t i, std::int64_t j, std::int64_t k) const {
    return (k * n[1] + j) * n[0] + i;
  }
  std::int64_t index(const Vec3& p) const {
    return index(coord(p.x(), 0), coord(p.y(), 1), coord(p.z(), 2));
  }
};

struct FacetGeometry {
  std::vector<Vec3> normal;  // unit, as wound; zero when degenerate
  std::vector<std::uint8_t> degenerate;
  double longest_edge = 0;
};

FacetGeometry facet_geometry(const TriangleMesh& mesh) {
  FacetGeometry g;
  const std::size_t nf = mesh.facets.size();
  g.normal.assign(nf, Vec3::Zero());
  g.degenerate.assign(nf, 0);
  std::vector<double> longest(nf, 0);
  par::for_each(nf, 4096, [&](std::size_t f) {
    const auto& t = mesh.facets[f];
    const Vec3 &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
    const Vec3 n = (b - a).cross(c - a);
    const double len = n.norm();
    longest[f] = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    if (len >= tol::kDegenerateArea2)
      g.normal[f] = n / len;
    else
      g.degenerate[f] = 1;
  });
  for (double l : longest) g.longest_edge = std::max(g.longest_edge, l);
  return g;
}

// Facets at each vertex (CSR, facet order).
struct Stars {
  std::vector<std::uint32_t> offset, facet;
};

Stars vertex_stars(const TriangleMesh& mesh) {
  Stars s;
  s.offset.assign(mesh.vertices.size() + 1, 0);
  for (const auto& t : mesh.facets)
    for (std::uint32_t v : t) ++s.offset[v + 1];
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) s.offset[v + 1] += s.offset[v];
  s.facet.resize(s.offset.back());
  std::vector<std::uint32_t> fill(s.offset.begin(), s.offset.end() - 1);
  for (std::uint32_t f = 0; f < mesh.facets.size(); ++f)
    for (std::uint32_t v : mesh.facets[f]) s.facet[fill[v]++] = f;
  return s;
}

// 1 where the vertex's star is not a disk wound consistently: some edge at it is not used by
// exactly two facets in opposite directions (or a facet there is degenerate).
std::vector<std::uint8_t> irregular_vertices(const TriangleMesh& mesh, const Stars& stars,
                                             const FacetGeometry& g) {
  const std::size_t nv = mesh.vertices.size();
  std::vector<std::uint8_t> bad(nv, 0);
  par::for_ranges(nv, 4096, [&](std::size_t b, std::size_t e) {
    std::vector<std::uint32_t> out, in;
    for (std::size_t v = b; v < e; ++v) {
      out.clear();
      in.clear();
      for (std::uint32_t k = stars.offset[v]; k < stars.offset[v + 1]; ++k) {
        const std::uint32_t f = stars.facet[k];
        const auto& t = mesh.facets[f];
        const int c = t[0] == v ? 0 : t[1] == v ? 1 : 2;
        if (g.degenerate[f] || t[(c + 1) % 3] == v || t[(c + 2) % 3] == v) bad[v] = 1;
        out.push_back(t[(c + 1) % 3]);  // edge v -> next
        in.push_back(t[(c + 2) % 3]);   // edge prev -> v
      }
      std::sort(out.begin(), out.end());
      std::sort(in.begin(), in.end());
      if (out != in || std::adjacent_find(out.begin(), out.end()) != out.end()) bad[v] = 1;
    }
  });
  return bad;
}

// Which side a ball touches each facet from: +1 along its normal as wound, -1 against it, 0
// either. A closed component (every vertex regular) is touched from outside only: a ball on
// the drop-cutter surface is clear of the mesh and joined to z = +inf by free space, so it is
// outside every closed component; outside is where the normals point when the component's
// signed volume is positive. (An inner shell's side may come out wrong; no ball from above
// reaches it.)
std::vector<std::int8_t> facet_sides(const TriangleMesh& mesh, const std::vector<std::uint8_t>& irregular) {
  const std::size_t nv = mesh.vertices.size(), nf = mesh.facets.size();
  std::vector<std::uint32_t> parent(nv);
  for (std::uint32_t v = 0; v < nv; ++v) parent[v] = v;
  auto find = [&](std::uint32_t v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (const auto& t : mesh.facets)
    for (int k = 1; k < 3; ++k) {
      const std::uint32_t a = find(t[0]), b = find(t[k]);
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
  std::vector<double> volume(nv, 0);
  std::vector<std::uint8_t> open(nv, 0);
  const Aabb3 box = bounding_box(mesh);
  const Vec3 o = 0.5 * (box.lo + box.hi);
  for (const auto& t : mesh.facets) {
    const std::uint32_t c = find(t[0]);
    const Vec3 a = mesh.vertices[t[0]] - o, b = mesh.vertices[t[1]] - o, d = mesh.vertices[t[2]] - o;
    volume[c] += a.dot(b.cross(d));
    for (std::uint32_t v : t) open[c] |= irregular[v];
  }
  std::vector<std::int8_t> side(nf, 0);
  for (std::size_t f = 0; f < nf; ++f) {
    const std::uint32_t c = find(mesh.facets[f][0]);
    if (!open[c] && volume[c] != 0) side[f] = volume[c] > 0 ? 1 : -1;
  }
  return side;
}

struct MeshFacts {
  const TriangleMesh& mesh;
  const Stars& stars;
  const FacetGeometry& g;
  const std::vector<std::uint8_t>& irregular;
  const std::vector<std::int8_t>& side;
};

constexpr std::uint32_t kNone = ~std::uint32_t(0);

// Where contacts on one element (on one side) put the ball centre: within `reach` of `at`.
struct CentreBall {
  Vec3 at;
  double reach = 0;
  Vec3 axis = Vec3::UnitZ();  // the side's normal cone
  double half_angle = std::numbers::pi;
  std::array<std::uint32_t, 3> verts{kNone, kNone, kNone};  // the element's mesh vertices
  bool unbounded = true;
};

// Collects an element's balls.
struct BallSink {
  std::vector<CentreBall>* out;
  double R = 0;
  void add(const CentreBall& b) { out->push_back(b); }
  void unbounded(const Vec3& centre, double size, std::array<std::uint32_t, 3> verts) {
    CentreBall b;
    b.at = centre;
    b.reach = size + R;
    b.verts = verts;
    add(b);
  }
  // A bounded cone: dropped when a ball from above cannot touch with a normal in it.
  void cone(const Vec3& centre, double size, const Vec3& axis, double half,
            std::array<std::uint32_t, 3> verts) {
    if (std::asin(std::clamp(-axis.z(), -1.0, 1.0)) >= half + tol::kConcaveZoneAngle) return;
    add({centre + R * axis, size + 2 * R * std::sin(0.5 * half), axis, half, verts, false});
  }
};

// The signs (as wound) of the sides a ball touches facet f from: its own side, or both.
int side_count(const MeshFacts& m, std::uint32_t f) { return m.side[f] != 0 ? 1 : 2; }
double side_sign(const MeshFacts& m, std::uint32_t f, int k) {
  return m.side[f] != 0 ? double(m.side[f]) : (k == 0 ? 1.0 : -1.0);
}

void facet_balls(const MeshFacts& m, std::uint32_t f, BallSink& sink) {
  if (m.g.degenerate[f]) return;  // its edges and vertices are irregular: unbounded balls
  const auto& t = m.mesh.facets[f];
  const Vec3 c = (m.mesh.vertices[t[0]] + m.mesh.vertices[t[1]] + m.mesh.vertices[t[2]]) / 3;
  double r = 0;
  for (std::uint32_t v : t) r = std::max(r, (m.mesh.vertices[v] - c).norm());
  for (int k = 0; k < side_count(m, f); ++k)
    sink.cone(c, r, side_sign(m, f, k) * m.g.normal[f], tol::kConcaveZoneAngle, {t[0], t[1], t[2]});
}

// The facet holding the half-edge b -> a, at the regular vertex a.
std::uint32_t opposite_facet(const MeshFacts& m, std::uint32_t a, std::uint32_t b) {
  for (std::uint32_t k = m.stars.offset[a]; k < m.stars.offset[a + 1]; ++k) {
    const auto& t = m.mesh.facets[m.stars.facet[k]];
    for (int c = 0; c < 3; ++c)
      if (t[c] == b && t[(c + 1) % 3] == a) return m.stars.facet[k];
  }
  return kNone;
}

std::uint32_t third_vertex(const std::array<std::uint32_t, 3>& t, std::uint32_t a, std::uint32_t b) {
  for (std::uint32_t v : t)
    if (v != a && v != b) return v;
  return t[0];
}

// Edge t[k] -> t[k + 1] of facet f, given once (by the facet where it runs up in index) when
// both ends are regular, else by every facet as an unbounded ball.
void edge_balls(const MeshFacts& m, std::uint32_t f, int k, BallSink& sink) {
  const auto& t = m.mesh.facets[f];
  const std::uint32_t a = t[k], b = t[(k + 1) % 3];
  const Vec3 &pa = m.mesh.vertices[a], &pb = m.mesh.vertices[b];
  const Vec3 mid = 0.5 * (pa + pb);
  const double half_len = 0.5 * (pb - pa).norm();
  if (m.irregular[a] || m.irregular[b]) return sink.unbounded(mid, half_len, {a, b, kNone});
  if (a > b) return;
  const std::uint32_t g = opposite_facet(m, a, b);
  if (g == kNone || m.g.degenerate[g]) return sink.unbounded(mid, half_len, {a, b, kNone});
  const Vec3 wg = m.mesh.vertices[third_vertex(m.mesh.facets[g], a, b)] - pa;
  for (int s = 0; s < side_count(m, f); ++s) {
    const double sign = side_sign(m, f, s);
    const Vec3 nf = sign * m.g.normal[f], ng = sign * m.g.normal[g];
    // Concave seen from this side: g rises above f's plane; a ball there cuts one of them.
    if (nf.dot(wg) > tol::kConcaveZoneAngle * wg.norm()) continue;
    const Vec3 sum = nf + ng;
    if (!(sum.norm() > tol::kConcaveZoneMinCos)) {
      sink.unbounded(mid, half_len, {a, b, kNone});
      continue;
    }
    const double half = 0.5 * std::atan2(nf.cross(ng).norm(), nf.dot(ng)) + tol::kConcaveZoneAngle;
    sink.cone(mid, half_len, sum.normalized(), half, {a, b, kNone});
  }
}

void vertex_balls(const MeshFacts& m, std::uint32_t v, BallSink& sink) {
  const std::uint32_t k0 = m.stars.offset[v], k1 = m.stars.offset[v + 1];
  if (k0 == k1) return;  // unreferenced
  const Vec3& p = m.mesh.vertices[v];
  if (m.irregular[v]) return sink.unbounded(p, 0, {v, kNone, kNone});
  const std::uint32_t f0 = m.stars.facet[k0];
  for (int s = 0; s < side_count(m, f0); ++s) {
    auto normal = [&](std::uint32_t f) {
      return m.side[f] != 0 ? double(m.side[f]) * m.g.normal[f] : side_sign(m, f0, s) * m.g.normal[f];
    };
    Vec3 sum = Vec3::Zero();
    for (std::uint32_t k = k0; k < k1; ++k) sum += normal(m.stars.facet[k]);
    if (!(sum.norm() > 0)) {
      sink.unbounded(p, 0, {v, kNone, kNone});
      continue;
    }
    const Vec3 axis = sum.normalized();
    double min_cos = 1;
    for (std::uint32_t k = k0; k < k1; ++k) min_cos = std::min(min_cos, normal(m.stars.facet[k]).dot(axis));
    if (!(min_cos > tol::kConcaveZoneMinCos)) {
      sink.unbounded(p, 0, {v, kNone, kNone});
      continue;
    }
    const double half = std::acos(min_cos) + tol::kConcaveZoneAngle;
    // Every edge rising above each tangent plane in the cone: no ball touches the vertex.
    bool rises = true;
    for (std::uint32_t k = k0; k < k1 && rises; ++k)
      for (std::uint32_t u : m.mesh.facets[m.stars.facet[k]])
        if (u != v && axis.dot(m.mesh.vertices[u] - p) <= std::sin(half) * (m.mesh.vertices[u] - p).norm())
          rises = false;
    if (!rises) sink.cone(p, 0, axis, half, {v, kNone, kNone});
  }
}

// Every element's balls, in facet order (its interior, then its edges), then vertex order.
std::vector<CentreBall> centre_balls(const MeshFacts& m, double R) {
  const std::size_t nf = m.mesh.facets.size(), nv = m.mesh.vertices.size();
  auto emit = [&](std::size_t i, BallSink& sink) {
    if (i < nf) {
      facet_balls(m, std::uint32_t(i), sink);
      for (int k = 0; k < 3; ++k) edge_balls(m, std::uint32_t(i), k, sink);
    } else {
      vertex_balls(m, std::uint32_t(i - nf), sink);
    }
  };
  // Blocks of elements, each filling its own vector, joined in block order.
  constexpr std::size_t kBlock = 4096;
  const std::size_t blocks = (nf + nv + kBlock - 1) / kBlock;
  std::vector<std::vector<CentreBall>> parts(blocks);
  par::for_each(blocks, 1, [&](std::size_t b) {
    BallSink sink{&parts[b], R};
    parts[b].reserve(2 * kBlock);
    for (std::size_t i = b * kBlock; i < std::min(nf + nv, (b + 1) * kBlock); ++i) emit(i, sink);
  });
  std::vector<CentreBall> balls;
  std::size_t total = 0;
  for (const auto& part : parts) total += part.size();
  balls.reserve(total);
  for (auto& part : parts) {
    balls.insert(balls.end(), part.begin(), part.end());
    std::vector<CentreBall>().swap(part);
  }
  return balls;
}

// Balls filed under every grid cell their box (grown by `grow`) meets: (cell, ball), sorted.
using CellEntries = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

template <class Use>
void each_cell(const Grid& grid, const Vec3& p, double d, Use&& use) {
  std::array<std::int64_t, 3> lo, hi;
  for (int a = 0; a < 3; ++a) {
    lo[a] = grid.coord(p[a] - d, a);
    hi[a] = grid.coord(p[a] + d, a);
  }
  for (std::int64_t k = lo[2]; k <= hi[2]; ++k)
    for (std::int64_t j = lo[1]; j <= hi[1]; ++j)
      for (std::int64_t i = lo[0]; i <= hi[0]; ++i) use(std::uint32_t(grid.index(i, j, k)));
}

template <class Ball>
CellEntries file_balls(const Grid& grid, const std::vector<Ball>& balls, double grow) {
  CellEntries entries;
  for (std::uint32_t i = 0; i < balls.size(); ++i)
    each_cell(grid, balls[i].at, balls[i].reach + grow,
              [&](std::uint32_t c) { entries.push_back({c, i}); });
  par::sort(entries.begin(), entries.end(), std::less<>());
  return entries;
}

// Whether use(j) holds for a ball j filed in a cell that the box of (p, d) meets.
template <class Use>
bool any_filed(const Grid& grid, const CellEntries& entries, const Vec3& p, double d, Use&& use) {
  bool found = false;
  each_cell(grid, p, d, [&](std::uint32_t c) {
    auto it = std::lower_bound(entries.begin(), entries.end(), std::pair<std::uint32_t, std::uint32_t>{c, 0});
    for (; !found && it != entries.end() && it->first == c; ++it) found = use(it->second);
  });
  return found;
}

// One element's vertices contain the other's (the same element, or a facet and its edge or
// vertex, an edge and its end): no ball touches both at two points with different normals
// (the two contacts would lie in one plane or line that the normals' difference leaves).
bool incident(const CentreBall& a, const CentreBall& b) {
  auto count = [](const CentreBall& x) { return 3 - int(std::count(x.verts.begin(), x.verts.end(), kNone)); };
  const CentreBall& small = count(a) <= count(b) ? a : b;
  const CentreBall& large = count(a) <= count(b) ? b : a;
  for (std::uint32_t v : small.verts)
    if (v != kNone && std::find(large.verts.begin(), large.verts.end(), v) == large.verts.end())
      return false;
  return true;
}

// Whether one ball can touch at a point of each element with normals min_angle apart.
bool can_pair(const CentreBall& a, const CentreBall& b, double min_angle, double slack) {
  if ((a.at - b.at).norm() > a.reach + b.reach + slack || incident(a, b)) return false;
  if (a.unbounded || b.unbounded) return true;
  const double needed = min_angle - a.half_angle - b.half_angle - tol::kConcaveZoneAngle;
  return needed <= 0 || a.axis.dot(b.axis) <= std::cos(needed);
}

// Per cell holding balls (runs of entries): the cone of their normal cones, so that a query
// skips a cell whose balls all lie within min_angle of its own.
struct CellCones {
  std::vector<std::uint32_t> cell, begin;  // run k: entries [begin[k], begin[k + 1])
  std::vector<Vec3> axis;
  std::vector<double> spread;  // pi: unbounded
};

CellCones cell_cones(const CellEntries& entries, const std::vector<CentreBall>& balls) {
  CellCones cc;
  for (std::size_t e = 0; e < entries.size(); ++e)
    if (e == 0 || entries[e].first != entries[e - 1].first) {
      cc.cell.push_back(entries[e].first);
      cc.begin.push_back(std::uint32_t(e));
    }
  cc.begin.push_back(std::uint32_t(entries.size()));
  const std::size_t runs = cc.cell.size();
  cc.axis.assign(runs, Vec3::UnitZ());
  cc.spread.assign(runs, std::numbers::pi);
  par::for_each(runs, 1024, [&](std::size_t k) {
    Vec3 sum = Vec3::Zero();
    for (std::uint32_t e = cc.begin[k]; e < cc.begin[k + 1]; ++e) {
      const CentreBall& b = balls[entries[e].second];
      if (b.unbounded) return;
      sum += b.axis;
    }
    if (!(sum.norm() > 0)) return;
    const Vec3 axis = sum.normalized();
    double spread = 0;
    for (std::uint32_t e = cc.begin[k]; e < cc.begin[k + 1]; ++e) {
      const CentreBall& b = balls[entries[e].second];
      spread = std::max(spread, std::atan2(axis.cross(b.axis).norm(), axis.dot(b.axis)) + b.half_angle);
    }
    cc.axis[k] = axis;
    cc.spread[k] = spread + tol::kConcaveZoneAngle;
  });
  return cc;
}

// The centre balls filed in a grid, each cell with the cone of its balls' cones.
struct FiledBalls {
  Grid grid;
  CellEntries entries;
  CellCones cones;
};

FiledBalls file_for_pairing(const std::vector<CentreBall>& balls, const Aabb3& box, double R,
                            double slack) {
  double reach_sum = 0;
  std::size_t bounded = 0;
  for (const CentreBall& b : balls)
    if (!b.unbounded) {
      reach_sum += b.reach;
      ++bounded;
    }
  Aabb3 grown = box;
  grown.lo.array() -= 2 * R;
  grown.hi.array() += 2 * R;
  FiledBalls f{Grid(grown, 2 * (bounded ? reach_sum / double(bounded) : R) + slack), {}, {}};
  f.entries = file_balls(f.grid, balls, 0.5 * slack);
  f.cones = cell_cones(f.entries, balls);
  return f;
}

// Whether ball a pairs with a ball filed in a cell it meets (cells whose cone lies within
// min_angle of a's are skipped).
bool pairs_with_filed(const CentreBall& a, const std::vector<CentreBall>& balls,
                      const FiledBalls& f, double min_angle, double slack) {
  bool hit = false;
  each_cell(f.grid, a.at, a.reach + 0.5 * slack, [&](std::uint32_t c) {
    if (hit) return;
    const auto run = std::lower_bound(f.cones.cell.begin(), f.cones.cell.end(), c);
    if (run == f.cones.cell.end() || *run != c) return;
    const std::size_t k = std::size_t(run - f.cones.cell.begin());
    const double needed = min_angle - a.half_angle - f.cones.spread[k] - tol::kConcaveZoneAngle;
    if (!a.unbounded && needed > 0 && a.axis.dot(f.cones.axis[k]) > std::cos(needed)) return;
    for (std::uint32_t e = f.cones.begin[k]; e < f.cones.begin[k + 1] && !hit; ++e)
      hit = can_pair(a, balls[f.entries[e].second], min_angle, slack);
  });
  return hit;
}

// The balls that pair with another; nullopt as soon as more than max_hits do (the same
// answer for any thread count: the count only grows).
std::optional<std::vector<ConcaveZone::Ball>> zone_balls(const std::vector<CentreBall>& balls,
                                                         const Aabb3& box, double R,
                                                         double min_angle, double slack,
                                                         std::size_t max_hits) {
  const FiledBalls filed = file_for_pairing(balls, box, R, slack);
  // Queries in the order of their cells, so that the searches stay in cache.
  std::vector<std::uint32_t> order(balls.size()), home(balls.size());
  for (std::uint32_t i = 0; i < balls.size(); ++i) {
    order[i] = i;
    home[i] = std::uint32_t(filed.grid.index(balls[i].at));
  }
  par::sort(order.begin(), order.end(), [&](std::uint32_t x, std::uint32_t y) {
    return home[x] != home[y] ? home[x] < home[y] : x < y;
  });
  std::vector<std::uint8_t> hit(balls.size(), 0);
  std::atomic<std::size_t> hits{0};
  par::for_each(balls.size(), 1024, [&](std::size_t q) {
    if (hits.load(std::memory_order_relaxed) > max_hits) return;
    const std::size_t i = order[q];
    hit[i] = pairs_with_filed(balls[i], balls, filed, min_angle, slack);
    if (hit[i]) hits.fetch_add(1, std::memory_order_relaxed);
  });
  if (hits.load() > max_hits) return std::nullopt;
  std::vector<ConcaveZone::Ball> out;
  for (std::size_t i = 0; i < balls.size(); ++i)
    if (hit[i]) out.push_back({balls[i].at, balls[i].reach});
  return out;
}

// The cells within R of a zone ball (with rounding up to a cell), then every cell above one.
std::vector<std::uint8_t> kept_cells(const Grid& grid, const std::vector<ConcaveZone::Ball>& zone,
                                     double R, double slack) {
  std::vector<std::uint8_t> mark(std::size_t(grid.n[0] * grid.n[1] * grid.n[2]), 0);
  // The balls no wider than a cell, by cell: each cell's box of their centres marks the cells
  // whose centre lies within h + R + slack + half a diagonal of that box; a wider ball, the
  // cells within its own reach + R + slack + half a diagonal.
  const double half_diagonal = 0.5 * std::sqrt(3.0) * grid.h;
  auto mark_near = [&](const Aabb3& around, double d) {
    each_cell(grid, 0.5 * (around.lo + around.hi), 0.5 * (around.hi - around.lo).maxCoeff() + d,
              [&](std::uint32_t c) {
                const std::int64_t i = c % grid.n[0], j = (c / grid.n[0]) % grid.n[1],
                                   k = c / (grid.n[0] * grid.n[1]);
                const Vec3 q = grid.lo + grid.h * Vec3(double(i) + 0.5, double(j) + 0.5, double(k) + 0.5);
                const Vec3 gap = (around.lo - q).cwiseMax(q - around.hi).cwiseMax(0.0);
                if (gap.squaredNorm() <= d * d) mark[c] = 1;
              });
  };
  std::vector<std::pair<std::uint32_t, std::uint32_t>> small;  // (cell, ball)
  for (std::uint32_t i = 0; i < zone.size(); ++i) {
    const ConcaveZone::Ball& b = zone[i];
    if (b.reach <= grid.h) {
      small.push_back({std::uint32_t(grid.index(b.at)), i});
      continue;
    }
    Aabb3 at;
    at.add(b.at);
    mark_near(at, b.reach + R + slack + half_diagonal);
  }
  std::sort(small.begin(), small.end());
  for (std::size_t s0 = 0, s1 = 0; s0 < small.size(); s0 = s1) {
    Aabb3 centres;
    for (s1 = s0; s1 < small.size() && small[s1].first == small[s0].first; ++s1)
      centres.add(zone[small[s1].second].at);
    mark_near(centres, grid.h + R + slack + half_diagonal);
  }
  for (std::int64_t j = 0; j < grid.n[1]; ++j)
    for (std::int64_t i = 0; i < grid.n[0]; ++i)
      for (std::int64_t k = 1; k < grid.n[2]; ++k)
        mark[std::size_t(grid.index(i, j, k))] |= mark[std::size_t(grid.index(i, j, k - 1))];
  return mark;
}

// Facets whose box meets a kept cell.
std::vector<std::uint8_t> kept_facets(const TriangleMesh& mesh,
                                      const std::vector<ConcaveZone::Ball>& zone,
                                      const Aabb3& box, double R, double slack) {
  // About 32 cells a facet at most: a coarse part gets coarse cells.
  const auto cells = std::min<std::int64_t>(kMaxCells, 32 * std::int64_t(mesh.facets.size()) + 65536);
  const Grid grid(box, kKeepCellPerRadius * R, cells);
  const std::vector<std::uint8_t> mark = kept_cells(grid, zone, R, slack);
  std::vector<std::uint8_t> keep(mesh.facets.size(), 0);
  par::for_each(mesh.facets.size(), 4096, [&](std::size_t f) {
    Aabb3 fb;
    for (std::uint32_t v : mesh.facets[f]) fb.add(mesh.vertices[v]);
    bool any = false;
    std::array<std::int64_t, 3> lo, hi;
    for (int a = 0; a < 3; ++a) {
      lo[a] = grid.coord(fb.lo[a], a);
      hi[a] = grid.coord(fb.hi[a], a);
    }
    for (std::int64_t k = lo[2]; k <= hi[2] && !any; ++k)
      for (std::int64_t j = lo[1]; j <= hi[1] && !any; ++j)
        for (std::int64_t i = lo[0]; i <= hi[0] && !any; ++i) any = mark[std::size_t(grid.index(i, j, k))];
    keep[f] = any;
  });
  return keep;
}

}  // namespace

bool ConcaveZone::holds(const Vec3& c) const {
  const Grid grid(lookup.lo, lookup.h, {lookup.n[0], lookup.n[1], lookup.n[2]});
  return any_filed(grid, lookup.entries, c, 0, [&](std::uint32_t j) {
    return (c - balls[j].at).norm() <= balls[j].reach + slack;
  });
}

KeptSubmesh kept_submesh(const TriangleMesh& mesh, const ConcaveZone& zone) {
  KeptSubmesh sub;
  std::vector<std::uint32_t> index(mesh.vertices.size(), kNone);
  for (std::uint32_t f = 0; f < mesh.facets.size(); ++f)
    if (zone.keep[f])
      for (std::uint32_t v : mesh.facets[f]) index[v] = 0;
  for (std::uint32_t v = 0; v < mesh.vertices.size(); ++v)
    if (index[v] == 0) {
      index[v] = std::uint32_t(sub.vertex.size());
      sub.vertex.push_back(v);
      sub.mesh.vertices.push_back(mesh.vertices[v]);
    }
  for (std::uint32_t f = 0; f < mesh.facets.size(); ++f)
    if (zone.keep[f]) {
      const auto& t = mesh.facets[f];
      sub.mesh.facets.push_back({index[t[0]], index[t[1]], index[t[2]]});
      sub.facet.push_back(f);
    }
  return sub;
}

ConcaveZone concave_zone(const TriangleMesh& mesh, double radius, double min_angle,
                         double slack, double max_paired_share) {
  Stopwatch clock;
  ConcaveZone z;
  z.slack = slack;
  z.keep.assign(mesh.facets.size(), 0);
  const Aabb3 box = bounding_box(mesh);
  if (mesh.facets.empty() || box.empty()) return z;
  const FacetGeometry g = facet_geometry(mesh);
  const Stars stars = vertex_stars(mesh);
  const std::vector<std::uint8_t> irregular = irregular_vertices(mesh, stars, g);
  const std::vector<std::int8_t> side = facet_sides(mesh, irregular);
  const MeshFacts facts{mesh, stars, g, irregular, side};
  {
    const std::vector<CentreBall> balls = centre_balls(facts, radius);
    z.elements = balls.size();
    auto zone = zone_balls(balls, box, radius, min_angle, slack,
                           std::size_t(max_paired_share * double(balls.size())));
    if (!zone) {
      z.keep.assign(mesh.facets.size(), 1);
      z.keep_facets = mesh.facets.size();
      z.build_s = clock.seconds();
      return z;
    }
    z.balls = std::move(*zone);
  }
  z.keep = kept_facets(mesh, z.balls, box, radius, slack);
  Aabb3 grown = box;
  grown.lo.array() -= 2 * radius;
  grown.hi.array() += 2 * radius;
  const Grid grid(grown, kLookupCellPerRadius * radius);
  z.lookup.lo = grid.lo;
  z.lookup.h = grid.h;
  for (int a = 0; a < 3; ++a) z.lookup.n[a] = grid.n[a];
  z.lookup.entries = file_balls(grid, z.balls, slack);
  for (std::uint8_t k : z.keep) z.keep_facets += k;
  z.build_s = clock.seconds();
  return z;
}

}  // namespace ncpath
