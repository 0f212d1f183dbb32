#pragma once
// The verifier for 2.5-D pockets (offset, pocket, and the walls of pocket3d): every move of
// the CL data against the input's walls and islands (their exact lines, arcs and NURBS
// curves, kernels/verify/wall_distance.hpp) and the floor.
//
// A move is the straight segment between consecutive points of one path. Below the stock top
// the tool's widest radius at or under the top (R, or less for a move whose tool barely dips
// below the top with a corner radius) must keep stock from every wall along the whole move:
// the horizontal distance from the move's xy segment to the walls is computed (a lower bound
// within `resolution` for NURBS). No move may go below the floor. Rapids that travel
// sideways must stay at or above `rapid_limit`; vertical rapids (retracts, approaches) are
// checked like feed moves. It does not use the planner's offsets, arcs or entries.
#include <limits>

#include "engine/cl_chunk.hpp"
#include "engine/verify_report.hpp"
#include "kernels/cutters/cutter.hpp"
#include "kernels/geom/tolerance.hpp"
#include "kernels/verify/wall_distance.hpp"

namespace ncpath {

struct ProfileVerifyParams {
  Cutter cutter;
  double stock = 0;                                         // mm to leave on walls and islands
  double top = 0;                                           // z of the stock top, mm
  double floor = -std::numeric_limits<double>::infinity();  // z, mm; -inf: no flat floor
  double rapid_limit = 0;  // z that rapids must not go below (top + clearance), mm
  double gouge_tolerance = tol::kVerifyGouge;
  double resolution = tol::kVerifyResolution;
  std::size_t worst = 8;
};

// The walls of `regions`, indexed for a tool of this radius plus stock.
WallSet profile_walls(const std::vector<Region>& regions, const ProfileVerifyParams& params);

// Checks the moves of one chunk; first_move / first_path: how many the job had before it.
// Parallel over moves; the same report for any thread count.
VerifyReport verify_profile_moves(const WallSet& walls, const ClChunk& cl,
                                  const ProfileVerifyParams& params, std::uint64_t first_move = 0,
                                  std::uint32_t first_path = 0);

}  // namespace ncpath
