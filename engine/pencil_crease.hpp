#pragma once
// Exact crease points of the pencil-cut (engine/pencil.hpp) on drive planes (stages 3 and 4):
// the sharp-concave junction of a plane's exact envelope (engine/scan.hpp plane_junctions)
// nearest to where a crease is expected, whose bi-contact angle reaches the threshold and
// whose crease tangent runs within ~45 degrees of the expected one.
#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "engine/drop_index.hpp"
#include "engine/scan.hpp"
#include "engine/surface_check.hpp"
#include "kernels/cleanup/pencil.hpp"

namespace ncpath {

// Crease tangents of linked pencil points agree within ~45 degrees (|t1 . t2| >= this).
inline constexpr double kCreaseMinCos = 0.7;

using ElementPair = std::array<ElementRef, 2>;  // the two elements a candidate touches

// Exact crease point between A and B on the drive plane halfway between their layers, near
// the chord's middle; false when that plane has none there.
bool crease_between(const ScanElements& se, const PencilCandidate& a, const PencilCandidate& b,
                    double min_angle, double floor_z, PencilCandidate& out);

// The crease point on the drive plane at v (a's family) where a's tangent line meets it, and
// its elements when `refs` is given; false when that plane has none near there.
bool crease_on_plane(const ScanElements& se, const PencilCandidate& a, double v, double min_angle,
                     double floor_z, PencilCandidate& out, ElementPair* refs = nullptr);

// Whether a crease point (with its elements) is one to trace.
using CreaseFilter = std::function<bool(const PencilCandidate&, const ElementPair&)>;

// Where the crease ends between a chain's end and the next layer (which does not see it), or
// stops being one `keep` accepts: bisection over planes up to `spacing` beyond the end, in
// direction dir (+1 / -1 along the layer normal), staying within [v_min, v_max] (the scanned
// rectangle); the point and its elements. False when it ends at the end layer already.
bool crease_end(const ScanElements& se, const PencilCandidate& end, double dir, double spacing,
                double v_min, double v_max, const CreaseFilter& keep, double min_angle,
                double floor_z, PencilCandidate& out, ElementPair& out_refs);


// Whether the chord a-b wants a crease point between its ends (depth: refinements so far,
// 16 at most): its error bound exceeds the tolerance (chords at least twice the tolerance
// long: shorter ones are within it of any crease between their ends), or, to depth 8 (1/256
// of the chord; near a kink of the crease at a wall's top), its middle lies more than half
// the tolerance below the CL surface (the drop-cutter `index` over floor_z). Smaller dips (a
// crease curving sideways into a wall) are left to the chord check.
bool chord_wants_refining(const PencilCandidate& a, const PencilCandidate& b, double tolerance,
                          int depth, const DropIndex& index, double floor_z);

// Drive-plane chains refined between a and b (a's family, not z-levels): exact crease points
// on the planes between their layers (crease_between) while the chord wants refining; the
// points strictly between a and b are appended to `out`, in order.
void refine_on_planes(const ScanElements& se, const DropIndex& index, const PencilCandidate& a,
                      const PencilCandidate& b, double tolerance, double min_angle,
                      double floor_z, int depth, std::vector<PencilCandidate>& out,
                      std::uint64_t& added);

// Z-level chains refined between a and b (b not below a): the crease point of a's two
// elements, else b's, at the middle height, kept when it lies on the CL surface (the crease
// may have moved to other elements in between); under an overhang or along walls, a point
// on a's or b's tangent line; while the chord wants refining. The points strictly between a
// and b are appended to `out`, in order.
struct ZLevelCreaseRefine {
  const TriangleMesh& mesh;
  const DropIndex& index;
  const PartProbe& part;
  double tolerance, R, floor_z;  // mm; R the ball's radius

  void operator()(const PencilCandidate& a, const ElementPair& ea, const PencilCandidate& b,
                  const ElementPair& eb, int depth, std::vector<PencilCandidate>& out,
                  std::uint64_t& added) const;
};

}  // namespace ncpath
