#pragma once
// Raster (zig-zag) drop-cutter finishing over a mesh.
//
// Scan lines run along x (or y) across a rectangle (the part's xy box grown by a margin,
// or a given one). Line i sits at v0 + i*interval and carries samples u0 + j*step (both
// ends included when the extent is a multiple; count = floor(extent/step) + 1). Odd lines
// run backwards. Consecutive lines are joined by a link path at depth: drop-cutter samples
// along the rectangle's side, so the link is as gouge-free as the cut. Optional adaptive
// sampling inserts midpoints until the straight move between consecutive CL points is
// within `adaptive_tolerance` of the CL curve at the midpoint.
//
// Every CL z is the exact drop-cutter maximum over all facets (see strip_index.hpp),
// raised to the floor where the tool touches nothing lower. Output is streamed to `sink`
// in chunks of whole lines; bytes are identical for any thread count.
#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "engine/cl_chunk.hpp"
#include "engine/run_control.hpp"
#include "kernels/cutters/cutter.hpp"
#include "kernels/mesh/triangle_mesh.hpp"

namespace ncpath {

enum class ScanDirection : std::uint8_t { kX = 0, kY = 1 };

struct RasterParams {
  ScanDirection direction = ScanDirection::kX;  // lines run along this axis
  double interval = 0.5;                        // mm between scan lines (stepover)
  double step = 0.1;                            // mm between samples along a line
  double margin = 0.0;                          // mm added on every side of the part's xy box
  std::optional<std::array<double, 4>> rect;    // x_min, y_min, x_max, y_max (mm); overrides
  double adaptive_tolerance = 0;                // mm; 0 = fixed sampling only
  double min_step = 0;                          // mm; smallest adaptive spacing; 0 = step / 64
  std::optional<double> floor_z;                // mm; default: the part's lowest z
  std::uint32_t chunk_lines = 64;               // lines per streamed chunk (memory vs overhead)
  double strip_height = 0;                      // mm of lines sharing one candidate set; 0 = auto
  double bin_width = 0;                         // mm of x-bins within a strip; 0 = auto
  // Only band `band` of `bands` (a job split across MPI ranks, batch/jobs/split_job.hpp):
  // strips band, band + bands, band + 2 * bands, ... of the raster's strips (every bands-th
  // one, so that every band has its share of the part), each line with its link to the next
  // as in the whole raster. The whole raster's paths are the bands' strips taken in turn
  // (RasterStats::strip_paths says where each strip ends). Not a user parameter (not in the
  // params JSON).
  std::uint32_t band = 0, bands = 1;
};

// Samples at origin + k * spacing, k = 0 .. floor(extent / spacing): their count.
std::size_t raster_sample_count(double extent, double spacing);

// Empty when usable; else a message naming the bad key ("interval must be > 0, got 0").
std::string validate(const RasterParams& params);

struct RasterStats {
  std::uint64_t lines = 0;            // lines computed (of the band, when split)
  std::uint64_t cut_points = 0;       // points on cut paths (incl. adaptive ones)
  std::uint64_t link_points = 0;      // points on link paths
  std::uint64_t adaptive_points = 0;  // points inserted by adaptive sampling
  std::uint64_t floor_points = 0;     // points where the tool touched nothing above the floor
  std::uint64_t facets = 0;           // facets used (non-degenerate)
  std::uint64_t facets_degenerate = 0;
  double floor_z = 0;            // mm
  std::array<double, 4> rect{};  // the rectangle actually scanned
  double index_s = 0;            // facet table + strip buckets
  double compute_s = 0;          // drop-cutting (wall time of the chunk computations)
  double sink_s = 0;             // time spent in sink (writing), overlapped with compute
  std::vector<std::int64_t> strip_paths;  // paths of each strip computed, in order
};

// Throws Cancelled if control.cancel is set; std::invalid_argument for bad params.
RasterStats run_raster(const TriangleMesh& mesh, const Cutter& cutter, const RasterParams& params,
                       const std::function<void(const ClChunk&)>& sink, RunControl& control);

}  // namespace ncpath
