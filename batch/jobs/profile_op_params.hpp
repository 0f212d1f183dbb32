#pragma once
// Parameters of the profile operations (offset, pocket, pocket3d) in batch files: reading the
// `params` table into the JobSpec. The checks, and the order / milling / stepover parsers the
// command line shares, are declared in job_spec.hpp and defined in profile_op_params.cpp.
// Internal to the batch library (job_spec.cpp); the keys are listed in docs/cli.md.
#include "batch/jobs/job_spec.hpp"
#include "batch/jobs/toml_keys.hpp"

namespace ncpath::jobs {

// offset: stepover (required; mm, or a percentage of job.tool's diameter like "40%"), stock,
// depth, tolerance, join_tolerance. The first problem lands in k.error, named by its key.
void parse_offset_params(Keys& k, JobSpec& job);
// pocket: stepover (absent: the default parse_job set), stock, depth (required), stepdown,
// tolerance, join_tolerance, order, milling, helix_radius, ramp_angle, clearance.
void parse_pocket_params(Keys& k, JobSpec& job);
// pocket3d: scallop (required), eps, delta, stock, tolerance (absent: from eps),
// join_tolerance, order, milling, clearance, min_interval.
void parse_pocket3d_params(Keys& k, JobSpec& job);

}  // namespace ncpath::jobs
