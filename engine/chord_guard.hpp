#pragma once
// The last stage of the mesh operations whose CL points are exact but whose chords are not
// (raster, pencil, fillet): every straight move between consecutive points is measured with
// the exact swept tool (engine/verify_mesh.hpp). A move that cuts in by at most `raise`
// (tol::kChordRaise: a chord sagging below a convex stretch of the CL surface, 65 % of a
// raster's chords on a dense scan) has its two ends raised by its gouge, the vertical lift
// that clears it (the tool then leaves at most `raise` of material there; a path's first and
// last points, where paths meet, are not raised), and the moves next to raised points are
// checked again. A move that still cuts in is replaced by a lift-over: straight up at its
// lower end, across at the height that clears the part, straight down at the other end.
//
// Why the vertical moves are safe: every point is a drop-cutter point, the highest height at
// which the tool touches the part over that xy; the tool (shank included) is free anywhere
// above it. The move across is raised by the exact lift that clears it (conservative by the
// lift's resolution). A step up a wall (a raster line reaching a part from the floor) thus
// becomes a climb and a move over the edge instead of a chord through the part.
//
// Sharing: this stage and the job's verifier use the same swept-tool kernel
// (kernels/verify/swept_tool.hpp, tested against the drop-cutter as an independent oracle)
// and the same read-only index of the mesh (built once: batch/jobs/shared_mesh.hpp); the
// verifier re-checks every move afterwards.
#include <cstdint>
#include <memory>

#include "engine/cl_chunk.hpp"
#include "engine/run_control.hpp"
#include "engine/verify_mesh.hpp"

namespace ncpath {

struct ChordGuardStats {
  std::uint64_t moves = 0;         // moves checked
  std::uint64_t raised = 0;        // points raised (at most `raise`) to clear shallow cuts
  double max_raise = 0;            // mm, the largest raise
  std::uint64_t lifted = 0;        // moves replaced by a lift-over
  std::uint64_t points_added = 0;  // CL points inserted
  double max_lift = 0;             // mm, largest height a lift-over rose above its higher end
  void add(const ChordGuardStats& o);
};

// `in` with every gouging move replaced by its lift-over (paths keep their kinds; inserted
// points have contact kind 0). Parallel over paths; the same bytes for any thread count.
// `checked` (optional): the moves are then measured, not only decided (the verifier's
// kMeasure, with its floor tol::kVerifyGouge and no clearance), and *checked receives them
// for the moves out (engine/verify_mesh.hpp PrecheckedMoves): a move kept is known, a move of
// a lift-over or of a rapid path is not. The job's verifier takes them instead of checking
// those moves a second time with the same kernel (when `tool` is its tool).
ClChunk guard_chords(const MeshVerifier& mesh, const SweptTool& tool, const ClChunk& in,
                     ChordGuardStats& stats, PrecheckedMoves* checked = nullptr,
                     double raise = tol::kChordRaise);

// The stage for one job: the mesh's swept-tool index (shared with the job's verifier), the
// tool, and the running stats.
class ChordGuard {
 public:
  ChordGuard(std::shared_ptr<const MeshVerifier> index, const Cutter& cutter, double stock = 0,
             double raise = tol::kChordRaise);
  ClChunk apply(const ClChunk& in, PrecheckedMoves* checked = nullptr);  // see guard_chords
  const ChordGuardStats& stats() const { return stats_; }
  double seconds() const { return seconds_; }  // in apply, so far

 private:
  std::shared_ptr<const MeshVerifier> mesh_;
  SweptTool tool_;
  double raise_;
  ChordGuardStats stats_;
  double seconds_ = 0;
};

}  // namespace ncpath
