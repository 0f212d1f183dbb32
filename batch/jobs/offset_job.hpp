#pragma once
// The offset operation of a job: read a pocket profile (DXF or TOML), chain and nest it,
// compute the multi-level offset loops, write them (exact segments, levels, OGH edges) and
// one closed, unlinked CL path per loop at z = -depth (pocket_job.hpp links them).
#include <cstdint>
#include <vector>

#include "batch/jobs/job_spec.hpp"
#include "batch/output/cl_writer.hpp"
#include "batch/output/gcode_writer.hpp"

namespace ncpath::jobs {

struct OffsetJobSummary {
  std::uint64_t points = 0;
  double compute_s = 0;
};

// Throws io::ReadError for unreadable or malformed profiles and for profiles that do not
// chain into closed, non-crossing loops.
// gcode: when not null, the loop paths are written there too.
OffsetJobSummary run_offset_job(const JobSpec& job, out::ClJob& cl, out::GcodeWriter* gcode,
                                std::vector<out::StatValue>& stats);

}  // namespace ncpath::jobs
