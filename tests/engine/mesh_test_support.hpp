#pragma once
// Meshes shared by the engine's scan and z-level tests: a random terrain (a height field on
// a jittered grid) and the real meshes from datasets/cache/meshes fit to 200 mm.
#include <gtest/gtest.h>

#include <filesystem>
#include <random>
#include <stdexcept>
#include <string>

#include "batch/io/mesh_reader.hpp"
#include "kernels/mesh/mesh_transform.hpp"
#include "kernels/mesh/triangle_mesh.hpp"

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

}  // namespace ncpath::test_meshes
