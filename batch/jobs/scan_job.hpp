#pragma once
// The scan operation of a job (issue 5): curve-based drive-plane scanning of a mesh with a
// ball-end mill (engine/scan.hpp). The mesh is read and transformed by the job runner, as for
// raster; this runs the engine and writes
//   - the CL paths (cut lines, links at depth, a rapid between the x and y families) to
//     cl/ as they stream in, and to the G-code writer when there is one;
//   - the exact CL curves: every typed segment and every junction with its kind and
//     bi-contact vectors, group `scan` (layout in docs/hdf5-schema.md), written once the
//     run is over (they are kept in memory meanwhile: a few hundred bytes per segment);
//   - every ScanStats field as a statistic.
#include <cstdint>
#include <vector>

#include "batch/jobs/job_spec.hpp"
#include "batch/output/cl_writer.hpp"
#include "batch/output/gcode_writer.hpp"
#include "engine/run_control.hpp"
#include "kernels/mesh/triangle_mesh.hpp"

namespace ncpath::jobs {

class SharedMesh;

struct ScanJobSummary {
  std::uint64_t points = 0;  // CL points written (cuts, links, the rapid)
  double compute_s = 0;      // the planes (wall time of the chunk computations)
};

// mesh: already transformed. Throws std::invalid_argument when the tool is not a ball, the
// parameters are bad or the mesh has no usable facet (the engine's message); Cancelled.
// With `shared` (scan jobs of the batch with the same mesh and ball share their elements:
// batch/jobs/shared_mesh.hpp), the elements come from it; `elements_shared` is the statistic
// of that name (an earlier job builds them).
ScanJobSummary run_scan_job(const JobSpec& job, const TriangleMesh& mesh, out::ClJob& cl,
                            out::GcodeWriter* gcode, RunControl& control,
                            std::vector<out::StatValue>& stats, SharedMesh* shared = nullptr,
                            bool elements_shared = false);

}  // namespace ncpath::jobs
