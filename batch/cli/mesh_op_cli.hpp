#pragma once
// The zlevel, pencil and fillet commands of the ncpath CLI: their options (defaults from
// ZLevelOpParams, PencilParams and FilletParams) and the job each builds, the same JobSpec a
// batch file with operation "zlevel", "pencil" or "fillet" gives.
#include <CLI/CLI.hpp>

#include <optional>
#include <string>
#include <vector>

#include "batch/cli/cli_options.hpp"
#include "batch/jobs/job_spec.hpp"

namespace ncpath::cli {

// ncpath zlevel --mesh M --tool ball:D (--levels z1,z2,... | --step-down S) [--tolerance T]
class ZLevelCommand {
 public:
  explicit ZLevelCommand(CLI::App& app);
  ZLevelCommand(const ZLevelCommand&) = delete;  // CLI11 holds pointers to the members
  ZLevelCommand& operator=(const ZLevelCommand&) = delete;
  bool parsed() const { return cmd_->parsed(); }
  // Adds the job (with its error, if any) to the batch.
  void add_job(jobs::BatchSpec& batch, bool& quiet) const;

 private:
  CLI::App* cmd_;
  CLI::Option *levels_opt_, *step_opt_;
  Common common_;
  GcodeCli gcode_;
  ZLevelOpParams params_;
};

// ncpath pencil --mesh M --tool ball:D [--interval --step-down --min-angle --tolerance
// --merge-distance --min-length --margin --floor-z --stock --direction]
class PencilCommand {
 public:
  explicit PencilCommand(CLI::App& app);
  PencilCommand(const PencilCommand&) = delete;
  PencilCommand& operator=(const PencilCommand&) = delete;
  bool parsed() const { return cmd_->parsed(); }
  void add_job(jobs::BatchSpec& batch, bool& quiet) const;

 private:
  CLI::App* cmd_;
  Common common_;
  GcodeCli gcode_;
  PencilParams params_;
  std::optional<double> floor_z_;
  std::string direction_ = "any";
};

// ncpath fillet --mesh M --tool ball:d --reference ball:D [--stepover S | --scallop H]
// [--max-passes N] [--stock --direction] [the pencil options, for the reference ball's pencil
// run]
class FilletCommand {
 public:
  explicit FilletCommand(CLI::App& app);
  FilletCommand(const FilletCommand&) = delete;
  FilletCommand& operator=(const FilletCommand&) = delete;
  bool parsed() const { return cmd_->parsed(); }
  void add_job(jobs::BatchSpec& batch, bool& quiet) const;

 private:
  CLI::App* cmd_;
  CLI::Option* scallop_opt_;
  Common common_;
  GcodeCli gcode_;
  std::string reference_;
  FilletParams params_;
  std::optional<double> floor_z_;
  std::string direction_ = "any";
};

}  // namespace ncpath::cli
