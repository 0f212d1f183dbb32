#include "engine/surface_check.hpp"

#include <algorithm>
#include <cmath>

namespace ncpath {

double surface_deficit(const DropIndex& index, double floor_z, const Vec3& q) {
  // On or above at q itself: no gouge whatever the neighbours say (one query, the common case).
  double d = std::max(floor_z, index.query(q.x(), q.y()).tip_z) - q.z();
  if (d <= 0) return d;
  for (int dx = -1; dx <= 1; ++dx)
    for (int dy = -1; dy <= 1; ++dy) {
      const double z = index.query(q.x() + 1e-6 * dx, q.y() + 1e-6 * dy).tip_z;
      d = std::min(d, std::max(floor_z, z) - q.z());
    }
  return d;
}

std::size_t lift_above_surface(const DropIndex& index, double floor_z, double spacing,
                               std::vector<Vec3>& pts) {
  const std::size_t n_pts = pts.size();
  std::vector<bool> raised(n_pts, false);
  // Chords to (re)check: all at first, then only those next to a raised point.
  std::vector<bool> check(n_pts > 0 ? n_pts - 1 : 0, true);
  for (int pass = 0; pass < 3; ++pass) {
    std::vector<double> lift(n_pts, 0);
    for (std::size_t i = 0; i < n_pts; ++i)
      if ((i > 0 && check[i - 1]) || (i + 1 < n_pts && check[i]) || n_pts == 1)
        lift[i] = std::max(0.0, surface_deficit(index, floor_z, pts[i]));
    for (std::size_t i = 0; i + 1 < n_pts; ++i) {
      if (!check[i]) continue;
      const Vec3 a = pts[i], b = pts[i + 1];
      const int n = std::max(2, int(std::ceil((b - a).norm() / spacing)));
      double deficit = 0;
      for (int j = 1; j < n; ++j)
        deficit = std::max(deficit, surface_deficit(index, floor_z, a + (b - a) * (double(j) / n)));
      lift[i] = std::max(lift[i], deficit);
      lift[i + 1] = std::max(lift[i + 1], deficit);
    }
    std::fill(check.begin(), check.end(), false);
    bool any = false;
    for (std::size_t i = 0; i < n_pts; ++i)
      if (lift[i] > 0) {
        pts[i].z() += lift[i];
        raised[i] = any = true;
        if (i > 0) check[i - 1] = true;
        if (i < check.size()) check[i] = true;
      }
    if (!any) break;
  }
  return std::size_t(std::count(raised.begin(), raised.end(), true));
}

}  // namespace ncpath
