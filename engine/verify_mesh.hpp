#pragma once
// Gouge verification of CL moves against a triangle mesh, independent of the planner and of
// the drop-cutter: every move (the straight segment between consecutive points of one path)
// is checked with the swept tool of kernels/verify/swept_tool.hpp (GJK in double) against
// every facet it may reach.
//
// Candidates come from a uniform grid over the mesh's xy box, in double precision: a facet
// sits in the cells its xy box overlaps. Consecutive moves of a path whose tips lie close
// together (a raster's, a pencil's: within R + stock) form a group, and the group walks the
// grid once: the cells under its swept box (its tips' box grown by R + stock, plus the
// clearance cap for rapids, in xy; z from the lowest tip minus stock to the highest tip plus
// 2r + shank + stock), seeing each facet once. Tiles of 4 x 4 cells bound their facets (xy
// box, top): a tile, and then a facet, beyond the body's reach from every tip or below its
// bottom at the lowest tip is dismissed for the whole group (rapids keep everything within
// the reach and the cap, for the clearance). The survivors, with their boxes rounded outward
// to float, are the group's candidates, in ascending facet index.
//
// Each move of the group then scans the candidates in that order, dismissing them by exact
// bounds before any GJK call: the facet's box against the move's, its xy distance from the
// move's xy segment (beyond R + stock nothing touches), its top below the swept bottom over
// that distance (profile of the tool grown by stock at the lowest tip), and its plane's
// distance from the swept body. Each move keeps its largest gouge so far as a floor: a facet
// costs one GJK call unless it gouges deeper than every facet before it. As every move sees
// its facets in ascending index, whatever group it is in, its result does not depend on
// how moves are grouped (nor on chunks or threads).
//
// Gouge = vertical lift (mm) that clears the move (swept_tool.hpp): what a machinist calls
// "cut in by X mm". Moves whose gouge is at most gouge_tolerance are clean.
//
// verify_moves runs moves in parallel (engine/parallel.hpp), blocks of consecutive moves a
// task; each move's result is its own (facets in index order) and block reports are merged in block order with strict total
// orders, so the report is identical for any thread count. MeshVerifier is built once per
// mesh and queried concurrently (const, no shared mutable state).
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "engine/cl_chunk.hpp"
#include "kernels/cutters/cutter.hpp"
#include "kernels/geom/tolerance.hpp"
#include "kernels/geom/vec.hpp"
#include "kernels/mesh/triangle_mesh.hpp"
#include "kernels/verify/swept_tool.hpp"

namespace ncpath {

inline constexpr std::uint32_t kNoMeshFacet = std::numeric_limits<std::uint32_t>::max();

struct MeshVerifyParams {
  double shank = 50;                           // mm of shank above the corner's centre
  double stock = 0;                            // mm of material to leave (tool grown by it)
  double gouge_tolerance = tol::kVerifyGouge;  // mm: a gouge is reported above this
  double safe_clearance = 0;  // mm: rapids whose clearance is below this are unsafe
  double clearance_cap = 10;  // mm: rapid clearances are measured up to this (> 0)
  int worst = 8;              // violations kept in the report
};

struct MoveViolation {
  std::uint64_t move = 0;                       // first_move_index + index of the move in the chunk
  std::uint32_t path = 0;                       // first_path_index + index of the path in the chunk
  Vec3 from = Vec3::Zero(), to = Vec3::Zero();  // the move's tool tips, mm
  double amount = 0;                   // mm: the gouge (worst), or the clearance (closest_rapid)
  std::uint32_t facet = kNoMeshFacet;  // index into mesh.facets that decided `amount`
};

struct MeshVerifyReport {
  std::uint64_t moves = 0;
  std::uint64_t rapid_moves = 0;
  std::uint64_t gouging_moves = 0;  // moves whose gouge exceeds gouge_tolerance
  std::uint64_t unsafe_rapids = 0;  // rapids whose clearance is below safe_clearance
  double max_gouge = 0;             // mm, largest gouge above the tolerance; 0 when none
  // mm, smallest gap (swept_gap, capped at clearance_cap) of a rapid to the mesh; negative
  // when a rapid cuts in; +inf without rapids.
  double min_rapid_clearance = std::numeric_limits<double>::infinity();
  MoveViolation closest_rapid;       // the rapid of min_rapid_clearance (amount = that clearance)
  std::vector<MoveViolation> worst;  // largest gouge first, ties by lower move index
  std::size_t worst_capacity = 8;    // at most this many (params.worst)
  std::uint64_t candidates = 0;      // facets whose boxes met a move's (statistics)
  std::uint64_t gjk_calls = 0;       // GJK distance evaluations (statistics)
  std::string error;                 // empty unless the chunk was malformed (see verify_moves)
};

// Folds `from` (e.g. the next chunk of a stream) into `into`. Counts add up, extremes keep
// the lower move index on ties, worst lists merge by the same order: the result does not
// depend on how moves were split into reports.
void merge(MeshVerifyReport& into, const MeshVerifyReport& from);

// What a move check finds out about the gouge: its depth (kMeasure), or only whether there
// is one above the floor (kDecide: the scan stops at the first facet that gouges, and
// MoveCheck::gouge is +inf for yes, 0 for no; clearances, when asked, are still measured).
enum class MoveCheckMode { kMeasure, kDecide };

class MeshVerifier {
 public:
  // Copies the facets (the mesh need not outlive the verifier). Facets with a non-finite
  // vertex are skipped and counted; degenerate ones are kept (a zero-area sliver can still
  // be cut into).
  explicit MeshVerifier(const TriangleMesh& mesh);
  ~MeshVerifier();
  MeshVerifier(const MeshVerifier&) = delete;
  MeshVerifier& operator=(const MeshVerifier&) = delete;

  struct MoveCheck {
    double gouge = 0;                                            // mm; 0 unless above gouge_floor
    std::uint32_t gouge_facet = kNoMeshFacet;                    // mesh facet of the gouge
    double clearance = std::numeric_limits<double>::infinity();  // mm, min gap within the cap
    std::uint32_t clearance_facet = kNoMeshFacet;
    std::uint32_t candidates = 0;  // facets of its group whose boxes met the move's
    std::uint32_t gjk_calls = 0;
  };

  // One move p0 -> p1 (tool tips, mm). The gouge is reported only above gouge_floor (mm,
  // >= 0). With clearance_cap > 0 (mm) also the smallest swept_gap over the facets whose
  // gap may be below the cap (+inf when none is). Thread-safe.
  MoveCheck check_move(const SweptTool& tool, const Vec3& p0, const Vec3& p1, double gouge_floor,
                       double clearance_cap = 0) const;

  // The moves from[k] -> to[k], k < n: out[k] is what check_move(tool, from[k], to[k], ...)
  // returns, bit for bit (every move scans its facets in ascending index, whatever it is
  // grouped with), but for `candidates`, which counts the facets of its group that the move
  // met. Consecutive moves whose tips lie within kGroupExtent x (R + stock) of
  // each other share one walk of the grid: a raster's or a pencil's short moves cost one
  // walk per group, not one each. A move with a non-finite tip is not checked (its out[k]
  // is a default MoveCheck). out must hold n checks. Thread-safe.
  void check_moves(const SweptTool& tool, const Vec3* from, const Vec3* to, std::size_t n,
                   double gouge_floor, double clearance_cap, MoveCheck* out,
                   MoveCheckMode mode = MoveCheckMode::kMeasure) const;
  // The moves tips[k] -> tips[k + 1] of one path (n - 1 of them; none when n < 2).
  void check_path(const SweptTool& tool, const Vec3* tips, std::size_t n, double gouge_floor,
                  double clearance_cap, MoveCheck* out,
                  MoveCheckMode mode = MoveCheckMode::kMeasure) const;
  // Performance settings (any values give the same checks): how far apart the tips of one
  // group may lie, in units of R + stock, and how many moves a group holds at most.
  static constexpr double kGroupExtent = 1.0;
  static constexpr std::size_t kMaxGroup = 64;

  std::uint64_t facet_count() const;  // facets held
  std::uint64_t skipped() const;      // facets skipped (non-finite vertices)

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// A mesh's swept-tool index, asked for when first needed (e.g. a batch's shared index, built
// on its first call): a pencil or fillet job then builds it only after its own largest
// structures are freed, so the two never take memory at once.
using SweptIndexSource = std::function<std::shared_ptr<const MeshVerifier>()>;

// Checks of a chunk's moves already made by this verifier's kernel (MeshVerifier::check_moves,
// kMeasure) with the verifier's tool and gouge floor and no clearance: the chord guard's
// (engine/chord_guard.hpp), which checks every move of a raster before it lifts the ones
// that gouge. One entry per move of the chunk, in verify_moves' numbering; known[m] = 0 where
// move m was not checked so (a move a lift-over made, a rapid: rapids need their clearance).
// A check is used only for the move it was made for: from[m] and to[m] must equal the
// chunk's move m bit for bit, else the move is checked again.
struct PrecheckedMoves {
  std::vector<MeshVerifier::MoveCheck> checks;
  std::vector<std::uint8_t> known;
  std::vector<Vec3> from, to;
};

// Verifies every move of the chunk: moves of kCut and kLinkAtDepth paths for gouges, moves of
// kRapid paths for gouges and clearance. Moves are numbered from first_move_index in chunk
// order (a path of n points has n - 1 moves), paths from first_path_index. A chunk whose
// sizes disagree (xyz, path_sizes, path_kinds) or that holds a non-finite point gets an
// error message and no verdict for the moves concerned. `prechecked` (its size must be the
// chunk's move count, else it is not used): the known moves are taken from it instead of
// being checked again (the same kernel, tool and floor give the same check, bit for bit, but
// for the candidates counted); the others are checked here. The report is the same.
MeshVerifyReport verify_moves(const MeshVerifier& verifier, const Cutter& cutter, const ClChunk& cl,
                              const MeshVerifyParams& params, std::uint64_t first_move_index = 0,
                              std::uint32_t first_path_index = 0,
                              const PrecheckedMoves* prechecked = nullptr);

}  // namespace ncpath
