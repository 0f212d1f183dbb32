#include "batch/io/mesh_reader.hpp"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <fstream>

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

// facet_count_hint: the bytes it looks at, and the fewest bytes a facet takes in a text
// file: an ASCII STL facet is seven lines with nine coordinates (about 90 bytes with one-digit
// coordinates); an OFF triangle is a face line and half a vertex line (11 bytes at least).
constexpr std::size_t kHintHeadBytes = 4096;
constexpr std::uint64_t kAsciiStlBytesPerFacetMin = 80;
constexpr std::uint64_t kOffBytesPerFacetMin = 11;

}  // namespace

MeshReadResult read_mesh(const std::filesystem::path& path) {
  const detail::FileBytes file(path);
  const std::string_view bytes = file.view();
  if (has_off_extension(path) ||
      (detail::starts_with_keyword(bytes, "off", true) && !is_size_consistent_binary_stl(bytes)))
    return detail::parse_off(path, bytes);
  return detail::parse_stl(path, bytes);
}

std::uint64_t facet_count_hint(const std::filesystem::path& path) {
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) return 0;
  std::string head(std::min<std::uintmax_t>(size, kHintHeadBytes), '\0');
  std::ifstream in(path, std::ios::binary);
  if (!in.read(head.data(), static_cast<std::streamsize>(head.size()))) return 0;
  std::uint32_t count = 0;
  if (head.size() >= 84) std::memcpy(&count, head.data() + 80, 4);
  if (head.size() >= 84 && 84 + 50 * std::uint64_t{count} == size) return count;
  std::uint64_t vertices = 0, faces = 0;
  if ((has_off_extension(path) || detail::starts_with_keyword(head, "off", true)) &&
      detail::off_header_counts(head, vertices, faces) && faces > 0)
    return faces;
  return size / (has_off_extension(path) ? kOffBytesPerFacetMin : kAsciiStlBytesPerFacetMin);
}

MeshReadResult read_stl(const std::filesystem::path& path) {
  const detail::FileBytes file(path);
  return detail::parse_stl(path, file.view());
}

MeshReadResult read_off(const std::filesystem::path& path) {
  const detail::FileBytes file(path);
  return detail::parse_off(path, file.view());
}

}  // namespace ncpath::io
