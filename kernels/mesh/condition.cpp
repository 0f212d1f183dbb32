#include "kernels/mesh/condition.hpp"

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <utility>

#include "kernels/geom/tolerance.hpp"

namespace ncpath {

namespace {

constexpr std::uint32_t kNone = 0xffffffffu;

struct Plane {
  Vec3 n = Vec3::Zero();  // unit
  double c = 0;           // n . p == c on the plane
  int axis = -1;          // 0, 1, 2 when n is exactly +-e_axis
};

bool facet_normal(const TriangleMesh& m, std::uint32_t f, Vec3& n) {
  const auto& t = m.facets[f];
  const Vec3& a = m.vertices[t[0]];
  n = (m.vertices[t[1]] - a).cross(m.vertices[t[2]] - a);
  if (n.squaredNorm() < tol::kDegenerateArea2) return false;
  return true;
}

// The plane fitted to the facets added so far: area-weighted normals (turned to agree with
// the first) and area-weighted centroids; `plane` is kept up to date.
struct PlaneFit {
  Vec3 normal_sum = Vec3::Zero(), centroid_sum = Vec3::Zero();
  double area = 0;
  Plane plane;
  void add(const TriangleMesh& m, std::uint32_t f, const Vec3& cross) {
    const auto& t = m.facets[f];
    const double a = 0.5 * cross.norm();
    const Vec3 c = (m.vertices[t[0]] + m.vertices[t[1]] + m.vertices[t[2]]) / 3;
    normal_sum += area > 0 && cross.dot(normal_sum) < 0 ? -0.5 * cross : 0.5 * cross;
    centroid_sum += a * c;
    area += a;
    plane.n = normal_sum.normalized();
    plane.c = plane.n.dot(centroid_sum / area);
  }
};

bool facet_near(const TriangleMesh& m, std::uint32_t f, const Plane& p) {
  for (std::uint32_t v : m.facets[f])
    if (std::abs(p.n.dot(m.vertices[v]) - p.c) > tol::kConditionPlane) return false;
  return true;
}

// Facets reached from `seed` through shared vertices that `accept` takes (seed first, then in
// breadth-first order). `mark`/`stamp` record the visit; `free` says whether a facet may join.
template <class Accept, class Free>
void grow(std::uint32_t seed, const TriangleMesh& m, const FacetsAround& around,
          std::vector<std::uint32_t>& mark, std::uint32_t stamp, Accept accept, Free free,
          std::vector<std::uint32_t>& out) {
  out.assign(1, seed);
  mark[seed] = stamp;
  for (std::size_t i = 0; i < out.size(); ++i)
    for (std::uint32_t v : m.facets[out[i]])
      for (std::uint32_t k = around.start[v]; k < around.start[v + 1]; ++k) {
        const std::uint32_t g = around.ids[k];
        if (mark[g] != stamp && free(g) && accept(g)) {
          mark[g] = stamp;
          out.push_back(g);
        }
      }
}

// The cluster's plane turned to an axis plane, else to vertical, when every vertex of its
// facets stays within kConditionPlane of it; else unchanged.
Plane snap_to_axis(const TriangleMesh& m, const std::vector<std::uint32_t>& facets, Plane p) {
  auto fits = [&](const Vec3& n) {
    double lo = INFINITY, hi = -INFINITY;
    for (std::uint32_t f : facets)
      for (std::uint32_t v : m.facets[f]) {
        const double d = n.dot(m.vertices[v]);
        lo = std::min(lo, d);
        hi = std::max(hi, d);
      }
    return hi - lo <= 2 * tol::kConditionPlane ? 0.5 * (lo + hi) : NAN;
  };
  for (int k = 0; k < 3; ++k) {
    if (std::abs(p.n[k]) < 0.5) continue;
    const Vec3 n = Vec3::Unit(k);
    if (const double c = fits(n); !std::isnan(c)) return {n, c, k};
  }
  const Vec3 h(p.n.x(), p.n.y(), 0);
  if (p.n.z() != 0 && h.norm() > 0.5) {
    const Vec3 n = h.normalized();
    if (const double c = fits(n); !std::isnan(c)) return {n, c, -1};
  }
  return p;
}

// Cluster id per facet (kNone for degenerate ones) and each cluster's plane; `binding[c]` is
// 1 when the cluster's plane constrains its vertices (two facets or more, or snapped).
struct Clusters {
  std::vector<std::uint32_t> of_facet;
  std::vector<Plane> plane;
  std::vector<std::uint8_t> binding;
};

void run_ranges(const RangeRunner& ranges, std::size_t n,
                const std::function<void(std::size_t, std::size_t)>& body) {
  if (ranges)
    ranges(n, body);
  else
    body(0, n);
}

// The plane of one facet (as PlaneFit gives it for the facet alone).
Plane facet_plane(const TriangleMesh& m, std::uint32_t f, const Vec3& cross) {
  PlaneFit fit;
  fit.add(m, f, cross);
  return fit.plane;
}

Clusters find_clusters(const TriangleMesh& m, const FacetsAround& around, const RangeRunner& ranges,
                       ConditionStats& st) {
  const auto nf = std::uint32_t(m.facets.size());
  Clusters cl;
  cl.of_facet.assign(nf, kNone);
  std::vector<Vec3> cross(nf);
  std::vector<std::uint8_t> usable(nf), lone(nf);
  run_ranges(ranges, nf, [&](std::size_t b, std::size_t e) {
    for (auto f = std::uint32_t(b); f < e; ++f) usable[f] = facet_normal(m, f, cross[f]);
  });
  // A facet with no usable facet around it near its own plane grows no cluster from itself
  // (the first step of the growth below, done here for all facets at once, with its snap).
  struct Single {
    Plane snapped;
    bool moved = false;
  };
  std::vector<Single> single(nf);
  run_ranges(ranges, nf, [&](std::size_t b, std::size_t e) {
    std::vector<std::uint32_t> one(1);
    for (auto f = std::uint32_t(b); f < e; ++f) {
      if (!usable[f]) continue;
      const Plane p = facet_plane(m, f, cross[f]);
      bool alone = true;
      for (std::uint32_t v : m.facets[f])
        for (std::uint32_t k = around.start[v]; alone && k < around.start[v + 1]; ++k) {
          const std::uint32_t g = around.ids[k];
          alone = g == f || !usable[g] || !facet_near(m, g, p);
        }
      lone[f] = alone;
      if (!alone) continue;
      one[0] = f;
      const Plane snapped = snap_to_axis(m, one, p);
      single[f] = {snapped, snapped.n != p.n};
    }
  });
  std::vector<std::uint32_t> mark(nf, 0), members;
  std::uint32_t stamp = 0;
  auto free = [&](std::uint32_t g) { return usable[g] && cl.of_facet[g] == kNone; };
  cl.plane.reserve(nf);
  cl.binding.reserve(nf);
  for (std::uint32_t seed = 0; seed < nf; ++seed) {
    if (!free(seed)) continue;
    members.assign(1, seed);
    Plane snapped = single[seed].snapped;
    bool moved = single[seed].moved;
    if (!lone[seed]) {
      PlaneFit fit;
      fit.add(m, seed, cross[seed]);
      grow(seed, m, around, mark, ++stamp,
           [&](std::uint32_t g) {
             if (!facet_near(m, g, fit.plane)) return false;
             fit.add(m, g, cross[g]);
             return true;
           },
           free, members);
      const Plane p = fit.plane;
      if (members.size() > 1)  // held fixed: every member within kConditionPlane of it
        grow(seed, m, around, mark, ++stamp, [&](std::uint32_t g) { return facet_near(m, g, p); },
             free, members);
      snapped = snap_to_axis(m, members, p);
      moved = snapped.n != p.n;
    }
    const auto id = std::uint32_t(cl.plane.size());
    for (std::uint32_t f : members) cl.of_facet[f] = id;
    cl.plane.push_back(snapped);
    cl.binding.push_back(members.size() > 1 || snapped.axis >= 0 || moved);
    if (members.size() > 1) {
      ++st.planes;
      st.planar_facets += members.size();
    }
    if (moved) ++st.axis_planes;
  }
  return cl;
}

// The smallest move putting v on every plane (least squares, nearly parallel planes counted
// once), or nullopt-like false when the planes do not meet within kConditionMove of v.
bool move_onto(const Vec3& v, const std::vector<const Plane*>& planes, Vec3& out) {
  Vec3 d;
  if (planes.size() == 1) {
    d = (planes[0]->c - planes[0]->n.dot(v)) * planes[0]->n;
  } else {
    Eigen::MatrixXd n(planes.size(), 3);  // thin U and V need dynamic columns
    Eigen::VectorXd r(planes.size());
    for (std::size_t i = 0; i < planes.size(); ++i) {
      n.row(Eigen::Index(i)) = planes[i]->n.transpose();
      r[Eigen::Index(i)] = planes[i]->c - planes[i]->n.dot(v);
    }
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(n, Eigen::ComputeThinU | Eigen::ComputeThinV);
    svd.setThreshold(tol::kConditionParallel);
    d = svd.solve(r);
  }
  if (!(d.norm() <= tol::kConditionMove)) return false;
  out = v + d;
  for (const Plane* p : planes)
    if (p->axis >= 0) out[p->axis] = p->n[p->axis] > 0 ? p->c : -p->c;
  return true;
}

// The facets of each cluster (binding ones only; others empty).
std::vector<std::vector<std::uint32_t>> cluster_facets(const TriangleMesh& m, const Clusters& cl) {
  std::vector<std::vector<std::uint32_t>> out(cl.plane.size());
  for (std::uint32_t f = 0; f < m.facets.size(); ++f)
    if (const std::uint32_t c = cl.of_facet[f]; c != kNone && cl.binding[c]) out[c].push_back(f);
  return out;
}

// Binding clusters whose planes coincide (every vertex of the later one within
// kConditionPlane of the earlier one's plane) take the earlier one's plane, bit for bit:
// pieces of one face that share no vertex (a wall interrupted by a fillet) then have exactly
// one plane, and their edges' shadows coincide. Candidates are found by the plane's offset
// (sorted; orientation made canonical) and compared by normal; clusters go in id order, so
// each takes the final plane of the lowest one it matches.
void unify_planes(const TriangleMesh& m, const std::vector<std::vector<std::uint32_t>>& facets,
                  Clusters& cl) {
  const std::size_t k = cl.plane.size();
  std::vector<Vec3> n(k);
  std::vector<double> off(k);
  std::vector<std::uint32_t> order;
  for (std::uint32_t c = 0; c < k; ++c) {
    if (facets[c].empty()) continue;
    const Plane& p = cl.plane[c];
    const bool flip = p.n.z() < 0 || (p.n.z() == 0 && (p.n.y() < 0 || (p.n.y() == 0 && p.n.x() < 0)));
    n[c] = flip ? Vec3(-p.n) : p.n;
    off[c] = flip ? -p.c : p.c;
    order.push_back(c);
  }
  const std::vector<std::uint32_t> ids = order;  // ascending
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return off[a] != off[b] ? off[a] < off[b] : a < b;
  });
  std::vector<std::size_t> pos(k);
  for (std::size_t i = 0; i < order.size(); ++i) pos[order[i]] = i;
  const double window = 2 * tol::kConditionPlane;
  auto fits = [&](std::uint32_t c, const Plane& p) {
    for (std::uint32_t f : facets[c])
      for (std::uint32_t v : m.facets[f])
        if (std::abs(p.n.dot(m.vertices[v]) - p.c) > tol::kConditionPlane) return false;
    return true;
  };
  for (const std::uint32_t b : ids) {
    std::size_t lo = pos[b], hi = pos[b] + 1;
    while (lo > 0 && off[b] - off[order[lo - 1]] <= window) --lo;
    while (hi < order.size() && off[order[hi]] - off[b] <= window) ++hi;
    std::uint32_t best = b;
    for (std::size_t j = lo; j < hi; ++j)
      if (order[j] < best && (n[order[j]] - n[b]).norm() <= tol::kConditionSameNormal)
        best = order[j];
    if (best != b && fits(b, cl.plane[best])) cl.plane[b] = cl.plane[best];
  }
}

// (vertex, cluster) pairs, sorted: the ends of the edges that lie in a vertical cluster's
// plane (both ends within kConditionPlane of it), the cluster's own and others: a ruling of
// the curved surface beside a wall, the edge of a ledge straight above the wall's foot, a
// wall's edge cut off from its face by a fillet. Their shadows run along the plane's shadow,
// so they must lie on it as exactly as the cluster's own vertices. The planes are found by
// the offset of the edge's xy line (buckets of 2 kConditionPlane, either sign).
std::vector<std::pair<std::uint32_t, std::uint32_t>> vertical_extensions(
    const TriangleMesh& m, const Clusters& cl, const std::vector<std::vector<std::uint32_t>>& members) {
  const double t = tol::kConditionPlane, w = 2 * t;
  auto key = [w](double c) { return std::int64_t(std::floor(std::abs(c) / w)); };
  std::unordered_multimap<std::int64_t, std::uint32_t> by_offset;
  for (std::uint32_t c = 0; c < cl.plane.size(); ++c)
    if (!members[c].empty() && cl.plane[c].n.z() == 0) by_offset.emplace(key(cl.plane[c].c), c);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
  if (by_offset.empty()) return out;
  auto on = [&](const Plane& p, std::uint32_t v) {
    return std::abs(p.n.dot(m.vertices[v]) - p.c) <= t;
  };
  for (const auto& f : m.facets)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t u = f[k], v = f[(k + 1) % 3];
      const Vec3 &a = m.vertices[u], &b = m.vertices[v];
      const Vec2 d(b.x() - a.x(), b.y() - a.y());
      const double len = d.norm();
      if (!(len > w)) continue;  // (nearly) vertical: no shadow line
      const double c = (d.x() * a.y() - d.y() * a.x()) / len;  // offset of the xy line
      for (std::int64_t q = key(c) - 1; q <= key(c) + 1; ++q) {
        const auto [lo, hi] = by_offset.equal_range(q);
        for (auto it = lo; it != hi; ++it)
          if (on(cl.plane[it->second], u) && on(cl.plane[it->second], v)) {
            out.emplace_back(u, it->second);
            out.emplace_back(v, it->second);
          }
      }
    }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace

ConditionedMesh condition_mesh(const TriangleMesh& mesh, const RangeRunner& ranges) {
  ConditionedMesh out;
  out.mesh = mesh;
  const FacetsAround around = facets_around(mesh);
  Clusters cl = find_clusters(mesh, around, ranges, out.stats);
  const auto facets = cluster_facets(mesh, cl);
  unify_planes(mesh, facets, cl);
  const auto extended = vertical_extensions(mesh, cl, facets);
  const std::size_t nv = mesh.vertices.size();
  std::vector<std::uint8_t> kept(nv, 0);
  run_ranges(ranges, nv, [&](std::size_t begin, std::size_t end) {
    std::vector<std::uint32_t> ids;
    std::vector<const Plane*> planes;
    for (auto v = std::uint32_t(begin); v < end; ++v) {
      ids.clear();
      for (std::uint32_t k = around.start[v]; k < around.start[v + 1]; ++k)
        if (const std::uint32_t c = cl.of_facet[around.ids[k]]; c != kNone && cl.binding[c])
          ids.push_back(c);
      for (auto it = std::lower_bound(extended.begin(), extended.end(), std::pair(v, 0u));
           it != extended.end() && it->first == v; ++it)
        ids.push_back(it->second);
      if (ids.empty()) continue;
      std::sort(ids.begin(), ids.end());
      planes.clear();
      for (auto it = ids.begin(); it != ids.end(); it = std::upper_bound(it, ids.end(), *it))
        planes.push_back(&cl.plane[*it]);
      Vec3 moved;
      if (move_onto(mesh.vertices[v], planes, moved))
        out.mesh.vertices[v] = moved;
      else
        kept[v] = 1;
    }
  });
  for (std::size_t v = 0; v < nv; ++v) {
    out.stats.kept_vertices += kept[v];
    if (out.mesh.vertices[v] == mesh.vertices[v]) continue;
    ++out.stats.moved_vertices;
    out.stats.max_move =
        std::max(out.stats.max_move, (out.mesh.vertices[v] - mesh.vertices[v]).norm());
  }
  return out;
}

}  // namespace ncpath
