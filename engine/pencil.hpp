#pragma once
// Pencil-cut clean-up of concave creases with a ball-end mill (issue 6, seed method 3,
// section 3), on the curve-based scans of issue 5.
//
// Stages (each timed):
//   1. candidates: the sharp-concave junctions of the exact CL curves of both drive-plane
//      families (engine/scan.hpp) at `interval`, and of the z-level contours
//      (engine/zlevel.hpp) at `step_down` (near-vertical creases cross no drive plane);
//      junctions with the floor are not creases of the part and are left out;
//   2. pencil points: candidates whose 3-D bi-contact angle (between b1 and b2) is at least
//      `min_angle` and whose two contacts (R b1 and R b2 below the ball centre) lie within
//      `tolerance` of the part (a z-level junction on a shadow puts its contact on the
//      vertical below the element: under an overhang, or beside a wall that is not quite
//      vertical, that is in the air; stats.contactless_points);
//      each is kept in the family whose layers its crease crosses most steeply
//      (kernels/cleanup/pencil.hpp, pencil_keep);
//   3. tracing: pencil points on consecutive layers of a family linked along their crease
//      tangents (b1 x b2) into chains; a chord A -> B whose error bound
//      h = d sin(thA) sin(thB) / sin(thA + thB) exceeds `tolerance` is refined by the exact
//      crease point on an intermediate drive plane (the local intersection of the two offset
//      elements, found by the exact envelope of that plane near the chord), recursively;
//   4. safety: the ball is swept along every chord exactly (engine/surface_check.hpp
//      lift_swept, MeshDistance::march with radius R - 1e-7); a chord whose ball touches
//      the part has both ends moved away from both contacts (along b1 + b2; straight up
//      where that would leave a point below the drop-cutter surface), first by its largest
//      penetration at samples a tenth of the interval apart over the cosine to the contact
//      normal, then in doubling steps until clear; a chord that would need more than
//      max(10 tolerance, 0.05 mm) has left the crease (two creases the refinement could not
//      bridge, or a wall in the way), or has an end the ball cannot reach from above
//      (surface_check.hpp reachable), and the piece is split there, so the path never
//      gouges (to 1e-7 mm);
//   5. pieces closer than `merge_distance` end to end are joined, pieces shorter than
//      `min_length` dropped, and the rest ordered and oriented greedily to shorten the air
//      moves between them. With a cut `direction` (climb or conventional, spindle M3:
//      kernels/cleanup/cut_direction.hpp) every piece with a material side is first turned
//      to run that way and the ordering keeps it; pieces without one (a symmetric V-groove,
//      a vertical corner) keep the orientation the ordering gives them.
// Conditioning. The mesh is first conditioned (kernels/mesh/condition.hpp): near-coplanar
// facets made coplanar, near-vertical walls vertical, so that the answer does not depend on
// how many digits the file carried; everything below runs on it with the stock grown by the
// largest vertex move (stats.condition.max_move, at most tol::kConditionMove).
// Stock to leave. With `stock` s the tool keeps s from the part everywhere: its centre runs
// on the offset surface at distance R + s. The stages above run for a ball of radius R + s
// (whose centre is the same) and every output point (paths, pencil points) is raised by s,
// the tool tip being centre - R z. s may be negative, down to > -R. The floor is treated
// like the part: the grown ball's tip rests on it (z = floor_z), so with stock the tool tip
// stays at least floor_z + s.
// Output: one cut path per piece (tool tip, mm), a rapid before every piece but the first,
// and the pencil points with their bi-contact vectors and angle.
#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "engine/cl_chunk.hpp"
#include "engine/run_control.hpp"
#include "kernels/cleanup/cut_direction.hpp"
#include "kernels/cutters/cutter.hpp"
#include "kernels/mesh/condition.hpp"
#include "kernels/geom/vec.hpp"
#include "kernels/mesh/triangle_mesh.hpp"

namespace ncpath {

struct PencilParams {
  double interval = 0.5;        // mm between drive planes (both families)
  double step_down = 1.0;       // mm between z-levels for near-vertical creases (0: none)
  double min_angle_deg = 20;    // bi-contact angle threshold, degrees
  double tolerance = 0.01;      // mm: chord error bound and drop-cutter check
  double merge_distance = 0;    // mm; 0: 2 * interval
  double min_length = 1.0;      // mm: shorter pieces are dropped
  // mm the drive planes reach beyond the part's xy box, besides the ball's radius they always
  // reach (every ball that touches the part)
  double margin = 0;
  // mm: a plane below the part where the grown ball (R + stock) rests, tool tip z of that
  // ball; the tool tip stays at least floor_z + stock. Default: the part's lowest z.
  std::optional<double> floor_z;
  double stock = 0;  // mm the tool keeps from the part (and the floor); > -R, see above
  CutDirection direction = CutDirection::kAny;  // kAny: oriented for short air moves only
  // Internal (no job key): the z-levels and the drive planes slice only the concave zone
  // (engine/concave_zone.hpp) when at most this share of its centre balls pair (concave_zone's max_paired_share). A
  // sliced subset has contours along its border on every level below it, so a wide zone
  // costs more than the whole part: bunny00 (75 k facets, 200 mm, ball 5) pairs 23 % and
  // keeps 53 % of the facets, and its z-levels took 3.9 s sliced against 1.9 s whole; its
  // Loop x2 scan (1.2 M) pairs 12 %, keeps 20 % and took 7.4 s against 16.9 s
  // (docs/performance.md, "The concave zone"). Tests set 0 (never) and 1 (always) to check
  // that the result does not depend on it.
  double zone_max_share = 1.0 / 6;
};

// Empty when usable; else a message naming the bad key. (The stock's lower bound depends on
// the ball: validate_stock.)
std::string validate(const PencilParams& params);

// Empty when stock (mm) is usable with a ball of radius R (mm): finite and > -R; else a
// message naming the key "stock".
std::string validate_stock(double stock, double radius);

struct PencilPoint {
  Vec3 position = Vec3::Zero();  // tool tip, mm
  Vec3 b1 = Vec3::Zero(), b2 = Vec3::Zero();
  double angle = 0;            // rad between b1 and b2
  std::uint8_t family = 0;     // 0 x lines, 1 y lines, 2 z-levels
  std::uint8_t kept = 0;       // 1: traced in this family (pencil_keep)
};

struct PencilStats {
  std::uint64_t planes = 0, levels = 0;
  std::uint64_t zlevel_open_chains = 0;  // z-level contours left open (their junctions lost)
  // Facets the z-levels and the drive planes sliced for candidates: the concave zone's
  // (engine/concave_zone.hpp) when it is narrow (PencilParams::zone_max_share), else all;
  // zone_s: finding the zone.
  std::uint64_t sliced_facets = 0;
  double zone_s = 0;
  std::uint64_t candidates = 0;     // sharp-concave junctions seen
  std::uint64_t pencil_points = 0;  // with angle >= min_angle
  // Candidates with angle >= min_angle dropped because a contact is farther than `tolerance`
  // from the part (z-level junctions under an overhang); not in pencil_points.
  std::uint64_t contactless_points = 0;
  // Candidates dropped because the ball hangs over the part's outline, on a sharp edge of it
  // (engine/pencil_outline.hpp); not in pencil_points.
  std::uint64_t hanging_points = 0;
  std::uint64_t kept_points = 0;    // after the family choice
  std::uint64_t chains = 0;         // linked chains before merging
  std::uint64_t refined_points = 0;  // exact crease points added by refinement
  std::uint64_t lifted_points = 0;   // path points raised by the drop-cutter check
  std::uint64_t split_chords = 0;    // chords that left the crease (pieces split there)
  std::uint64_t paths = 0;           // pieces cut
  std::uint64_t neutral_paths = 0;   // with a cut direction: pieces without a material side
                                     // (oriented by the ordering); 0 with kAny
  double traced_length = 0;          // mm, cut length of the pieces
  double air_length = 0;             // mm, straight distance between consecutive pieces
  double elements_s = 0, scan_s = 0, zlevel_s = 0, link_s = 0, refine_s = 0, check_s = 0;
  double index_s = 0;  // the drop-cutter and distance indexes (refinement and check)
  // The input conditioning (kernels/mesh/condition.hpp; its time is in elements_s): the
  // stages run with the stock grown by condition.max_move.
  ConditionStats condition;
};

struct PencilResult {
  std::vector<std::vector<Vec3>> paths;  // in cutting order, tool tip, mm
  // Per path point, the bi-contact vectors b1, b2 of the crease there (unit, contact to ball
  // centre; a lifted point keeps those of the crease point below it).
  std::vector<std::vector<std::array<Vec3, 2>>> path_normals;
  std::vector<PencilPoint> points;       // every pencil point (angle >= threshold)
  PencilStats stats;
};

// The cutter must be a ball (radius R). Throws Cancelled, std::invalid_argument for bad
// params (a stock <= -R included).
// `conditioned`: condition_for_slicing(mesh) made once by the caller for several operations
// on the mesh; null: made here.
PencilResult run_pencil(const TriangleMesh& mesh, const Cutter& cutter, const PencilParams& params,
                        RunControl& control, const ConditionedMesh* conditioned = nullptr);

// The result as CL paths (a rapid one-point path before every piece but the first).
ClChunk pencil_chunk(const PencilResult& result);

}  // namespace ncpath
