#pragma once
// Keeping polylines of tool-tip points on or above a mesh's drop-cutter surface (the CL
// surface of the cutter), checked by the exact point drop-cutter (engine/drop_index.hpp).
// Used by the clean-up operations, whose points come from crease tracing and ray marching
// rather than from the drop-cutter itself.
#include <array>
#include <cstddef>
#include <vector>

#include "engine/drop_index.hpp"
#include "engine/mesh_distance.hpp"
#include "kernels/geom/tolerance.hpp"  // tol::kSurfaceSlack, tol::kReachSlack, tol::kSweepSlack
#include "kernels/geom/vec.hpp"

namespace ncpath {

// How far the tool tip at q is below the CL surface (mm, <= 0 when on or above it or less
// than tol::kSurfaceSlack below it: a point computed on the surface, e.g. an exact crease point,
// needs one query, not nine). The
// drop-cutter height is only upper semicontinuous: at the foot of a wall it is the wall's
// top although the tool there merely touches the wall (or, in a corner, both walls). A real
// gouge is an open set, so the smallest deficit over q and its eight neighbours 1e-6 mm away
// tells them apart; gouges narrower than that are not seen.
// A measure for refinement and lift sizes, not a safety check: the paths are made safe by
// lift_swept and checked by the job's verifier.
double surface_deficit(const DropIndex& index, double floor_z, const Vec3& q);

// The part as the ball-end clean-up operations see it: its drop-cutter (the ball of `radius`),
// its exact distance (the swept ball), the lowest tip and the part's top.
struct PartProbe {
  const DropIndex& index;
  const MeshDistance& distance;
  double radius;   // mm, the index's ball
  double floor_z;  // mm: the tool touches nothing lower
  double top_z;    // mm, the part's highest point
};

// Whether the ball with its tip at q can be there, reached from above (exact): q is not below
// floor_z, the ball at q is in the part by at most tol::kReachSlack, and the ball swept straight
// up from q to the part's top (radius - tol::kReachSlack, MeshDistance::march) touches nothing,
// so the shank's space is free. One drop-cutter query when q is on or above the CL surface.
// Unlike surface_deficit's neighbours, it tells a ball touching a steep wall (reachable)
// from one 1.8e-4 mm under a near-vertical wall's CL surface (not), which the fillet-cut of
// anchor_dense had taken for reachable.
bool reachable(const PartProbe& part, const Vec3& q);

// The exact check: the ball (radius R) swept along every chord of the tool-tip polyline, by
// MeshDistance::march with radius R - tol::kSweepSlack, so a chord is accepted only if its ball
// nowhere comes closer than that to the mesh (not just at samples: a crease bending sideways
// between two samples dips in between). A chord that does is lifted at both ends: the first
// time by the largest drop-cutter deficit at its samples (no farther apart than `spacing`;
// 0: none) and where its ball first touches, later by at least twice its previous lift (the
// first repeat by the deficit where it touches then); it
// and its neighbours are swept again, up to `rounds` rounds. A chord whose lifts would add
// up to more than max_lift (mm: a wall in the way, or a link that left the crease) is not
// lifted further. Points below floor_z are raised to it. Returns the number of points
// raised; `touching` (when given) gets one flag per chord: still touching at the end
// (callers must not cut such a chord). `directions` (when given): per point, the unit
// direction it is lifted in instead of +z (the pencil's: away from both contacts, which also
// clears a ball rolling around a vertical edge, where no vertical lift can); the lift is
// then the ball's penetration over the cosine between that direction and the contact normal.
std::size_t lift_swept(const MeshDistance& distance, const DropIndex& index, double floor_z,
                       double radius, double max_lift, double spacing,
                       std::vector<Vec3>& points, int rounds = 24,
                       std::vector<bool>* touching = nullptr,
                       const std::vector<Vec3>* directions = nullptr);

// lift_swept()'s directions for the pencil's crease points: per point, the unit direction
// away from both its contacts, the bisector of the contact normals b1, b2 (from the part to
// the ball's centre), at cos(beta / 2) = |b1 + b2| / 2 to each; up where they nearly oppose.
std::vector<Vec3> away_from_contacts(const std::vector<std::array<Vec3, 2>>& b);

}  // namespace ncpath
