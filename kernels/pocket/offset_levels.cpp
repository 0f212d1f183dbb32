#include "kernels/pocket/offset_levels.hpp"

#include <algorithm>
#include <cmath>

namespace ncpath {

std::vector<std::vector<std::uint32_t>> group_regions(const std::vector<OffsetLoop>& loops) {
  const std::size_t n = loops.size();
  std::vector<std::int64_t> owner(n, -1);
  for (std::size_t h = 0; h < n; ++h) {
    if (loops[h].area2 <= 0) continue;  // holes are counter-clockwise
    const Vec2 p = loops[h].segs.front().a;
    double best_area = 1e300;
    for (std::size_t o = 0; o < n; ++o) {
      if (loops[o].area2 >= 0) continue;
      const double a = -loops[o].area2;
      if (a < best_area && winding_number(loops[o].segs, p) != 0) {
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

void sequential_for_each(std::size_t n, const std::function<void(std::size_t)>& task) {
  for (std::size_t i = 0; i < n; ++i) task(i);
}

OffsetLevels offset_levels(const std::vector<std::vector<Seg2>>& input, double first,
                           double step, std::uint32_t max_levels, const ForEach& for_each) {
  return offset_levels_from(offset_loops(input, first), step, max_levels, for_each);
}

OffsetLevels offset_levels_from(OffsetResult r, double step, std::uint32_t max_levels,
                                const ForEach& for_each) {
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
    std::vector<OffsetLoop> prev;
    for (std::size_t k = prev_start; k < prev_end; ++k) prev.push_back(out.loops[k].loop);
    ++level;
    // Regions are independent: offset them as tasks into their own slots, then append the
    // slots in region order.
    const std::vector<std::vector<std::uint32_t>> regions = group_regions(prev);
    std::vector<OffsetResult> slots(regions.size());
    for_each(regions.size(), [&](std::size_t r) {
      std::vector<std::vector<Seg2>> loops;
      for (std::uint32_t k : regions[r]) loops.push_back(prev[k].segs);
      slots[r] = offset_loops(loops, step);
    });
    for (std::size_t r = 0; r < regions.size(); ++r) {
      out.open_fragments += slots[r].stats.open_fragments;
      for (OffsetLoop& l : slots[r].loops) {
        for (std::uint32_t& p : l.parents)
          p = static_cast<std::uint32_t>(prev_start + regions[r][p]);
        out.loops.push_back({std::move(l), level});
      }
    }
    prev_start = prev_end;
    if (out.loops.size() == prev_end) break;
    out.level_start.push_back(static_cast<std::uint32_t>(out.loops.size()));
  }
  return out;
}

}  // namespace ncpath
