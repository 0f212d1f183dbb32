#pragma once
// Writer of ncpath CL files (HDF5, schema "ncpath-cl" version 1; layout in
// docs/hdf5-schema.md). One ClFile per batch run, one ClJob per job in it.
//
//   out::ClFile file("run.h5", "0.1.0");
//   out::ClJob job = file.begin_job("part_a", info);
//   job.append_paths(xyz, contact, path_sizes, path_kinds);   // as often as needed
//   job.set_status("ok", "");
//   job.write_stats(stats);
//   job.close();
//   file.close();
//
// Errors: std::runtime_error for anything HDF5 or the file system refuses (the message names
// the file and the operation); std::invalid_argument for bad arguments (nothing is written);
// std::logic_error for misuse (second open job, use after close or move).
//
// Threads: one ClFile and its jobs are used by one thread at a time. Different ClFiles may
// be written from different threads at once: every HDF5 call of ClFile and ClJob is made
// under one process-wide lock (Debian's HDF5 is not a thread-safe build), and the writer
// compresses outside it.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <variant>

#include "batch/output/sha256.hpp"  // sha256_file, for JobInfo::input_sha256
#include "engine/cl_chunk.hpp"
#include "kernels/cutters/drop_cutter.hpp"

namespace ncpath::out {

inline constexpr std::string_view kFormatName = "ncpath-cl";  // file attribute `format`
inline constexpr std::int64_t kFormatVersion = 1;             // file attribute `format_version`

// The codes stored per path in /jobs/<job>/cl/path_kind and per point in
// /jobs/<job>/cl/contact_kind are the engine's and the kernels' own enums
// (ncpath::PathKind in engine/cl_chunk.hpp, ncpath::ContactKind in
// kernels/cutters/drop_cutter.hpp), so the two can never drift apart.
using PathKind = ncpath::PathKind;
inline constexpr std::uint8_t kContactNone = static_cast<std::uint8_t>(ContactKind::kNone);
inline constexpr std::uint8_t kContactVertex = static_cast<std::uint8_t>(ContactKind::kVertex);
inline constexpr std::uint8_t kContactEdge = static_cast<std::uint8_t>(ContactKind::kEdge);
inline constexpr std::uint8_t kContactFacet = static_cast<std::uint8_t>(ContactKind::kFacet);

// Provenance of one job, written as string attributes of /jobs/<job>.
struct JobInfo {
  std::string operation;     // e.g. "drop_raster"
  std::string input_path;    // as given by the user
  std::string input_sha256;  // lowercase hex of the input file (sha256_file)
  std::string tool_json;     // cutter definition, JSON text
  std::string params_json;   // operation parameters, JSON text
};

// One statistic: a scalar dataset /jobs/<job>/stats/<name> of type int64, float64 or string,
// with attribute `unit` when unit is non-empty (e.g. "s", "bytes").
struct StatValue {
  std::string name;
  std::variant<std::int64_t, double, std::string> value;
  std::string unit;
};

namespace detail {
struct FileState;
}

class ClJob;

// One CL file, created (or truncated) by the constructor. Not copyable; movable (a moved-from
// ClFile can only be destroyed or assigned to).
class ClFile {
 public:
  // Creates/truncates `path` and writes the file attributes. Throws std::runtime_error naming
  // the path when the file cannot be created. Turns off HDF5's automatic error printing for
  // the process (errors become exceptions instead).
  ClFile(const std::filesystem::path& path, std::string_view ncpath_version);
  ~ClFile();  // closes an open job, then the file; never throws (use close() to see errors)
  ClFile(ClFile&&) noexcept;
  ClFile& operator=(ClFile&&) noexcept;
  ClFile(const ClFile&) = delete;
  ClFile& operator=(const ClFile&) = delete;

  // Starts /jobs/<name>. `name` must be a valid HDF5 link name (non-empty, no '/', not "."/"..")
  // and unique in the file, else std::invalid_argument. Only one job may be open at a time
  // (std::logic_error otherwise). The job's status is "internal_error" / "job did not finish"
  // until ClJob::set_status is called, so a job that dies half-way is never reported ok.
  ClJob begin_job(const std::string& name, const JobInfo& info);

  // Copies job `name` from the CL file at `from` (written and closed by another ClFile, e.g.
  // a job's spool file) into this file's /jobs, exactly: every dataset's stored chunks,
  // attributes and statistics, members in the same order. The job comes after the jobs
  // already here. std::invalid_argument when `from` has no such job or this file has one of
  // that name; std::logic_error while a job is open here; std::runtime_error from HDF5.
  void copy_job(const std::filesystem::path& from, const std::string& name);

  // Root attributes of a batch's file: `batch_jobs` (the jobs the batch has) and
  // `batch_complete` (0 until the batch has ended and every job is in the file; a file whose
  // writer was killed keeps 0), flushed at once. std::runtime_error from HDF5.
  void mark_batch(std::int64_t jobs, bool complete);

  // Closes an open job and the file, reporting errors (std::runtime_error). Idempotent.
  void close();

  const std::filesystem::path& path() const;

 private:
  std::shared_ptr<detail::FileState> state_;
};

// One open job. Movable, not copyable. Closed by close() or the destructor; also closed (and
// made inert) when its ClFile is closed first.
class ClJob {
 public:
  ClJob(ClJob&&) noexcept;
  ClJob& operator=(ClJob&&) noexcept;  // closes the job held before, if any
  ClJob(const ClJob&) = delete;
  ClJob& operator=(const ClJob&) = delete;
  ~ClJob();  // close(), errors swallowed

  // Appends whole paths in cutting order.
  //   xyz:        3*n doubles, x0 y0 z0 x1 y1 z1 ...: tool-tip (CL) points, mm, finite except
  //               z = NaN at points whose contact is kContactNone (the tool touched nothing).
  //   contact:    n bytes, one kContact* code per point.
  //   path_sizes: one point count per path; their sum is n (empty paths are allowed).
  //   path_kinds: one PathKind value per path.
  // Arguments are all checked before anything is written (std::invalid_argument).
  // Memory: at most one chunk per dataset (about 1 MB in all) is buffered; every chunk is
  // written to disk exactly once when full, the last partial ones at close(). The file bytes
  // therefore depend only on the concatenated data, never on how it was split across calls.
  void append_paths(std::span<const double> xyz, std::span<const std::uint8_t> contact,
                    std::span<const std::uint32_t> path_sizes,
                    std::span<const std::uint8_t> path_kinds);

  // status: "ok" or an error code ("invalid_input", "invalid_parameter", "io_error",
  // "cancelled", "internal_error"); message: what a person can act on ("" for ok). Written
  // at once (replaces the previous value); may be called several times. Strings must not
  // contain NUL characters.
  void set_status(std::string_view status, std::string_view message);

  // Adds one scalar dataset per stat under /jobs/<job>/stats. Names follow the job-name rules
  // and must not already exist in this job (std::invalid_argument; checked before writing).
  void write_stats(std::span<const StatValue> stats);

  // Writes a whole array as /jobs/<job>/<group>/<name> (the group is created when needed):
  // shape [rows] when cols == 0, else [rows, cols] (data.size() == rows * cols). Chunked and
  // compressed like the CL datasets; attributes `unit` and `enum`/`description` when given.
  // For results other than CL paths (offset loops, graphs). Names must be new in the group.
  void write_array(const std::string& group, const std::string& name,
                   std::span<const double> data, std::size_t cols, std::string_view unit = "",
                   std::string_view description = "");
  void write_array(const std::string& group, const std::string& name,
                   std::span<const std::int64_t> data, std::size_t cols,
                   std::string_view unit = "", std::string_view description = "");
  void write_array(const std::string& group, const std::string& name,
                   std::span<const std::uint8_t> data, std::size_t cols,
                   std::string_view unit = "", std::string_view description = "");

  // The same kind of array, streamed: created now with no rows (and its attributes), rows
  // appended in order by append_rows(id, ...), the last ones written when the job closes. At
  // most a few chunks per array are held in memory (h5::ChunkAppender), so tables of any
  // length stream through. The file holds the same data as one write_array of all the rows.
  enum class ArrayType : std::uint8_t { kFloat64, kInt64, kUInt8 };
  using ArrayId = std::size_t;
  ArrayId begin_array(const std::string& group, const std::string& name, ArrayType type,
                      std::size_t cols, std::string_view unit = "",
                      std::string_view description = "");
  // data.size() must be a multiple of the array's width and the type its own
  // (std::invalid_argument, nothing written).
  void append_rows(ArrayId id, std::span<const double> data);
  void append_rows(ArrayId id, std::span<const std::int64_t> data);
  void append_rows(ArrayId id, std::span<const std::uint8_t> data);

  // Writes the buffered tails, closes the job's HDF5 objects and flushes the file (finished
  // jobs are then on disk; HDF5 does not promise that a file survives a later crash of the
  // process, but a flushed one usually reads). Idempotent.
  void close();

  // Called with a copy of every run of paths appended, after the checks and before it is
  // written (the job's verifier reads the CL data this way: batch/jobs/job_verify.hpp).
  void set_observer(std::function<void(const ClChunk&)> observer) {
    observer_ = std::move(observer);
  }

  std::int64_t points_written() const;  // n so far (including buffered)
  std::int64_t paths_written() const;   // paths so far (including buffered)

 private:
  friend class ClFile;
  ClJob(std::shared_ptr<detail::FileState> file, std::uint64_t serial);

  // Throws std::logic_error unless this job is the file's open job.
  detail::FileState& open_file(const char* operation) const;

  std::shared_ptr<detail::FileState> file_;  // null when moved-from
  std::uint64_t serial_ = 0;                 // which begin_job of file_ this job is
  std::function<void(const ClChunk&)> observer_;
};

// The ArrayType of T (double, std::int64_t or std::uint8_t).
template <class T>
constexpr ClJob::ArrayType array_type_of() {
  static_assert(std::is_same_v<T, double> || std::is_same_v<T, std::int64_t> ||
                std::is_same_v<T, std::uint8_t>);
  if constexpr (std::is_same_v<T, double>) return ClJob::ArrayType::kFloat64;
  if constexpr (std::is_same_v<T, std::int64_t>) return ClJob::ArrayType::kInt64;
  return ClJob::ArrayType::kUInt8;
}

}  // namespace ncpath::out
