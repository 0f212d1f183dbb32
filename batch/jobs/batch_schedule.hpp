#pragma once
// Which jobs of a batch run at the same time. Jobs start in batch order, at most `slots` at
// once, and a job starts only while the memory estimates of the running jobs and its own
// fit the budget. A job always starts when nothing else runs, so a batch never refuses a
// job it would run alone; it only runs fewer at once.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "batch/jobs/job_spec.hpp"

namespace ncpath::jobs {

// Bytes a job may need at its peak: the facets of its mesh (io::facet_count_hint, on the
// generous side) times the bytes per facet its operation was measured to use on dense
// scans (docs/performance.md, "Memory per facet"), plus a fixed base. Profile jobs (offset,
// pocket, pocket3d) and jobs whose spec is invalid get the base only.
std::uint64_t estimate_job_bytes(const JobSpec& job);

// The default memory budget: three quarters of the memory the system has available now
// (MemAvailable in /proc/meminfo), or 4 GiB when that cannot be read.
std::uint64_t default_memory_limit();

// "8G", "512M", "1.5GiB", "2048" (bytes): binary multiples K, M, G, T, with an optional
// "B" or "iB". Returns "" and sets bytes, or the problem to follow the option's name.
std::string parse_byte_size(const std::string& text, std::uint64_t& bytes);

class Admission {
 public:
  // estimates: one per job, in batch order; limit: the budget in bytes; slots >= 1.
  Admission(std::vector<std::uint64_t> estimates, std::uint64_t limit, std::size_t slots);

  // The jobs that may start now, in batch order (none when the next one has to wait); they
  // count as running from now on.
  std::vector<std::size_t> start_ready();
  // Job `job` (running) has ended.
  void finished(std::size_t job);

  std::size_t running() const { return running_; }
  std::size_t started() const { return next_; }

 private:
  std::vector<std::uint64_t> estimates_;
  std::uint64_t limit_;
  std::size_t slots_;
  std::size_t next_ = 0;     // first job not started
  std::size_t running_ = 0;  // jobs started and not finished
  std::uint64_t in_use_ = 0; // the running jobs' estimates
  std::vector<bool> running_flag_;
};

}  // namespace ncpath::jobs
