// Exact rational quadratic ellipse arcs: the image of the classic circle construction under
// the affine map (cos, sin) -> major * cos + minor * sin, which NURBS are invariant under.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "kernels/curves/nurbs.hpp"

namespace ncpath {

Nurbs2 nurbs_ellipse(const Vec2& centre, const Vec2& major_axis, double ratio, double start,
                     double end) {
  Nurbs2 e;
  e.degree = 2;
  e.ctrl.clear();
  // Invalid input gives an empty curve, which validate() rejects.
  if (!(end > start) || !(ratio > 0) || !(major_axis.norm() > 0) || !centre.allFinite() ||
      !std::isfinite(end - start))
    return e;
  const double two_pi = 2 * std::numbers::pi;
  const bool full = end - start >= two_pi * (1 - 1e-15);
  if (end - start > two_pi) end = start + two_pi;
  const Vec2 minor = ratio * Vec2(-major_axis.y(), major_axis.x());
  auto at = [&](double th) -> Vec2 {
    return centre + major_axis * std::cos(th) + minor * std::sin(th);
  };
  // Spans of at most 90 degrees keep the middle weight cos(half span) >= cos 45.
  const int k =
      std::max(1, static_cast<int>(std::ceil((end - start) / (std::numbers::pi / 2) - 1e-12)));
  const double step = (end - start) / k;
  const double w_mid = std::cos(step / 2);
  e.knots.assign(3, start);
  e.ctrl.push_back(at(start));
  e.weights.push_back(1);
  for (int i = 0; i < k; ++i) {
    const double a = start + i * step;
    const double mid = a + step / 2;
    // Intersection of the end tangents: the circle's at distance 1 / cos(half span).
    e.ctrl.push_back(centre + (major_axis * std::cos(mid) + minor * std::sin(mid)) / w_mid);
    e.weights.push_back(w_mid);
    e.ctrl.push_back(i + 1 == k ? at(end) : at(a + step));
    e.weights.push_back(1);
    if (i + 1 < k) e.knots.insert(e.knots.end(), 2, a + step);
  }
  e.knots.insert(e.knots.end(), 3, end);
  if (full) e.ctrl.back() = e.ctrl.front();  // closed exactly
  return e;
}

}  // namespace ncpath
