#pragma once
// Path determination for contour-parallel pockets (seed method 2): the offset loops of one
// connected part of a pocket, their offset generation history (OGH) and the clean-up curves
// of the uncut regions become one continuous planar path, with no retraction.
//
//  1. Tool-path tree: BFS over the OGH (parent/child loops of consecutive levels, plus
//     "same-level" edges that join loops of one level region whose histories never meet,
//     e.g. the two loops of a ring around an island) from the start loop: fewest links.
//  2. Links: a tree edge between loops of consecutive levels becomes a segment of length
//     `stepover` between a point of the inner loop and its nearest point on the outer loop.
//     The inner loop is part of the outer region eroded by the stepover, so the segment lies
//     in the disc of radius `stepover` around its inner end, inside the outer loop's region:
//     it never leaves the pocket and never crosses an island. The link is placed at the
//     loop's entry point when the other loop is within `stepover` of it (no travel),
//     otherwise at a vertex of the inner loop that is.
//  3. Order: siblings are met along their parent loop in the cutting direction (out and
//     back, the link travelled twice); the child with the largest subtree goes last, one
//     way, after the parent loop is closed. DFS over this order gives the path.
//  4. Clean-up: each clean-up loop (a loop of an uncut region, at distance >= R from the
//     level loops that bound its band) is attached to the bounding loop cut last, at a pair
//     of points at distance R: the link lies in the disc the tool swept at that point of
//     the loop. The detour is link, the whole clean-up loop, link back.
// Cutting direction: climb milling (spindle M3) keeps the material being cut on the right of
// travel: a loop cut outward (entered from a deeper level, or the first loop when cutting
// outward) runs against its stored direction, a loop cut inward along it; clean-up loops
// along theirs (the uncut material is on their right). Conventional milling flips all.
#include <cstdint>
#include <vector>

#include "kernels/curves/segment.hpp"

namespace ncpath {

struct PlanLoop {
  const std::vector<Seg2>* segs = nullptr;  // closed, material on the right; outlives the plan
  std::uint32_t level = 0;                  // 1 = first offset
  std::vector<std::uint32_t> parents;       // OGH: indices of loops of level - 1
  std::uint32_t group = 0;  // loops of one level region (a clockwise loop and its holes)
  double step = 0;          // distance from its parents' level, mm (0: PlanParams::stepover)
};

struct CleanupLoop {
  std::vector<Seg2> segs;             // closed, uncut material on the right
  std::vector<std::uint32_t> bounds;  // indices of the level loops bounding its band
};

enum class MoveKind : std::uint8_t { kCut, kLink, kCleanup, kCleanupLink };
struct Move2 {
  Seg2 seg;
  MoveKind kind = MoveKind::kCut;
};

struct PlanParams {
  double tool_radius = 3;  // mm
  double stepover = 1.5;   // mm
  bool outward = true;     // first loop innermost (else at level 1: an island's, else outer)
  bool climb = true;
};

// One connected part of the pocket, cut as one path.
struct PlannedPath {
  std::uint32_t root = 0;            // first loop
  Vec2 start = Vec2::Zero();         // on the first loop
  std::vector<Move2> moves;          // continuous, from start
  std::vector<Seg2> first_loop;      // the first loop as cut, from start back to start
  std::vector<Move2> back;           // from the end of moves back to start, in cut material
  std::vector<std::uint32_t> loops;  // loops of this part, ascending
  std::uint64_t links = 0;           // loop-to-loop links
  std::uint64_t cleanup_curves = 0;  // clean-up loops attached
  std::vector<std::uint32_t>
      unattached;                // clean-up loops no bounding loop reaches (should be none)
  std::uint64_t long_links = 0;  // links longer than the stepover (should be none)
  double slotting_length = 0;    // mm: first loop + links beyond R into uncut bands
};

// Extra edges joining loops of one level region that the OGH leaves disconnected (deepest
// level first, each along a shortest segment that crosses no loop of the region). Appended
// as (a, b, point on a, point on b).
struct SameLevelEdge {
  std::uint32_t a = 0, b = 0;
  Vec2 pa = Vec2::Zero(), pb = Vec2::Zero();
};
std::vector<SameLevelEdge> same_level_edges(const std::vector<PlanLoop>& loops);

// Connected parts: OGH and same-level edges. Each part's loops ascending; parts in order of
// their first loop.
std::vector<std::vector<std::uint32_t>> connected_parts(const std::vector<PlanLoop>& loops,
                                                        const std::vector<SameLevelEdge>& extra);

// Plans the path of one part, starting at `start` (a point of loop `root`). cleanups: all
// clean-up loops of the pocket; those whose bounds lie in this part are attached.
PlannedPath plan_part(const std::vector<PlanLoop>& loops, const std::vector<SameLevelEdge>& extra,
                      const std::vector<CleanupLoop>& cleanups,
                      const std::vector<std::uint32_t>& part, std::uint32_t root, const Vec2& start,
                      const PlanParams& params);

// True when the segment a-b stays inside the region bounded by `region` loops (material on
// the right): it crosses none of them away from its end points and its midpoint is inside.
bool segment_inside(const std::vector<const std::vector<Seg2>*>& region, const Vec2& a,
                    const Vec2& b);

}  // namespace ncpath
