#include "kernels/pocket/offset_levels.hpp"

#include <algorithm>
#include <cmath>

namespace ncpath {

namespace {

// Loops given by an accessor, so callers need not copy them into a vector first.
template <class Loop>
std::vector<std::vector<std::uint32_t>> group_regions_of(std::size_t n, Loop loop) {
  std::vector<std::int64_t> owner(n, -1);
  for (std::size_t h = 0; h < n; ++h) {
    if (loop(h).area2 <= 0) continue;  // holes are counter-clockwise
    const Vec2 p = loop(h).segs.front().a;
    double best_area = 1e300;
    for (std::size_t o = 0; o < n; ++o) {
      if (loop(o).area2 >= 0) continue;
      const double a = -loop(o).area2;
      if (a < best_area && winding_number(loop(o).segs, p) != 0) {
        best_area = a;
        owner[h] = static_cast<std::int64_t>(o);
      }
    }
  }
  std::vector<std::vector<std::uint32_t>> regions;
  std::vector<std::int64_t> region_of(n, -1);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t root = owner[i] >= 0 ? static_cast<std::size_t>(owner[i]) : i;
    if (region_of[root] < 0) {
      region_of[root] = static_cast<std::int64_t>(regions.size());
      regions.emplace_back();
    }
    regions[static_cast<std::size_t>(region_of[root])].push_back(static_cast<std::uint32_t>(i));
  }
  return regions;
}

}  // namespace

std::vector<std::vector<std::uint32_t>> group_regions(const std::vector<OffsetLoop>& loops) {
  return group_regions_of(loops.size(),
                          [&](std::size_t k) -> const OffsetLoop& { return loops[k]; });
}

std::vector<std::vector<std::uint32_t>> group_regions(const std::vector<const OffsetLoop*>& loops) {
  return group_regions_of(loops.size(),
                          [&](std::size_t k) -> const OffsetLoop& { return *loops[k]; });
}

void sequential_for_each(std::size_t n, const std::function<void(std::size_t)>& task) {
  for (std::size_t i = 0; i < n; ++i) task(i);
}

OffsetLevels offset_levels(const std::vector<std::vector<Seg2>>& input, double first, double step,
                           std::uint32_t max_levels, const ForEach& for_each) {
  return offset_levels_from(offset_loops(input, first), step, max_levels, for_each);
}

OffsetLevels offset_levels_from(OffsetResult r, double step, std::uint32_t max_levels,
                                const ForEach& for_each) {
  return offset_levels_from(
      std::move(r), [step](std::uint32_t, const std::vector<const OffsetLoop*>&) { return step; },
      max_levels, for_each);
}

OffsetLevels offset_levels_from(OffsetResult r, const StepFn& step, std::uint32_t max_levels,
                                const ForEach& for_each, bool half_step_last) {
  OffsetLevels out;
  out.open_fragments += r.stats.open_fragments;
  std::uint32_t level = 1;
  std::size_t prev_start = 0;
  for (OffsetLoop& l : r.loops) {
    l.parents.clear();  // parents of level 1 are input loops, not levels: none in the graph
    out.loops.push_back({std::move(l), level});
  }
  out.level_start.push_back(static_cast<std::uint32_t>(out.loops.size()));
  while (level < max_levels) {
    const std::size_t prev_end = out.loops.size();
    if (prev_end == prev_start) break;
    auto prev = [&](std::size_t k) -> const OffsetLoop& { return out.loops[prev_start + k].loop; };
    ++level;
    // Regions are independent: offset them as tasks into their own slots, then append the
    // slots in region order (out.loops is not touched while the tasks run).
    const std::vector<std::vector<std::uint32_t>> regions =
        group_regions_of(prev_end - prev_start, prev);
    std::vector<OffsetResult> slots(regions.size());
    std::vector<double> steps(regions.size());
    for_each(regions.size(), [&](std::size_t r) {
      std::vector<std::vector<Seg2>> loops;
      std::vector<double> area2;
      std::vector<const OffsetLoop*> region;
      for (std::uint32_t k : regions[r]) {
        loops.push_back(prev(k).segs);
        area2.push_back(prev(k).area2);
        region.push_back(&prev(k));
      }
      steps[r] = step(level - 1, region);
      slots[r] = offset_loops(loops, steps[r], &area2);
      // One more level at half the step where the full step leaves nothing: the region's
      // inradius is below the step, so the half-step level's is below half of it and this
      // ends (each extra level is at least half a step inside its parent).
      if (half_step_last && slots[r].loops.empty()) {
        steps[r] *= 0.5;
        slots[r] = offset_loops(loops, steps[r], &area2);
      }
    });
    for (std::size_t r = 0; r < regions.size(); ++r) {
      out.open_fragments += slots[r].stats.open_fragments;
      for (OffsetLoop& l : slots[r].loops) {
        for (std::uint32_t& p : l.parents)
          p = static_cast<std::uint32_t>(prev_start + regions[r][p]);
        out.loops.push_back({std::move(l), level, steps[r]});
      }
    }
    prev_start = prev_end;
    if (out.loops.size() == prev_end) break;
    out.level_start.push_back(static_cast<std::uint32_t>(out.loops.size()));
  }
  return out;
}

}  // namespace ncpath
