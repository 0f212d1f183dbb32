#pragma once
// The offset operation of a job: read a pocket profile (DXF or TOML), chain and nest it,
// compute the multi-level offset loops, write them (exact segments, levels, OGH edges) and,
// until path linking exists, one closed CL path per loop at z = -depth.
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

// Throws io::ReadError for unreadable or malformed profiles, std::invalid_argument for
// profiles that do not chain into closed, non-crossing loops.
// gcode: when not null, the loop paths are written there too.
OffsetJobSummary run_offset_job(const JobSpec& job, out::ClJob& cl, out::GcodeWriter* gcode,
                                std::vector<out::StatValue>& stats);

}  // namespace ncpath::jobs
