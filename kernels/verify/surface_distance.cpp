#include "kernels/verify/surface_distance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>

#include "kernels/geom/tolerance.hpp"

namespace ncpath {

namespace {

double box_extent(const BezierPatch& p) { return (p.hi - p.lo).maxCoeff(); }

// Distance from the segment [a, b] to a box (a lower bound of the distance to its patch).
double segment_box_gap(const Vec3& a, const Vec3& b, const Vec3& lo, const Vec3& hi) {
  // The segment's box against the patch's box: a cheap lower bound.
  const Vec3 slo = a.cwiseMin(b), shi = a.cwiseMax(b);
  const Vec3 gap = (lo - shi).cwiseMax(slo - hi).cwiseMax(Vec3::Zero());
  return gap.norm();
}

struct Newton3 {
  const NurbsSurface& s;
  const BezierPatch& p;
  Vec3 a, d;
  double f(const Eigen::Vector3d& x, SurfacePoint& sp) const {
    sp = evaluate(s, x[0], x[1]);
    return 0.5 * (sp.p - (a + x[2] * d)).squaredNorm();
  }
  Eigen::Vector3d clamp(Eigen::Vector3d x) const {
    x[0] = std::clamp(x[0], p.u0, p.u1);
    x[1] = std::clamp(x[1], p.v0, p.v1);
    x[2] = std::clamp(x[2], 0.0, 1.0);
    return x;
  }
};

}  // namespace

SurfaceProbe::SurfaceProbe(const NurbsSurface& surface, double piece) : surface_(surface) {
  std::vector<BezierPatch> stack = bezier_patches(surface);
  while (!stack.empty()) {
    BezierPatch p = std::move(stack.back());
    stack.pop_back();
    if (box_extent(p) <= piece) {
      pieces_.push_back(std::move(p));
      continue;
    }
    BezierPatch l, r;
    split_patch(p, l, r);
    stack.push_back(std::move(l));
    stack.push_back(std::move(r));
  }
  // The plan grid: cells of about two pieces.
  std::vector<std::pair<Vec2, Vec2>> boxes;
  for (const BezierPatch& p : pieces_) boxes.emplace_back(p.lo.head<2>(), p.hi.head<2>());
  grid_ = PlanGrid(boxes, 2 * piece);
}

double SurfaceProbe::piece_distance(const BezierPatch& p, const Vec3& a, const Vec3& b) const {
  // Projected Newton on f(u, v, w) = |S(u, v) - (a + w d)|^2 / 2 over the piece's box and
  // w in [0, 1], with a backtracking line search along the projected path. Variables at a
  // bound whose gradient pushes outwards are held there (active set).
  const Newton3 nt{surface_, p, a, b - a};
  const double dd = nt.d.squaredNorm();
  SurfacePoint sp;
  Eigen::Vector3d x(0.5 * (p.u0 + p.u1), 0.5 * (p.v0 + p.v1), 0);
  sp = evaluate(surface_, x[0], x[1]);
  if (dd > 0) x[2] = std::clamp((sp.p - a).dot(nt.d) / dd, 0.0, 1.0);
  double fx = nt.f(x, sp);
  const double lo[3] = {p.u0, p.v0, 0}, hi[3] = {p.u1, p.v1, 1};
  for (int it = 0; it < 50; ++it) {
    const Vec3 r = sp.p - (a + x[2] * nt.d);
    Eigen::Vector3d g(r.dot(sp.su), r.dot(sp.sv), -r.dot(nt.d));
    Eigen::Matrix3d h;
    h << sp.su.dot(sp.su) + r.dot(sp.suu), sp.su.dot(sp.sv) + r.dot(sp.suv), -sp.su.dot(nt.d), 0,
        sp.sv.dot(sp.sv) + r.dot(sp.svv), -sp.sv.dot(nt.d), 0, 0, dd;
    h(1, 0) = h(0, 1);
    h(2, 0) = h(0, 2);
    h(2, 1) = h(1, 2);
    for (int k = 0; k < 3; ++k) {
      const bool pinned =
          (x[k] <= lo[k] && g[k] > 0) || (x[k] >= hi[k] && g[k] < 0) || (k == 2 && dd == 0);
      if (!pinned) continue;
      g[k] = 0;
      for (int j = 0; j < 3; ++j) h(k, j) = h(j, k) = k == j ? 1.0 : 0.0;
    }
    Eigen::Vector3d step = h.ldlt().solve(-g);
    if (!(g.dot(step) < 0)) step = -g;  // not a descent direction: steepest descent
    bool moved = false;
    for (double t = 1; t > tol::kVerifyNewtonStep; t *= 0.5) {
      const Eigen::Vector3d y = nt.clamp(x + t * step);
      SurfacePoint sq;
      const double fy = nt.f(y, sq);
      if (fy < fx) {
        moved = (y - x).norm() > tol::kVerifyNewtonStep;
        x = y;
        fx = fy;
        sp = sq;
        break;
      }
    }
    if (!moved) break;
  }
  return std::sqrt(2 * fx);
}

double SurfaceProbe::segment_distance(const Vec3& a, const Vec3& b, double cap) const {
  thread_local std::vector<std::uint32_t> items;
  const Vec2 grow = Vec2::Constant(cap);
  grid_.query(a.head<2>().cwiseMin(b.head<2>()) - grow, a.head<2>().cwiseMax(b.head<2>()) + grow,
              items);
  // Nearest boxes first: the first Newton answers bound the rest, which are then skipped.
  thread_local std::vector<std::pair<double, std::uint32_t>> order;
  order.clear();
  for (std::uint32_t k : items) {
    const double g = segment_box_gap(a, b, pieces_[k].lo, pieces_[k].hi);
    if (g < cap) order.emplace_back(g, k);
  }
  std::sort(order.begin(), order.end());
  double best = cap;
  for (const auto& [g, k] : order) {
    if (g >= best) break;
    best = std::min(best, piece_distance(pieces_[k], a, b));
  }
  return best;
}

bool SurfaceProbe::height_at(const Vec2& xy, double& z) const {
  thread_local std::vector<std::uint32_t> items;
  grid_.query(xy, xy, items);
  for (std::uint32_t k : items) {
    const BezierPatch& p = pieces_[k];
    if (xy.x() < p.lo.x() || xy.x() > p.hi.x() || xy.y() < p.lo.y() || xy.y() > p.hi.y()) continue;
    double u = 0.5 * (p.u0 + p.u1), v = 0.5 * (p.v0 + p.v1);
    for (int it = 0; it < 40; ++it) {
      const SurfacePoint sp = evaluate(surface_, u, v);
      const Vec2 r = xy - sp.p.head<2>();
      if (r.norm() < tol::kVerifyPlanResidual) {
        z = sp.p.z();
        return true;
      }
      Eigen::Matrix2d j;
      j << sp.su.x(), sp.sv.x(), sp.su.y(), sp.sv.y();
      const Eigen::Vector2d step = j.colPivHouseholderQr().solve(Eigen::Vector2d(r.x(), r.y()));
      const double nu = std::clamp(u + step[0], p.u0, p.u1),
                   nv = std::clamp(v + step[1], p.v0, p.v1);
      if (nu == u && nv == v) break;  // pinned at the piece's border: not over this piece
      u = nu;
      v = nv;
    }
  }
  return false;
}

}  // namespace ncpath
