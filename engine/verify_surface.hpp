#pragma once
// The verifier for sculptured pocket bottoms (pocket3d, ball-end mills): every move of the
// ball against the exact NURBS bottom (kernels/verify/surface_distance.hpp), and the scallop
// the whole path leaves: on a plan grid over the reachable bottom, the lowest point the ball's
// surface passed over each grid point minus the bottom's height there.
//
// "Reachable": inside the pocket (inside the boundary, outside the islands) and at least
// `reach` mm from every wall (inside the outermost pass: R + stock plus the planner's
// documented margins, batch/jobs/job_verify.cpp), so that corners the ball cannot enter and
// the band along the walls no pass is spaced for are not counted.
#include <vector>

#include "engine/cl_chunk.hpp"
#include "engine/verify_report.hpp"
#include "kernels/pocket/profile.hpp"
#include "kernels/verify/surface_distance.hpp"
#include "kernels/verify/wall_distance.hpp"

namespace ncpath {

// Moves of one chunk: where the ball (radius R, tip at the CL points) cuts into the bottom.
VerifyReport verify_bottom_moves(const SurfaceProbe& bottom, const ClChunk& cl, double radius,
                                 double top, std::uint64_t first_move = 0,
                                 std::uint32_t first_path = 0);

class ScallopGrid {
 public:
  // spacing: grid step in x and y, mm. walls: the pocket's walls (their cap must exceed reach).
  ScallopGrid(const std::vector<Region>& regions, const WallSet& walls, const SurfaceProbe& bottom,
              double radius, double reach, double spacing);
  // Lowers every grid point's envelope by the ball swept along the chunk's moves below top.
  void add(const ClChunk& cl, double top);
  // Largest (envelope - bottom) over reachable grid points passed over by the ball; where.
  double max_scallop(Vec2* where = nullptr) const;
  std::size_t points() const { return xy_.size(); }

 private:
  double radius_, spacing_;
  std::vector<Vec2> xy_;        // reachable grid points
  std::vector<double> bottom_;  // the bottom's z there
  std::vector<double> lowest_;  // lowest ball surface so far (+inf: never passed over)
};

}  // namespace ncpath
