// Multi-level pocket offsets, the cases of issue 3: a closed loop of 10,000 segments (5,000
// arcs and 5,000 lines) through r(t) = 100 + A sin(20 t), offset inward by 0.5 mm per
// level from the previous loop until empty; and the same with 12 circular islands.
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>

#include "kernels/pocket/offset_levels.hpp"

namespace ncpath {
namespace {

Vec2 wave(double t, double amplitude) {
  const double r = 100 + amplitude * std::sin(20 * t);
  return {r * std::cos(t), r * std::sin(t)};
}

// Circle through three points.
Vec2 circumcentre(const Vec2& a, const Vec2& b, const Vec2& c) {
  const double d =
      2 * (a.x() * (b.y() - c.y()) + b.x() * (c.y() - a.y()) + c.x() * (a.y() - b.y()));
  const double a2 = a.squaredNorm(), b2 = b.squaredNorm(), c2 = c.squaredNorm();
  return {(a2 * (b.y() - c.y()) + b2 * (c.y() - a.y()) + c2 * (a.y() - b.y())) / d,
          (a2 * (c.x() - b.x()) + b2 * (a.x() - c.x()) + c2 * (b.x() - a.x())) / d};
}

// Clockwise (material inside): walk t downwards.
std::vector<Seg2> wave_loop(int segments, double amplitude) {
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

std::vector<Seg2> circle_ccw(const Vec2& c, double r) {
  const Vec2 p(c.x() + r, c.y()), q(c.x() - r, c.y());
  return {make_arc(p, q, c, true), make_arc(q, p, c, true)};
}

void levels(benchmark::State& state, double amplitude, bool islands) {
  std::vector<std::vector<Seg2>> input = {wave_loop(10000, amplitude)};
  if (islands)
    for (int k = 0; k < 12; ++k) {
      const double a = 2 * std::numbers::pi * k / 12;
      input.push_back(circle_ccw({50 * std::cos(a), 50 * std::sin(a)}, 5));
    }
  std::size_t n_levels = 0, loops = 0, open = 0;
  for (auto _ : state) {
    // The input is the zero-distance level: offset it by 0.5 from itself, then by 0.5 each.
    const OffsetLevels out = offset_levels(input, 0.5, 0.5);
    n_levels = out.level_start.size();
    loops = out.loops.size();
    open = out.open_fragments;
    benchmark::DoNotOptimize(out.loops.data());
  }
  state.counters["levels"] = static_cast<double>(n_levels);
  state.counters["loops"] = static_cast<double>(loops);
  state.counters["open_fragments"] = static_cast<double>(open);
}

BENCHMARK_CAPTURE(levels, wave_a8_85, 8.85, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(levels, wave_a10, 10.0, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(levels, wave_a8_85_islands12, 8.85, true)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace ncpath
