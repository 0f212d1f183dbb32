#include "kernels/cleanup/pencil.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <unordered_map>

#include "kernels/geom/tolerance.hpp"
#include "kernels/mesh/closest_point.hpp"

namespace ncpath {

double bicontact_angle(const Vec3& b1, const Vec3& b2) {
  return std::atan2(b1.cross(b2).norm(), b1.dot(b2));
}

Vec3 crease_tangent(const Vec3& b1, const Vec3& b2) {
  const Vec3 c = b1.cross(b2);
  const double n = c.norm();
  return n > 0 ? Vec3(c / n) : Vec3::Zero();
}

Vec3 layer_normal(std::uint8_t family) {
  return family == 0 ? Vec3(0, 1, 0) : family == 1 ? Vec3(1, 0, 0) : Vec3(0, 0, 1);
}

double chord_error(const Vec3& a, const Vec3& ta, const Vec3& b, const Vec3& tb) {
  const Vec3 ab = b - a;
  const double d = ab.norm();
  if (!(d > 0)) return 0;
  const Vec3 u = ab / d;
  const double tha = std::acos(std::min(1.0, std::abs(u.dot(ta)))),
               thb = std::acos(std::min(1.0, std::abs(u.dot(tb))));
  const double s = std::sin(tha + thb);
  if (tha + thb == 0) return 0;
  if (!(s > 1e-12)) return std::numeric_limits<double>::infinity();
  return d * std::sin(tha) * std::sin(thb) / s;
}

bool pencil_keep(const PencilCandidate& c, const bool scanned[3]) {
  const Vec3 t = crease_tangent(c.b1, c.b2);
  const double own = std::abs(t.dot(layer_normal(c.family)));
  for (std::uint8_t f = 0; f < 3; ++f) {
    if (f == c.family || !scanned[f]) continue;
    const double other = std::abs(t.dot(layer_normal(f)));
    if (other > own + tol::kPencilFamilyTie ||
        (std::abs(other - own) <= tol::kPencilFamilyTie && f < c.family))
      return false;
  }
  return true;
}

namespace {

// Best point of `layer` (indices into pts) for a point at p with tangent t, predicted on the
// layer's plane; -1 when none qualifies.
std::int64_t best_match(std::span<const PencilCandidate> pts, const std::vector<std::uint32_t>& layer,
                        const Vec3& p, const Vec3& t, std::uint8_t family,
                        const PencilLinkParams& prm) {
  if (layer.empty()) return -1;
  const Vec3 n = layer_normal(family);
  const double tn = t.dot(n);
  if (!(std::abs(tn) > 1e-9)) return -1;
  const double s = (pts[layer[0]].p.dot(n) - p.dot(n)) / tn;
  const Vec3 q = p + s * t;
  std::int64_t best = -1;
  double best_d = prm.max_gap;
  for (std::uint32_t i : layer) {
    const double d = (pts[i].p - q).norm();
    const Vec3 ti = crease_tangent(pts[i].b1, pts[i].b2);
    if (d <= best_d && std::abs(ti.dot(t)) >= prm.min_cos) {
      best_d = d;
      best = i;
    }
  }
  return best;
}

}  // namespace

std::vector<std::vector<std::uint32_t>> link_layers(std::span<const PencilCandidate> pts,
                                                    const PencilLinkParams& prm) {
  std::map<std::uint32_t, std::vector<std::uint32_t>> layers;
  for (std::uint32_t i = 0; i < pts.size(); ++i) layers[pts[i].layer].push_back(i);
  std::vector<std::int64_t> next(pts.size(), -1), prev(pts.size(), -1);
  for (auto it = layers.begin(); it != layers.end(); ++it) {
    auto nx = std::next(it);
    if (nx == layers.end() || nx->first != it->first + 1) continue;
    for (std::uint32_t a : it->second) {
      const Vec3 ta = crease_tangent(pts[a].b1, pts[a].b2);
      const std::int64_t b = best_match(pts, nx->second, pts[a].p, ta, pts[a].family, prm);
      if (b < 0 || prev[std::size_t(b)] >= 0) continue;
      const Vec3 tb = crease_tangent(pts[std::size_t(b)].b1, pts[std::size_t(b)].b2);
      const std::int64_t back =
          best_match(pts, it->second, pts[std::size_t(b)].p, tb, pts[a].family, prm);
      if (back != a) continue;
      next[a] = b;
      prev[std::size_t(b)] = a;
    }
  }
  std::vector<std::vector<std::uint32_t>> chains;
  for (const auto& [layer, ids] : layers)
    for (std::uint32_t i : ids) {
      if (prev[i] >= 0) continue;
      std::vector<std::uint32_t> c;
      for (std::int64_t k = i; k >= 0; k = next[std::size_t(k)]) c.push_back(std::uint32_t(k));
      chains.push_back(std::move(c));
    }
  return chains;
}

std::vector<OrderedPath> order_paths(std::span<const std::vector<Vec3>> paths,
                                     std::span<const std::uint8_t> fixed) {
  std::vector<OrderedPath> out;
  if (paths.empty()) return out;
  std::vector<bool> used(paths.size(), false);
  out.push_back({0, false});
  used[0] = true;
  Vec3 at = paths[0].back();
  for (std::size_t n = 1; n < paths.size(); ++n) {
    double best = std::numeric_limits<double>::infinity();
    OrderedPath pick;
    for (std::uint32_t i = 0; i < paths.size(); ++i) {
      if (used[i] || paths[i].empty()) continue;
      const double d0 = (paths[i].front() - at).norm(), d1 = (paths[i].back() - at).norm();
      if (d0 < best) {
        best = d0;
        pick = {i, false};
      }
      if (d1 < best && !(i < fixed.size() && fixed[i])) {
        best = d1;
        pick = {i, true};
      }
    }
    if (!std::isfinite(best)) break;
    used[pick.index] = true;
    out.push_back(pick);
    at = pick.reversed ? paths[pick.index].front() : paths[pick.index].back();
  }
  return out;
}

double polyline_length(std::span<const Vec3> p) {
  double s = 0;
  for (std::size_t i = 1; i < p.size(); ++i) s += (p[i] - p[i - 1]).norm();
  return s;
}

namespace {

// Outward direction at end e (0 start, 1 end) of polyline p; zero for a single point.
Vec3 outward(const std::vector<Vec3>& p, int e) {
  if (p.size() < 2) return Vec3::Zero();
  const Vec3 d = e == 0 ? Vec3(p[0] - p[1]) : Vec3(p.back() - p[p.size() - 2]);
  const double n = d.norm();
  return n > 0 ? Vec3(d / n) : Vec3::Zero();
}

}  // namespace

void close_loops(std::vector<std::vector<Vec3>>& paths, double merge_distance, double min_cos) {
  for (std::vector<Vec3>& p : paths) {
    if (p.size() < 3 || p.front() == p.back()) continue;
    if ((p.front() - p.back()).norm() > merge_distance) continue;
    const Vec3 oa = outward(p, 0), ob = outward(p, 1);
    if (!oa.isZero() && !ob.isZero() && -oa.dot(ob) >= min_cos) p.push_back(p.front());
  }
}

namespace {

// Segments of the paths taken so far, found by a grid of cell `cell` (> 2 eps): a segment is
// listed in the cells of samples at most half a cell apart, so a point within eps of it
// finds it in the 27 cells around its own.
class SegmentGrid {
 public:
  explicit SegmentGrid(double cell) : cell_(cell) {}
  void add(const Vec3& a, const Vec3& b) {
    const auto id = std::uint32_t(seg_.size());
    seg_.push_back({a, b});
    const int n = 1 + int(std::ceil(2 * (b - a).norm() / cell_));
    std::array<std::int64_t, 3> last{};
    for (int i = 0; i <= n; ++i) {
      const auto k = key(a + (double(i) / n) * (b - a));
      if (i > 0 && k == last) continue;
      grid_[k].push_back(id);
      last = k;
    }
  }
  // Whether a segment within eps of p runs along the unit vector t (|cos| >= min_cos).
  bool covers(const Vec3& p, const Vec3& t, double eps, double min_cos) const {
    const auto k = key(p);
    for (std::int64_t dx = -1; dx <= 1; ++dx)
      for (std::int64_t dy = -1; dy <= 1; ++dy)
        for (std::int64_t dz = -1; dz <= 1; ++dz) {
          const auto it = grid_.find({k[0] + dx, k[1] + dy, k[2] + dz});
          if (it == grid_.end()) continue;
          for (std::uint32_t id : it->second)
            if (near_along(seg_[id], p, t, eps, min_cos)) return true;
        }
    return false;
  }

 private:
  static bool near_along(const std::array<Vec3, 2>& s, const Vec3& p, const Vec3& t, double eps,
                         double min_cos) {
    const Vec3 d = s[1] - s[0];
    const double len = d.norm();
    if (!(len > 0) || std::abs(d.dot(t)) < min_cos * len) return false;
    Vec3 c;
    point_segment_closest(p, s[0], s[1], c);
    return (p - c).norm() <= eps;
  }
  std::array<std::int64_t, 3> key(const Vec3& p) const {
    return {std::int64_t(std::floor(p.x() / cell_)), std::int64_t(std::floor(p.y() / cell_)),
            std::int64_t(std::floor(p.z() / cell_))};
  }
  double cell_;
  std::vector<std::array<Vec3, 2>> seg_;
  std::map<std::array<std::int64_t, 3>, std::vector<std::uint32_t>> grid_;
};

// Unit tangent of a polyline at point i (central difference; one-sided at the ends).
Vec3 tangent_at(const std::vector<Vec3>& p, std::size_t i) {
  const Vec3 d = p[std::min(i + 1, p.size() - 1)] - p[i > 0 ? i - 1 : 0];
  const double n = d.norm();
  return n > 0 ? Vec3(d / n) : Vec3::Zero();
}

}  // namespace

std::vector<PathRun> cusp_runs(std::span<const std::vector<Vec3>> paths) {
  std::vector<PathRun> runs;
  for (std::uint32_t k = 0; k < paths.size(); ++k) {
    const std::vector<Vec3>& p = paths[k];
    if (p.empty()) continue;
    std::uint32_t from = 0;
    for (std::uint32_t i = 1; i + 1 < p.size(); ++i) {
      const Vec3 a = p[i] - p[i - 1], b = p[i + 1] - p[i];
      if (!(a.dot(b) < -0.5 * a.norm() * b.norm())) continue;
      runs.push_back({k, from, i});
      from = i;
    }
    runs.push_back({k, from, std::uint32_t(p.size() - 1)});
  }
  return runs;
}

std::vector<PathRun> uncovered_runs(std::span<const std::vector<Vec3>> paths, double eps,
                                    double min_cos) {
  std::vector<double> length(paths.size());
  for (std::size_t k = 0; k < paths.size(); ++k) length[k] = polyline_length(paths[k]);
  std::vector<std::uint32_t> order(paths.size());
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return length[a] > length[b]; });
  SegmentGrid taken(std::max(4 * eps, 0.5));
  std::vector<PathRun> runs;
  for (std::uint32_t k : order) {
    const std::vector<Vec3>& p = paths[k];
    std::vector<std::uint8_t> covered(p.size());
    for (std::size_t i = 0; i < p.size(); ++i) {
      const Vec3 t = tangent_at(p, i);
      covered[i] = !t.isZero() && taken.covers(p[i], t, eps, min_cos);
    }
    const std::size_t first = runs.size();
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (covered[i]) continue;
      std::size_t j = i;
      while (j + 1 < p.size() && !covered[j + 1]) ++j;
      if (j > i) runs.push_back({k, std::uint32_t(i), std::uint32_t(j)});
      i = j;
    }
    for (std::size_t r = first; r < runs.size(); ++r)
      for (std::uint32_t i = runs[r].from; i < runs[r].to; ++i) taken.add(p[i], p[i + 1]);
  }
  return runs;
}

std::vector<std::vector<Vec3>> merge_paths(std::vector<std::vector<Vec3>> paths,
                                           double merge_distance, double min_cos,
                                           double min_length) {
  std::erase_if(paths, [](const std::vector<Vec3>& p) { return p.empty(); });
  const std::size_t n = paths.size();
  // Candidate end pairs through a grid of cell merge_distance (ends: 2 * path + end).
  struct Pair {
    double d;
    std::uint32_t a, b;  // end ids
  };
  std::vector<Pair> pairs;
  if (merge_distance > 0) {
    const double cell = merge_distance;
    auto key = [&](const Vec3& p) {
      return std::array<std::int64_t, 3>{std::int64_t(std::floor(p.x() / cell)),
                                         std::int64_t(std::floor(p.y() / cell)),
                                         std::int64_t(std::floor(p.z() / cell))};
    };
    std::map<std::array<std::int64_t, 3>, std::vector<std::uint32_t>> grid;
    auto end_point = [&](std::uint32_t e) -> const Vec3& {
      return e % 2 == 0 ? paths[e / 2].front() : paths[e / 2].back();
    };
    for (std::uint32_t e = 0; e < 2 * n; ++e) grid[key(end_point(e))].push_back(e);
    for (std::uint32_t e = 0; e < 2 * n; ++e) {
      const auto k = key(end_point(e));
      for (std::int64_t dx = -1; dx <= 1; ++dx)
        for (std::int64_t dy = -1; dy <= 1; ++dy)
          for (std::int64_t dz = -1; dz <= 1; ++dz) {
            auto it = grid.find({k[0] + dx, k[1] + dy, k[2] + dz});
            if (it == grid.end()) continue;
            for (std::uint32_t f : it->second) {
              if (f <= e || f / 2 == e / 2) continue;
              const double d = (end_point(e) - end_point(f)).norm();
              if (d > merge_distance) continue;
              const Vec3 oa = outward(paths[e / 2], int(e % 2)),
                         ob = outward(paths[f / 2], int(f % 2));
              if (!oa.isZero() && !ob.isZero() && -oa.dot(ob) < min_cos) continue;
              pairs.push_back({d, e, f});
            }
          }
    }
  }
  std::sort(pairs.begin(), pairs.end(), [](const Pair& x, const Pair& y) {
    return x.d != y.d ? x.d < y.d : (x.a != y.a ? x.a < y.a : x.b < y.b);
  });
  // Accept greedily: both ends free, no cycle (union-find on paths).
  std::vector<std::int64_t> mate(2 * n, -1);
  std::vector<std::uint32_t> root(n);
  std::iota(root.begin(), root.end(), 0u);
  auto find = [&](std::uint32_t x) {
    while (root[x] != x) x = root[x] = root[root[x]];
    return x;
  };
  for (const Pair& pr : pairs) {
    if (mate[pr.a] >= 0 || mate[pr.b] >= 0) continue;
    const std::uint32_t ra = find(pr.a / 2), rb = find(pr.b / 2);
    if (ra == rb) continue;
    root[ra] = rb;
    mate[pr.a] = pr.b;
    mate[pr.b] = pr.a;
  }
  // Walk each group from a path with a free end.
  std::vector<bool> done(n, false);
  std::vector<std::vector<Vec3>> out;
  for (std::uint32_t s = 0; s < n; ++s) {
    if (done[s]) continue;
    int free_end = mate[2 * s] < 0 ? 0 : (mate[2 * s + 1] < 0 ? 1 : -1);
    if (free_end < 0) continue;  // inside a group; reached from its free end
    std::vector<Vec3> poly;
    std::uint32_t cur = s;
    int enter = free_end;  // we enter `cur` at this end
    while (true) {
      done[cur] = true;
      const auto& p = paths[cur];
      if (enter == 0)
        poly.insert(poly.end(), p.begin(), p.end());
      else
        poly.insert(poly.end(), p.rbegin(), p.rend());
      const std::uint32_t leave = 2 * cur + std::uint32_t(1 - enter);
      if (mate[leave] < 0) break;
      const auto nx = std::uint32_t(mate[leave]);
      cur = nx / 2;
      enter = int(nx % 2);
    }
    if (polyline_length(poly) >= min_length) out.push_back(std::move(poly));
  }
  return out;
}

bool crease_at_height(const std::function<Vec3(const Vec3&)>& closest1,
                      const std::function<Vec3(const Vec3&)>& closest2, const Vec2& guess,
                      double zc, double R, double reach, Vec2& out) {
  Vec2 x = guess;
  for (int it = 0; it < 30; ++it) {
    const Vec3 c(x.x(), x.y(), zc);
    const Vec3 d1 = c - closest1(c), d2 = c - closest2(c);
    const double l1 = d1.norm(), l2 = d2.norm();
    if (!(l1 > 0 && l2 > 0)) return false;
    const Vec2 f(l1 - R, l2 - R);
    if (f.cwiseAbs().maxCoeff() < 1e-10) {
      out = x;
      return (x - guess).norm() <= reach;
    }
    Eigen::Matrix2d J;
    J << d1.x() / l1, d1.y() / l1, d2.x() / l2, d2.y() / l2;
    const double det = J.determinant();
    if (!(std::abs(det) > 1e-12)) return false;
    x -= J.inverse() * f;
    if ((x - guess).norm() > 2 * reach) return false;
  }
  return false;
}

}  // namespace ncpath
