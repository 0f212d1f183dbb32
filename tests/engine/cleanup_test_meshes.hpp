#pragma once
// Shared by the fillet-cut tests (fillet_test.cpp, fillet_options_test.cpp): the filleted
// V-groove and the brute-force distance from a point to a mesh. The plain V-groove and the box
// pocket of the pencil tests are the scan kernel tests' (tests/kernels/scan/scan_test_support).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "kernels/mesh/triangle_mesh.hpp"
#include "tests/kernels/scan/scan_test_support.hpp"

namespace ncpath::test_meshes {

// Flanks z = |x| for |x| >= rho / sqrt 2 up to |x| = 10, joined by the circle of radius rho
// centred at (0, rho sqrt 2) in xz (tangent to both flanks), along y in [-8, 8]; n arc facets.
inline TriangleMesh filleted_groove(double rho, int n) {
  std::vector<Vec2> prof;  // (x, z)
  prof.emplace_back(-10, 10);
  const Vec2 c(0, rho * std::sqrt(2.0));
  for (int i = 0; i <= n; ++i) {
    const double a = -0.75 * std::numbers::pi + 0.5 * std::numbers::pi * i / n;  // -135..-45 deg
    prof.push_back(c + rho * Vec2(std::cos(a), std::sin(a)));
  }
  prof.emplace_back(10, 10);
  TriangleMesh m;
  for (const Vec2& q : prof) {
    m.vertices.emplace_back(q.x(), -8, q.y());
    m.vertices.emplace_back(q.x(), 8, q.y());
  }
  for (std::uint32_t i = 0; i + 1 < prof.size(); ++i) {
    const std::uint32_t a = 2 * i;
    m.facets.push_back({a, a + 2, a + 3});
    m.facets.push_back({a, a + 3, a + 1});
  }
  return m;
}

// Brute force (no engine code): the distance (mm) from p to the nearest facet of m.
inline double point_mesh_distance(const TriangleMesh& m, const Vec3& p) {
  double d = INFINITY;
  for (const auto& f : m.facets)
    d = std::min(d, scan_test::point_triangle_distance(p, m.vertices[f[0]], m.vertices[f[1]],
                                                       m.vertices[f[2]]));
  return d;
}

}  // namespace ncpath::test_meshes
