#pragma once
// The zlevel operation of a job (issue 5): z-level contouring of a mesh with a ball-end mill
// (engine/zlevel.hpp). The mesh is read and transformed by the job runner, as for scan; this
// runs the engine and writes
//   - the CL paths (one closed cut path per contour, a one-point rapid path before every
//     contour but the first) to cl/ as they stream in, and to the G-code writer when there
//     is one;
//   - the exact contours: every typed segment (line, circular or elliptic arc) with its
//     element and shadow flag, every junction with its kind and bi-contact vectors, and the
//     level and hole flag of every contour, group `zlevel` (layout in docs/hdf5-schema.md),
//     written once the run is over (kept in memory meanwhile: about 200 bytes a segment);
//   - every ZLevelOpStats field as a statistic.
#include <cstdint>
#include <vector>

#include "batch/jobs/job_spec.hpp"
#include "batch/output/cl_writer.hpp"
#include "batch/output/gcode_writer.hpp"
#include "engine/run_control.hpp"
#include "kernels/mesh/triangle_mesh.hpp"

namespace ncpath::jobs {

struct ZLevelJobSummary {
  std::uint64_t points = 0;  // CL points written (contours and rapids)
  double compute_s = 0;      // the levels (wall time of the chunk computations)
};

// mesh: already transformed. Throws std::invalid_argument when the tool is not a ball, the
// parameters are bad or the mesh has no usable facet (the engine's message); Cancelled.
ZLevelJobSummary run_zlevel_job(const JobSpec& job, const TriangleMesh& mesh, out::ClJob& cl,
                                out::GcodeWriter* gcode, RunControl& control,
                                std::vector<out::StatValue>& stats,
                                const ConditionedMesh* conditioned = nullptr);

}  // namespace ncpath::jobs
