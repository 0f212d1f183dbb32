#pragma once
// Small meshes built in the tests: known shapes and random ones.
#include <cmath>
#include <random>
#include <vector>

#include "kernels/mesh/triangle_mesh.hpp"

namespace ncpath::test {

// n x n grid over [0, size]^2 with heights from f(x, y); two triangles per cell.
template <class F>
TriangleMesh height_field(int n, double size, F&& f) {
  TriangleMesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = size * i / n, y = size * j / n;
      m.vertices.emplace_back(x, y, f(x, y));
    }
  auto id = [n](int i, int j) { return static_cast<std::uint32_t>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      m.facets.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.facets.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return m;
}

// Closes the (n+1) x (n+1) vertex grid of m (vertex j (n+1) + i; counter-clockwise from
// above) into a solid: its rim walled straight down to z = base_z and the base closed by a fan
// around (cx, cy), wound outward.
inline void close_grid(TriangleMesh& m, int n, double base_z, double cx, double cy) {
  auto id = [n](int i, int j) { return static_cast<std::uint32_t>(j * (n + 1) + i); };
  std::vector<std::uint32_t> rim;
  for (int i = 0; i < n; ++i) rim.push_back(id(i, 0));
  for (int j = 0; j < n; ++j) rim.push_back(id(n, j));
  for (int i = n; i > 0; --i) rim.push_back(id(i, n));
  for (int j = n; j > 0; --j) rim.push_back(id(0, j));
  const auto first = static_cast<std::uint32_t>(m.vertices.size());
  for (std::uint32_t v : rim) m.vertices.emplace_back(m.vertices[v].x(), m.vertices[v].y(), base_z);
  const auto centre = static_cast<std::uint32_t>(m.vertices.size());
  m.vertices.emplace_back(cx, cy, base_z);
  const auto k = static_cast<std::uint32_t>(rim.size());
  for (std::uint32_t q = 0; q < k; ++q) {
    const std::uint32_t r = (q + 1) % k;
    m.facets.push_back({rim[q], first + q, first + r});
    m.facets.push_back({rim[q], first + r, rim[r]});
    m.facets.push_back({centre, first + r, first + q});
  }
}

inline TriangleMesh random_height_field(int n, double size, double amplitude, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> U(0, amplitude);
  return height_field(n, size, [&](double, double) { return U(rng); });
}

// Random triangle soup in [0, size]^2 x [0, height]: overlapping, steep, any orientation.
inline TriangleMesh random_soup(int count, double size, double height, double tri_size,
                                unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> U(0, 1), D(-1, 1);
  TriangleMesh m;
  for (int k = 0; k < count; ++k) {
    const Vec3 c{U(rng) * size, U(rng) * size, U(rng) * height};
    for (int v = 0; v < 3; ++v) m.vertices.push_back(c + tri_size * Vec3{D(rng), D(rng), D(rng)});
    const auto b = static_cast<std::uint32_t>(3 * k);
    m.facets.push_back({b, b + 1, b + 2});
  }
  return m;
}

// Upper hemisphere of radius s centred at the origin, vertices on the sphere.
inline TriangleMesh hemisphere(double s, int rings, int segments) {
  TriangleMesh m;
  m.vertices.emplace_back(0, 0, s);
  for (int i = 1; i <= rings; ++i) {
    const double phi = (M_PI / 2) * i / rings;
    for (int k = 0; k < segments; ++k) {
      const double th = 2 * M_PI * k / segments;
      m.vertices.emplace_back(s * std::sin(phi) * std::cos(th), s * std::sin(phi) * std::sin(th),
                              s * std::cos(phi));
    }
  }
  auto ring = [&](int i, int k) {
    return static_cast<std::uint32_t>(1 + (i - 1) * segments + (k % segments));
  };
  for (int k = 0; k < segments; ++k) m.facets.push_back({0, ring(1, k), ring(1, k + 1)});
  for (int i = 1; i < rings; ++i)
    for (int k = 0; k < segments; ++k) {
      m.facets.push_back({ring(i, k), ring(i + 1, k), ring(i + 1, k + 1)});
      m.facets.push_back({ring(i, k), ring(i + 1, k + 1), ring(i, k + 1)});
    }
  return m;
}

}  // namespace ncpath::test
