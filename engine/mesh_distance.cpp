#include "engine/mesh_distance.hpp"

#include <embree3/rtcore.h>

#include <Eigen/Geometry>  // cross

#include <algorithm>
#include <cassert>
#include <vector>

#include "engine/embree_user_scene.hpp"
#include "engine/parallel.hpp"
#include "kernels/geom/tolerance.hpp"
#include "kernels/mesh/closest_point.hpp"

namespace ncpath {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Float query radius that Embree may compare with its float box distances without culling
// any facet whose exact distance is <= d: covers the rounding of the query point to float
// (|p| is its largest coordinate magnitude) and of Embree's distance arithmetic.
float query_radius(double d, double p_mag) {
  if (!(d < kInf)) return std::numeric_limits<float>::infinity();
  return pad_up(d + tol::kFloatBoxPad * (1.0 + p_mag));
}

// Embree point query at p (rounded to float) with a float radius from query_radius.
RTCPointQuery point_query(const Vec3& p, float radius) {
  RTCPointQuery pq;
  pq.x = static_cast<float>(p.x());
  pq.y = static_cast<float>(p.y());
  pq.z = static_cast<float>(p.z());
  pq.time = 0;
  pq.radius = radius;
  return pq;
}

struct Tri {
  Vec3 p[3];  // mm
};

// 3 x 21 bits of the centroid's cell in the box, interleaved.
std::uint64_t morton_key(const Aabb3& box, const Tri& t) {
  const Vec3 g = (t.p[0] + t.p[1] + t.p[2]) / 3;
  std::uint64_t key = 0;
  for (int k = 0; k < 3; ++k) {
    const double ext = box.hi[k] - box.lo[k];
    const double u = ext > 0 ? (g[k] - box.lo[k]) / ext : 0;
    auto cell = static_cast<std::uint64_t>(std::clamp(u, 0.0, 1.0) * ((1 << 21) - 1));
    for (int b = 0; b < 21; ++b) key |= ((cell >> b) & 1u) << (3 * b + k);
  }
  return key;
}

// Reorders the facets along a Morton curve: the facets Embree visits for one query are
// then close in memory (mesh files often list facets in no spatial order, and the
// callbacks' cache misses dominate the query time). Results do not depend on the order:
// ties are broken by the source index.
void sort_along_morton_curve(const Aabb3& box, std::vector<Tri>& tris,
                             std::vector<std::uint32_t>& source) {
  const std::size_t n = tris.size();
  std::vector<std::pair<std::uint64_t, std::uint32_t>> order(n);  // (key, current slot)
  par::for_each(n, 4096, [&](std::size_t i) {
    order[i] = {morton_key(box, tris[i]), static_cast<std::uint32_t>(i)};
  });
  par::sort(order.begin(), order.end(), [](const auto& a, const auto& b) { return a < b; });
  std::vector<Tri> t2(n);
  std::vector<std::uint32_t> s2(n);
  par::for_each(n, 4096, [&](std::size_t i) {
    t2[i] = tris[order[i].second];
    s2[i] = source[order[i].second];
  });
  tris = std::move(t2);
  source = std::move(s2);
}

}  // namespace

struct MeshDistance::Impl {
  std::vector<Tri> tris;
  std::vector<std::uint32_t> source;  // tris[i] came from mesh.facets[source[i]]
  std::uint64_t skipped = 0;
  Aabb3 box;             // of the kept facets, mm
  double mean_edge = 0;  // mm, sets march()'s window
  // Last, so it is released before the facets its callbacks read.
  EmbreeUserScene embree;

  static void bounds(const RTCBoundsFunctionArguments* args) {
    const auto* self = static_cast<const Impl*>(args->geometryUserPtr);
    const Tri& f = self->tris[args->primID];
    const Vec3 lo = f.p[0].cwiseMin(f.p[1]).cwiseMin(f.p[2]);
    const Vec3 hi = f.p[0].cwiseMax(f.p[1]).cwiseMax(f.p[2]);
    RTCBounds* b = args->bounds_o;
    b->lower_x = pad_down(lo.x());
    b->lower_y = pad_down(lo.y());
    b->lower_z = pad_down(lo.z());
    b->upper_x = pad_up(hi.x());
    b->upper_y = pad_up(hi.y());
    b->upper_z = pad_up(hi.z());
  }

  // Embree wants intersect/occluded callbacks for a user geometry; only point queries run.
  static void intersect(const RTCIntersectFunctionNArguments*) {}
  static void occluded(const RTCOccludedFunctionNArguments*) {}

  // Per-query state handed to the point-query callbacks through userPtr.
  struct ClosestQuery {
    const Impl* m;
    Vec3 p;
    double p_mag, max_distance;  // |p|_inf, mm
    Closest best;
  };
  struct SweepQuery {
    const Impl* m;
    Vec3 x, d;        // window start and unit direction
    double r, p_mag;  // ball radius, |x|_inf, mm
    double t_best;    // first contact so far; the window length while hit is false
    bool hit = false;
  };

  // Callbacks may arrive in any order; the kept answer is the lexicographic minimum of
  // (distance, facet index), so the result does not depend on it.
  static bool closest_callback(RTCPointQueryFunctionArguments* args) {
    auto* q = static_cast<ClosestQuery*>(args->userPtr);
    const Tri& f = q->m->tris[args->primID];
    Vec3 point;
    const double d = point_triangle_closest(q->p, f.p[0], f.p[1], f.p[2], point);
    const std::uint32_t facet = q->m->source[args->primID];
    if (!(d <= q->max_distance)) return false;
    if (d > q->best.distance || (d == q->best.distance && facet > q->best.facet)) return false;
    q->best = {d, point, facet};
    // Shrink, never grow, and keep boxes at exactly this distance (ties) in reach.
    const float r = query_radius(d, q->p_mag);
    if (r >= args->query->radius) return false;
    args->query->radius = r;
    return true;
  }

  static bool sweep_callback(RTCPointQueryFunctionArguments* args) {
    auto* q = static_cast<SweepQuery*>(args->userPtr);
    const Tri& f = q->m->tris[args->primID];
    const double t = sweep_ball_triangle(q->x, q->d, q->r, q->t_best, f.p[0], f.p[1], f.p[2]);
    if (!(t <= q->t_best) || (q->hit && t == q->t_best)) return false;
    q->t_best = t;
    q->hit = true;
    // A facet touched by time t lies within r + t of the window start.
    const float radius = query_radius(q->r + t, q->p_mag);
    if (radius >= args->query->radius) return false;
    args->query->radius = radius;
    return true;
  }
};

MeshDistance::MeshDistance(const TriangleMesh& mesh) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  const std::size_t n = mesh.facets.size();
  // Count, scan, fill (STYLE habit 8): which facets are usable, their slots, the copies.
  auto usable = [&](std::size_t i, Tri& t) {
    for (int k = 0; k < 3; ++k) {
      t.p[k] = mesh.vertices[mesh.facets[i][k]];
      if (!t.p[k].allFinite()) return false;
    }
    return (t.p[1] - t.p[0]).cross(t.p[2] - t.p[0]).norm() >= tol::kDegenerateArea2;
  };
  std::vector<std::uint32_t> slot(n + 1, 0);
  par::for_each(n, 4096, [&](std::size_t i) {
    Tri t;
    slot[i + 1] = usable(i, t) ? 1 : 0;
  });
  for (std::size_t i = 0; i < n; ++i) slot[i + 1] += slot[i];
  m.tris.resize(slot[n]);
  m.source.resize(slot[n]);
  m.skipped = n - slot[n];
  par::for_each(n, 4096, [&](std::size_t i) {
    if (slot[i + 1] == slot[i]) return;
    usable(i, m.tris[slot[i]]);
    m.source[slot[i]] = static_cast<std::uint32_t>(i);
  });
  double edge_sum = 0;
  for (const Tri& t : m.tris)
    for (int k = 0; k < 3; ++k) {
      m.box.add(t.p[k]);
      edge_sum += (t.p[(k + 1) % 3] - t.p[k]).norm();
    }
  m.mean_edge = m.tris.empty() ? 0 : edge_sum / (3.0 * m.tris.size());
  sort_along_morton_curve(m.box, m.tris, m.source);

  m.embree = EmbreeUserScene(m.tris.size(), &m, &Impl::bounds, &Impl::intersect, &Impl::occluded);
}

MeshDistance::~MeshDistance() = default;

std::uint64_t MeshDistance::facet_count() const { return impl_->tris.size(); }
std::uint64_t MeshDistance::skipped() const { return impl_->skipped; }

MeshDistance::Closest MeshDistance::closest(const Vec3& p, double max_distance) const {
  const Impl& m = *impl_;
  Impl::ClosestQuery q{&m, p, p.cwiseAbs().maxCoeff(), max_distance, {}};
  if (m.tris.empty() || !(max_distance >= 0)) return q.best;
  RTCPointQuery pq = point_query(p, query_radius(max_distance, q.p_mag));
  RTCPointQueryContext ctx;
  rtcInitPointQueryContext(&ctx);
  rtcPointQuery(m.embree.scene(), &pq, &ctx, &Impl::closest_callback, &q);
  return q.best;
}

std::optional<double> MeshDistance::march(const Vec3& origin, const Vec3& dir, double radius,
                                          double s_max) const {
  const Impl& m = *impl_;
  assert(std::abs(dir.norm() - 1) < 1e-9);
  if (m.tris.empty() || !(s_max >= 0)) return std::nullopt;
  // No contact once the centre has left the box grown by the radius for good: clip s_max
  // to the ray's exit from it (generously padded; the clip only saves steps).
  const double pad = radius + tol::kFloatBoxPad * (1 + radius + m.box.lo.cwiseAbs().maxCoeff() +
                                                   m.box.hi.cwiseAbs().maxCoeff());
  for (int k = 0; k < 3; ++k) {
    const double lo = m.box.lo[k] - pad, hi = m.box.hi[k] + pad;
    if (dir[k] == 0) {
      if (origin[k] < lo || origin[k] > hi) return std::nullopt;
      continue;
    }
    const double t0 = (lo - origin[k]) / dir[k], t1 = (hi - origin[k]) / dir[k];
    s_max = std::min(s_max, std::max(t0, t1));
  }
  if (!(s_max >= 0)) return std::nullopt;

  // Sphere-trace while the free distance is at least a window; within it, solve the first
  // contact exactly over the next two windows. Every round advances by at least a window,
  // so grazing rays (where pure sphere tracing converges ever more slowly) still finish.
  const double window = std::max(0.25 * radius, 2.0 * m.mean_edge);
  double s = 0;
  while (true) {
    const Vec3 x = origin + s * dir;
    const double gap = closest(x).distance - radius;
    if (gap >= window) {
      s += gap;
      if (s > s_max) return std::nullopt;
      continue;
    }
    const double span = std::min(2.0 * window, s_max - s);
    Impl::SweepQuery q{&m, x, dir, radius, x.cwiseAbs().maxCoeff(), span};
    RTCPointQuery pq = point_query(x, query_radius(radius + span, q.p_mag));
    RTCPointQueryContext ctx;
    rtcInitPointQueryContext(&ctx);
    rtcPointQuery(m.embree.scene(), &pq, &ctx, &Impl::sweep_callback, &q);
    if (q.hit) return s + q.t_best;
    if (s + span >= s_max) return std::nullopt;
    s += span;
  }
}

}  // namespace ncpath
