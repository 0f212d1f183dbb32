#pragma once
// Pockets with a sculptured (NURBS) bottom and a ball-end mill (issue 7, seed method 1).
//
// Formulation (CL-Cartesian; the seed intersects the ruled surface through each offset
// profile with the bottom, which is the same path seen from the contact side): the tool
// centre runs in plan on the contour-parallel offset profiles of the pocket (boundary
// shrinking by R + stock, islands growing), and at every plan point the tool is dropped onto
// the bottom surface (kernels/surface/surface_drop.hpp: exact ball drop) — the CL point is
// the tip, the CC point and the surface normal come with it. Walls and islands are never
// gouged (the ball's plan footprint stays within R of its centre, which keeps R + stock
// from them) and neither is the bottom (every CL point is a drop, and every straight move
// between two is raised until it clears the drop curve at its check points).
//
//  - Path interval: for each level region the plan distance to the next level is the
//    smallest, along its loops, of the distance between neighbouring passes that leaves a
//    scallop of height h on the bottom: with the normal curvature k of the bottom across
//    the path at the contact point (radius rho = 1/k, > 0 for a dome) the ball centres lie
//    on a curve of radius rho + R, and the cusp between two balls R from both centres at
//    rho + h from the curvature centre gives their chord
//      L = 2 |rho + R| sqrt(q (2 - q)),  q = (2 R h - h^2) / (2 (rho + R)(rho + h)),
//    (flat bottom: L = 2 sqrt(2 R h - h^2)); the plan distance is L / sqrt(1 + m^2) with m
//    the bottom's slope across the path.
//  - Step length: along every run of moves of one kind, the fewest CL points such that the
//    chords stay within eps of the plan path, keep R + stock from walls and islands (the
//    first level is placed eps/2 farther from them, so chords may sag toward them), and
//    stay within delta/2 of the drop curve either way (checked every R/2, at least 3
//    points); each chord the longest that passes (doubling, then four bisections); then
//    chords that dip below the drop curve at a check point are raised (both ends) by the
//    deficit: never below the bottom, at most delta above it.
//  - Where the next offset by the interval is empty, a level at half the interval (the
//    centre or the middle of a ring would otherwise be up to twice the interval wide).
//  - Order, linking, clean-up of uncut regions: as for flat pockets (engine/pocket_stages);
//    one continuous path per part; entry by plunge to the first CL point.
#include <cstdint>
#include <string>
#include <vector>

#include "engine/cl_chunk.hpp"
#include "engine/pocket_path.hpp"  // CutOrder, Milling, RegionTooSmall
#include "kernels/pocket/profile.hpp"
#include "kernels/surface/nurbs_surface.hpp"

namespace ncpath {

struct Pocket3dParams {
  double tool_radius = 6;   // ball radius R, mm
  double scallop = 0.4;     // cusp height h left between passes, mm, in (0, R)
  double eps = 0.5;         // plan tolerance, mm
  double delta = 0.5;       // surface tolerance, mm
  double stock = 0;         // left on walls and islands, mm (plus eps / 2: see above)
  double tolerance = 0.01;  // profile NURBS curves become arcs within this, mm
  double top = 0;           // stock top, mm
  double clearance = 1;     // above top where feed moves start, mm
  double safe_z = 5;        // rapids, mm, >= top + clearance
  double min_interval = 0;  // smallest plan path interval, mm (0: R / 100)
  // Where a level region's next offset by its interval is empty, one more level at half the
  // interval, so that the middle of the last gap (the centre of a pocket, the middle of a
  // ring around an island) keeps the scallop bound too. Off: exactly the flat pocket's
  // levels.
  bool half_step_last = true;
  CutOrder order = CutOrder::kOutward;
  Milling milling = Milling::kClimb;
};

struct Pocket3dStats : PocketPlanStats {
  std::uint64_t cl_points = 0;                // CL points of cutting and linking moves
  std::uint64_t drops = 0;                    // ball drops onto the bottom (CL points and checks)
  std::uint64_t lifted_points = 0;            // CL points raised so that chords clear the bottom
  double max_lift = 0;                        // mm
  double min_interval = 0, max_interval = 0;  // plan path intervals used, mm
  double cl_s = 0;                            // seconds: CL points (drops, chord checks, lifting)
};

struct Pocket3dPath {
  ClChunk cl;                  // tool tips in cutting order (kinds as for flat pockets)
  std::vector<double> cc;      // 3 per CL point: contact point, NaN off the bottom
  std::vector<double> normal;  // 3 per CL point: upward unit bottom normal at cc, or NaN
  std::vector<double>
      loop_interval;  // per offset loop: plan distance from its parents (0: level 1)
  std::vector<std::uint32_t> loop_level;  // per offset loop
  Pocket3dStats stats;
};

// "" when usable, else a message naming the bad parameter.
std::string validate(const Pocket3dParams& p);

// Throws std::invalid_argument for bad parameters, a bad surface (validate /
// check_height_field message), a pocket that does not lie over the surface ("boundary point
// (x, y) of region 0 is outside the bottom surface's plan outline"), and RegionTooSmall.
Pocket3dPath plan_pocket3d(const std::vector<Region>& regions, const NurbsSurface& bottom,
                           const Pocket3dParams& params);

// The plan chord between neighbouring ball centres that leaves a cusp of height h over a
// bottom of signed curvature radius rho (> 0 convex; +inf flat), ball radius r.
double scallop_chord(double r, double h, double rho);

}  // namespace ncpath
