// ClFile: creating the file and starting jobs (ClJob is in cl_job.cpp).
#include "batch/output/cl_writer.hpp"

#include <stdexcept>
#include <utility>

#include "batch/output/cl_state.hpp"

namespace ncpath::out {

ClFile::ClFile(const std::filesystem::path& path, std::string_view ncpath_version)
    : state_(std::make_shared<detail::FileState>()) {
  const auto lock = h5::library_lock();
  // Errors are turned into exceptions carrying HDF5's message; no printing to stderr.
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  check_no_nul(ncpath_version, "ncpath_version");

  detail::FileState& s = *state_;
  s.path = path;
  s.ctx.file = path.string();
  h5::Handle fcpl = h5::untimed_create_plist(H5P_FILE_CREATE, s.ctx);
  h5::Handle fapl = h5::own(H5Pcreate(H5P_FILE_ACCESS), s.ctx, "create file access list");
  // Closing the file really closes it, even if some object were still open.
  h5::check(H5Pset_fclose_degree(fapl.get(), H5F_CLOSE_STRONG), s.ctx, "set close degree");
  s.file =
      h5::own(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, fcpl.get(), fapl.get()), s.ctx, "create file");

  h5::write_attribute(s.file.get(), "format", kFormatName, s.ctx);
  h5::write_attribute(s.file.get(), "format_version", kFormatVersion, s.ctx);
  h5::write_attribute(s.file.get(), "ncpath_version", ncpath_version, s.ctx);
  s.jobs = h5::create_group(s.file.get(), "jobs", s.ctx);
}

void ClFile::mark_batch(std::int64_t jobs, bool complete) {
  if (!state_) throw std::logic_error("ClFile::mark_batch: moved-from ClFile");
  const auto lock = h5::library_lock();
  detail::FileState& s = *state_;
  for (const char* name : {"batch_jobs", "batch_complete"})
    if (H5Aexists(s.file.get(), name) > 0)
      h5::check(H5Adelete(s.file.get(), name), s.ctx, std::string("replace attribute ") + name);
  h5::write_attribute(s.file.get(), "batch_jobs", jobs, s.ctx);
  h5::write_attribute(s.file.get(), "batch_complete", std::int64_t{complete}, s.ctx);
  h5::check(H5Fflush(s.file.get(), H5F_SCOPE_LOCAL), s.ctx, "flush file");
}

ClFile::~ClFile() {
  try {
    if (state_) state_->close();
  } catch (...) {  // never throws; close() is the reporting path
  }
}

ClFile::ClFile(ClFile&&) noexcept = default;

ClFile& ClFile::operator=(ClFile&& other) noexcept {
  if (this != &other) {
    try {
      if (state_) state_->close();
    } catch (...) {
    }
    state_ = std::move(other.state_);
  }
  return *this;
}

void ClFile::close() {
  if (state_) state_->close();
}

void ClFile::copy_job(const std::filesystem::path& from, const std::string& name) {
  if (!state_ || !state_->file.valid())
    throw std::logic_error("copy_job('" + name + "'): the file is closed");
  detail::FileState& s = *state_;
  const auto lock = h5::library_lock();
  if (s.job)
    throw std::logic_error("copy_job('" + name + "'): job '" + s.job->name + "' is open");
  check_link_name(name, "job name");
  const h5::Context src_ctx{from.string()};
  h5::Handle src =
      h5::own(H5Fopen(from.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), src_ctx, "open spool file");
  const std::string src_path = "/jobs/" + name;
  const htri_t there = H5Lexists(src.get(), "jobs", H5P_DEFAULT) > 0
                           ? H5Lexists(src.get(), src_path.c_str(), H5P_DEFAULT)
                           : 0;
  if (there <= 0)
    throw std::invalid_argument("copy_job: '" + from.string() + "' has no job '" + name + "'");
  if (H5Lexists(s.jobs.get(), name.c_str(), H5P_DEFAULT) > 0)
    throw std::invalid_argument("copy_job: a job named '" + name + "' already exists in '" +
                                s.ctx.file + "'");
  const h5::Handle lcpl = h5::utf8_link_plist(s.ctx);
  h5::check(H5Ocopy(src.get(), src_path.c_str(), s.jobs.get(), name.c_str(), H5P_DEFAULT,
                    lcpl.get()),
            s.ctx, "copy job '" + name + "' from '" + from.string() + "'");
  h5::check(H5Fflush(s.file.get(), H5F_SCOPE_LOCAL), s.ctx, "flush file");
}

const std::filesystem::path& ClFile::path() const {
  if (!state_) throw std::logic_error("ClFile::path: moved-from ClFile");
  return state_->path;
}

ClJob ClFile::begin_job(const std::string& name, const JobInfo& info) {
  if (!state_ || !state_->file.valid()) {
    throw std::logic_error("begin_job('" + name + "'): the file is closed");
  }
  detail::FileState& s = *state_;
  const auto lock = h5::library_lock();
  if (s.job) {
    throw std::logic_error("begin_job('" + name + "'): job '" + s.job->name +
                           "' is still open in '" + s.ctx.file + "'");
  }
  check_link_name(name, "job name");
  check_no_nul(info.operation, "JobInfo::operation");
  check_no_nul(info.input_path, "JobInfo::input_path");
  check_no_nul(info.input_sha256, "JobInfo::input_sha256");
  check_no_nul(info.tool_json, "JobInfo::tool_json");
  check_no_nul(info.params_json, "JobInfo::params_json");
  const htri_t exists = H5Lexists(s.jobs.get(), name.c_str(), H5P_DEFAULT);
  h5::check(exists, s.ctx, "look up job '" + name + "'");
  if (exists > 0) {
    throw std::invalid_argument("begin_job: a job named '" + name + "' already exists in '" +
                                s.ctx.file + "'");
  }

  auto job = std::make_unique<detail::JobState>();
  job->name = name;
  job->group = h5::create_group(s.jobs.get(), name, s.ctx);
  const hid_t g = job->group.get();
  h5::write_attribute(g, "operation", info.operation, s.ctx);
  h5::write_attribute(g, "status", kDefaultStatus, s.ctx);
  h5::write_attribute(g, "message", kDefaultMessage, s.ctx);
  h5::write_attribute(g, "input_path", info.input_path, s.ctx);
  h5::write_attribute(g, "input_sha256", info.input_sha256, s.ctx);
  h5::write_attribute(g, "tool", info.tool_json, s.ctx);
  h5::write_attribute(g, "params", info.params_json, s.ctx);

  const std::string prefix = "/jobs/" + name + "/cl/";
  h5::Handle cl = h5::create_group(g, "cl", s.ctx);
  h5::Handle points = h5::create_appendable(cl.get(), "points", H5T_IEEE_F64LE, 3, kPointChunkRows,
                                            kDeflateLevel, s.ctx);
  h5::write_attribute(points.get(), "units", "mm", s.ctx);
  h5::write_attribute(points.get(), "columns", "x,y,z", s.ctx);
  h5::Handle offsets = h5::create_appendable(cl.get(), "path_offsets", H5T_STD_I64LE, 0,
                                             kOffsetChunkRows, kDeflateLevel, s.ctx);
  h5::Handle kinds = h5::create_appendable(cl.get(), "path_kind", H5T_STD_U8LE, 0,
                                           kPathKindChunkRows, kDeflateLevel, s.ctx);
  h5::write_attribute(kinds.get(), "enum", kPathKindEnum, s.ctx);
  h5::Handle contact = h5::create_appendable(cl.get(), "contact_kind", H5T_STD_U8LE, 0,
                                             kContactChunkRows, kDeflateLevel, s.ctx);
  h5::write_attribute(contact.get(), "enum", kContactKindEnum, s.ctx);
  job->stats = h5::create_group(g, "stats", s.ctx);

  job->points.emplace(std::move(points), prefix + "points", sizeof(double), 3, kPointChunkRows,
                      kDeflateLevel, &s.ctx);
  job->contact.emplace(std::move(contact), prefix + "contact_kind", 1, 0, kContactChunkRows,
                       kDeflateLevel, &s.ctx);
  job->offsets.emplace(std::move(offsets), prefix + "path_offsets", sizeof(std::int64_t), 0,
                       kOffsetChunkRows, kDeflateLevel, &s.ctx);
  job->kinds.emplace(std::move(kinds), prefix + "path_kind", 1, 0, kPathKindChunkRows,
                     kDeflateLevel, &s.ctx);
  const std::int64_t zero = 0;  // path_offsets starts with 0
  job->offsets->append(&zero, 1);

  s.job = std::move(job);
  return ClJob(state_, ++s.job_serial);
}

}  // namespace ncpath::out
