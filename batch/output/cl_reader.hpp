#pragma once
// Reading a CL file back (docs/hdf5-schema.md): the jobs, their attributes and their paths,
// in runs of whole paths so that a large job is never held whole. Used by `ncpath verify`.
// Errors: std::runtime_error naming the file and what HDF5 refused.
#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "engine/cl_chunk.hpp"

namespace ncpath::out {

struct StoredJob {
  std::string name, operation, status, input_path, tool_json, params_json;
};

// Every job of the file, in the order they were written.
std::vector<StoredJob> read_jobs(const std::filesystem::path& file);

// Calls sink with runs of whole paths of `job`, in order, each of about `points` points (one
// path may be longer). Contact kinds are filled in.
void read_paths(const std::filesystem::path& file, const std::string& job,
                const std::function<void(const ClChunk&)>& sink, std::size_t points = 1 << 20);

}  // namespace ncpath::out
