#pragma once
// Cut direction of the clean-up paths (pencil, fillet) for a spindle turning clockwise seen
// from above (M3). Climb milling keeps the material being cut on the right of travel: there
// the teeth sweep backwards, so they meet the material moving with the feed and leave it
// thick to thin; conventional milling keeps it on the left. (The convention of Milling,
// engine/pocket_path.hpp: "climb" means the same for every operation.)
//
// Material side of a crease. At a crease point the ball touches two surfaces; b1, b2 are the
// unit vectors from the contacts to the ball centre. m = -(b1 + b2) projected on xy points
// from the centre into the corner, where the material is; its length is how lopsided the
// crease is seen from above: 1 at the foot of a vertical wall (b1 the floor's (0, 0, 1),
// b2 the wall's normal), 0 in a symmetric V-groove, whose material lies equally on both
// sides. A path p_0 ... p_n with material vectors m_i has the score
//   S = sum over chords of (t_i x z) . (m_i + m_{i+1}) / 2,   t_i = (p_{i+1} - p_i) on xy,
// t x z being the right-hand normal of t scaled by the chord's xy length (mm): S > 0 when
// the material lies mostly on the right of travel (climb), S < 0 on the left
// (conventional). Reversing the path negates S. A path whose |S| is at most
// tol::kCutSideNeutral times its xy length (symmetric grooves, vertical corners) has no side.
#include <array>
#include <cstdint>
#include <span>
#include <string_view>

#include "kernels/geom/tolerance.hpp"
#include "kernels/geom/vec.hpp"

namespace ncpath {

enum class CutDirection : std::uint8_t {
  kAny,           // no preference: the operation's own orientation (shortest air moves, zig-zag)
  kClimb,         // the material on the right of travel (spindle M3)
  kConventional,  // the material on the left of travel
};

const char* cut_direction_name(CutDirection direction);  // "any", "climb", "conventional"
// "any" / "climb" / "conventional" -> out; false (out untouched) for anything else.
bool parse_cut_direction(std::string_view text, CutDirection& out);

// m = -(b1 + b2) on xy: from the ball centre into the corner (not normalised).
Vec2 material_vector(const Vec3& b1, const Vec3& b2);

struct CutSideScore {
  double score = 0;      // S above, mm: > 0 climb, < 0 conventional as the path runs
  double xy_length = 0;  // mm: the path's length projected on xy
};

// The score of a path (tool points, mm) with the bi-contact vectors {b1, b2} of its crease at
// each point (normals.size() == path.size()).
CutSideScore cut_side_score(std::span<const Vec3> path,
                            std::span<const std::array<Vec3, 2>> normals);

// +1: the path as it runs is cut climb, -1: conventional, 0: it has no material side
// (|score| <= neutral * xy_length).
int cut_side(const CutSideScore& s, double neutral = tol::kCutSideNeutral);

// Whether a path of side `side` (cut_side) must be reversed to be cut in `direction`: never
// for kAny or side 0.
bool reverse_for(CutDirection direction, int side);

}  // namespace ncpath
