#pragma once
// Point operation: drop the tool at a given list of xy points, answer in the same order.
// Points where the tool touches nothing get z = NaN and contact kind 0; they are counted,
// never given a made-up height. Queries go through the Embree drop index.
#include <cstdint>
#include <functional>
#include <span>

#include "engine/cl_chunk.hpp"
#include "engine/run_control.hpp"
#include "kernels/cutters/cutter.hpp"
#include "kernels/mesh/triangle_mesh.hpp"

namespace ncpath {

struct DropPointsStats {
  std::uint64_t points = 0;
  std::uint64_t no_contact = 0;
  std::uint64_t facets = 0;
  std::uint64_t facets_degenerate = 0;
  double index_s = 0, compute_s = 0, sink_s = 0;
};

// xy holds 2 doubles per point (mm). path_sizes splits the points into paths (sum = number
// of points); each path is handed to `sink` whole, at most ~64K points per call unless one
// path is longer.
DropPointsStats run_drop_points(const TriangleMesh& mesh, const Cutter& cutter,
                                std::span<const double> xy,
                                std::span<const std::uint32_t> path_sizes,
                                const std::function<void(const ClChunk&)>& sink,
                                RunControl& control);

}  // namespace ncpath
