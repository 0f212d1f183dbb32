// ClJob: appending paths, status and statistics of one job (ClFile is in cl_writer.cpp).
#include "batch/output/cl_writer.hpp"

#include <cmath>
#include <set>
#include <stdexcept>
#include <utility>
#include <variant>

#include "batch/output/cl_state.hpp"

namespace ncpath::out {

ClJob::ClJob(std::shared_ptr<detail::FileState> file, std::uint64_t serial)
    : file_(std::move(file)), serial_(serial) {}

ClJob::ClJob(ClJob&& other) noexcept
    : file_(std::move(other.file_)),
      serial_(std::exchange(other.serial_, 0)),
      observer_(std::move(other.observer_)) {}

ClJob& ClJob::operator=(ClJob&& other) noexcept {
  if (this != &other) {
    try {
      close();
    } catch (...) {
    }
    file_ = std::move(other.file_);
    serial_ = std::exchange(other.serial_, 0);
    observer_ = std::move(other.observer_);
  }
  return *this;
}

ClJob::~ClJob() {
  try {
    close();
  } catch (...) {  // never throws; close() is the reporting path
  }
}

detail::FileState& ClJob::open_file(const char* operation) const {
  if (!file_ || !file_->job || file_->job_serial != serial_) {
    throw std::logic_error(std::string("ClJob::") + operation +
                           ": the job is closed (or moved from)");
  }
  return *file_;
}

void ClJob::close() {
  if (!file_) return;
  std::shared_ptr<detail::FileState> file = std::move(file_);
  if (file->job && file->job_serial == serial_) file->close_job();
}

std::int64_t ClJob::points_written() const {
  return open_file("points_written").job->points->rows();
}

std::int64_t ClJob::paths_written() const { return open_file("paths_written").job->kinds->rows(); }

void ClJob::append_paths(std::span<const double> xyz, std::span<const std::uint8_t> contact,
                         std::span<const std::uint32_t> path_sizes,
                         std::span<const std::uint8_t> path_kinds) {
  detail::FileState& s = open_file("append_paths");
  detail::JobState& j = *s.job;
  const std::string where = "append_paths (job '" + j.name + "'): ";
  if (j.broken) {
    throw std::runtime_error(where + "an earlier write to '" + s.ctx.file +
                             "' failed; the job takes no more paths");
  }
  // Check everything before writing anything.
  const std::size_t n = contact.size();
  if (xyz.size() != 3 * n) {
    throw std::invalid_argument(where + "xyz has " + std::to_string(xyz.size()) +
                                " values, expected 3 * " + std::to_string(n) + " points");
  }
  if (path_sizes.size() != path_kinds.size()) {
    throw std::invalid_argument(where + std::to_string(path_sizes.size()) + " path sizes but " +
                                std::to_string(path_kinds.size()) + " path kinds");
  }
  std::uint64_t total = 0;
  for (const std::uint32_t size : path_sizes) total += size;
  if (total != n) {
    throw std::invalid_argument(where + "path sizes add up to " + std::to_string(total) +
                                ", but there are " + std::to_string(n) + " points");
  }
  for (std::size_t k = 0; k < path_kinds.size(); ++k) {
    if (path_kinds[k] > kMaxPathKind) {
      throw std::invalid_argument(where + "path " + std::to_string(k) + " has kind " +
                                  std::to_string(path_kinds[k]) + " (valid: 0..2)");
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (contact[i] > kMaxContactKind) {
      throw std::invalid_argument(where + "point " + std::to_string(i) + " has contact kind " +
                                  std::to_string(contact[i]) + " (valid: 0..3)");
    }
  }
  // x and y are always finite; z is NaN exactly where the tool touched nothing (the point
  // operation reports misses that way instead of inventing a height).
  for (std::size_t i = 0; i < xyz.size(); ++i) {
    const bool z_of_miss = i % 3 == 2 && contact[i / 3] == kContactNone && std::isnan(xyz[i]);
    if (!std::isfinite(xyz[i]) && !z_of_miss) {
      throw std::invalid_argument(where + "point " + std::to_string(i / 3) +
                                  " has a non-finite coordinate");
    }
  }

  if (observer_) {
    ClChunk copy;
    copy.xyz.assign(xyz.begin(), xyz.end());
    copy.contact.assign(contact.begin(), contact.end());
    copy.path_sizes.assign(path_sizes.begin(), path_sizes.end());
    copy.path_kinds.assign(path_kinds.begin(), path_kinds.end());
    observer_(copy);
  }
  // Path by path, so that the order in which chunks fill up (and get written) depends only on
  // the data, not on how the caller split it across calls.
  try {
    std::size_t start = 0;
    for (std::size_t k = 0; k < path_sizes.size(); ++k) {
      const std::size_t size = path_sizes[k];
      j.kinds->append(&path_kinds[k], 1);
      j.points->append(xyz.data() + 3 * start, size);
      j.contact->append(contact.data() + start, size);
      const std::int64_t end = j.points->rows();
      j.offsets->append(&end, 1);
      start += size;
    }
  } catch (...) {
    j.broken = true;
    throw;
  }
}

void ClJob::set_status(std::string_view status, std::string_view message) {
  detail::FileState& s = open_file("set_status");
  const auto lock = h5::library_lock();
  check_status_code(status);
  check_no_nul(message, "set_status: message");
  h5::write_attribute(s.job->group.get(), "status", status, s.ctx);
  h5::write_attribute(s.job->group.get(), "message", message, s.ctx);
}

void ClJob::write_stats(std::span<const StatValue> stats) {
  detail::FileState& s = open_file("write_stats");
  const auto lock = h5::library_lock();
  const hid_t group = s.job->stats.get();
  std::set<std::string> seen;
  for (const StatValue& st : stats) {
    check_link_name(st.name, "statistic name");
    check_no_nul(st.unit, "statistic unit");
    if (const auto* text = std::get_if<std::string>(&st.value)) {
      check_no_nul(*text, "statistic value");
    }
    const htri_t exists = H5Lexists(group, st.name.c_str(), H5P_DEFAULT);
    h5::check(exists, s.ctx, "look up statistic '" + st.name + "'");
    if (exists > 0 || !seen.insert(st.name).second) {
      throw std::invalid_argument("write_stats: statistic '" + st.name +
                                  "' written twice in job '" + s.job->name + "'");
    }
  }
  for (const StatValue& st : stats) {
    std::visit([&](const auto& v) { h5::write_scalar(group, st.name, v, s.ctx); }, st.value);
    if (!st.unit.empty()) {
      h5::Handle ds = h5::own(H5Dopen2(group, st.name.c_str(), H5P_DEFAULT), s.ctx,
                              "open statistic '" + st.name + "'");
      h5::write_attribute(ds.get(), "unit", st.unit, s.ctx);
    }
  }
}

}  // namespace ncpath::out
