#pragma once
// Parameters of the zlevel, pencil and fillet operations in batch files: reading the `params`
// table, and writing them back as the JSON of the job's `params` attribute (defaults included).
// Internal to the batch library (job_spec.cpp, job_spec_json.cpp); the keys are listed in
// docs/cli.md.
#include <nlohmann/json.hpp>

#include "batch/jobs/toml_keys.hpp"
#include "engine/fillet.hpp"
#include "engine/pencil.hpp"
#include "engine/zlevel.hpp"

namespace ncpath::jobs {

// zlevel: levels (array of tool-tip z, mm) or step_down (mm), exactly one of them (checked
// here when `params` has either; a job with neither is refused by parse_job), tolerance,
// chunk_levels. The first problem lands in k.error, named by its key.
void parse_zlevel_params(Keys& k, ZLevelOpParams& p);
// pencil: interval, step_down, min_angle (degrees), tolerance, merge_distance, min_length,
// margin, floor_z, stock, direction.
void parse_pencil_params(Keys& k, PencilParams& p);
// fillet: reference (required, a ball larger than `tool`, the job's own), stepover, scallop,
// max_passes, stock and direction (FilletParams' own), and the other pencil keys of the
// reference run (into p.pencil). reference_text: as written.
void parse_fillet_params(Keys& k, const Cutter& tool, FilletParams& p, std::string& reference_text);

// Adds the operation's keys to j.
void zlevel_params_json(const ZLevelOpParams& p, nlohmann::ordered_json& j);
void pencil_params_json(const PencilParams& p, nlohmann::ordered_json& j);
void fillet_params_json(const FilletParams& p, const std::string& reference_text,
                        nlohmann::ordered_json& j);

}  // namespace ncpath::jobs
