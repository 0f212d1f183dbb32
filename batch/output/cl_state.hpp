#pragma once
// Private to ncpath_output (includes hdf5.h): the state shared by ClFile and ClJob, the
// schema constants and the argument checks. The layout itself is in docs/hdf5-schema.md.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "batch/output/chunk_appender.hpp"
#include "batch/output/cl_writer.hpp"
#include "batch/output/h5_util.hpp"

namespace ncpath::out {

// Chunk sizes, in rows. Points: 32768 x 3 doubles = 768 KiB, the largest power of two that
// still fits HDF5's default 1 MiB chunk cache of readers (h5py, h5dump), so reading a slice
// does not inflate the same chunk again for every call. The per-point and per-path byte and
// int64 datasets use 64 KiB chunks; they are small next to the points.
inline constexpr hsize_t kPointChunkRows = 32768;
inline constexpr hsize_t kContactChunkRows = 65536;
inline constexpr hsize_t kOffsetChunkRows = 8192;
inline constexpr hsize_t kPathKindChunkRows = 65536;
// zlib level 1 after byte shuffle: most of the size gain of higher levels on CL data at a
// fraction of the time (the writer must keep up with the engine).
inline constexpr unsigned kDeflateLevel = 1;

inline constexpr std::string_view kPathKindEnum = "0=cut,1=link_at_depth,2=rapid";
inline constexpr std::string_view kContactKindEnum = "0=none,1=vertex,2=edge,3=facet";
inline constexpr std::uint8_t kMaxPathKind = static_cast<std::uint8_t>(PathKind::kRapid);
inline constexpr std::uint8_t kMaxContactKind = kContactFacet;

// What a job says until set_status is called: a job that dies half-way is never "ok".
inline constexpr std::string_view kDefaultStatus = "internal_error";
inline constexpr std::string_view kDefaultMessage = "job did not finish";

// std::invalid_argument unless `name` is a usable HDF5 link name: non-empty, no '/', not "."
// or "..", no NUL. `what` names the argument in the message.
void check_link_name(const std::string& name, const char* what);
// std::invalid_argument when `value` contains a NUL (HDF5 C strings end at the first one).
void check_no_nul(std::string_view value, const char* what);
// std::invalid_argument unless status looks like "ok" or "invalid_input" ([a-z0-9_]+).
void check_status_code(std::string_view status);

namespace detail {

struct JobState {
  std::string name;
  h5::Handle group;
  h5::Handle stats;
  std::optional<h5::ChunkAppender> points;   // [N, 3] float64
  std::optional<h5::ChunkAppender> contact;  // [N] uint8
  std::optional<h5::ChunkAppender> offsets;  // [P + 1] int64
  std::optional<h5::ChunkAppender> kinds;    // [P] uint8
  struct Streamed {                          // the arrays of ClJob::begin_array, by id
    h5::ChunkAppender rows;
    ClJob::ArrayType type;
    std::size_t width;  // values per row
  };
  std::vector<Streamed> arrays;
  bool broken = false;  // an HDF5 write failed half-way: the datasets are inconsistent
};

// Owned jointly by the ClFile and its jobs (shared_ptr), so a job can tell that its file was
// closed before it. Never moves, so ChunkAppenders may point at ctx.
struct FileState {
  std::filesystem::path path;
  h5::Context ctx;
  h5::Handle file;
  h5::Handle jobs;
  std::unique_ptr<JobState> job;  // the open job, if any
  std::uint64_t job_serial = 0;   // serial of the most recent begin_job

  // Writes the open job's buffered tails, closes its objects and flushes the file. The job
  // is gone afterwards even when this throws (the first error is rethrown).
  void close_job();
  // close_job(), then closes the file. Idempotent; the first error is rethrown.
  void close();
  ~FileState();  // close(), errors swallowed
};

}  // namespace detail
}  // namespace ncpath::out
