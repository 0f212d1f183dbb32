#pragma once
// The pocket operation of a job: read a pocket profile (DXF or TOML), chain and nest it,
// plan the linked pocket tool path (engine/pocket_path.hpp: offset loops, clean-up of uncut
// regions, helix/ramp/plunge entry, depth passes) and write it as CL paths, in cutting
// order, and as G-code when asked. Every PocketPathStats field becomes a statistic.
#include <cstdint>
#include <vector>

#include "batch/jobs/job_spec.hpp"
#include "batch/output/cl_writer.hpp"
#include "batch/output/gcode_writer.hpp"
#include "engine/pocket_path.hpp"

namespace ncpath::jobs {

struct PocketJobSummary {
  std::uint64_t points = 0;
  double compute_s = 0;  // plan_pocket, all stages
};

// The rapid height of a linked pocket job (pocket, pocket3d), mm: the G-code's safe height
// when G-code is written, else job.gcode_safe_z, else kDefaultSafeAboveTop above the top.
// Throws std::invalid_argument (naming --safe-z / gcode.safe_z) when it is below
// top + clearance, the plane where feed moves start.
double pocket_safe_z(const JobSpec& job, const out::GcodeWriter* gcode, double top,
                     double clearance);

// The statistics every linked pocket job writes (pocket, pocket3d), with their units.
void push_plan_stats(const PocketPlanStats& s, std::vector<out::StatValue>& stats);

// Throws io::ReadError for unreadable or malformed profiles and for profiles that do not
// chain into closed, non-crossing loops; std::invalid_argument for parameters the planner
// refuses and for a region the tool does not fit in (the message then names the input
// entities of that region's boundary, e.g. "LWPOLYLINE 2F").
// gcode: when not null, the path is written there too; its safe height is the path's rapid
// height (else job.gcode_safe_z, else 5 mm above the top z = 0).
PocketJobSummary run_pocket_job(const JobSpec& job, out::ClJob& cl, out::GcodeWriter* gcode,
                                std::vector<out::StatValue>& stats);

}  // namespace ncpath::jobs
