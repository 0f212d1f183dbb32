#pragma once
// Reading a CL file back (docs/hdf5-schema.md): the jobs, their attributes and their paths,
// in runs of whole paths so that a large job is never held whole. Used by `ncpath verify`.
// Errors: std::runtime_error naming the file and what HDF5 refused. Thread-safe like the
// writer: every HDF5 call is made under h5::library_lock().
#include <cstddef>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "batch/output/cl_writer.hpp"
#include "engine/cl_chunk.hpp"

namespace ncpath::out {

struct StoredJob {
  std::string name, operation, status, message, input_path, input_sha256, tool_json, params_json;
};

// Every job of the file, in the order they were written.
std::vector<StoredJob> read_jobs(const std::filesystem::path& file);

// The paths of one stored job, read by ranges of whole paths; the file stays open (read
// only) while the reader lives. Its path offsets and kinds are held in memory (17 bytes per
// path), its points are read as asked for.
class PathReader {
 public:
  PathReader(const std::filesystem::path& file, const std::string& job);
  ~PathReader();
  PathReader(const PathReader&) = delete;
  PathReader& operator=(const PathReader&) = delete;

  std::size_t paths() const;
  std::size_t points(std::size_t first, std::size_t count) const;  // in paths [first, +count)
  // Paths [first, first + count) into `out` (replacing what it held), contact kinds filled in.
  void read(std::size_t first, std::size_t count, ClChunk& out);

 private:
  struct State;
  std::unique_ptr<State> s_;
};

// Calls sink with runs of whole paths of `job`, in order, each of about `points` points (one
// path may be longer). Contact kinds are filled in.
void read_paths(const std::filesystem::path& file, const std::string& job,
                const std::function<void(const ClChunk&)>& sink, std::size_t points = 1 << 20);

// The statistics of `job` (/jobs/<job>/stats) in the order they were written, with units.
std::vector<StatValue> read_stats(const std::filesystem::path& file, const std::string& job);

// The float64 array /jobs/<job>/<path> (e.g. "verify/worst"), row-major, with its number of
// columns (0: one-dimensional); std::nullopt when the job has no such dataset.
struct Float64Array {
  std::vector<double> data;
  std::size_t cols = 0;
};
std::optional<Float64Array> read_float64_array(const std::filesystem::path& file,
                                               const std::string& job, const std::string& path);

}  // namespace ncpath::out
