#pragma once
// Z-level contouring of a mesh with a ball-end mill (issue 5): at each tool-tip level the
// exact contours of the region where the ball would touch the part (kernels/scan/zlevel.hpp),
// as closed CL paths with their typed segments and bi-contact junctions.
//
// Levels: an explicit list, or a step-down from the part's top: top - step, top - 2 step, ...
// while above the part's lowest point; cut from the top down. Candidates per level are the
// prefix of the facets and reachable edges sorted by their highest point (an element whose
// highest point is below the level has no region there); their boxes are gathered once for
// all levels (zlevel_element_boxes). The levels of each chunk (chunk_levels) after the first
// know the region of the previous chunk's last level to lie inside theirs (ZLevelInside in
// kernels/scan/zlevel.hpp): the elements deep inside it are left out of their candidates
// (zlevel_filter_deep, once per chunk, the ones left out before staying out), and the kernel
// drops the regions and certifies the curve pieces lying deep inside it. On a part with
// steep walls most elements above a level are such: anchor_large at 1 mm steps, 20.8 s ->
// about 7 s (docs/performance.md).
//
// Polylines: lines exactly; an arc (circle or ellipse, centre c, axes r1 a and r2 a_perp) by
// the polygon circumscribed to it in its affine frame: vertices at t0 + (j - 1/2) dt scaled by
// 1 / cos(dt / 2), between the exact end points, so that every chord is tangent to the arc and
// lies outside the region (no gouge) within `tolerance` of it (r_max (1/cos(dt/2) - 1) <= tol).
//
// Paths: one closed cut path per contour (first point repeated), each after the first reached
// by a one-point rapid path (retract, move, plunge). Levels run in parallel (TBB), chunks go
// to the sink in order: identical output for any thread count.
#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "engine/cl_chunk.hpp"
#include "engine/concave_zone.hpp"
#include "engine/run_control.hpp"
#include "engine/scan.hpp"  // ScanElementRef
#include "kernels/cutters/cutter.hpp"
#include "kernels/mesh/condition.hpp"
#include "kernels/mesh/triangle_mesh.hpp"

namespace ncpath {

struct ZLevelOpParams {
  std::vector<double> levels;  // tool-tip z, mm (any order); or:
  double step_down = 0;        // mm between levels from the top (0: use `levels`)
  double tolerance = 0.001;    // mm: chordal tolerance of the arcs' polylines
  std::uint32_t chunk_levels = 4;
  // Condition the mesh first (condition_for_slicing, kernels/mesh/condition.hpp) and slice it
  // for the ball grown by the largest vertex move, at the same centre heights: the contours
  // keep the tool clear of the part as given. false: the mesh is conditioned already (pencil).
  bool condition = true;
  // Optional (pencil, fillet), a zone of the mesh as sliced (conditioned or not, as above):
  // slice only its kept facets (zone->kept) and report only the junctions whose ball centre
  // it holds: those are the whole mesh's there (engine/concave_zone.hpp). The contours are
  // then partial.
  const ConcaveZone* zone = nullptr;
};

// Empty when usable; else a message naming the bad key.
std::string validate(const ZLevelOpParams& params);

// Exact contour segments: kind 0 line, 1 circular arc, 2 elliptic arc; geometry (mm, rad):
// centre x, y, r1, r2, angle of `axis` from +x, t0, t1 (arcs: p(t) = centre + r1 cos t axis +
// r2 sin t perp(axis), t from t0 to t1 counter-clockwise; lines: zeros). shadow: the element
// lies above the level there (the ball passes under it: a wall or an overhang).
struct ZLevelSegmentRecord {
  std::int64_t path = 0;  // cut path index within the operation (0, 1, ... over contours)
  std::uint8_t kind = 0;
  std::uint8_t shadow = 0;
  ScanElementRef element;
  std::array<double, 3> start{}, end{};
  std::array<double, 7> geometry{};
};

// Junctions: the same record as the scan's (path, kind, position, b1, b2, elements, angle).
using ZLevelJunctionRecord = ScanJunctionRecord;

struct ZLevelChunk {
  ClChunk cl;
  std::vector<ZLevelSegmentRecord> segments;
  std::vector<ZLevelJunctionRecord> junctions;
  std::vector<double> contour_level;      // per contour (cut path): its tip z
  std::vector<std::uint8_t> contour_hole;  // per contour: 1 when a hole (clockwise)
};

struct ZLevelOpStats {
  std::uint64_t levels = 0, contours = 0, holes = 0, segments = 0, points = 0;
  std::uint64_t junctions = 0, sharp_concave = 0, tangent = 0, convex = 0;
  std::uint64_t candidates = 0;   // summed over levels
  std::uint64_t open_chains = 0;  // contours the kernel could not close (0 expected)
  std::uint64_t facets = 0, edges = 0, vertices = 0;
  double top_z = 0, bottom_z = 0;  // the part's z range, mm
  ConditionStats condition;        // the input conditioning (zeros when not asked)
  double elements_s = 0, compute_s = 0, sink_s = 0;
};

// The cutter must be a ball. Throws Cancelled, std::invalid_argument for bad params.
// `conditioned`: condition_for_slicing(mesh) made once by the caller for several operations
// on the mesh (used when params.condition); null: made here.
ZLevelOpStats run_zlevel(const TriangleMesh& mesh, const Cutter& cutter,
                         const ZLevelOpParams& params,
                         const std::function<void(const ZLevelChunk&)>& sink,
                         RunControl& control, const ConditionedMesh* conditioned = nullptr);

}  // namespace ncpath
