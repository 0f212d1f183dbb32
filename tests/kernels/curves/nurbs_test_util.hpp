#pragma once
// Independent oracles for the NURBS tests. Nothing here calls kernels/curves/nurbs_*.cpp:
// evaluation is the textbook Cox-de Boor recursion, distances come from dense sampling plus a
// local golden-section search, segment distances and intersections are written out again.
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "kernels/curves/segment.hpp"
#include "kernels/pocket/profile.hpp"

namespace ncpath::test {

inline double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// Cox-de Boor basis N_{i,p}(t) by the recursive definition (right end closed on the last span).
inline double basis(const std::vector<double>& U, int i, int p, double t) {
  if (p == 0) {
    if (U[i] <= t && t < U[i + 1]) return 1;
    // t == last knot belongs to the last non-empty span.
    if (t == U.back() && U[i] < U[i + 1] && U[i + 1] == U.back()) return 1;
    return 0;
  }
  double v = 0;
  if (U[i + p] > U[i]) v += (t - U[i]) / (U[i + p] - U[i]) * basis(U, i, p - 1, t);
  if (U[i + p + 1] > U[i + 1])
    v += (U[i + p + 1] - t) / (U[i + p + 1] - U[i + 1]) * basis(U, i + 1, p - 1, t);
  return v;
}

inline Vec2 eval(const Nurbs2& c, double t) {
  Vec2 num = Vec2::Zero();
  double den = 0;
  for (std::size_t i = 0; i < c.ctrl.size(); ++i) {
    const double b = basis(c.knots, static_cast<int>(i), c.degree, t) * c.weights[i];
    num += b * c.ctrl[i];
    den += b;
  }
  return num / den;
}

// Unit tangent by central differences of the oracle evaluation (one-sided at the ends).
inline Vec2 tangent(const Nurbs2& c, double t) {
  const double t0 = c.knots.front(), t1 = c.knots.back(), h = 1e-6 * (t1 - t0);
  const double a = std::max(t0, t - h), b = std::min(t1, t + h);
  return (eval(c, b) - eval(c, a)).normalized();
}

// Classic 9-point rational quadratic circle, counter-clockwise from (cx + r, cy).
inline Nurbs2 circle9(const Vec2& c, double r) {
  const double s = std::sqrt(0.5);
  Nurbs2 n;
  n.degree = 2;
  const double xs[] = {1, 1, 0, -1, -1, -1, 0, 1, 1}, ys[] = {0, 1, 1, 1, 0, -1, -1, -1, 0};
  for (int i = 0; i < 9; ++i) {
    n.ctrl.push_back(c + r * Vec2(xs[i], ys[i]));
    n.weights.push_back(i % 2 ? s : 1.0);
  }
  n.knots = {0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1};
  return n;
}

// Clamped uniform B-spline of degree p through the given control points (weights 1 unless
// given), knots 0 .. spans.
inline Nurbs2 clamped(int p, std::vector<Vec2> ctrl, std::vector<double> w = {}) {
  Nurbs2 n;
  n.degree = p;
  n.ctrl = std::move(ctrl);
  n.weights = w.empty() ? std::vector<double>(n.ctrl.size(), 1.0) : std::move(w);
  const int spans = static_cast<int>(n.ctrl.size()) - p;
  n.knots.assign(p + 1, 0.0);
  for (int i = 1; i < spans; ++i) n.knots.push_back(i);
  n.knots.insert(n.knots.end(), p + 1, static_cast<double>(spans));
  return n;
}

// Random cubic with a gently wandering control polygon (x increasing), optionally rational.
inline Nurbs2 random_cubic(unsigned seed, int n_ctrl, bool rational) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(-1, 1), W(0.5, 2.0);
  std::vector<Vec2> ctrl;
  std::vector<double> w;
  for (int i = 0; i < n_ctrl; ++i) {
    ctrl.emplace_back(10.0 * i + 2 * U(rng), 6 * U(rng));
    w.push_back(rational ? W(rng) : 1.0);
  }
  return clamped(3, ctrl, w);
}

inline std::vector<double> params(const Nurbs2& c, int n) {
  std::vector<double> t;
  const double t0 = c.knots.front(), t1 = c.knots.back();
  for (int i = 0; i <= n; ++i) t.push_back(t0 + (t1 - t0) * i / n);
  return t;
}

// Distance from p to the curve: nearest of `n` dense samples, then golden-section search for
// the minimum of |C(t) - p| on the neighbouring sample interval.
struct CurveDistance {
  const Nurbs2& c;
  std::vector<double> t;
  std::vector<Vec2> p;
  explicit CurveDistance(const Nurbs2& curve, int n = 4000) : c(curve), t(params(curve, n)) {
    for (double u : t) p.push_back(eval(c, u));
  }
  double operator()(const Vec2& q) const {
    std::size_t best = 0;
    for (std::size_t i = 1; i < p.size(); ++i)
      if ((p[i] - q).squaredNorm() < (p[best] - q).squaredNorm()) best = i;
    double lo = t[best > 0 ? best - 1 : 0], hi = t[std::min(best + 1, t.size() - 1)];
    const double g = (std::sqrt(5.0) - 1) / 2;
    auto f = [&](double u) { return (eval(c, u) - q).norm(); };
    double a = hi - g * (hi - lo), b = lo + g * (hi - lo), fa = f(a), fb = f(b);
    for (int i = 0; i < 80; ++i) {
      if (fa < fb) {
        hi = b, b = a, fb = fa, a = hi - g * (hi - lo), fa = f(a);
      } else {
        lo = a, a = b, fa = fb, b = lo + g * (hi - lo), fb = f(b);
      }
    }
    return std::min({f(lo), f(hi), (p[best] - q).norm()});
  }
};

inline double seg_point_distance(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double l2 = ab.squaredNorm();
  const double s = l2 > 0 ? std::clamp((p - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
  return (p - a - s * ab).norm();
}

inline double polyline_distance(const std::vector<Vec2>& pl, const Vec2& p) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 1 < pl.size(); ++i)
    best = std::min(best, seg_point_distance(p, pl[i], pl[i + 1]));
  return best;
}

// Proper crossings between non-adjacent chords of one polyline (closed: first and last chords
// are adjacent too). Brute force.
inline int self_crossings(const std::vector<Vec2>& pl, bool closed) {
  const int m = static_cast<int>(pl.size()) - 1;
  int count = 0;
  for (int i = 0; i < m; ++i)
    for (int j = i + 2; j < m; ++j) {
      if (closed && i == 0 && j == m - 1) continue;
      const Vec2 &a = pl[i], &b = pl[i + 1], &c = pl[j], &d = pl[j + 1];
      const double d1 = cross2(b - a, c - a), d2 = cross2(b - a, d - a);
      const double d3 = cross2(d - c, a - c), d4 = cross2(d - c, b - c);
      if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0)))
        ++count;
    }
  return count;
}

// Point at fraction f of a line or arc, with the sweep worked out here (not segment.cpp).
inline double seg_sweep(const Seg2& s) {
  if (s.kind == SegKind::kLine) return 0;
  double a = std::atan2(cross2(s.a - s.c, s.b - s.c), (s.a - s.c).dot(s.b - s.c));
  if (s.kind == SegKind::kArcCcw && a <= 0) a += 2 * std::numbers::pi;
  if (s.kind == SegKind::kArcCw && a >= 0) a -= 2 * std::numbers::pi;
  return a;
}
inline Vec2 seg_at(const Seg2& s, double f) {
  if (s.kind == SegKind::kLine) return s.a + f * (s.b - s.a);
  const double a = std::atan2(s.a.y() - s.c.y(), s.a.x() - s.c.x()) + f * seg_sweep(s);
  return s.c + s.r * Vec2(std::cos(a), std::sin(a));
}
// Distance from p to a line or arc: radial distance where p's direction from the centre is
// inside the arc's sweep, else the nearer end point.
inline double seg_distance(const Seg2& s, const Vec2& p) {
  if (s.kind == SegKind::kLine) return seg_point_distance(p, s.a, s.b);
  const double sw = seg_sweep(s);
  double a = std::atan2(cross2(s.a - s.c, p - s.c), (s.a - s.c).dot(p - s.c));
  if (sw > 0 && a < 0) a += 2 * std::numbers::pi;
  if (sw < 0 && a > 0) a -= 2 * std::numbers::pi;
  if (std::abs(a) <= std::abs(sw)) return std::abs((p - s.c).norm() - s.r);
  return std::min((p - s.a).norm(), (p - s.b).norm());
}
inline double chain_distance(const std::vector<Seg2>& segs, const Vec2& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const Seg2& s : segs) best = std::min(best, seg_distance(s, p));
  return best;
}

// Dense polyline of a segment chain (n points per segment).
inline std::vector<Vec2> chain_polyline(const std::vector<Seg2>& segs, int n) {
  std::vector<Vec2> pl;
  for (const Seg2& s : segs)
    for (int i = pl.empty() ? 0 : 1; i <= n; ++i) pl.push_back(seg_at(s, double(i) / n));
  return pl;
}

}  // namespace ncpath::test
