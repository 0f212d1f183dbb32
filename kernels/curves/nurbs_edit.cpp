// NURBS editing that leaves the curve unchanged: Boehm knot insertion, splitting, sub-curves,
// joins and reversal. Rational curves are processed in homogeneous coordinates.
#include <algorithm>
#include <cassert>
#include <cmath>

#include "kernels/curves/nurbs.hpp"
#include "kernels/curves/nurbs_detail.hpp"
#include "kernels/geom/tolerance.hpp"

namespace ncpath {
namespace nurbs_detail {

int snap_knot(const Nurbs2& c, double& t) {
  const auto& U = c.knots;
  const double eps = tol::kKnotSnap * (U.back() - U.front());
  auto it = std::lower_bound(U.begin(), U.end(), t);
  // Nearest knot is *it or the one before.
  double best = std::numeric_limits<double>::infinity();
  if (it != U.end() && *it - t <= eps) best = *it;
  if (it != U.begin() && t - *(it - 1) <= eps && t - *(it - 1) < best - t) best = *(it - 1);
  if (std::isfinite(best)) t = best;
  const auto [lo, hi] = std::equal_range(U.begin(), U.end(), t);
  return static_cast<int>(hi - lo);
}

void insert_knot_once(Nurbs2& c, double t) {
  const int p = c.degree;
  const auto& U = c.knots;
  const int k = find_span(c, t);
  int s = 0;
  while (s <= k && U[k - s] == t) ++s;
  assert(s < p && t > U.front() && t < U.back());
  // New homogeneous points Q_i = a P_i + (1 - a) P_{i-1}, i = k-p+1 .. k-s.
  SmallBuf<Eigen::Vector3d, 16> q(p + 1);
  auto homog = [&](int i) {
    const double w = c.weights[i];
    return Eigen::Vector3d(w * c.ctrl[i].x(), w * c.ctrl[i].y(), w);
  };
  for (int i = k - p + 1; i <= k - s; ++i) {
    const double a = (t - U[i]) / (U[i + p] - U[i]);
    q[i - (k - p + 1)] = a * homog(i) + (1 - a) * homog(i - 1);
  }
  c.ctrl.insert(c.ctrl.begin() + (k - s), c.ctrl[k - s]);
  c.weights.insert(c.weights.begin() + (k - s), c.weights[k - s]);
  for (int i = k - p + 1; i <= k - s; ++i) {
    const Eigen::Vector3d& h = q[i - (k - p + 1)];
    c.ctrl[i] = Vec2(h.x(), h.y()) / h.z();
    c.weights[i] = h.z();
  }
  c.knots.insert(c.knots.begin() + k + 1, t);
}

}  // namespace nurbs_detail

Nurbs2 nurbs_reversed(const Nurbs2& c) {
  Nurbs2 r;
  r.degree = c.degree;
  r.ctrl.assign(c.ctrl.rbegin(), c.ctrl.rend());
  r.weights.assign(c.weights.rbegin(), c.weights.rend());
  const double t0 = c.knots.front(), t1 = c.knots.back();
  const std::size_t m = c.knots.size();
  r.knots.resize(m);
  for (std::size_t i = 0; i < m; ++i) r.knots[i] = (t0 + t1) - c.knots[m - 1 - i];
  // t0 + t1 - t1 need not round to t0: keep the end knots exact (and the vector clamped).
  for (int i = 0; i <= c.degree; ++i) {
    r.knots[i] = t0;
    r.knots[m - 1 - i] = t1;
  }
  for (std::size_t i = 1; i < m; ++i) r.knots[i] = std::max(r.knots[i], r.knots[i - 1]);
  return r;
}

Nurbs2 nurbs_insert_knot(const Nurbs2& c, double t, int times) {
  Nurbs2 out = c;
  int s = nurbs_detail::snap_knot(out, t);
  if (!(t > nurbs_t0(c) && t < nurbs_t1(c))) return out;  // ends are already full
  // Beyond multiplicity p the curve would not change but lose continuity information.
  for (; times > 0 && s < c.degree; --times, ++s) nurbs_detail::insert_knot_once(out, t);
  return out;
}

void nurbs_split(const Nurbs2& c, double t, Nurbs2& left, Nurbs2& right) {
  const int p = c.degree;
  nurbs_detail::snap_knot(c, t);
  assert(t > nurbs_t0(c) && t < nurbs_t1(c));
  const Nurbs2 w = nurbs_insert_knot(c, t, p);
  const auto& U = w.knots;
  const int a = static_cast<int>(std::lower_bound(U.begin(), U.end(), t) - U.begin());
  // Knots U[a .. a+p-1] == t; control point a-1 is the curve point at t.
  left.degree = right.degree = p;
  left.ctrl.assign(w.ctrl.begin(), w.ctrl.begin() + a);
  left.weights.assign(w.weights.begin(), w.weights.begin() + a);
  left.knots.assign(U.begin(), U.begin() + a + p);
  left.knots.push_back(t);
  right.ctrl.assign(w.ctrl.begin() + (a - 1), w.ctrl.end());
  right.weights.assign(w.weights.begin() + (a - 1), w.weights.end());
  right.knots.assign(p + 1, t);
  right.knots.insert(right.knots.end(), U.begin() + a + p, U.end());
}

}  // namespace ncpath
