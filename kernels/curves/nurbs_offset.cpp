// Tiller-Hanson offsets: the control polygon's legs are offset along their right normals and
// consecutive offset legs intersected; the result, with the original weights and knots, is
// compared with the true offset C(t) + d N_right(t), and spans that deviate are refined by
// Boehm knot insertion at their midpoints.
#include <algorithm>
#include <cmath>
#include <vector>

#include "kernels/curves/nurbs.hpp"
#include "kernels/curves/nurbs_detail.hpp"
#include "kernels/geom/tolerance.hpp"

namespace ncpath {
namespace {

using nurbs_detail::curve_size;

constexpr int kMaxRounds = 24;  // refinement rounds; each halves every failing span
// Deviation probes per span, as fractions of the span (ends included, and close to them).
constexpr double kProbes[] = {0.0, 0.02, 0.125, 0.25, 0.375, 0.5, 0.625, 0.75, 0.875, 0.98};

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }
Vec2 right_normal(const Vec2& u) { return Vec2(u.y(), -u.x()); }

// The Tiller-Hanson control polygon of c offset by d (same degree, knots and weights).
Nurbs2 control_offset(const Nurbs2& c, double d) {
  const int n = static_cast<int>(c.ctrl.size());
  const double zero = tol::kNurbsZeroLength * curve_size(c);
  std::vector<Vec2> u(n - 1);
  std::vector<char> ok(n - 1);
  for (int i = 0; i + 1 < n; ++i) {
    const Vec2 e = c.ctrl[i + 1] - c.ctrl[i];
    ok[i] = e.norm() > zero;
    u[i] = ok[i] ? Vec2(e.normalized()) : Vec2(1, 0);
  }
  // Legs of zero length (repeated control points) borrow the nearest real leg's direction.
  int last = -1;
  for (int i = 0; i + 1 < n; ++i)
    if (ok[i]) {
      for (int j = last + 1; j < i; ++j) u[j] = u[i];
      last = i;
    }
  for (int j = last + 1; last >= 0 && j + 1 < n; ++j) u[j] = u[last];
  Nurbs2 o = c;
  if (last < 0) return o;  // the curve is a point
  o.ctrl[0] = c.ctrl[0] + d * right_normal(u[0]);
  o.ctrl[n - 1] = c.ctrl[n - 1] + d * right_normal(u[n - 2]);
  for (int i = 1; i + 1 < n; ++i) {
    const Vec2 na = right_normal(u[i - 1]), nb = right_normal(u[i]);
    const Vec2 A = c.ctrl[i] + d * na, B = c.ctrl[i] + d * nb;
    const double x = cross(u[i - 1], u[i]);
    if (std::abs(x) < tol::kOffsetParallelLegs) {
      // Parallel legs: the offset vertex itself (the normals' mean is 0 for a reversal).
      o.ctrl[i] = c.ctrl[i] + 0.5 * d * (na + nb);
    } else {
      o.ctrl[i] = A + (cross(B - A, u[i]) / x) * u[i - 1];
    }
  }
  return o;
}

// The true offset point of `c` at t.
Vec2 true_offset(const Nurbs2& c, double t, double d) {
  return nurbs_point(c, t) + d * right_normal(nurbs_detail::unit_tangent(c, t, +1));
}

}  // namespace

NurbsOffset nurbs_offset(const Nurbs2& curve, double d, double tol) {
  NurbsOffset r;
  r.error = validate(curve);
  if (!r.error.empty()) return r;
  if (!std::isfinite(d) || !std::isfinite(tol)) {
    r.error = "offset distance and tolerance must be finite";
    return r;
  }
  if (d == 0) {
    r.pieces.push_back(curve);
    return r;
  }
  tol = std::max(tol, tol::kNurbsMinTol);
  Nurbs2 c = curve;  // refined copy of the original; the offset shares its knots
  Nurbs2 o;
  std::vector<double> bad;
  for (int round = 0;; ++round) {
    o = control_offset(c, d);
    bad.clear();
    r.max_deviation = 0;
    const auto& U = c.knots;
    for (std::size_t k = c.degree; k + 1 < U.size() - c.degree; ++k) {
      const double a = U[k], b = U[k + 1];
      if (!(b > a)) continue;
      double worst = 0;
      for (double f : kProbes) {
        const double t = a + f * (b - a);
        worst = std::max(worst, (nurbs_point(o, t) - true_offset(curve, t, d)).norm());
      }
      if (k + 2 == U.size() - c.degree)
        worst = std::max(worst, (nurbs_point(o, b) - true_offset(curve, b, d)).norm());
      r.max_deviation = std::max(r.max_deviation, worst);
      if (worst > tol) bad.push_back(0.5 * (a + b));
    }
    if (bad.empty() || round == kMaxRounds) break;
    const int before = r.knots_inserted;
    for (double t : bad) {
      // A span too short to halve in double precision cannot be refined further.
      if (nurbs_detail::snap_knot(c, t) > 0) continue;
      nurbs_detail::insert_knot_once(c, t);
      ++r.knots_inserted;
    }
    if (r.knots_inserted == before) break;
  }
  r.pieces = nurbs_detail::trim_offset_loops(curve, o, d, tol);
  return r;
}

}  // namespace ncpath
