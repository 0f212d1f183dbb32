#pragma once
// The fillet operation of a job (issue 6): fillet-cut clean-up with a ball-end mill smaller
// than the reference finishing ball, in passes that follow the reference ball's pencil paths
// across what it left in the concave creases (engine/fillet.hpp). The mesh is read and
// transformed by the job runner; this runs the engine (not streamed: the passes of a crease
// are known only once its reference pencil path is) and writes
//   - the CL paths (per reference pencil path: its passes as cut paths, zig-zag, joined by
//     links at depth, or with a cut direction one-way, joined by one-point rapid paths; a
//     one-point rapid path before every pencil path's first pass but the first) to cl/, and
//     to the G-code writer when there is one;
//   - every FilletStats field as a statistic, the reference pencil run's prefixed
//     `reference_`.
#include <cstdint>
#include <memory>
#include <vector>

#include "batch/jobs/job_spec.hpp"
#include "batch/output/cl_writer.hpp"
#include "batch/output/gcode_writer.hpp"
#include "engine/run_control.hpp"
#include "engine/verify_mesh.hpp"
#include "kernels/mesh/triangle_mesh.hpp"

namespace ncpath::jobs {

struct FilletJobSummary {
  std::uint64_t points = 0;  // CL points written (passes, links and rapids)
  double compute_s = 0;      // run_fillet: the reference pencil run and the passes
};

// mesh: already transformed; swept: its swept-tool index (the chord guard's), asked for after
// the computation, whose structures are freed by then. Throws
// std::invalid_argument when the tool is not a ball, is not smaller than the reference, or the
// parameters are bad (the engine's message); Cancelled.
FilletJobSummary run_fillet_job(const JobSpec& job, const TriangleMesh& mesh,
                                const SweptIndexSource& swept, out::ClJob& cl,
                                out::GcodeWriter* gcode, RunControl& control,
                                std::vector<out::StatValue>& stats,
                                const ConditionedMesh* conditioned = nullptr);

}  // namespace ncpath::jobs
