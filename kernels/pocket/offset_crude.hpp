#pragma once
// Internals of offset-loop dissection (kernels/pocket/offset.cpp): the crude offset loop,
// joins at corners. Not a public API.
#include <cstdint>
#include <vector>

#include "kernels/pocket/offset.hpp"

namespace ncpath::pocket_detail {

struct RawSeg {
  Seg2 s;
  std::uint32_t loop;        // input loop it was offset from
  std::uint32_t prev, next;  // neighbours in the crude loop (indices into the raw list)
  bool connector;            // a line joining offsets that miss each other: not itself an offset
};

// The crude offset loop of one input loop (its curves' raw offsets, in order), appended to
// raw; joins may trim the runs in place. At a concave corner whose end segments miss each
// other (runs of many short arcs overlap over several segments) the runs are cut back to
// their crossing nearest the vertex, searched within 20 d of curve.
void crude_loop(OffsetRuns& runs, std::uint32_t loop_id, double d, std::vector<RawSeg>& raw);

}  // namespace ncpath::pocket_detail
