#pragma once
// SHA-256 of a file's bytes, for the provenance of CL files (JobInfo::input_sha256).
#include <filesystem>
#include <string>

namespace ncpath::out {

// Lowercase hex digest (64 characters) of the whole file, read in 1 MiB blocks. Throws
// std::runtime_error naming the path when the file cannot be opened or read.
std::string sha256_file(const std::filesystem::path& path);

}  // namespace ncpath::out
