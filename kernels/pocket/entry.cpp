#include "kernels/pocket/entry.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace ncpath {

std::vector<Vec3> helix_points(const Vec2& centre, const Vec2& start, double z0, double z1,
                               double angle_rad, bool ccw, double chord) {
  const double r = (start - centre).norm();
  std::vector<Vec3> out{Vec3(start.x(), start.y(), z0)};
  if (r <= 0) {
    out.emplace_back(start.x(), start.y(), z1);
    return out;
  }
  // Chords within `chord` of the circle: half-angle acos(1 - chord / r).
  const double half = std::acos(std::clamp(1 - chord / r, -1.0, 1.0));
  const int per_turn = std::max(8, static_cast<int>(std::ceil(std::numbers::pi / half)));
  const double drop_per_turn = 2 * std::numbers::pi * r * std::tan(angle_rad);
  const int turns = std::max(1, static_cast<int>(std::ceil((z0 - z1) / drop_per_turn)));
  const double a0 = std::atan2(start.y() - centre.y(), start.x() - centre.x());
  const double dir = ccw ? 1 : -1;
  const int steps = (turns + 1) * per_turn;  // the last turn at the bottom
  for (int k = 1; k <= steps; ++k) {
    const double f = static_cast<double>(k) / per_turn;  // turns done
    const double z = f >= turns ? z1 : z0 + (z1 - z0) * f / turns;
    if (k % per_turn == 0) {
      out.emplace_back(start.x(), start.y(), z);  // exactly back at the start point
      continue;
    }
    const double a = a0 + dir * 2 * std::numbers::pi * f;
    out.emplace_back(centre.x() + r * std::cos(a), centre.y() + r * std::sin(a), z);
  }
  return out;
}

std::vector<Vec3> ramp_points(const std::vector<Seg2>& loop, double z0, double z1, double angle_rad,
                              double chord) {
  std::vector<Vec2> pts;
  for (const Seg2& s : loop) append_polyline(s, chord, pts);
  if (pts.empty()) return {};
  pts.push_back(loop.front().a);  // closed
  const double length = (z0 - z1) / std::tan(angle_rad);
  std::vector<Vec3> out{Vec3(pts[0].x(), pts[0].y(), z0)};
  double travelled = 0;
  // Whole turns until the ramp has descended `length` mm of travel; the point where it
  // reaches z1 is inserted exactly.
  while (true) {
    for (std::size_t k = 1; k < pts.size(); ++k) {
      const double step = (pts[k] - pts[k - 1]).norm();
      if (travelled < length && travelled + step > length) {
        const Vec2 q = pts[k - 1] + (length - travelled) / step * (pts[k] - pts[k - 1]);
        out.emplace_back(q.x(), q.y(), z1);
      }
      travelled += step;
      const double f = std::min(1.0, travelled / length);
      out.emplace_back(pts[k].x(), pts[k].y(), z0 + (z1 - z0) * f);
    }
    if (travelled >= length || !(travelled > 0)) break;
  }
  out.back().z() = z1;
  return out;
}

}  // namespace ncpath
