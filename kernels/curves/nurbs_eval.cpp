// NURBS validation and evaluation: de Boor on homogeneous control points (w x, w y, w) for the
// point and its first two derivatives (the derivative curves' control points are formed
// locally), then the rational quotient rule.
#include <algorithm>
#include <cassert>
#include <cmath>
#include <string>

#include "kernels/curves/nurbs.hpp"
#include "kernels/curves/nurbs_detail.hpp"
#include "kernels/geom/tolerance.hpp"

namespace ncpath {

using nurbs_detail::SmallBuf;
using H = Eigen::Vector3d;  // homogeneous point (w x, w y, w)

std::string validate(const Nurbs2& c) {
  const int p = c.degree;
  const std::size_t n = c.ctrl.size();
  if (p < 1) return "NURBS degree must be >= 1 (got " + std::to_string(p) + ")";
  if (n < static_cast<std::size_t>(p) + 1)
    return "NURBS of degree " + std::to_string(p) + " needs at least " + std::to_string(p + 1) +
           " control points (got " + std::to_string(n) + ")";
  if (c.knots.size() != n + p + 1)
    return "NURBS knot count must be control points + degree + 1 = " + std::to_string(n + p + 1) +
           " (got " + std::to_string(c.knots.size()) + ")";
  if (c.weights.size() != n)
    return "NURBS weight count must equal the control point count " + std::to_string(n) + " (got " +
           std::to_string(c.weights.size()) + ")";
  for (std::size_t i = 0; i < n; ++i) {
    if (!c.ctrl[i].allFinite())
      return "NURBS control point " + std::to_string(i) + " is not finite";
    if (!std::isfinite(c.weights[i])) return "NURBS weight " + std::to_string(i) + " is not finite";
    if (!(c.weights[i] > 0)) return "NURBS weight " + std::to_string(i) + " is not > 0";
  }
  const std::size_t m = c.knots.size();
  for (std::size_t i = 0; i < m; ++i) {
    if (!std::isfinite(c.knots[i])) return "NURBS knot " + std::to_string(i) + " is not finite";
    if (i > 0 && c.knots[i] < c.knots[i - 1])
      return "NURBS knots decrease at index " + std::to_string(i);
  }
  for (int i = 1; i <= p; ++i) {
    if (c.knots[i] != c.knots[0])
      return "NURBS knot vector is not clamped: the first degree + 1 knots must be equal";
    if (c.knots[m - 1 - i] != c.knots[m - 1])
      return "NURBS knot vector is not clamped: the last degree + 1 knots must be equal";
  }
  if (!(c.knots[m - 1] > c.knots[0])) return "NURBS knot range is empty (first knot == last)";
  // An interior knot of multiplicity > degree would make the curve discontinuous.
  for (std::size_t i = p + 1; i + p + 1 < m;) {
    std::size_t j = i;
    while (j + 1 < m && c.knots[j + 1] == c.knots[i]) ++j;
    if (c.knots[i] < c.knots[m - 1] && static_cast<int>(j - i + 1) > p)
      return "NURBS interior knot " + std::to_string(c.knots[i]) + " has multiplicity " +
             std::to_string(j - i + 1) + " > degree (the curve would be discontinuous)";
    i = j + 1;
  }
  return "";
}

std::vector<double> clamped_uniform_knots(std::size_t n, int p) {
  std::vector<double> knots;
  const int m = static_cast<int>(n);
  for (int i = 0; i < m + p + 1; ++i)
    knots.push_back(i <= p ? 0.0 : (i >= m ? 1.0 : static_cast<double>(i - p) / (m - p)));
  return knots;
}

double nurbs_t0(const Nurbs2& c) { return c.knots.front(); }
double nurbs_t1(const Nurbs2& c) { return c.knots.back(); }

namespace nurbs_detail {

int find_span(const Nurbs2& c, double t) {
  const int n = static_cast<int>(c.ctrl.size());
  const int p = c.degree;
  const auto& U = c.knots;
  if (std::isnan(t)) return p;
  if (t >= U[n]) return n - 1;  // last non-empty span (clamped: U[n] == t1, U[n-1] < t1)
  if (t <= U[p]) {
    int k = p;
    while (U[k + 1] <= U[p]) ++k;  // skip empty spans (cannot happen when clamped)
    return k;
  }
  // Largest k with U[k] <= t.
  const auto it = std::upper_bound(U.begin() + p, U.begin() + n + 1, t);
  return static_cast<int>(it - U.begin()) - 1;
}

std::vector<double> breakpoints(const Nurbs2& c) {
  std::vector<double> b;
  for (double u : c.knots)
    if (b.empty() || u > b.back()) b.push_back(u);
  return b;
}

double curve_size(const Nurbs2& c) {
  Vec2 lo = c.ctrl.front(), hi = c.ctrl.front();
  for (const Vec2& q : c.ctrl) {
    lo = lo.cwiseMin(q);
    hi = hi.cwiseMax(q);
  }
  return std::max((hi - lo).norm(), 1e-300);
}

bool is_closed(const Nurbs2& c) {
  return (c.ctrl.front() - c.ctrl.back()).norm() <= tol::kNurbsZeroLength * curve_size(c);
}

}  // namespace nurbs_detail

namespace {

// de Boor for a degree-q piece on span k: d[0..q] are the local control points, knots U.
// Knot indices do not depend on which derivative curve is evaluated (see nurbs_derivatives).
H de_boor(SmallBuf<H, 16>& d, int q, int k, const std::vector<double>& U, double t) {
  for (int r = 1; r <= q; ++r)
    for (int j = q; j >= r; --j) {
      const double lo = U[j + k - q], hi = U[j + 1 + k - r];
      const double a = (t - lo) / (hi - lo);
      d[j] = (1 - a) * d[j - 1] + a * d[j];
    }
  return d[q];
}

H homog(const Nurbs2& c, int i) {
  const double w = c.weights[i];
  return H(w * c.ctrl[i].x(), w * c.ctrl[i].y(), w);
}

// Homogeneous point and derivatives (order <= 2) at t.
void homog_derivs(const Nurbs2& c, double t, int order, H out[3]) {
  const int p = c.degree;
  const auto& U = c.knots;
  const int k = nurbs_detail::find_span(c, t);
  t = std::clamp(t, U.front(), U.back());
  SmallBuf<H, 16> q(p + 1), d(p + 1);
  for (int j = 0; j <= p; ++j) q[j] = homog(c, k - p + j);
  for (int j = 0; j <= p; ++j) d[j] = q[j];
  out[0] = de_boor(d, p, k, U, t);
  out[1] = out[2] = H::Zero();
  if (order < 1) return;
  // First derivative curve: degree p - 1, points p (Q[j+1] - Q[j]) / (U[k+j+1] - U[k-p+j+1]).
  SmallBuf<H, 16> d1(p + 1);
  for (int j = 0; j < p; ++j) d1[j] = p * (q[j + 1] - q[j]) / (U[k + j + 1] - U[k - p + j + 1]);
  for (int j = 0; j < p; ++j) d[j] = d1[j];
  out[1] = de_boor(d, p - 1, k, U, t);
  if (order < 2 || p < 2) return;
  // Second derivative curve: degree p - 2.
  for (int j = 0; j + 1 < p; ++j)
    d[j] = (p - 1) * (d1[j + 1] - d1[j]) / (U[k + j + 1] - U[k - p + j + 2]);
  out[2] = de_boor(d, p - 2, k, U, t);
}

}  // namespace

Vec2 nurbs_point(const Nurbs2& c, double t) {
  assert(validate(c).empty());
  // Clamped curves interpolate their end control points: return them exactly so that chains
  // built from curve ends meet bitwise.
  if (t <= c.knots.front()) return c.ctrl.front();
  if (t >= c.knots.back()) return c.ctrl.back();
  H h[3];
  homog_derivs(c, t, 0, h);
  return Vec2(h[0].x(), h[0].y()) / h[0].z();
}

void nurbs_derivatives(const Nurbs2& c, double t, Vec2& d0, Vec2& d1, Vec2& d2) {
  assert(validate(c).empty());
  H h[3];
  homog_derivs(c, t, 2, h);
  const double w = h[0].z(), w1 = h[1].z(), w2 = h[2].z();
  const Vec2 a0(h[0].x(), h[0].y()), a1(h[1].x(), h[1].y()), a2(h[2].x(), h[2].y());
  d0 = a0 / w;
  if (t <= c.knots.front()) d0 = c.ctrl.front();
  if (t >= c.knots.back()) d0 = c.ctrl.back();
  // Quotient rule for C = A / w.
  d1 = (a1 - w1 * d0) / w;
  d2 = (a2 - 2 * w1 * d1 - w2 * d0) / w;
}

double nurbs_curvature(const Nurbs2& c, double t) {
  Vec2 d0, d1, d2;
  nurbs_derivatives(c, t, d0, d1, d2);
  const double s = d1.norm();
  if (s == 0) return 0;  // undefined at a cusp; 0 keeps callers finite
  return (d1.x() * d2.y() - d1.y() * d2.x()) / (s * s * s);
}

namespace nurbs_detail {

Vec2 unit_tangent(const Nurbs2& c, double t, int side) {
  Vec2 d0, d1, d2;
  nurbs_derivatives(c, t, d0, d1, d2);
  const double range = c.knots.back() - c.knots.front();
  const double size = curve_size(c);
  if (d1.norm() > tol::kNurbsZeroSpeed * size / range) return d1.normalized();
  // Zero speed: the direction of travel is that of a short chord on the requested side.
  if (t >= c.knots.back()) side = -1;
  if (t <= c.knots.front()) side = +1;
  for (double h = 1e-6 * range; h < range; h *= 8) {
    const double u = std::clamp(t + side * h, c.knots.front(), c.knots.back());
    const Vec2 ch = side * (nurbs_point(c, u) - d0);
    if (ch.norm() > tol::kNurbsZeroLength * size) return ch.normalized();
  }
  return Vec2(1, 0);  // the curve is a point
}

}  // namespace nurbs_detail
}  // namespace ncpath
