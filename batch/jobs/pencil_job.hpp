#pragma once
// The pencil operation of a job (issue 6): pencil-cut clean-up of the concave creases of a
// mesh with a ball-end mill (engine/pencil.hpp). The mesh is read and transformed by the job
// runner; this runs the engine (not streamed: the paths are known only once every crease is
// traced, refined, checked and ordered) and writes
//   - the CL paths (one cut path per crease piece, oriented for the cut direction when one is
//     given, a one-point rapid path before every piece but the first; tool tips, raised by
//     the stock) to cl/, and to the G-code writer when there is one;
//   - every pencil point (a sharp-concave junction whose bi-contact angle reaches min_angle)
//     with its bi-contact vectors, angle, family and whether it was traced, group `pencil`
//     (layout in docs/hdf5-schema.md);
//   - every PencilStats field as a statistic.
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

struct PencilJobSummary {
  std::uint64_t points = 0;  // CL points written (pieces and rapids)
  double compute_s = 0;      // run_pencil, all stages
};

// mesh: already transformed; swept: its swept-tool index (the chord guard's), asked for after
// the computation, whose structures are freed by then. Throws
// std::invalid_argument when the tool is not a ball, the parameters are bad or the mesh has no
// usable facet (the engine's message); Cancelled.
PencilJobSummary run_pencil_job(const JobSpec& job, const TriangleMesh& mesh,
                                const SweptIndexSource& swept, out::ClJob& cl,
                                out::GcodeWriter* gcode, RunControl& control,
                                std::vector<out::StatValue>& stats,
                                const ConditionedMesh* conditioned = nullptr);

}  // namespace ncpath::jobs
