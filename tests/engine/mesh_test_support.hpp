#pragma once
// Meshes shared by the engine's scan and z-level tests: a random terrain (a height field on
// a jittered grid) and the real meshes from datasets/cache/meshes fit to 200 mm; and the
// brute-force no-gouge check of ball paths used by the clean-up tests.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "batch/io/mesh_reader.hpp"
#include "kernels/mesh/mesh_transform.hpp"
#include "kernels/mesh/triangle_mesh.hpp"
#include "tests/kernels/scan/scan_test_support.hpp"

namespace ncpath::test_meshes {

// A random height field on an n x n grid over 40 x 40 mm, heights in [0, 6] mm.
inline TriangleMesh terrain(std::mt19937_64& rng, int n) {
  std::uniform_real_distribution<double> h(0, 6), jitter(-0.4, 0.4);
  TriangleMesh m;
  const double step = 40.0 / (n - 1);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      m.vertices.emplace_back(i * step + jitter(rng), j * step + jitter(rng), h(rng));
  auto id = [n](int i, int j) { return std::uint32_t(j * n + i); };
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      m.facets.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.facets.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return m;
}


// A mesh of datasets/cache/meshes by name (without .off), fit to 200 mm in xy.
inline TriangleMesh load(const std::string& name) {
  const std::filesystem::path p =
      std::filesystem::path(NCPATH_SOURCE_DIR) / "datasets/cache/meshes" / (name + ".off");
  if (!std::filesystem::exists(p))
    throw std::runtime_error(p.string() + " is missing: run datasets/fetch-cgal-meshes.sh");
  io::MeshReadResult r = io::read_mesh(p);
  MeshTransform t;
  t.fit_xy_mm = 200;
  EXPECT_TRUE(apply_transform(t, r.mesh).ok());
  return std::move(r.mesh);
}

// Brute force (no engine code): a ball of radius R whose tip follows `paths` (mm) keeps R from
// every facet at every point and at 8 samples along every chord. Facets whose bounding box is
// R or more from the ball centre cannot be nearer than R and are skipped (exact, only faster).
inline void expect_no_gouge(const TriangleMesh& mesh, const std::vector<std::vector<Vec3>>& paths,
                            double R) {
  std::vector<Aabb3> boxes(mesh.facets.size());
  for (std::size_t k = 0; k < mesh.facets.size(); ++k)
    for (std::uint32_t v : mesh.facets[k]) boxes[k].add(mesh.vertices[v]);
  for (const auto& path : paths)
    for (std::size_t i = 0; i < path.size(); ++i) {
      const int n = i + 1 < path.size() ? 8 : 1;
      for (int s = 0; s < n; ++s) {
        const Vec3 q =
            i + 1 < path.size() ? Vec3(path[i] + (path[i + 1] - path[i]) * (s / 8.0)) : path[i];
        const Vec3 centre = q + Vec3(0, 0, R);
        double d = INFINITY;
        for (std::size_t k = 0; k < mesh.facets.size(); ++k) {
          const Vec3 out = (boxes[k].lo - centre).cwiseMax(centre - boxes[k].hi).cwiseMax(0.0);
          if (out.norm() >= R) continue;
          const auto& f = mesh.facets[k];
          d = std::min(
              d, scan_test::point_triangle_distance(centre, mesh.vertices[f[0]],
                                                    mesh.vertices[f[1]], mesh.vertices[f[2]]));
        }
        // 1e-6 mm: the resolution of the engine's check at walls (engine/surface_check.hpp).
        ASSERT_GE(d, R - 1e-6) << "gouge at " << q.transpose();
      }
    }
}

}  // namespace ncpath::test_meshes
