#pragma once
// Uncut regions between consecutive offset levels (issue 4, first step).
//
// The tool centre runs along the loops of every level, so the material it removes is the
// set of points within the tool radius R of some loop. Between level k and level k+1 lies
// the band B = (inside level k) \ (inside level k+1); what stays uncut in it is the set of
// points of B farther than R from both levels' loops, i.e. B eroded by R. B's boundary is
// level k's loops as they are (material on the right) and level k+1's loops reversed, so
// the same offset-loop dissection that made the levels finds the uncut regions: corner
// uncut where a stepover is wide, neck uncut where a level splits, and (with no inner
// level) centre uncut inside the innermost loops.
#include <vector>

#include "kernels/pocket/offset.hpp"

namespace ncpath {

// outer: the loops of level k (one region: a clockwise loop and its holes); inner: the
// loops of level k+1 inside it (empty for the centre). Returns the uncut regions as loops
// (material on the right), empty when the band is cut completely.
//
// Every boundary point of an uncut region lies on the band's crude offset loops by R and
// at least R from both levels. Segments of the crude loops certified to come closer than
// that to the other level everywhere (band_cut's test) hold no such point, nor does any
// crossing that matters, so only windows around the other segments (stretches of the crude
// loops, two segments past them either side) are dissected, their pieces validated against
// all of the band: the result is that of uncut_between_full, loop for loop (same order, same
// segments), at a fraction of the cost where the uncut regions are small.
std::vector<OffsetLoop> uncut_between(const std::vector<const OffsetLoop*>& outer,
                                      const std::vector<const OffsetLoop*>& inner,
                                      double tool_radius);
// The same by the complete dissection of the band (the reference of the tests).
std::vector<OffsetLoop> uncut_between_full(const std::vector<const OffsetLoop*>& outer,
                                           const std::vector<const OffsetLoop*>& inner,
                                           double tool_radius);

// A sufficient test that uncut_between finds nothing: every segment of the band's crude
// offset loops by R (both levels' offsets into the band, joined at the corners) is
// certified to lie closer than R - kOffsetValid - kUncutCertify to the other level
// everywhere (exact bounds on the distance, no sampling), so no point of it can be on the
// boundary of an uncut region. Stops at the first segment it cannot certify. False means
// "compute it" (always for the centre band).
bool band_cut(const std::vector<const OffsetLoop*>& outer,
              const std::vector<const OffsetLoop*>& inner, double tool_radius);

// Splits a loop that touches itself at a vertex into the simple loops it is made of and
// drops those enclosing no area (the zero-width bridges an erosion leaves where a band is
// exactly 2R wide: no material there, and the tool would travel them for nothing).
void split_pinched(OffsetLoop loop, std::vector<OffsetLoop>& out);

// Loops reversed (material on the other side): turns an erosion into a dilation.
std::vector<std::vector<Seg2>> reversed_loops(const std::vector<std::vector<Seg2>>& loops);

// Material a tool of radius R cannot reach in a pocket region (loops with the material on
// the right): the region minus its opening (erosion by R, then dilation by R) — corners
// sharper than the tool and gaps narrower than it. Returns the reachable region's loops
// (the opening) and the unreachable area, mm^2.
// The region (loops, material on the right) grown by d: the points within d of it.
std::vector<OffsetLoop> dilate(const std::vector<std::vector<Seg2>>& region, double d);

struct Reach {
  std::vector<OffsetLoop> reachable;
  double unreachable_area = 0;
};
Reach tool_reach(const std::vector<std::vector<Seg2>>& region, double tool_radius);

}  // namespace ncpath
