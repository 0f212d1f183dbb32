#include "engine/concave_zone.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <numbers>
#include <optional>
#include <span>

#include <Eigen/Geometry>

#include "engine/concave_zone_detail.hpp"
#include "engine/parallel.hpp"
#include "engine/run_control.hpp"
#include "kernels/geom/tolerance.hpp"

namespace ncpath {

namespace {

using concave_zone_detail::CentreBall;
using concave_zone_detail::kNone;

constexpr double kKeepCellPerRadius = 0.25;  // the kept region's cell edge, in R
constexpr double kLookupCellPerRadius = 1;   // holds()'s cell edge, in R
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
    each_cell(grid, balls[i].at, balls[i].reach + grow, [&](std::uint32_t c) {
      entries.push_back({c, i});
    });
  par::sort(entries.begin(), entries.end(), std::less<>());
  return entries;
}

// Whether use(j) holds for a ball j filed in a cell that the box of (p, d) meets.
template <class Use>
bool any_filed(const Grid& grid, const CellEntries& entries, const Vec3& p, double d, Use&& use) {
  bool found = false;
  each_cell(grid, p, d, [&](std::uint32_t c) {
    auto it = std::lower_bound(entries.begin(), entries.end(),
                               std::pair<std::uint32_t, std::uint32_t>{c, 0});
    for (; !found && it != entries.end() && it->first == c; ++it) found = use(it->second);
  });
  return found;
}

// One element's vertices contain the other's (the same element, or a facet and its edge or
// vertex, an edge and its end): no ball touches both at two points with different normals
// (the two contacts would lie in one plane or line that the normals' difference leaves).
bool incident(const CentreBall& a, const CentreBall& b) {
  auto count = [](const CentreBall& x) {
    return 3 - int(std::count(x.verts.begin(), x.verts.end(), kNone));
  };
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
  if (a.unbounded() || b.unbounded()) return true;
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
      if (b.unbounded()) return;
      sum += b.axis;
    }
    if (!(sum.norm() > 0)) return;
    const Vec3 axis = sum.normalized();
    double spread = 0;
    for (std::uint32_t e = cc.begin[k]; e < cc.begin[k + 1]; ++e) {
      const CentreBall& b = balls[entries[e].second];
      spread =
          std::max(spread, std::atan2(axis.cross(b.axis).norm(), axis.dot(b.axis)) + b.half_angle);
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
    if (!b.unbounded()) {
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
    if (!a.unbounded() && needed > 0 && a.axis.dot(f.cones.axis[k]) > std::cos(needed)) return;
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
                const Vec3 q =
                    grid.lo + grid.h * Vec3(double(i) + 0.5, double(j) + 0.5, double(k) + 0.5);
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
                                      const std::vector<ConcaveZone::Ball>& zone, const Aabb3& box,
                                      double R, double slack) {
  // About 32 cells a facet at most: a coarse part gets coarse cells.
  const auto cells =
      std::min<std::int64_t>(kMaxCells, 32 * std::int64_t(mesh.facets.size()) + 65536);
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
        for (std::int64_t i = lo[0]; i <= hi[0] && !any; ++i)
          any = mark[std::size_t(grid.index(i, j, k))];
    keep[f] = any;
  });
  return keep;
}

// The facets marked in `keep` as a mesh of their own.
KeptSubmesh kept_submesh(const TriangleMesh& mesh, const std::vector<std::uint8_t>& keep) {
  KeptSubmesh sub;
  std::vector<std::uint32_t> index(mesh.vertices.size(), kNone);
  for (std::uint32_t f = 0; f < mesh.facets.size(); ++f)
    if (keep[f])
      for (std::uint32_t v : mesh.facets[f]) index[v] = 0;
  for (std::uint32_t v = 0; v < mesh.vertices.size(); ++v)
    if (index[v] == 0) {
      index[v] = std::uint32_t(sub.vertex.size());
      sub.vertex.push_back(v);
      sub.mesh.vertices.push_back(mesh.vertices[v]);
    }
  for (std::uint32_t f = 0; f < mesh.facets.size(); ++f)
    if (keep[f]) {
      const auto& t = mesh.facets[f];
      sub.mesh.facets.push_back({index[t[0]], index[t[1]], index[t[2]]});
      sub.facet.push_back(f);
    }
  return sub;
}

}  // namespace

bool ConcaveZone::holds(const Vec3& c) const {
  const Grid grid(lookup.lo, lookup.h, {lookup.n[0], lookup.n[1], lookup.n[2]});
  return any_filed(grid, lookup.entries, c, 0, [&](std::uint32_t j) {
    return (c - balls[j].at).norm() <= balls[j].reach + slack;
  });
}

ConcaveZone concave_zone(const TriangleMesh& mesh, double radius, double min_angle, double slack,
                         double max_paired_share) {
  Stopwatch clock;
  ConcaveZone z;
  z.slack = slack;
  const Aabb3 box = bounding_box(mesh);
  if (mesh.facets.empty() || box.empty()) return z;
  {
    const std::vector<CentreBall> balls = concave_zone_detail::centre_balls(mesh, radius);
    z.elements = balls.size();
    auto zone = zone_balls(balls, box, radius, min_angle, slack,
                           std::size_t(max_paired_share * double(balls.size())));
    if (!zone) {
      z.wide = true;
      z.keep_facets = mesh.facets.size();
      z.build_s = clock.seconds();
      return z;
    }
    z.balls = std::move(*zone);
  }
  z.kept = kept_submesh(mesh, kept_facets(mesh, z.balls, box, radius, slack));
  z.keep_facets = z.kept.facet.size();
  Aabb3 grown = box;
  grown.lo.array() -= 2 * radius;
  grown.hi.array() += 2 * radius;
  const Grid grid(grown, kLookupCellPerRadius * radius);
  z.lookup.lo = grid.lo;
  z.lookup.h = grid.h;
  for (int a = 0; a < 3; ++a) z.lookup.n[a] = grid.n[a];
  z.lookup.entries = file_balls(grid, z.balls, slack);
  z.build_s = clock.seconds();
  return z;
}

}  // namespace ncpath
