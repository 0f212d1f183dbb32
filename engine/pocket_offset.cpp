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

void first_offsets(const Profile& profile, double d, double tolerance, OffsetRuns& runs) {
  for (const ProfileCurve& c : profile.curves) {
    if (c.nurbs < 0) {
      Seg2 o;
      if (raw_offset(c.seg, d, o, &runs.inverted)) runs.add(c.seg.a, &o, 1);
      continue;
    }
    // Tiller-Hanson: the offset NURBS (self-loops cut out) within tolerance, then arcs.
    const NurbsOffset off =
        nurbs_offset(profile.nurbs[static_cast<std::size_t>(c.nurbs)], d, tolerance);
    std::vector<Seg2> chain;
    for (const Nurbs2& piece : off.pieces) {
      std::vector<Seg2> arcs = nurbs_to_arcs(piece, tolerance, c.seg.source);
      if (arcs.empty()) continue;
      if (!chain.empty()) arcs.front().a = chain.back().b;  // pieces meet at their cut
      chain.insert(chain.end(), arcs.begin(), arcs.end());
    }
    runs.add(c.seg.a, chain.data(), chain.size());
  }
}

PocketOffsetResult offset_pocket(const std::vector<Region>& regions, const PocketOffsetParams& p,
                                 const StepFn* step) {
  std::vector<OffsetLevels> per_region(regions.size());
  const ForEach parallel = [](std::size_t n, const std::function<void(std::size_t)>& task) {
    par::for_each(n, 1, task);
  };
  // Level 1 lies wall_margin farther from every wall (the CL polylines' chords may sag that
  // much toward it), and in a region with NURBS walls twice the tolerance farther again: the
  // Tiller-Hanson offset and its arcs are each within half the tolerance of the truth as
  // measured, up to about twice that in fact, either way. So every approximation falls on the
  // free side, and the tool never comes closer than R + stock to the true walls.
  const double half_tol = 0.5 * p.tolerance;
  par::for_each(regions.size(), 1, [&](std::size_t r) {
    std::vector<const Profile*> profiles{&regions[r].boundary};
    for (const Profile& island : regions[r].islands) profiles.push_back(&island);
    bool nurbs = false;
    for (const Profile* pr : profiles) nurbs = nurbs || !pr->nurbs.empty();
    const double first = p.tool_radius + p.stock + p.wall_margin + (nurbs ? 2 * p.tolerance : 0);
    std::vector<std::vector<Seg2>> shapes;
    std::vector<OffsetRuns> runs(profiles.size());
    for (std::size_t l = 0; l < profiles.size(); ++l) {
      shapes.push_back(profile_segments(*profiles[l], half_tol));
      first_offsets(*profiles[l], first, half_tol, runs[l]);
    }
    // NURBS offsets and NURBS shapes are each within half the tolerance of the truth (the
    // Tiller-Hanson offset measures up to about twice its own budget): validation allows
    // twice the tolerance.
    const double slack = nurbs ? 2 * p.tolerance : 0;
    OffsetResult level1 = offset_prepared(std::move(runs), shapes, first, nullptr, slack);
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
