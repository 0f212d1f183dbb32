#pragma once
// The verifier in every job: it watches the CL paths as the job writes them (ClJob's
// observer) and checks every move against the job's *input* geometry with its own queries —
// the mesh (engine/verify_mesh.hpp) or the pocket's walls, islands and floor
// (engine/verify_profile.hpp) — never the planner's intermediate results. At the end it
// writes stats/verify_* and the worst locations (verify/worst) and says whether the job
// failed its verification (a gouge deeper than tol::kVerifyGouge).
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "batch/jobs/job_spec.hpp"
#include "batch/output/cl_writer.hpp"
#include "engine/verify_mesh.hpp"
#include "engine/chord_guard.hpp"
#include "engine/verify_report.hpp"
#include "kernels/mesh/triangle_mesh.hpp"

namespace ncpath::jobs {

class JobVerifier {
 public:
  virtual ~JobVerifier();
  // From now on every path appended to cl is checked (full: every move; sample: every
  // kSampleEvery-th move).
  void attach(out::ClJob& cl);
  // Checks the next run of paths (what attach() does with each append).
  void feed(const ClChunk& cl);
  // The next run of paths comes with checks of its moves made by this verifier's kernel,
  // tool and floor (the raster's chord guard: engine/chord_guard.hpp): in full mode a mesh
  // verifier takes the known ones instead of checking them again (verify_moves). Used by the
  // next feed only; ignored by the other verifiers and in sample mode.
  void use_prechecked(PrecheckedMoves checked) { prechecked_ = std::move(checked); }
  // Appends the statistics (verify_*) and returns the report. The checks ran inside the
  // job's appends: their time is taken out of the job's write_s, if it has one already.
  const VerifyReport& finish(std::vector<out::StatValue>& stats);
  // Detaches from cl and writes the worst locations (verify/worst).
  void write_worst(out::ClJob& cl);
  // A bound the operation promises and the path does not keep (pocket3d: the scallop), for
  // an ok job's message; "" when kept. Valid after finish().
  virtual std::string bound_warning() const { return ""; }

  static constexpr std::uint64_t kSampleEvery = 8;

 protected:
  explicit JobVerifier(VerifyMode mode) : mode_(mode) {}
  // Checks one run of paths (moves numbered from first_move, paths from first_path).
  virtual VerifyReport check(const ClChunk& cl, std::uint64_t first_move,
                             std::uint32_t first_path) = 0;
  // Statistics of the verifier's own, after the last chunk: the operation's bounds
  // (pocket3d: the scallop), the mesh index's build time (verify_index_s).
  virtual void bound_stats(std::vector<out::StatValue>&) {}
  // Of the time check() took, what went into building the verifier's index (not verify_s).
  virtual double index_seconds() const { return 0; }
  // The checks given for the run of paths check() is called with (full mode), or null.
  const PrecheckedMoves* prechecked() const {
    return mode_ == VerifyMode::kFull && !prechecked_.known.empty() ? &prechecked_ : nullptr;
  }

 private:
  VerifyMode mode_;
  out::ClJob* attached_ = nullptr;
  VerifyReport report_;
  PrecheckedMoves prechecked_;
  std::uint64_t moves_seen_ = 0;
  std::uint32_t paths_seen_ = 0;
  double seconds_ = 0;
};

// For offset and pocket jobs: reads the job's profile again (its own read) and checks the
// moves against its walls, islands and floor. For pocket3d: walls and islands (the bottom is
// checked by the mesh of the surface: engine/verify_surface.hpp).
std::unique_ptr<JobVerifier> profile_verifier(const JobSpec& job);

// For mesh jobs: the swept-tool index of the mesh as the job uses it (transformed), e.g.
// SharedMesh::swept_index() (the verifier only reads it), asked for at the first check; its
// time is the statistic verify_index_s (0 when the chord guard or an earlier job built it).
std::unique_ptr<JobVerifier> mesh_verifier(const JobSpec& job, SweptIndexSource index);

// For pocket3d jobs: the walls and islands as above, the ball against the exact bottom, and
// the realised scallop on a grid (stats verify_max_scallop, verify_scallop_bound).
std::unique_ptr<JobVerifier> pocket3d_verifier(const JobSpec& job);

// What the verifier needs of a job stored in a CL file (operation, input, transform, tool,
// stock, depth, surface, ...), from its attributes. Throws std::invalid_argument when they
// do not say (an unknown operation, unreadable JSON).
JobSpec stored_job_spec(const std::string& operation, const std::string& input_path,
                        const std::string& tool_json, const std::string& params_json);

// Statistics of a job's chord guard (engine/chord_guard.hpp): chord_guard_moves,
// chord_guard_lifted, chord_guard_points_added, chord_guard_max_lift, chord_guard_s.
void push_guard_stats(const ChordGuard& guard, std::vector<out::StatValue>& stats);

// A report's worst violations as /jobs/<job>/verify/worst (float64, kWorstColumns per row:
// move, path, x0, y0, z0, x1, y1, z1, amount, kind), and back from those rows.
inline constexpr std::size_t kWorstColumns = 10;
void write_verify_worst(out::ClJob& cl, const VerifyReport& report);
std::vector<VerifyViolation> violations_from_rows(std::span<const double> rows);

// "move 12 ... cuts 0.01 mm into the wall" when the job fails its verification, else "".
std::string verification_failure(const VerifyReport& report);

}  // namespace ncpath::jobs
