#pragma once
// Exact crease points of the pencil-cut on drive planes (engine/pencil.hpp, stages 3 and 4):
// the sharp-concave junction of a plane's exact envelope (engine/scan.hpp plane_junctions)
// nearest to where a crease is expected, whose bi-contact angle reaches the threshold and
// whose crease tangent runs within ~45 degrees of the expected one.
#include "engine/scan.hpp"
#include "kernels/cleanup/pencil.hpp"

namespace ncpath {

// Crease tangents of linked pencil points agree within ~45 degrees (|t1 . t2| >= this).
inline constexpr double kCreaseMinCos = 0.7;

// Exact crease point between A and B on the drive plane halfway between their layers, near
// the chord's middle; false when that plane has none there.
bool crease_between(const ScanElements& se, const PencilCandidate& a, const PencilCandidate& b,
                    double min_angle, double floor_z, PencilCandidate& out);

// The crease point on the drive plane at v (a's family) where a's tangent line meets it;
// false when that plane has none near there.
bool crease_on_plane(const ScanElements& se, const PencilCandidate& a, double v, double min_angle,
                     double floor_z, PencilCandidate& out);

// Where the crease ends between a chain's end and the next layer (which does not see it):
// bisection over planes up to `spacing` beyond the end, in direction dir (+1 / -1 along the
// layer normal), staying within [v_min, v_max] (the scanned rectangle). False when it ends at
// the end layer already.
bool crease_end(const ScanElements& se, const PencilCandidate& end, double dir, double spacing,
                double v_min, double v_max, double min_angle, double floor_z,
                PencilCandidate& out);

}  // namespace ncpath
