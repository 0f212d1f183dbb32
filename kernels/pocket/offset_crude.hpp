#pragma once
// Internals of offset-loop dissection (kernels/pocket/offset.cpp): the crude offset loop,
// joins at corners (offset_crude.cpp), the dissection of crude loops or of stretches of
// them (offset_dissect.cpp), and the certification that decides which stretches an uncut
// region can touch (uncut_certify.cpp). Not a public API.
#include <cstdint>
#include <functional>
#include <vector>

#include "kernels/pocket/offset.hpp"

namespace ncpath::pocket_detail {

struct RawSeg {
  Seg2 s;
  std::uint32_t loop;        // input loop it was offset from (in dissect: its chain)
  std::uint32_t prev, next;  // neighbours in the crude loop (indices into the raw list)
  bool connector;            // a line joining offsets that miss each other: not itself an offset
};

// RawSeg::prev / next at the ends of an open chain.
inline constexpr std::uint32_t kNoRaw = 0xffffffffu;

// The raw offsets of one input loop's curves by d (raw_offset), each with its input curve;
// curves whose offset vanishes are left out.
struct RawOffsets {
  std::vector<Seg2> segs;
  std::vector<Seg2> curves;  // segs[k] is the offset of curves[k]
  double d = 0;
  bool inverted = false;  // some arc turned inside out: the loop needs validation
};
RawOffsets raw_offsets(const Seg2* curves, std::size_t count, double d);

// The crude offset loop of one input loop, appended to raw: consecutive offsets joined at
// their vertex (an arc around it where the input turns left, trimmed at their crossing
// where it turns right, a connector line where they miss each other); joins trim the
// offsets in place.
void crude_loop(RawOffsets& offsets, std::uint32_t loop_id, std::vector<RawSeg>& raw);

// A chain of raw segments for dissect: a whole crude loop (closed), or a stretch of one
// (open; a windowed dissection, kernels/pocket/uncut.cpp) whose end segments hold no point
// of the result. Its segments are contiguous in the raw list, RawSeg::loop is its index.
struct Chain {
  std::uint32_t input = 0;  // input loop it was offset from (result loops' parents)
  bool closed = true;
  bool inverted = false;   // the input loop's offset has an inside-out arc (RawOffsets)
  double input_area2 = 0;  // loop_area2 of the input loop (used for closed chains)
};

struct DissectParams {
  bool several_inputs = false;  // more than one input loop (a crude loop crossing nothing may
                                // lie within d of another)
  bool pocket = false;          // largest input loop clockwise: holes outside every boundary go
};

// True when no input curve comes closer to the piece than the offset distance less `slack`
// (tol::kOffsetValid, or tol::kOffsetMarginal to tell a marginal miss from a real one); the
// piece is cut from raw[raw_index].
using PieceValid =
    std::function<bool(const Seg2& piece, std::uint32_t raw_index, double slack)>;

// Steps 3 to 6 of offset_loops on the chains' raw segments. rank (optional): each raw
// segment's index in the complete crude loops; sweep ties and the order loops are started
// in follow it, so that a dissection of stretches lists the complete one's loops in the same
// order, each from the same piece.
OffsetResult dissect(const std::vector<RawSeg>& raw, const std::vector<Chain>& chains,
                     const std::vector<std::uint32_t>* rank, const DissectParams& params,
                     const PieceValid& valid);

class SegGrid;

// Certifies the segments raw[begin, end) (one crude loop, in order) as lying closer than
// `limit` to the curves of `level` everywhere (uncut_certify.cpp: exact bounds, bisecting
// where they are not tight enough). Marks the others in bad, or with bad null stops at the
// first; true when there is one.
bool uncertified(const std::vector<RawSeg>& raw, std::size_t begin, std::size_t end, SegGrid& level,
                 double limit, std::vector<std::uint8_t>* bad);

}  // namespace ncpath::pocket_detail
