#include "engine/pocket_offset.hpp"

#include <algorithm>

#include "engine/parallel.hpp"
#include "kernels/curves/nurbs.hpp"
#include "kernels/pocket/offset.hpp"

namespace ncpath {

std::vector<Seg2> profile_segments(const Profile& profile, double tolerance) {
  std::vector<Seg2> out;
  for (const ProfileCurve& c : profile.curves) {
    if (c.nurbs < 0) {
      out.push_back(c.seg);
      continue;
    }
    std::vector<Seg2> arcs =
        nurbs_to_arcs(profile.nurbs[static_cast<std::size_t>(c.nurbs)], tolerance, c.seg.source);
    // Keep the chain exact at the joints with the neighbouring curves.
    if (!arcs.empty()) {
      arcs.front().a = c.seg.a;
      arcs.back().b = c.seg.b;
    }
    out.insert(out.end(), arcs.begin(), arcs.end());
  }
  return out;
}

PocketOffsetResult offset_pocket(const std::vector<Region>& regions, const PocketOffsetParams& p,
                                 const StepFn* step) {
  std::vector<OffsetLevels> per_region(regions.size());
  const ForEach parallel = [](std::size_t n, const std::function<void(std::size_t)>& task) {
    par::for_each(n, 1, task);
  };
  // Level 1 lies wall_margin farther from every wall (the CL polylines' chords may sag that
  // much toward it), and in a region with NURBS walls the tolerance farther again: those walls
  // are offset as arcs within half the tolerance of them (sampled, so allowed twice that).
  // So every approximation falls on the free side, and the tool never comes closer than
  // R + stock to the true walls. The dissection then only meets exact lines and arcs.
  const double half_tol = 0.5 * p.tolerance;
  par::for_each(regions.size(), 1, [&](std::size_t r) {
    std::vector<std::vector<Seg2>> shapes{profile_segments(regions[r].boundary, half_tol)};
    bool nurbs = !regions[r].boundary.nurbs.empty();
    for (const Profile& island : regions[r].islands) {
      shapes.push_back(profile_segments(island, half_tol));
      nurbs = nurbs || !island.nurbs.empty();
    }
    const double first = p.tool_radius + p.stock + p.wall_margin + (nurbs ? p.tolerance : 0);
    OffsetResult level1 = offset_loops(shapes, first);
    per_region[r] =
        step
            ? offset_levels_from(std::move(level1), *step, p.max_levels, parallel, p.half_step_last)
            : offset_levels_from(std::move(level1), p.stepover, p.max_levels, parallel);
  });
  PocketOffsetResult out;
  for (std::size_t r = 0; r < regions.size(); ++r) {
    const auto base = static_cast<std::uint32_t>(out.loops.size());
    out.open_fragments += per_region[r].open_fragments;
    for (LevelLoop& l : per_region[r].loops) {
      for (std::uint32_t& parent : l.loop.parents) parent += base;
      out.levels = std::max(out.levels, l.level);
      out.loops.push_back({std::move(l.loop), static_cast<std::uint32_t>(r), l.level, l.step});
    }
  }
  return out;
}

}  // namespace ncpath
