#include "batch/output/cl_state.hpp"

#include <exception>
#include <stdexcept>
#include <utility>

namespace ncpath::out {

void check_link_name(const std::string& name, const char* what) {
  if (name.empty() || name == "." || name == ".." ||
      name.find_first_of(std::string_view("/\0", 2)) != std::string::npos) {
    throw std::invalid_argument(std::string(what) + " '" + name +
                                "' is not a valid name (empty, '.', '..', or contains '/' "
                                "or NUL)");
  }
}

void check_no_nul(std::string_view value, const char* what) {
  if (value.find('\0') != std::string_view::npos) {
    throw std::invalid_argument(std::string(what) + " contains a NUL character");
  }
}

void check_status_code(std::string_view status) {
  bool ok = !status.empty();
  for (const char c : status) {
    ok = ok && ((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_');
  }
  if (!ok) {
    throw std::invalid_argument("set_status: status '" + std::string(status) +
                                "' is not a code like \"ok\" or \"invalid_input\"");
  }
}

namespace detail {

void FileState::close_job() {
  if (!job) return;  // the appenders lock around their HDF5 calls, compressing without it
  std::unique_ptr<JobState> j = std::move(job);
  std::exception_ptr first;
  for (auto* a : {&j->points, &j->contact, &j->offsets, &j->kinds}) {
    try {
      if (*a && !j->broken) (*a)->finish();
    } catch (...) {
      if (!first) first = std::current_exception();
    }
    if (*a) (*a)->close();
  }
  for (JobState::Streamed& a : j->arrays) {
    try {
      if (!j->broken) a.rows.finish();
    } catch (...) {
      if (!first) first = std::current_exception();
    }
    a.rows.close();
  }
  j.reset();
  // Flushing after every job puts finished jobs on disk: best effort if the process dies later.
  try {
    const auto lock = h5::library_lock();
    if (H5Fflush(file.get(), H5F_SCOPE_LOCAL) < 0) h5::fail(ctx, "flush file");
  } catch (...) {
    if (!first) first = std::current_exception();
  }
  if (first) std::rethrow_exception(first);
}

void FileState::close() {
  if (!file.valid()) return;
  const auto lock = h5::library_lock();
  std::exception_ptr first;
  try {
    close_job();
  } catch (...) {
    first = std::current_exception();
  }
  jobs.reset();
  const hid_t id = file.release();  // H5Fclose, not H5Idec_ref: its error matters
  try {
    if (H5Fclose(id) < 0) h5::fail(ctx, "close file");
  } catch (...) {
    if (!first) first = std::current_exception();
  }
  if (first) std::rethrow_exception(first);
}

FileState::~FileState() {
  try {
    close();
  } catch (...) {  // destructors never throw; ClFile::close() reports errors
  }
}

}  // namespace detail
}  // namespace ncpath::out
