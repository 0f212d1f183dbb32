#include "engine/verify_surface.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/parallel.hpp"
#include "kernels/curves/nurbs.hpp"
#include "kernels/geom/tolerance.hpp"
#include "kernels/verify/plan_grid.hpp"

namespace ncpath {

namespace {

// Closed polylines of every boundary and island (even-odd: inside the pocket).
std::vector<std::vector<Vec2>> region_polylines(const std::vector<Region>& regions, double chord) {
  std::vector<std::vector<Vec2>> out;
  for (const Region& r : regions) {
    std::vector<const Profile*> profiles{&r.boundary};
    for (const Profile& i : r.islands) profiles.push_back(&i);
    for (const Profile* p : profiles) {
      std::vector<Vec2> pts;
      for (const ProfileCurve& c : p->curves) {
        if (c.nurbs < 0) {
          append_polyline(c.seg, chord, pts);
          continue;
        }
        std::vector<Vec2> np = nurbs_polyline(p->nurbs[static_cast<std::size_t>(c.nurbs)], chord);
        if (!np.empty() && (np.back() - c.seg.a).norm() < (np.front() - c.seg.a).norm())
          std::reverse(np.begin(), np.end());
        pts.insert(pts.end(), np.begin(), np.end());
      }
      out.push_back(std::move(pts));
    }
  }
  return out;
}

bool inside(const std::vector<std::vector<Vec2>>& loops, const Vec2& q) {
  bool in = false;
  for (const std::vector<Vec2>& l : loops)
    for (std::size_t k = 0, n = l.size(); k < n; ++k) {
      const Vec2& a = l[k];
      const Vec2& b = l[(k + 1) % n];
      if ((a.y() > q.y()) != (b.y() > q.y()) &&
          q.x() < a.x() + (q.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y()))
        in = !in;
    }
  return in;
}

// Lowest point of a ball (radius R, centres c0 -> c1) over plan point q: min over t of
// c(t).z - sqrt(R^2 - rho(t)^2) where the ball lies over q (rho <= R); convex in t there, so
// a golden-section search finds it. +inf when the ball never lies over q.
double lowest_over(const Vec3& c0, const Vec3& c1, const Vec2& q, double R) {
  const Vec2 p0 = c0.head<2>() - q, d = c1.head<2>() - c0.head<2>();
  // rho(t)^2 = |p0 + t d|^2 <= R^2: t in [t0, t1].
  const double A = d.squaredNorm(), B = p0.dot(d), C = p0.squaredNorm() - R * R;
  double t0 = 0, t1 = 1;
  if (A == 0) {
    if (C > 0) return std::numeric_limits<double>::infinity();
  } else {
    const double disc = B * B - A * C;
    if (disc < 0) return std::numeric_limits<double>::infinity();
    const double s = std::sqrt(disc);
    t0 = std::max(0.0, (-B - s) / A);
    t1 = std::min(1.0, (-B + s) / A);
    if (t0 > t1) return std::numeric_limits<double>::infinity();
  }
  const auto g = [&](double t) {
    const Vec2 p = p0 + t * d;
    return c0.z() + t * (c1.z() - c0.z()) - std::sqrt(std::max(0.0, R * R - p.squaredNorm()));
  };
  const double phi = 0.5 * (std::sqrt(5.0) - 1);
  double a = t0, b = t1, x1 = b - phi * (b - a), x2 = a + phi * (b - a);
  double f1 = g(x1), f2 = g(x2);
  for (int it = 0; it < 60 && b - a > tol::kVerifyNewtonStep; ++it) {
    if (f1 <= f2) {
      b = x2;
      x2 = x1;
      f2 = f1;
      x1 = b - phi * (b - a);
      f1 = g(x1);
    } else {
      a = x1;
      x1 = x2;
      f1 = f2;
      x2 = a + phi * (b - a);
      f2 = g(x2);
    }
  }
  return std::min({f1, f2, g(t0), g(t1)});
}

}  // namespace

VerifyReport verify_bottom_moves(const SurfaceProbe& bottom, const ClChunk& cl, double radius,
                                 double top, std::uint64_t first_move, std::uint32_t first_path) {
  const ChunkMoves mv = chunk_moves(cl);
  const std::vector<std::uint32_t>& first = mv.first;
  std::vector<double> gap(first.size(), std::numeric_limits<double>::infinity());
  const Vec3 up(0, 0, radius);
  const double cap = radius + tol::kVerifyReach;
  par::for_each(first.size(), 64, [&](std::size_t m) {
    const Vec3 a = cl.point(first[m]), b = cl.point(first[m] + 1);
    if (std::min(a.z(), b.z()) >= top) return;  // above the stock: nothing to cut
    const double d = bottom.segment_distance(a + up, b + up, cap);
    if (d < cap) gap[m] = d - radius;
  });
  VerifyReport out;
  out.moves = first.size();
  for (std::size_t m = 0; m < gap.size(); ++m) {
    out.min_clearance = std::min(out.min_clearance, gap[m]);
    if (-gap[m] > tol::kVerifyGouge)
      out.add({first_move + m, first_path + mv.path[m], cl.point(first[m]), cl.point(first[m] + 1),
               -gap[m], ViolationKind::kBottom});
  }
  return out;
}

ScallopGrid::ScallopGrid(const std::vector<Region>& regions, const WallSet& walls,
                         const SurfaceProbe& bottom, double radius, double reach, double spacing)
    : radius_(radius), spacing_(spacing) {
  const std::vector<std::vector<Vec2>> loops = region_polylines(regions, 0.01 * reach);
  Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const auto& l : loops)
    for (const Vec2& p : l) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  if (loops.empty()) return;
  const int nx = static_cast<int>((hi.x() - lo.x()) / spacing) + 1;
  const int ny = static_cast<int>((hi.y() - lo.y()) / spacing) + 1;
  std::vector<Vec2> cand;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) cand.emplace_back(lo.x() + i * spacing, lo.y() + j * spacing);
  std::vector<double> z(cand.size(), std::numeric_limits<double>::quiet_NaN());
  par::for_each(cand.size(), 64, [&](std::size_t k) {
    if (!inside(loops, cand[k]) || walls.distance(cand[k], cand[k], tol::kVerifyResolution) < reach)
      return;
    double h;
    if (bottom.height_at(cand[k], h)) z[k] = h;
  });
  for (std::size_t k = 0; k < cand.size(); ++k)
    if (!std::isnan(z[k])) {
      xy_.push_back(cand[k]);
      bottom_.push_back(z[k]);
    }
  lowest_.assign(xy_.size(), std::numeric_limits<double>::infinity());
}

void ScallopGrid::add(const ClChunk& cl, double top) {
  const ChunkMoves mv = chunk_moves(cl);
  const std::vector<std::uint32_t>& first = mv.first;
  // Moves below the top, bucketed by the grid cells their swept ball covers (count, fill).
  std::vector<std::uint32_t> moves;
  for (std::size_t m = 0; m < first.size(); ++m)
    if (std::min(cl.xyz[3 * first[m] + 2], cl.xyz[3 * first[m] + 5]) < top)
      moves.push_back(static_cast<std::uint32_t>(m));
  if (moves.empty() || xy_.empty()) return;
  // The moves on a grid of cells 2R wide, by the plan boxes of their swept balls.
  std::vector<std::pair<Vec2, Vec2>> boxes;
  for (std::uint32_t m : moves) {
    const Vec2 a = cl.point(first[m]).head<2>(), b = cl.point(first[m] + 1).head<2>();
    boxes.emplace_back(a.cwiseMin(b) - Vec2::Constant(radius_),
                       a.cwiseMax(b) + Vec2::Constant(radius_));
  }
  const PlanGrid grid(boxes, 2 * radius_);
  const Vec3 up(0, 0, radius_);
  par::for_ranges(xy_.size(), 256, [&](std::size_t b0, std::size_t e0) {
    std::vector<std::uint32_t> near;
    for (std::size_t k = b0; k < e0; ++k) {
      const Vec2& q = xy_[k];
      grid.query(q, q, near);
      double best = lowest_[k];
      for (std::uint32_t e : near) {
        const std::uint32_t m = moves[e];
        best = std::min(
            best, lowest_over(cl.point(first[m]) + up, cl.point(first[m] + 1) + up, q, radius_));
      }
      lowest_[k] = best;
    }
  });
}

double ScallopGrid::max_scallop(Vec2* where) const {
  double worst = 0;
  for (std::size_t k = 0; k < xy_.size(); ++k) {
    const double s = lowest_[k] - bottom_[k];  // +inf where the ball never passed: uncut
    if (s > worst) {
      worst = s;
      if (where) *where = xy_[k];
    }
  }
  return worst;
}

}  // namespace ncpath
