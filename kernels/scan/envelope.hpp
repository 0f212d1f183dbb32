#pragma once
// The CL curve of one drive plane (issue 5): the upper envelope of the plane's slice pieces
// (kernels/scan/plane_slice.hpp), kept exact as typed spans, its junctions with their
// bi-contact vectors, and a discretisation within a chordal tolerance for output.
//
// Every piece is a concave function of x on its range (a line, or the upper arc of a circle
// or an ellipse), so the envelope of two pieces on an interval is decided by certified
// bounds: with chord_A the chord of A over [s, t] (A >= chord_A there),
//   min (A - B) >= min (chord_A - B) = -max (B - chord_A),   max (A - B) <= max (A - chord_B),
// and both maxima are exact (argmax_tilted: the point of the conic whose tangent has the
// chord's slope). Intervals that neither bound settles are split at a crossing (Illinois
// root of A - B on a sign change) or in the middle; ties within tol::kEnvelopeTie go to the
// piece with the lower element id, so the result does not depend on the order of pieces.
// The envelope of the linear pieces (facet lines, the floor) is built first, by divide and
// conquer over the pieces sorted by x0; curved pieces that lie under it everywhere (exact
// test: the maximum of the concave piece minus each line) are dropped, and the envelope of
// the rest is merged in.
//
// Jumps: the drop-cutter height is discontinuous where the tool passes a vertical wall (it
// falls from the wall's top edge to what lies below). The curve there gets a vertical
// segment; its contact normal is the upper piece's at its end (horizontal for a wall).
#include <cstdint>
#include <span>
#include <vector>

#include "kernels/geom/tolerance.hpp"
#include "kernels/geom/vec.hpp"
#include "kernels/scan/plane_slice.hpp"

namespace ncpath {

// How the CL curve turns at a junction, seen by the tool travelling along it.
enum class JunctionKind : std::uint8_t {
  kConvex = 0,        // the curve turns down (a ridge)
  kSharpConcave = 1,  // the curve turns up: the tool touches two elements at once
  kTangent = 2,       // it continues smoothly from one element to the next
};
const char* junction_kind_name(JunctionKind kind);

// One piece of the envelope: pieces[piece] is on top for x in [x0, x1].
struct EnvelopeSpan {
  std::uint32_t piece = 0;
  double x0 = 0, x1 = 0;
};

struct EnvelopeCounters {
  std::uint64_t decisions = 0;  // interval decisions between two pieces
  std::uint64_t crossings = 0;  // crossings located by root finding
  std::uint64_t unsettled = 0;  // intervals decided at their midpoint after the split budget
  std::uint64_t hidden = 0;     // curved pieces found under the linear pieces' envelope
};

// Upper envelope of `pieces` (ranges [x0, x1], any order): spans sorted by x, disjoint,
// consecutive spans touching wherever pieces cover x; x where no piece lies is left out.
void upper_envelope(std::span<const SlicePiece> pieces, std::vector<EnvelopeSpan>& out,
                    EnvelopeCounters* counters = nullptr, double tie = tol::kEnvelopeTie);

// A segment of a plane's CL curve: a span of one piece, or a vertical segment at x0 == x1
// (z0 > z1 or z0 < z1: the tool passes a wall), in the direction of increasing x.
struct CurveSegment {
  std::uint32_t piece = 0;  // index into the plane's pieces (vertical: the upper piece)
  bool vertical = false;
  double x0 = 0, x1 = 0;  // mm
  double z0 = 0, z1 = 0;  // tool-tip z at x0 and x1, mm
};

// A junction between consecutive segments: position (x, tip z) in the plane, kind, the
// elements on either side (kNoElement for the floor) and their bi-contact vectors: unit
// vectors from each element's contact point to the ball centre.
struct CurveJunction {
  double x = 0, z = 0;  // mm
  JunctionKind kind = JunctionKind::kTangent;
  std::uint32_t segment = 0;  // index of the segment that starts here
  std::uint32_t element1 = 0, element2 = 0;
  Vec3 b1 = Vec3::Zero(), b2 = Vec3::Zero();
};

// A plane's CL curve: runs of touching segments. run_starts[k] is the first segment of run k
// (a new run starts where no piece covers x; with a floor piece there is one run).
struct PlaneCurve {
  std::vector<CurveSegment> segments;
  std::vector<CurveJunction> junctions;
  std::vector<std::uint32_t> run_starts;
};

// Segments and junctions from an envelope of `pieces`.
void plane_curve(std::span<const SlicePiece> pieces, std::span<const EnvelopeSpan> spans,
                 PlaneCurve& out);

// Kind of the turn from direction (1, s1) into (1, s2) (slopes may be +-inf: vertical).
JunctionKind junction_kind(double dx1, double dz1, double dx2, double dz2);

// Appends the polyline (x, tip z) of one segment, without its end point, within `tolerance`
// (mm, perpendicular distance between each chord and the arc). Each chord is lifted by its
// largest vertical gap to the arc, so the polyline never lies below the exact curve (no
// gouge) and lies at most `tolerance` (perpendicular) above it; `lift` receives, for each
// point, the lift of the chord that starts there: a point's z is raised by the larger lift
// of its two chords (the caller's job, across segments). Lines give their start only.
void discretise_segment(const SlicePiece& piece, const CurveSegment& seg, double tolerance,
                        std::vector<Vec2>& points, std::vector<double>& lift);

}  // namespace ncpath
