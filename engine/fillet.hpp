#pragma once
// Fillet-cut clean-up (issue 6, seed method 3, section 4): after finishing with a reference
// ball of radius R_ref, a smaller ball (radius r < R_ref) removes what the reference left in
// concave creases, in passes that follow the reference tool's pencil paths.
//
// At a point of a reference pencil path the reference ball's centre P touches two surfaces,
// b1 and b2 the unit vectors from the contacts to P, beta the angle between them and
// t = b1 x b2 / |b1 x b2| the crease direction. Rotating b1 toward b2 about t gives
// v_j (theta_j = beta j / n, j = 0..n); the ray from P along -v_j meets the clean-up ball's
// CL surface (the centres at distance r from the part) where the small ball, moving from P
// toward the part, first touches it: the ray is marched with the exact distance to the mesh
// (engine/mesh_distance.hpp, sphere tracing: never past the first contact), so the point is
// gouge-free by construction. j = 0 and j = n put the small ball where the reference ball
// touched each surface; the passes in between sweep the fillet. The points of pass j along
// the pencil path are linked into one path (tool tip = centre - r z). The number of passes
// comes from the step-over between neighbouring passes (or from a scallop height h, step
// 2 sqrt(2 r h - h^2)), measured at the widest point of the path.
//
// Output: per pencil path, passes zig-zag (pass 0 forward, pass 1 backward, ...) joined by
// links at depth; every chord is checked by the exact swept ball (lift_swept, no lift limit;
// a touching chord is lifted by its sampled drop-cutter deficits, then until clear)
// (engine/surface_check.hpp); points the small ball cannot reach from above (under an
// overhang) are dropped.
//
// Cut direction (`direction`, spindle M3, kernels/cleanup/cut_direction.hpp). kAny: the
// zig-zag above. kClimb / kConventional: every pass runs one way, the way that cuts in that
// direction, judged by the material side of the reference crease (its b1, b2 at the pencil
// path points the pass's points come from); consecutive passes are joined by a one-point
// rapid path (the next pass's first point) instead of a link at depth. A pass without a
// material side (a symmetric groove) runs along its pencil path.
//
// Stock to leave (`stock` s, > -r): both balls keep s from the part. The reference pencil
// paths are those of run_pencil with that stock (a reference ball of radius R_ref + s), the
// small ball's centres are where a ball of radius r + s first touches the part, and the tips
// (centre - r z) lie s above those of that grown ball; the floor is treated like the part
// (engine/pencil.hpp). The scallop height is measured for the real ball r: on the stock
// surface, the part offset by s.
//
// FilletParams::stock and ::direction are the fillet's own: they apply to both balls and to
// the passes. The nested `pencil` params say how the reference paths are found; their own
// stock and direction must stay at the defaults (0, kAny: the reference run gets the
// fillet's stock, and its paths keep the ordering's orientation).
#include <cstdint>
#include <string>
#include <vector>

#include "engine/cl_chunk.hpp"
#include "engine/pencil.hpp"
#include "engine/run_control.hpp"
#include "kernels/cutters/cutter.hpp"
#include "kernels/mesh/triangle_mesh.hpp"

namespace ncpath {

struct FilletParams {
  double reference_diameter = 10;  // mm: the finishing ball whose pencil paths are followed
  PencilParams pencil;             // how the reference pencil paths are found
  double stepover = 0;             // mm between neighbouring passes (0: from `scallop`)
  double scallop = 0.005;          // mm: cusp height between passes when stepover is 0
  std::uint32_t max_passes = 64;   // most passes per pencil path
  double stock = 0;                // mm both balls keep from the part, > -r (see above)
  CutDirection direction = CutDirection::kAny;  // kAny: zig-zag; else one-way passes
};

// Empty when usable; else a message naming the bad key. (The stock's lower bound depends on
// the clean-up ball: validate_stock, engine/pencil.hpp.)
std::string validate(const FilletParams& params);

struct FilletStats {
  PencilStats pencil;               // the reference pencil run
  std::uint64_t passes = 0;         // over all pencil paths
  std::uint64_t points = 0;         // fillet CL points
  std::uint64_t rays = 0, misses = 0;  // rays marched; rays that met nothing (dropped points)
  std::uint64_t unreachable = 0;    // points under an overhang (dropped)
  std::uint64_t lifted_points = 0;
  // With a cut direction: passes without a material side (run along their pencil path); 0
  // with kAny.
  std::uint64_t neutral_passes = 0;
  double cut_length = 0;            // mm
  double pencil_s = 0, rays_s = 0;  // reference pencil; rays, passes and their check
};

struct FilletResult {
  std::vector<std::vector<Vec3>> paths;  // tool tip, mm, in cutting order
  std::vector<PathKind> kinds;           // kCut for passes, kLinkAtDepth between them (kAny)
                                         // or kRapid (one point), kRapid between pencil paths
  FilletStats stats;
};

// `cutter` is the clean-up ball (radius r < reference radius). Throws Cancelled,
// std::invalid_argument for bad params (a stock <= -r included).
// `conditioned`: as for run_pencil (the reference ball's pencil paths).
FilletResult run_fillet(const TriangleMesh& mesh, const Cutter& cutter, const FilletParams& params,
                        RunControl& control, const ConditionedMesh* conditioned = nullptr);

ClChunk fillet_chunk(const FilletResult& result);

}  // namespace ncpath
