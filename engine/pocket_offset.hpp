#pragma once
// Multi-level contour-parallel offsets of pocket regions (boundary + islands), the input of
// pocket tool paths: level 1 at the tool radius plus stock to leave, then one level per
// stepover until nothing is left, with the offset generation history (parents).
//
// Level 1 lies at R + stock + wall_margin (the CL polylines' chordal tolerance) from the
// walls, and in a region with NURBS walls one tolerance farther: NURBS curves become arcs
// within half the tolerance (sampled: allowed twice that) before anything is offset, so every
// approximation falls on the free side of the true walls (at most the tolerance plus the
// chordal tolerance of extra material on the walls of such a region). Every level is an exact
// offset of lines and arcs.
//
// Input regions are independent (parallel tasks); within a level, the independent
// sub-regions of a region are parallel tasks too (kernels/pocket/offset_levels.hpp). Output
// order does not depend on the thread count.
#include <cstdint>
#include <vector>

#include "kernels/pocket/offset_levels.hpp"
#include "kernels/pocket/profile.hpp"

namespace ncpath {

struct PocketOffsetParams {
  double tool_radius = 3;   // mm
  double stepover = 1;      // mm between levels
  double stock = 0;         // mm left on walls and islands
  double tolerance = 0.01;  // mm: NURBS walls become arcs within half of it: see above
  double wall_margin = 0;   // mm farther from the walls: the CL polylines' chordal tolerance
  std::uint32_t max_levels = 100000;
  bool half_step_last = false;  // with per-level steps: see offset_levels_from
};

struct PocketLoop {
  OffsetLoop loop;           // loop.parents: indices into PocketOffsetResult::loops
  std::uint32_t region = 0;  // input region
  std::uint32_t level = 0;   // 1 = at tool radius + stock
  double step = 0;           // distance from its parents' level (0 at level 1), mm
};

struct PocketOffsetResult {
  std::vector<PocketLoop> loops;  // region by region, level by level
  std::uint64_t open_fragments = 0;
  std::uint32_t levels = 0;  // deepest level reached
};

// Lines and arcs of a profile, NURBS curves replaced by arcs within `tolerance`.
std::vector<Seg2> profile_segments(const Profile& profile, double tolerance);

// step: when given, the distance from each level region to the next (e.g. from a scallop
// height); params.stepover is then unused. Called from parallel tasks: thread-safe.
PocketOffsetResult offset_pocket(const std::vector<Region>& regions,
                                 const PocketOffsetParams& params, const StepFn* step = nullptr);

}  // namespace ncpath
