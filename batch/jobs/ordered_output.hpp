#pragma once
// The batch's one CL file, written in batch order whatever order its jobs end in, each job's
// datasets the same bytes however many jobs ran at once.
//
// A job writes straight into the file when every earlier job is in it already and no other
// job is writing there: always so when jobs run one at a time. Otherwise it writes a spool
// file of its own next to the output (`<output>.spool-<index>.h5`), which is copied into
// the file exactly (out::ClFile::copy_job: the stored chunks as they are) and removed once
// every earlier job is in. Thread-safe: jobs call begin and finished from their threads.
#include <cstddef>
#include <filesystem>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "batch/output/cl_writer.hpp"

namespace ncpath::jobs {

class OrderedOutput {
 public:
  OrderedOutput(out::ClFile& file, std::size_t jobs);
  ~OrderedOutput();  // removes spool files left behind by a batch that stopped early
  OrderedOutput(const OrderedOutput&) = delete;
  OrderedOutput& operator=(const OrderedOutput&) = delete;

  // Starts job `index`'s group, in the file or in a new spool file. Throws like
  // out::ClFile::begin_job.
  out::ClJob begin(std::size_t index, const std::string& name, const out::JobInfo& info);
  // Job `index` has closed its ClJob: it and every finished job after it, up to the first
  // one still running, go into the file. std::runtime_error when the file cannot be written;
  // after that, finished jobs are no longer copied (the batch is stopping).
  void finished(std::size_t index);

  // The spool file of job `index` (whether or not it is used).
  std::filesystem::path spool_path(std::size_t index) const;
  // Jobs that went through a spool file so far.
  std::size_t spooled() const;

 private:
  enum class Where { kNotBegun, kFile, kSpool };
  struct Job {
    Where where = Where::kNotBegun;
    std::string name;
    std::unique_ptr<out::ClFile> spool;
    bool finished = false;
  };
  void write_finished_in_order();  // holding mutex_

  mutable std::mutex mutex_;
  out::ClFile& file_;
  std::vector<Job> jobs_;
  std::size_t next_ = 0;  // first job not in the file yet
  std::size_t spooled_ = 0;
  bool failed_ = false;  // writing into the file failed
};

}  // namespace ncpath::jobs
