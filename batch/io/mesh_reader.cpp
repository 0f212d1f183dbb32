#include "batch/io/mesh_reader.hpp"

#include <algorithm>
#include <cctype>
#include <cstring>

#include "batch/io/reader_support.hpp"

namespace ncpath::io {
namespace {

bool has_off_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".off";
}

// A binary STL whose size matches its facet count is an STL whatever its first bytes say.
bool is_size_consistent_binary_stl(std::string_view bytes) {
  if (bytes.size() < 84) return false;
  std::uint32_t count;
  std::memcpy(&count, bytes.data() + 80, 4);
  return 84 + 50 * std::uint64_t{count} == bytes.size();
}

}  // namespace

MeshReadResult read_mesh(const std::filesystem::path& path) {
  const std::string bytes = detail::read_file_bytes(path);
  if (has_off_extension(path) ||
      (detail::starts_with_keyword(bytes, "off", true) && !is_size_consistent_binary_stl(bytes)))
    return detail::parse_off(path, bytes);
  return detail::parse_stl(path, bytes);
}

MeshReadResult read_stl(const std::filesystem::path& path) {
  return detail::parse_stl(path, detail::read_file_bytes(path));
}

MeshReadResult read_off(const std::filesystem::path& path) {
  return detail::parse_off(path, detail::read_file_bytes(path));
}

}  // namespace ncpath::io
