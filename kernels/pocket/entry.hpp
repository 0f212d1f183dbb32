#pragma once
// Entry moves of a pocket path: how the tool gets from one height to the next, down into the
// material, at the start point of the first loop. Tool-tip points, mm.
//  - helix: the tool centre runs on a circle of radius r around c through the start point,
//    descending at most `angle` per unit of travel, then once more round at the bottom (the
//    floor of the circle is flat); the circle lies where the tool may go when c is at least r
//    from every loop of the region it is in.
//  - ramp: along the first loop as it will be cut, from the start point, descending over
//    (z0 - z1) / tan(angle) mm of travel (several times round if the loop is short), then
//    along the loop at z1 back to the start point. The loop is where the tool centre may go.
//  - plunge: straight down.
#include <vector>

#include "kernels/curves/segment.hpp"
#include "kernels/geom/vec.hpp"

namespace ncpath {

// Points from (start, z0) down to (start, z1); the first point is (start, z0). ccw: the
// turning direction. chord: chordal tolerance of the circle, mm.
std::vector<Vec3> helix_points(const Vec2& centre, const Vec2& start, double z0, double z1,
                               double angle_rad, bool ccw, double chord);

// Points from (loop start, z0) down to (loop start, z1) along `loop` (closed, in the
// direction it will be cut).
std::vector<Vec3> ramp_points(const std::vector<Seg2>& loop, double z0, double z1, double angle_rad,
                              double chord);

}  // namespace ncpath
