#pragma once
// Keeping polylines of tool-tip points on or above a mesh's drop-cutter surface (the CL
// surface of the cutter), checked by the exact point drop-cutter (engine/drop_index.hpp).
// Used by the clean-up operations, whose points come from crease tracing and ray marching
// rather than from the drop-cutter itself.
#include <cstddef>
#include <vector>

#include "engine/drop_index.hpp"
#include "kernels/geom/vec.hpp"

namespace ncpath {

// How far the tool tip at q is below the CL surface (mm, <= 0 when on or above it). The
// drop-cutter height is only upper semicontinuous: at the foot of a wall it is the wall's
// top although the tool there merely touches the wall (or, in a corner, both walls). A real
// gouge is an open set, so the smallest deficit over q and its eight neighbours 1e-6 mm away
// tells them apart; gouges narrower than that are not seen.
double surface_deficit(const DropIndex& index, double floor_z, const Vec3& q);

// Raises points so that the polyline lies on or above the CL surface at its points and at
// samples along every chord no farther apart than `spacing` (at least its middle): a chord
// whose samples dip is lifted at both ends by the largest dip; the chords next to a raised
// point are checked again (a lift can expose a neighbour), up to three passes. Returns the
// number of points raised.
std::size_t lift_above_surface(const DropIndex& index, double floor_z, double spacing,
                               std::vector<Vec3>& points);

}  // namespace ncpath
