#pragma once
// Pencil-cut tracing (issue 6, seed method 3 section 3): the sharp-concave junctions of the
// scanned CL curves (drive planes of both families and z-level contours) whose 3-D
// bi-contact angle is large enough are pencil points; pencil points on consecutive layers
// (planes, levels) that lie on one crease are linked into chains.
//
// Geometry. At a sharp-concave point the ball touches two elements; b1, b2 are the unit
// vectors from the two contacts to the ball centre. The crease of the CL surface there is
// the intersection of the two offset surfaces, whose normals are b1 and b2: its tangent is
// t = b1 x b2 / |b1 x b2|. The bi-contact angle beta = angle(b1, b2) is how sharp the crease
// is in 3-D (0: smooth); the 2-D turning angle of one drive-plane curve also depends on how
// the plane crosses the crease, which is why the seed uses beta.
//
// Linking. A chord A -> B between two crease points with unit tangents tA, tB deviates from
// the crease (a curve with those end tangents) by at most
//   h = d sin(thA) sin(thB) / sin(thA + thB),
// d = |AB|, thA and thB the angles between the chord and the tangents (the height of the
// triangle formed by the chord and the two tangent lines). A link is accepted when the
// tangents agree and the point lies where A's tangent meets B's layer (within a gap);
// chords whose h exceeds the tolerance are refined by the caller (an exact crease point on
// an intermediate layer) until they pass.
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "kernels/geom/vec.hpp"

namespace ncpath {

// A sharp-concave junction of a scanned CL curve.
struct PencilCandidate {
  Vec3 p = Vec3::Zero();   // CL point (tool tip), mm
  Vec3 b1 = Vec3::Zero();  // unit bi-contact vectors (contact -> ball centre)
  Vec3 b2 = Vec3::Zero();
  std::uint8_t family = 0;  // 0: x lines (planes y = v), 1: y lines (planes x = v), 2: z-levels
  std::uint32_t layer = 0;  // plane or level index within the family (consecutive layers are
                            // adjacent; z-levels count downwards)
};

// Angle between b1 and b2, rad.
double bicontact_angle(const Vec3& b1, const Vec3& b2);

// Unit crease tangent b1 x b2 (zero when b1 and b2 are parallel).
Vec3 crease_tangent(const Vec3& b1, const Vec3& b2);

// Unit normal of a family's layers: y for x lines, x for y lines, z for z-levels.
Vec3 layer_normal(std::uint8_t family);

// The seed's chord error bound h = d sin(thA) sin(thB) / sin(thA + thB) (mm) for the chord
// a -> b and unit tangents ta, tb (their signs do not matter). Infinity when a tangent is
// perpendicular to the chord or thA + thB >= pi (the tangent lines do not meet ahead).
double chord_error(const Vec3& a, const Vec3& ta, const Vec3& b, const Vec3& tb);

struct PencilLinkParams {
  double max_gap = 1.0;   // mm: B within this of where A's tangent meets B's layer
  double min_cos = 0.7;   // tangents at A and B within acos(min_cos) of each other
};

// Whether a pencil point is kept in its family: its crease crosses the family's layers at
// least as steeply as those of every other scanned family (|t . n|; within
// tol::kPencilFamilyTie of each other it is a tie, won by the lower family, so that the points
// of one crease at 45 degrees, whose tangents differ by rounding from point to point, all go
// to one family), so that each stretch of crease is traced once, by the layers that cut it
// best. `scanned[f]` tells which families were scanned.
bool pencil_keep(const PencilCandidate& c, const bool scanned[3]);

// Links points of one family on consecutive layers (layer k to k + 1) by mutual best match:
// A's prediction on B's layer (A + s tA) and B's on A's layer both within max_gap, tangents
// agreeing. Returns chains of indices into `points`, each in increasing layer order, every
// point in exactly one chain (single points are chains of one). Deterministic.
std::vector<std::vector<std::uint32_t>> link_layers(std::span<const PencilCandidate> points,
                                                    const PencilLinkParams& params);

// Greedy ordering of polylines to shorten the air moves between them: start with the first
// polyline, then repeatedly take the nearest remaining end (reversing the polyline when its
// last point is nearer). `fixed`: empty (every polyline may be reversed), or one flag per
// polyline, 1 for those that keep their direction (only their first point is a candidate:
// a path oriented for its cut direction). Returns (index, reversed) pairs.
struct OrderedPath {
  std::uint32_t index = 0;
  bool reversed = false;
};
std::vector<OrderedPath> order_paths(std::span<const std::vector<Vec3>> paths,
                                     std::span<const std::uint8_t> fixed = {});

// Length of a polyline, mm.
double polyline_length(std::span<const Vec3> p);

// Joins polylines whose ends are within `merge_distance` (mm) and whose end directions agree
// (cos >= min_cos), repeatedly, in a deterministic order; drops the results shorter than
// `min_length` (mm). Returns the joined polylines.
std::vector<std::vector<Vec3>> merge_paths(std::vector<std::vector<Vec3>> paths,
                                           double merge_distance, double min_cos,
                                           double min_length);

// Closes the polylines whose ends are within `merge_distance` (mm) of each other and whose end
// directions agree (cos >= min_cos, as merge_paths) by repeating the first point at the end:
// a crease that goes around (a boss's foot) is one closed path, not a path with a gap.
void close_loops(std::vector<std::vector<Vec3>>& paths, double merge_distance, double min_cos);

// A run of points [from, to] of path `path` (indices into the paths given).
struct PathRun {
  std::uint32_t path = 0, from = 0, to = 0;
};

// The paths cut where they turn back on themselves (consecutive chords more than 120 degrees
// apart: a chain joined to another that starts back along the same crease): runs sharing
// the turning point, covering every path.
std::vector<PathRun> cusp_runs(std::span<const std::vector<Vec3>> paths);

// Paths traced more than once kept once (a crease turning through 45 degrees at a corner is
// followed by both drive-plane families past the turn): the paths are taken longest first,
// and a point lying within `eps` (mm) of a path taken before, on a segment whose direction
// agrees with the point's tangent (|cos| >= min_cos), is covered. Returns the runs of
// uncovered points in the order taken (single points dropped); a run's ends then lie about a
// point spacing from the path that covers its neighbours, to be joined end to end.
// Deterministic.
std::vector<PathRun> uncovered_runs(std::span<const std::vector<Vec3>> paths, double eps,
                                    double min_cos);

// The crease point at ball-centre height zc of two elements given by their closest-point
// functions: the (x, y) where the ball centre (x, y, zc) is at distance R from both, by
// Newton from `guess` (the gradient of a distance is the unit vector from the closest point
// to the centre, so the Jacobian rows are the horizontal parts of b1 and b2). False when it
// does not converge to within 1e-10 mm in a few steps or moves farther than `reach`.
bool crease_at_height(const std::function<Vec3(const Vec3&)>& closest1,
                      const std::function<Vec3(const Vec3&)>& closest2, const Vec2& guess,
                      double zc, double R, double reach, Vec2& out);

}  // namespace ncpath
