#pragma once
// Exact drop-cutter against one triangle, double precision.
//
// The tool (axis +Z through (x, y)) comes down from above until it first touches the
// triangle. The answer is the highest tool-tip z over the three kinds of contact:
//   facet  - the cutter is tangent to the triangle's plane at an interior point;
//   edge   - the cutter touches the interior of an edge;
//   vertex - the cutter touches a vertex.
// Ball and flat are closed form; the bull-nose edge contact is solved by safeguarded
// Newton (on a quartic in the sine of the torus angle) to tol::kContactSolve.
//
// A triangle counts as two-sided (orientation is irrelevant to a tool from above).
#include <cstdint>
#include <limits>

#include "kernels/cutters/cutter.hpp"
#include "kernels/geom/vec.hpp"

namespace ncpath {

enum class ContactKind : std::uint8_t { kNone = 0, kVertex = 1, kEdge = 2, kFacet = 3 };
const char* contact_kind_name(ContactKind kind);

// Highest contact found so far at one (x, y). tip_z = -inf and kind kNone mean "touches
// nothing".
struct CutterContact {
  double tip_z = -std::numeric_limits<double>::infinity();  // tool tip z, mm
  Vec3 cc = Vec3::Zero();                                   // contact point on the part, mm
  ContactKind kind = ContactKind::kNone;
  std::uint32_t facet = std::numeric_limits<std::uint32_t>::max();  // facet index
};

// Per-triangle data computed once per mesh (the engine builds a table of these).
struct PreparedFacet {
  Vec3 p[3];                                        // vertices, mm
  Vec3 n;                                           // unit normal oriented so that n.z >= 0
  double plane_d;                                   // n . p[0]
  double min_x, max_x, min_y, max_y, min_z, max_z;  // bounding box, mm
  // Edge k runs p[k] -> p[(k+1)%3]. Horizontal unit direction, horizontal length, slope
  // dz/du and sqrt(1 + slope^2); len_xy == 0 marks a vertical edge (its vertices carry its
  // contacts).
  double ex[3], ey[3], len_xy[3], slope[3], slope_norm[3];
  double xy_winding;  // +1 when p[0], p[1], p[2] run counter-clockwise in xy, else -1
  bool vertical;      // |n.z| < tol::kVerticalNormalZ: no facet contact
};

// The tip height at which the cutter touches the facet's infinite plane, as a linear
// function of the tool position: a x + b y + c. It bounds every contact with the facet
// from above (callers use it to skip facets). Vertical facets: a = b = 0, c = +inf.
struct PlaneTip {
  double a, b, c;
};
PlaneTip plane_tip(const Cutter& cutter, const PreparedFacet& f);

// False when the triangle is degenerate (area below tol::kDegenerateArea2).
bool prepare_facet(const Vec3& a, const Vec3& b, const Vec3& c, PreparedFacet& out);

// Raises `best` to this facet's contact at (x, y) when it is strictly higher. Returns
// true when it did. `facet_index` is stored in best.facet.
bool drop_facet(const Cutter& cutter, const PreparedFacet& f, double x, double y,
                std::uint32_t facet_index, CutterContact& best);

// The single-contact pieces, exposed for tests. Each returns false when that contact does
// not exist at (x, y); otherwise writes the tip z (and the contact point).
bool drop_on_edge(const Cutter& cutter, const Vec3& p, const Vec3& q, double x, double y,
                  double& tip_z, Vec3& cc);
bool drop_on_vertex(const Cutter& cutter, const Vec3& v, double x, double y, double& tip_z);

}  // namespace ncpath
