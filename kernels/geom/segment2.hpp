#pragma once
// Small planar segment helpers shared by the kernels.
#include <algorithm>

#include "kernels/geom/vec.hpp"

namespace ncpath {

// Distance from p to the segment [a, b] (a point when a == b).
inline double point_segment_distance(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double l2 = ab.squaredNorm();
  const double s = l2 > 0 ? std::clamp((p - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
  return (p - (a + s * ab)).norm();
}

}  // namespace ncpath
