#pragma once
// Runs a batch: its jobs as tasks (each one parallel inside), several at once when cores
// would otherwise idle and their memory estimates fit the budget (batch_schedule.hpp), all
// results into one HDF5 CL file in batch order (ordered_output.hpp): every job's datasets
// are the same however many ran at once. A job that fails is recorded with its status and
// message and the batch goes on.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "batch/jobs/job_spec.hpp"
#include "batch/output/cl_writer.hpp"

namespace ncpath::jobs {

struct JobOutcome {
  std::string name;
  std::string status;   // "ok", "invalid_input", "invalid_parameter", "io_error", ...
  std::string message;  // what went wrong, for a person; when ok: a warning or empty
  std::uint64_t points = 0;
  double seconds = 0;    // wall time of the whole job
  double compute_s = 0;  // drop-cutting only
  std::uint64_t peak_rss_bytes = 0;
};

// Called from the threads that run the jobs, several at once when jobs run at the same
// time: the functions must be thread-safe. `index` is the job's place in the batch.
struct BatchObserver {
  std::function<void(std::size_t index, std::size_t count, const JobSpec&)> job_started;
  std::function<void(std::size_t index, std::uint64_t done, std::uint64_t total)> progress;
  std::function<void(std::size_t index, const JobOutcome&)> job_finished;
};

// The warning an ok job carries as its message ("" when none): z-level contour chains that
// could not be closed (stats open_chains of zlevel, zlevel_open_chains of pencil) are missing
// from the output or give no pencil candidates.
std::string open_chain_warning(const std::vector<out::StatValue>& stats);

// The warning of an ok job that wrote no point: "warning: nothing to cut (0 points): " and
// why, for the job's operation (a profile: the tool fits in none of its regions).
std::string nothing_to_cut_warning(const JobSpec& job);
// `message` led by nothing_to_cut_warning(job) when the job wrote no point (points == 0).
std::string with_nothing_to_cut(const JobSpec& job, std::uint64_t points,
                                const std::string& message);

// "warning: " and the input's warning (profile_input.hpp kInputWarningStat: units the reader
// had to guess, regions left out), or "" when there is none.
std::string input_warning(const std::vector<out::StatValue>& stats);

// Every warning an ok job carries, "; "-separated ("" when none): the input's
// (profile_input.hpp kInputWarningStat: units the reader had to guess), then
// open_chain_warning's.
std::string ok_job_warning(const std::vector<out::StatValue>& stats);

// Throws std::runtime_error only when the output file itself cannot be written.
std::vector<JobOutcome> run_batch(const BatchSpec& batch, const BatchObserver& observer);

}  // namespace ncpath::jobs
