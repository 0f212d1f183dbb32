#pragma once
// Multi-level contour-parallel offsets and the offset generation history (OGH) graph.
//
// Level 1 is the input offset by `first` (tool radius + stock to leave); every further
// level offsets the previous level's loops by `step` (the stepover), until nothing is left.
// Offsetting the previous level instead of the input by the summed distance is exact for
// lines and arcs (erosion composes) and keeps each validation local to one stepover.
//
// Loops of one level fall into independent regions (an outer, clockwise loop and the
// counter-clockwise holes inside it); the next level of each region depends on that region
// only, so callers may offset regions in parallel (engine/pocket_offset.hpp does).
#include <cstdint>
#include <functional>
#include <vector>

#include "kernels/pocket/offset.hpp"

namespace ncpath {

// Groups the loops of one level into regions: each clockwise loop with the
// counter-clockwise loops directly inside it (smallest enclosing clockwise loop). A
// counter-clockwise loop inside no clockwise loop (an island's offset when the input has
// no boundary) forms a region of its own. Regions are listed in order of their first loop.
std::vector<std::vector<std::uint32_t>> group_regions(const std::vector<OffsetLoop>& loops);
std::vector<std::vector<std::uint32_t>> group_regions(const std::vector<const OffsetLoop*>& loops);

struct LevelLoop {
  OffsetLoop loop;          // loop.parents: indices into OffsetLevels::loops of the level above
  std::uint32_t level = 0;  // 1 = first offset of the input
  double step = 0;          // distance from the level above (0 for level 1), mm
};

struct OffsetLevels {
  std::vector<LevelLoop> loops;            // level by level, in a deterministic order
  std::vector<std::uint32_t> level_start;  // loops of level k: [level_start[k-1], level_start[k])
  std::uint64_t open_fragments = 0;        // summed over all levels (0 when all is well)
};

// Runs task(i) for every i in [0, n); tasks are independent and write only their own slot.
// The default runs them in order on the calling thread (kernels own no threads); the engine
// passes its parallel for_each.
using ForEach = std::function<void(std::size_t n, const std::function<void(std::size_t)>& task)>;
void sequential_for_each(std::size_t n, const std::function<void(std::size_t)>& task);

// input: closed loops, material on the right. Stops after max_levels. Output is the same
// whatever `for_each` runs the regions with.
OffsetLevels offset_levels(const std::vector<std::vector<Seg2>>& input, double first, double step,
                           std::uint32_t max_levels = 1000000,
                           const ForEach& for_each = sequential_for_each);
// The same from a given first level (e.g. offset_loops at another distance than step).
OffsetLevels offset_levels_from(OffsetResult first_level, double step,
                                std::uint32_t max_levels = 1000000,
                                const ForEach& for_each = sequential_for_each);
// The same with a step chosen per level region: step(level, loops) gives the distance from
// the region of `level` (its clockwise loop and holes) to the next level (e.g. from the
// scallop height along those loops). Called from the for_each tasks: must be thread-safe.
using StepFn =
    std::function<double(std::uint32_t level, const std::vector<const OffsetLoop*>& region)>;
// half_step_last: when a region's offset by its step is empty, offset it by half the step
// instead (at most once in a row): the last gap between neighbouring loops is then at most
// the step (a ball's scallop stays within its bound in the middle too).
OffsetLevels offset_levels_from(OffsetResult first_level, const StepFn& step,
                                std::uint32_t max_levels = 1000000,
                                const ForEach& for_each = sequential_for_each,
                                bool half_step_last = false);

}  // namespace ncpath
