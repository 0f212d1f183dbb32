#pragma once
// Runs a batch: every job in turn (each one parallel inside), all results into one HDF5 CL
// file. A job that fails is recorded with its status and message and the batch goes on.
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

struct BatchObserver {
  std::function<void(std::size_t index, std::size_t count, const JobSpec&)> job_started;
  std::function<void(std::uint64_t done, std::uint64_t total)> progress;
  std::function<void(const JobOutcome&)> job_finished;
};

// The warning an ok job carries as its message ("" when none): z-level contour chains that
// could not be closed (stats open_chains of zlevel, zlevel_open_chains of pencil) are missing
// from the output or give no pencil candidates.
std::string open_chain_warning(const std::vector<out::StatValue>& stats);

// Throws std::runtime_error only when the output file itself cannot be written.
std::vector<JobOutcome> run_batch(const BatchSpec& batch, const BatchObserver& observer);

}  // namespace ncpath::jobs
