#pragma once
// Independent answers for drop-cutter tests. Nothing here calls the kernels under test: the
// cutter's lower surface height h(rho) and plain geometry only.
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace ncpath::test {

using V3 = Eigen::Vector3d;

// Lower-surface height above the tip at horizontal distance rho, written out again here
// (R = radius, r = corner radius) so tests do not trust cutter.cpp. NaN beyond R.
inline double h_profile(double R, double r, double rho) {
  if (rho > R) return std::numeric_limits<double>::quiet_NaN();
  const double a = R - r;
  if (rho <= a) return 0.0;
  const double t = rho - a;
  return r - std::sqrt(std::max(0.0, r * r - t * t));
}

// Tip height at which the tool touches point p, or -inf when p is outside the tool's disc.
inline double tip_for_point(double R, double r, const V3& p, double x, double y) {
  // Points on the rim (rho == R up to rounding) still touch.
  const double rho = std::hypot(p.x() - x, p.y() - y);
  if (rho > R * (1 + 1e-12)) return -std::numeric_limits<double>::infinity();
  return p.z() - h_profile(R, r, std::min(rho, R));
}

// Maximises a concave function on [lo, hi] by golden-section search.
inline double golden_max(const std::function<double(double)>& f, double lo, double hi) {
  const double g = (std::sqrt(5.0) - 1) / 2;
  double a = lo, b = hi;
  double c = b - g * (b - a), d = a + g * (b - a);
  double fc = f(c), fd = f(d);
  for (int i = 0; i < 200 && b - a > 1e-13 * (1 + std::abs(a)); ++i) {
    if (fc < fd) {
      a = c;
      c = d;
      fc = fd;
      d = a + g * (b - a);
      fd = f(d);
    } else {
      b = d;
      d = c;
      fd = fc;
      c = b - g * (b - a);
      fc = f(c);
    }
  }
  return std::max({f(lo), f(hi), fc, fd});
}

// Highest tip over the points of segment pq inside the tool's disc (concave in the
// segment parameter, so golden section finds it), or -inf.
inline double tip_for_segment(double R, double r, const V3& p, const V3& q, double x, double y) {
  // Clip the segment's xy projection to the disc |xy - (x, y)| <= R.
  const double dx = q.x() - p.x(), dy = q.y() - p.y();
  const double fx = p.x() - x, fy = p.y() - y;
  const double A = dx * dx + dy * dy, B = 2 * (fx * dx + fy * dy), C = fx * fx + fy * fy - R * R;
  double lo = 0, hi = 1;
  if (A == 0) {
    if (C > 0) return -std::numeric_limits<double>::infinity();
  } else {
    const double disc = B * B - 4 * A * C;
    if (disc < 0) return -std::numeric_limits<double>::infinity();
    const double s = std::sqrt(disc);
    lo = std::max(0.0, (-B - s) / (2 * A));
    hi = std::min(1.0, (-B + s) / (2 * A));
    if (lo > hi) return -std::numeric_limits<double>::infinity();
  }
  auto f = [&](double t) {
    const V3 pt = p + t * (q - p);
    const double rho = std::min(R, std::hypot(pt.x() - x, pt.y() - y));
    return pt.z() - h_profile(R, r, rho);
  };
  return golden_max(f, lo, hi);
}

// Lower bound on the true drop height against triangle abc: vertices, edges (golden
// section) and an n x n barycentric grid of interior points. The exact answer is >= this.
inline double tip_lower_bound(double R, double r, const V3& a, const V3& b, const V3& c, double x,
                              double y, int n = 40) {
  double best = -std::numeric_limits<double>::infinity();
  best = std::max(best, tip_for_segment(R, r, a, b, x, y));
  best = std::max(best, tip_for_segment(R, r, b, c, x, y));
  best = std::max(best, tip_for_segment(R, r, c, a, x, y));
  for (int i = 0; i <= n; ++i)
    for (int j = 0; i + j <= n; ++j) {
      const double u = double(i) / n, v = double(j) / n;
      best = std::max(best, tip_for_point(R, r, a + u * (b - a) + v * (c - a), x, y));
    }
  return best;
}

// Distance from p to the segment ab (3D).
inline double point_segment_distance(const V3& a, const V3& b, const V3& p) {
  const V3 ab = b - a;
  const double l2 = ab.squaredNorm();
  const double t = l2 > 0 ? std::clamp((p - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

// Exact distance from point p to triangle abc (closest point by region tests).
inline double point_triangle_distance(const V3& p, const V3& a, const V3& b, const V3& c) {
  const V3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return (p - a).norm();
  const V3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return (p - b).norm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + d1 / (d1 - d3) * ab)).norm();
  const V3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return (p - c).norm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + d2 / (d2 - d6) * ac)).norm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return (p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).norm();
  const double denom = 1 / (va + vb + vc);
  return (p - (a + ab * (vb * denom) + ac * (vc * denom))).norm();
}

}  // namespace ncpath::test
