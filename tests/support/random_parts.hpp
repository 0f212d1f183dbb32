#pragma once
// Random parts for the robustness tests of the exact curve kernels (scan, z-levels, pencil):
//   random_cad_part   a plate with CAD-like features, each a closed convex prism overlapping
//                     the others (the union is the part, as an STL soup of several solids is):
//                     pocket walls, slots, steps, bosses (boxes, cylinders), chamfered and
//                     filleted blocks, ramps, overhangs (a slab on a stem), some turned about z;
//                     flat faces, vertical walls, concave creases where features meet.
//   random_relief     a closed height field over a jittered grid (random bumps and waves, no two
//                     facets coplanar), on a base with vertical sides: a scan-like relief.
//                     Where a bump dips below the base the solid turns inside out (the sides
//                     rise from the surface to the base), as messy scans do; kept on purpose
//                     (relief seeds 2077 and 2140 found a scan cut there).
// Both fit in about [0, 40] x [0, 40] x [0, 15] mm and depend only on the seed.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

#include "kernels/mesh/triangle_mesh.hpp"
#include "tests/support/meshes.hpp"

namespace ncpath::test {

namespace random_parts_detail {

inline void append(TriangleMesh& to, const TriangleMesh& from) {
  const auto base = std::uint32_t(to.vertices.size());
  to.vertices.insert(to.vertices.end(), from.vertices.begin(), from.vertices.end());
  for (const auto& f : from.facets) to.facets.push_back({f[0] + base, f[1] + base, f[2] + base});
}

// The prism of a convex polygon (counter-clockwise, in the plane (u, w)) swept along the third
// axis over [a, b]: axis 2 sweeps an xy outline along z, axis 1 an xz profile along y.
inline TriangleMesh prism(const std::vector<std::array<double, 2>>& poly, int axis, double a,
                          double b) {
  TriangleMesh m;
  const auto n = std::uint32_t(poly.size());
  auto point = [&](const std::array<double, 2>& p, double t) {
    return axis == 2 ? Vec3(p[0], p[1], t) : Vec3(p[0], t, p[1]);
  };
  for (double t : {a, b})
    for (const auto& p : poly) m.vertices.push_back(point(p, t));
  for (std::uint32_t k = 1; k + 1 < n; ++k) {
    m.facets.push_back({0, k + 1, k});          // cap at a
    m.facets.push_back({n, n + k, n + k + 1});  // cap at b
  }
  for (std::uint32_t k = 0; k < n; ++k) {
    const std::uint32_t j = (k + 1) % n;
    m.facets.push_back({k, j, n + j});
    m.facets.push_back({k, n + j, n + k});
  }
  // (u, w, t) -> (u, t, w) mirrors: turn the facets so that they face outwards again.
  if (axis == 1)
    for (auto& f : m.facets) std::swap(f[1], f[2]);
  return m;
}

inline std::vector<std::array<double, 2>> rectangle(double x0, double y0, double x1, double y1) {
  return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
}

// The xy outline turned by `angle` about (cx, cy).
inline void turn(std::vector<std::array<double, 2>>& poly, double angle, double cx, double cy) {
  const double c = std::cos(angle), s = std::sin(angle);
  for (auto& p : poly) {
    const double x = p[0] - cx, y = p[1] - cy;
    p = {cx + c * x - s * y, cy + s * x + c * y};
  }
}

inline void turn_mesh(TriangleMesh& m, double angle, double cx, double cy) {
  const double c = std::cos(angle), s = std::sin(angle);
  for (Vec3& v : m.vertices) {
    const double x = v.x() - cx, y = v.y() - cy;
    v = Vec3(cx + c * x - s * y, cy + s * x + c * y, v.z());
  }
}

}  // namespace random_parts_detail

inline TriangleMesh random_cad_part(std::uint64_t seed) {
  using namespace random_parts_detail;
  std::mt19937_64 rng(seed);
  auto U = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  auto I = [&](int a, int b) { return std::uniform_int_distribution<int>(a, b)(rng); };
  const double W = U(25, 40), D = U(25, 40), T = U(2, 6);
  TriangleMesh part = prism(rectangle(0, 0, W, D), 2, 0, T);
  const int features = I(2, 6);
  for (int f = 0; f < features; ++f) {
    // Axis-aligned most of the time, as CAD parts are; else turned about its centre.
    const double angle = I(0, 2) == 0 ? U(0, std::numbers::pi) : 0.0;
    const double w = U(3, 0.5 * W), d = U(3, 0.5 * D);
    const double x0 = U(0, W - w), y0 = U(0, D - d), cx = x0 + 0.5 * w, cy = y0 + 0.5 * d;
    const double h = U(1, 8), sink = U(0, 0.5 * T);  // features stand on the plate or dip into it
    TriangleMesh m;
    switch (I(0, 7)) {
      case 0: {  // pocket: four walls around it
        const double t = U(0.8, 0.3 * std::min(w, d));
        for (auto r : {rectangle(x0, y0, x0 + w, y0 + t), rectangle(x0, y0 + d - t, x0 + w, y0 + d),
                       rectangle(x0, y0, x0 + t, y0 + d), rectangle(x0 + w - t, y0, x0 + w, y0 + d)}) {
          turn(r, angle, cx, cy);
          append(m, prism(r, 2, T - sink, T + h));
        }
        break;
      }
      case 1: {  // slot: two blocks with a gap
        const double gap = U(1, 0.4 * w);
        for (auto r : {rectangle(x0, y0, x0 + 0.5 * (w - gap), y0 + d),
                       rectangle(x0 + 0.5 * (w + gap), y0, x0 + w, y0 + d)}) {
          turn(r, angle, cx, cy);
          append(m, prism(r, 2, T - sink, T + h));
        }
        break;
      }
      case 2: {  // step: a block to the plate's edge
        auto r = rectangle(x0, 0, x0 + w, D);
        append(m, prism(r, 2, T - sink, T + h));
        break;
      }
      case 3: {  // boss: a box
        auto r = rectangle(x0, y0, x0 + w, y0 + d);
        turn(r, angle, cx, cy);
        append(m, prism(r, 2, T - sink, T + h));
        break;
      }
      case 4: {  // boss: a cylinder
        const double rad = 0.5 * std::min(w, d);
        std::vector<std::array<double, 2>> c;
        const int n = I(6, 48);
        for (int k = 0; k < n; ++k) {
          const double a = 2 * std::numbers::pi * k / n;
          c.push_back({cx + rad * std::cos(a), cy + rad * std::sin(a)});
        }
        append(m, prism(c, 2, T - sink, T + h));
        break;
      }
      case 5: {  // a block with chamfered top edges (an xz profile swept along y)
        const double c = U(0.3, 0.45) * std::min(w, h);
        m = prism({{x0, T - sink}, {x0 + w, T - sink}, {x0 + w, T + h - c},
                   {x0 + w - c, T + h}, {x0 + c, T + h}, {x0, T + h - c}},
                  1, y0, y0 + d);
        turn_mesh(m, angle, cx, cy);
        break;
      }
      case 6: {  // a block with filleted top edges
        const double r = U(0.3, 0.45) * std::min(w, h);
        const int n = I(2, 12);
        std::vector<std::array<double, 2>> p = {{x0, T - sink}, {x0 + w, T - sink}};
        for (int side = 0; side < 2; ++side)  // right quarter, then left, counter-clockwise
          for (int k = 0; k <= n; ++k) {
            const double a = std::numbers::pi / 2 * (side + double(k) / n);
            const double cx2 = side == 0 ? x0 + w - r : x0 + r;
            p.push_back({cx2 + r * std::cos(a), T + h - r + r * std::sin(a)});
          }
        m = prism(p, 1, y0, y0 + d);
        turn_mesh(m, angle, cx, cy);
        break;
      }
      default: {  // overhang: a wide slab on a thin stem, or a ramp
        if (I(0, 1) == 0) {
          auto stem = rectangle(cx - 0.2 * w, cy - 0.2 * d, cx + 0.2 * w, cy + 0.2 * d);
          auto slab = rectangle(x0, y0, x0 + w, y0 + d);
          turn(stem, angle, cx, cy);
          turn(slab, angle, cx, cy);
          append(m, prism(stem, 2, T - sink, T + h));
          append(m, prism(slab, 2, T + h, T + h + U(0.5, 2)));
        } else {
          m = prism({{x0, T - sink}, {x0 + w, T - sink}, {x0 + w, T + h}}, 1, y0, y0 + d);
          turn_mesh(m, angle, cx, cy);
        }
      }
    }
    append(part, m);
  }
  return part;
}

inline TriangleMesh random_relief(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  auto U = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  const int n = std::uniform_int_distribution<int>(12, 40)(rng);
  const double size = 40, step = size / n, base = -U(1, 4);
  struct Bump {
    double x, y, r, h;
  };
  std::vector<Bump> bumps(std::uniform_int_distribution<int>(2, 8)(rng));
  for (Bump& b : bumps) b = {U(0, size), U(0, size), U(3, 15), U(-4, 8)};
  const double kx = U(0.05, 0.4), ky = U(0.05, 0.4), wave = U(0, 1.5);
  auto height = [&](double x, double y) {
    double z = wave * std::sin(kx * x) * std::cos(ky * y);
    for (const Bump& b : bumps) {
      const double q = ((x - b.x) * (x - b.x) + (y - b.y) * (y - b.y)) / (b.r * b.r);
      z += b.h * std::exp(-q);
    }
    return z;
  };
  TriangleMesh m;
  auto id = [n](int i, int j) { return std::uint32_t(j * (n + 1) + i); };
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      // Inner points jittered (no two facets coplanar); the rim stays on the square.
      const bool rim_x = i == 0 || i == n, rim_y = j == 0 || j == n;
      const double x = i * step + (rim_x ? 0 : U(-0.3, 0.3) * step);
      const double y = j * step + (rim_y ? 0 : U(-0.3, 0.3) * step);
      m.vertices.emplace_back(x, y, height(x, y));
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      m.facets.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.facets.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  // The rim walled down to the base, and the base closed by a fan.
  close_grid(m, n, base, 0.5 * size, 0.5 * size);
  return m;
}

}  // namespace ncpath::test
