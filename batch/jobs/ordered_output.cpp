#include "batch/jobs/ordered_output.hpp"

#include <stdexcept>
#include <system_error>

namespace ncpath::jobs {

OrderedOutput::OrderedOutput(out::ClFile& file, std::size_t jobs) : file_(file), jobs_(jobs) {}

OrderedOutput::~OrderedOutput() {
  for (std::size_t i = 0; i < jobs_.size(); ++i) {
    if (jobs_[i].where != Where::kSpool) continue;
    jobs_[i].spool.reset();
    std::error_code ec;
    std::filesystem::remove(spool_path(i), ec);
  }
}

std::filesystem::path OrderedOutput::spool_path(std::size_t index) const {
  std::filesystem::path p = file_.path();
  p += ".spool-" + std::to_string(index) + ".h5";
  return p;
}

std::size_t OrderedOutput::spooled() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return spooled_;
}

out::ClJob OrderedOutput::begin(std::size_t index, const std::string& name,
                                const out::JobInfo& info) {
  const std::lock_guard<std::mutex> lock(mutex_);
  Job& job = jobs_.at(index);
  if (job.where != Where::kNotBegun)
    throw std::logic_error("OrderedOutput::begin: job " + std::to_string(index) + " begun twice");
  job.name = name;
  // At next_ no other job writes into the file: one that did would be before this one.
  if (index == next_) {
    job.where = Where::kFile;
    return file_.begin_job(name, info);
  }
  job.where = Where::kSpool;
  ++spooled_;
  job.spool = std::make_unique<out::ClFile>(spool_path(index), NCPATH_VERSION);
  return job.spool->begin_job(name, info);
}

void OrderedOutput::finished(std::size_t index) {
  const std::lock_guard<std::mutex> lock(mutex_);
  Job& job = jobs_.at(index);
  if (job.where == Where::kNotBegun || job.finished)
    throw std::logic_error("OrderedOutput::finished: job " + std::to_string(index) +
                           " is not running");
  if (job.spool) job.spool->close();
  job.finished = true;
  if (failed_) return;  // the file failed before: the batch is stopping
  try {
    write_finished_in_order();
  } catch (...) {
    failed_ = true;  // a copy may have stopped half-way: no more writes into the file
    throw;
  }
}

void OrderedOutput::write_finished_in_order() {
  while (next_ < jobs_.size() && jobs_[next_].finished) {
    Job& job = jobs_[next_];
    if (job.where == Where::kSpool) {
      file_.copy_job(spool_path(next_), job.name);
      job.spool.reset();
      std::error_code ec;
      std::filesystem::remove(spool_path(next_), ec);
      job.where = Where::kFile;
    }
    ++next_;
  }
}

}  // namespace ncpath::jobs
