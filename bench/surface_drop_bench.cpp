// Ball-end drop onto a NURBS surface (kernels/surface/surface_drop): a wavy bicubic surface of
// 4 x 4 patches over 100 x 100 mm (waves of +-6 mm, creases at the patch seams from control
// noise, concave regions tighter than the ball), ball radii 6 and 1.5 mm, at 4096 random
// positions over the surface and 10 % beyond its border. Also the plain evaluation and the
// height-field check for scale.
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "kernels/surface/surface_drop.hpp"

namespace ncpath {
namespace {

NurbsSurface wavy_surface(int patches, double size) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> U(-1, 1);
  const int n = 3 * patches + 1;
  std::vector<Vec3> ctrl;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double x = size * i / (n - 1), y = size * j / (n - 1);
      const double z = 6 * std::sin(2 * std::numbers::pi * x / (0.4 * size)) *
                           std::cos(2 * std::numbers::pi * y / (0.5 * size)) +
                       0.5 * U(rng);
      ctrl.emplace_back(x, y, z);
    }
  return bezier_grid_surface(patches, patches, ctrl);
}

const SurfaceDrop& dropper() {
  static const SurfaceDrop d(wavy_surface(4, 100));
  return d;
}

const std::vector<Vec2>& points() {
  static const std::vector<Vec2> p = [] {
    std::mt19937_64 rng(2);
    std::uniform_real_distribution<double> U(-10, 110);
    std::vector<Vec2> v;
    for (int i = 0; i < 4096; ++i) v.emplace_back(U(rng), U(rng));
    return v;
  }();
  return p;
}

void drop(benchmark::State& state, double radius) {
  const SurfaceDrop& d = dropper();
  const std::vector<Vec2>& pts = points();
  std::size_t i = 0;
  for (auto _ : state) {
    const SurfaceContact c = d.drop(pts[i++ & 4095], radius);
    benchmark::DoNotOptimize(c);
  }
  state.SetItemsProcessed(state.iterations());
}

void evaluate_point(benchmark::State& state) {
  const NurbsSurface& s = dropper().surface();
  const std::vector<Vec2>& pts = points();
  std::size_t i = 0;
  for (auto _ : state) {
    const Vec2& p = pts[i++ & 4095];
    const SurfacePoint sp =
        evaluate(s, std::clamp(p.x() / 25, 0.0, 4.0), std::clamp(p.y() / 25, 0.0, 4.0));
    benchmark::DoNotOptimize(sp);
  }
  state.SetItemsProcessed(state.iterations());
}

void height_field(benchmark::State& state) {
  const NurbsSurface& s = dropper().surface();
  for (auto _ : state) {
    const std::string e = check_height_field(s);
    benchmark::DoNotOptimize(e.data());
  }
}

BENCHMARK_CAPTURE(drop, wavy4x4_r6, 6.0);
BENCHMARK_CAPTURE(drop, wavy4x4_r1_5, 1.5);
BENCHMARK(evaluate_point)->Name("evaluate/wavy4x4");
BENCHMARK(height_field)->Name("check_height_field/wavy4x4")->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace ncpath
