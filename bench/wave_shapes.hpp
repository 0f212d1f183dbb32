#pragma once
// Bench shapes shared by the offset and pocket benchmarks: a closed loop of `segments`
// segments (half arcs, half lines) through r(t) = 100 + A sin(20 t), clockwise (material
// inside), and counter-clockwise circles (islands).
#include <cmath>
#include <numbers>
#include <vector>

#include "kernels/curves/segment.hpp"

namespace ncpath::bench {

inline Vec2 wave(double t, double amplitude) {
  const double r = 100 + amplitude * std::sin(20 * t);
  return {r * std::cos(t), r * std::sin(t)};
}

// Circle through three points.
inline Vec2 circumcentre(const Vec2& a, const Vec2& b, const Vec2& c) {
  const double d =
      2 * (a.x() * (b.y() - c.y()) + b.x() * (c.y() - a.y()) + c.x() * (a.y() - b.y()));
  const double a2 = a.squaredNorm(), b2 = b.squaredNorm(), c2 = c.squaredNorm();
  return {(a2 * (b.y() - c.y()) + b2 * (c.y() - a.y()) + c2 * (a.y() - b.y())) / d,
          (a2 * (c.x() - b.x()) + b2 * (a.x() - c.x()) + c2 * (b.x() - a.x())) / d};
}

// Clockwise (material inside): walk t downwards.
inline std::vector<Seg2> wave_loop(int segments, double amplitude) {
  std::vector<Seg2> loop;
  const double two_pi = 2 * std::numbers::pi;
  for (int k = 0; k < segments; ++k) {
    const double t0 = two_pi * (segments - k) / segments,
                 t1 = two_pi * (segments - k - 1) / segments;
    const Vec2 a = k == 0 ? wave(0, amplitude) : loop.back().b;
    const Vec2 b = k + 1 == segments ? wave(0, amplitude) : wave(t1, amplitude);
    if (k % 2 == 0) {
      loop.push_back(make_line(a, b));
    } else {
      const Vec2 m = wave(0.5 * (t0 + t1), amplitude);
      const Vec2 c = circumcentre(a, m, b);
      const double turn = (m - a).x() * (b - m).y() - (m - a).y() * (b - m).x();
      loop.push_back(make_arc(a, b, c, turn > 0));
    }
  }
  return loop;
}

inline std::vector<Seg2> circle_ccw(const Vec2& c, double r) {
  const Vec2 p(c.x() + r, c.y()), q(c.x() - r, c.y());
  return {make_arc(p, q, c, true), make_arc(q, p, c, true)};
}

// The twelve islands of the benchmarks: radius 5 on a circle of radius 50.
inline std::vector<std::vector<Seg2>> twelve_islands() {
  std::vector<std::vector<Seg2>> out;
  for (int k = 0; k < 12; ++k) {
    const double a = 2 * std::numbers::pi * k / 12;
    out.push_back(circle_ccw({50 * std::cos(a), 50 * std::sin(a)}, 5));
  }
  return out;
}

}  // namespace ncpath::bench
