#pragma once
// The pocket3d operation of a job (issue 7): read a pocket profile (DXF or TOML) and its
// sculptured bottom (a NURBS surface, batch/io/surface_toml.hpp), plan the ball-end path
// (engine/pocket3d.hpp: offset loops spaced for the scallop height, CL points dropped onto
// the bottom within eps in plan and delta on the surface, linked like a flat pocket) and
// write it: CL paths in cutting order, the CC point and bottom normal of every CL point and
// the level and path interval of every offset loop (group `pocket3d`), every Pocket3dStats
// field as a statistic, and G-code when asked.
#include <cstdint>
#include <vector>

#include "batch/jobs/job_spec.hpp"
#include "batch/output/cl_writer.hpp"
#include "batch/output/gcode_writer.hpp"

namespace ncpath::jobs {

struct Pocket3dJobSummary {
  std::uint64_t points = 0;
  double compute_s = 0;  // plan_pocket3d, all stages
};

// Throws io::ReadError for an unreadable or malformed profile or surface, for a profile that
// does not chain into closed, non-crossing loops, and for a bottom that rises above the stock
// top z = 0 inside the pocket; std::invalid_argument for parameters the planner refuses, a
// pocket that does not lie over the surface ("... is outside the bottom surface's plan
// outline ...") and a region the ball does not fit in (named by its boundary's entities).
// gcode: when not null, the path is written there too; its safe height is the path's rapid
// height (else job.gcode_safe_z, else 5 mm above the top z = 0).
Pocket3dJobSummary run_pocket3d_job(const JobSpec& job, out::ClJob& cl, out::GcodeWriter* gcode,
                                    std::vector<out::StatValue>& stats);

}  // namespace ncpath::jobs
