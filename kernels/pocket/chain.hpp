#pragma once
// From a soup of profile curves (lines, arcs, NURBS in any order and direction, as the readers
// deliver them) to pocket regions: chain the curves into closed loops by matching end points,
// check the loops, and nest them by containment. Pure geometry: no I/O, no threads.
//
// Rules:
//  - End points closer than join_tol (mm) are one vertex; they are snapped to their midpoint
//    exactly (NURBS: the end control point; arcs keep both ends on a circle by moving the
//    centre onto the new chord's bisector), so consecutive curves of a loop share bitwise
//    equal points. largest_gap_closed reports the widest such gap.
//  - Every vertex must join exactly two curve ends. One end alone is an open profile, three or
//    more a branching one; two curves between the same vertices that cover the same path are
//    duplicates. Each is an error that names the entities (SourceEntity type and handle) and
//    the point.
//  - Loops must not intersect themselves or each other (tested on polylines within
//    tol::kProfileTestChord; the error gives the point), and must enclose a non-zero area.
//  - Nesting depth decides the role: even depth = pocket boundary (made clockwise), odd depth =
//    island (made counter-clockwise). A loop inside an island's hole starts a new Region.
#include <string>
#include <vector>

#include "kernels/geom/tolerance.hpp"
#include "kernels/pocket/profile.hpp"

namespace ncpath {

struct ChainResult {
  // One per even-depth loop, in the order of their first curve in the input. Every
  // Profile::nurbs holds copies (reversed where needed) of the NURBS its curves use.
  std::vector<Region> regions;
  double largest_gap_closed = 0;  // mm; 0 when all ends met bitwise
  std::string error;              // empty on success; then regions is non-empty
};

// curves: the soup. A curve with nurbs >= 0 is nurbs[curve.nurbs], with seg.a / seg.b its end
// points (clamped: the first and last control points). seg.source indexes sources (or is
// kNoSource). join_tol: mm, >= 0; tol::kProfileJoinLoose is the documented larger option.
ChainResult chain_and_nest(const std::vector<ProfileCurve>& curves,
                           const std::vector<Nurbs2>& nurbs,
                           const std::vector<SourceEntity>& sources,
                           double join_tol = tol::kProfileJoin);

}  // namespace ncpath
