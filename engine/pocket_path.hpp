#pragma once
// Pocket tool paths (issue 4): from pocket regions (boundary + islands) to one linked,
// retraction-free tool path per connected part of the pocket, at one or several depths.
//
// Stages (each timed in the statistics):
//  1. offsets: contour-parallel levels with the offset generation history (OGH),
//     engine/pocket_offset.hpp;
//  2. uncut regions: between every pair of consecutive levels (and inside the innermost
//     loops) the band eroded by the tool radius, kernels/pocket/uncut.hpp; each loop of an
//     uncut region becomes a clean-up curve (the tool centre runs along it, which covers the
//     region since its inradius is at most stepover - R <= R), attached to a bounding level
//     loop by a link of length R (inside the disc the tool swept there);
//  3. linking: BFS over the OGH from the start loop gives the tool-path tree with the
//     fewest links; every link joins two loops of consecutive levels by a segment of length
//     `stepover` (so it lies inside the material of the outer level); siblings are ordered
//     along their parent loop; the child with the largest subtree is cut last, one way;
//     DFS gives one path (kernels/pocket/path_plan.hpp);
//  4. depth passes and entry: a helix inside the first loop when it fits, else a ramp along
//     it, else a plunge; passes at every step-down are joined at depth.
// A retraction happens only between parts of the pocket that are disconnected at the
// tool's reach (different level-1 regions).
//
// Coordinates: mm; the stock top is z = top, the floor z = top - depth; CL points are the
// tool tip. Material to cut lies on the right of boundaries (clockwise) and islands
// (counter-clockwise), as everywhere in kernels/pocket.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine/cl_chunk.hpp"
#include "kernels/pocket/profile.hpp"

namespace ncpath {

enum class CutOrder : std::uint8_t {
  kOutward,  // default: start at the innermost loop, cut outward (least slotting)
  kInward,   // seed 000: start at an island's first level (else the boundary's), cut inward
};
enum class Milling : std::uint8_t {
  kClimb,         // spindle M3 (clockwise): the material being cut on the right of travel
  kConventional,  // the opposite direction
};

struct PocketPathParams {
  double tool_radius = 3;            // mm, > 0
  double stepover = 1.5;             // mm, in (0, 2 * tool_radius]
  double stock = 0;                  // mm left on walls and islands, >= 0
  double tolerance = 0.01;           // mm: NURBS curves become arcs within this
  double chordal_tolerance = 0.001;  // mm: arcs become CL polylines within this
  double top = 0;                    // z of the stock top, mm
  double depth = 1;                  // mm below top, > 0
  double stepdown = 0;               // mm per pass; 0: one pass at full depth
  double clearance = 1;              // mm above top where feed moves start
  double safe_z = 5;                 // mm, absolute: height of rapids, >= top + clearance
  CutOrder order = CutOrder::kOutward;
  Milling milling = Milling::kClimb;
  double helix_radius = 0;    // mm; 0: half the tool radius
  double ramp_angle_deg = 3;  // helix and ramp descent angle, degrees, in (0, 90)
};

// Statistics of every contour-parallel pocket (flat here, sculptured in engine/pocket3d.hpp).
struct PocketPlanStats {
  std::uint64_t loops = 0;           // offset loops (one depth)
  std::uint64_t levels = 0;          // deepest level
  std::uint64_t open_fragments = 0;  // offset pieces that did not close (0 when all is well)
  std::uint64_t components = 0;      // parts of the pocket cut as one path each
  std::uint64_t links = 0;           // loop-to-loop links per pass
  std::uint64_t cleanup_curves = 0;  // per pass
  double cut_length = 0;             // mm, cutting moves (loops, clean-up, entries)
  double link_length = 0;            // mm, links at depth (loop to loop, pass to pass)
  double rapid_length = 0;           // mm, moves at safe height and retractions
  std::uint64_t retractions = 0;     // climbs to safe height between components
  double uncut_area_before = 0;      // mm^2, uncut regions of the offset loops alone
  double uncut_area_after = 0;       // mm^2, what the clean-up curves do not cover
  double unreachable_area = 0;       // mm^2, corners and gaps the tool cannot reach
  double offset_s = 0, uncut_s = 0, link_s = 0;  // seconds per stage
};

struct PocketPathStats : PocketPlanStats {
  std::uint64_t depth_passes = 0;
  double cleanup_length = 0;   // mm, clean-up curves and their links, all passes
  double slotting_length = 0;  // mm, full-engagement cutting (estimate, see docs)
  std::uint64_t helix_entries = 0, ramp_entries = 0, plunge_entries = 0;
  double path_s = 0;  // seconds: entries, passes, CL points
};

struct PocketPath {
  // The whole job in cutting order: kCut (loops, clean-up curves, entries), kLinkAtDepth
  // (links between loops and between passes), kRapid (moves at safe_z). Consecutive paths
  // join end to start.
  ClChunk cl;
  PocketPathStats stats;
};

// A region the tool does not fit in (regions[region]): "region 2 (boundary starting at
// (x, y)): the tool (diameter 6 mm, stock 0 mm) does not fit in the pocket".
struct RegionTooSmall : std::invalid_argument {
  RegionTooSmall(std::size_t r, const std::string& message)
      : std::invalid_argument(message), region(r) {}
  std::size_t region;  // index into the regions passed in
};

// Throws std::invalid_argument with a clear message for bad parameters (stepover <= 0 or
// larger than the tool diameter, depth <= 0, negative stock, ...), RegionTooSmall for a
// region the tool does not fit in.
// The output is the same for any thread count.
PocketPath plan_pocket(const std::vector<Region>& regions, const PocketPathParams& params);

// "" when the parameters are usable, else a message naming the bad one.
std::string validate(const PocketPathParams& params);

}  // namespace ncpath
