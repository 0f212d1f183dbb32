#include "batch/io/reader_support.hpp"

#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <memory>
#include <system_error>

#include "kernels/mesh/mesh_transform.hpp"

namespace ncpath::io::detail {
namespace {

bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
}

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

// The file opened for reading, or ReadError("is a directory" / "cannot open: <reason>").
File open_for_reading(const std::filesystem::path& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw ReadError(path, "", "cannot read: it is a directory, not a file");
  errno = 0;
  File file(std::fopen(path.c_str(), "rb"));
  if (!file) {
    const int err = errno;
    throw ReadError(path, "",
                    std::string("cannot open: ") + (err ? std::strerror(err) : "unknown error"));
  }
  return file;
}

// ReadError("read failed") when the stream has an error, `used` bytes in.
void check_read(const std::filesystem::path& path, std::FILE* file, std::size_t used) {
  if (std::ferror(file))
    throw ReadError(path, "byte " + std::to_string(used),
                    std::string("read failed: ") + std::strerror(errno));
}

}  // namespace

std::string read_file_bytes(const std::filesystem::path& path) {
  const File file = open_for_reading(path);
  std::error_code ec;
  // One read of the announced size, then chunks until the end in case the size was not
  // known (a pipe) or the file grew. Growing the string chunk by chunk from the start would
  // reallocate and copy big files several times.
  std::string bytes;
  const auto size = std::filesystem::file_size(path, ec);
  std::size_t used = 0;
  if (!ec && size > 0) {
    bytes.resize(static_cast<std::size_t>(size));
    used = std::fread(bytes.data(), 1, bytes.size(), file.get());
  }
  constexpr std::size_t kChunk = std::size_t{1} << 20;
  while (used == bytes.size() && !std::ferror(file.get())) {
    bytes.resize(used + kChunk);
    const std::size_t got = std::fread(bytes.data() + used, 1, kChunk, file.get());
    used += got;
    if (got < kChunk) break;
  }
  bytes.resize(used);
  check_read(path, file.get(), used);
  return bytes;
}

FileBytes::FileBytes(const std::filesystem::path& path) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec || size == 0 || !std::filesystem::is_regular_file(path, ec)) {
    copy_ = read_file_bytes(path);  // its messages; a pipe, an empty file
    return;
  }
  const File file = open_for_reading(path);
  buf_.reset(new char[size]);  // not value-initialised: no zero fill
  size_ = std::fread(buf_.get(), 1, size, file.get());
  check_read(path, file.get(), size_);
  if (size_ == size && std::fgetc(file.get()) != EOF) {  // it grew since: read it as it is now
    buf_.reset();
    size_ = 0;
    copy_ = read_file_bytes(path);
  }
}

bool starts_with_keyword(std::string_view s, std::string_view keyword, bool allow_comments) {
  if (s.starts_with("\xEF\xBB\xBF")) s.remove_prefix(3);
  std::size_t i = 0;
  for (;;) {
    while (i < s.size() && is_space(s[i])) ++i;
    if (allow_comments && i < s.size() && s[i] == '#') {
      while (i < s.size() && s[i] != '\n') ++i;
      continue;
    }
    break;
  }
  if (s.size() - i < keyword.size()) return false;
  if (!keyword_is(s.substr(i, keyword.size()), keyword)) return false;
  const std::size_t after = i + keyword.size();
  return after == s.size() || is_space(s[after]);
}

bool parse_double(std::string_view token, double& out) {
  const char* first = token.data();
  const char* last = first + token.size();
  // from_chars rejects a leading '+', which some exporters write.
  if (first != last && *first == '+' && last - first > 1 && first[1] != '-' && first[1] != '+')
    ++first;
  if (first == last) return false;
  const auto res = std::from_chars(first, last, out, std::chars_format::general);
  if (res.ec == std::errc::result_out_of_range && res.ptr == last) {
    // 1e999 or 1e-999: from_chars leaves `out` alone. The wider long double range gives the
    // right double: +-inf on overflow (rejected by the caller as non-finite, with the
    // token), +-0 or a subnormal on underflow (a valid, if odd, coordinate).
    long double wide;
    const auto w = std::from_chars(first, last, wide, std::chars_format::general);
    if (w.ec != std::errc() || w.ptr != last) return false;
    out = static_cast<double>(wide);
    return true;
  }
  return res.ec == std::errc() && res.ptr == last;
}

bool parse_uint(std::string_view token, std::uint64_t& out) {
  const char* first = token.data();
  const char* last = first + token.size();
  if (first != last && *first == '+') ++first;
  if (first == last) return false;
  const auto res = std::from_chars(first, last, out, 10);
  return res.ec == std::errc() && res.ptr == last;
}

bool keyword_is(std::string_view token, std::string_view lower_keyword) {
  if (token.size() != lower_keyword.size()) return false;
  for (std::size_t i = 0; i < token.size(); ++i) {
    char c = token[i];
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    if (c != lower_keyword[i]) return false;
  }
  return true;
}

std::string quote(std::string_view token) {
  constexpr std::size_t kMax = 40;
  std::string s = "'";
  for (std::size_t i = 0; i < token.size() && i < kMax; ++i) {
    const unsigned char c = static_cast<unsigned char>(token[i]);
    s += (c >= 0x20 && c < 0x7F) ? static_cast<char>(c) : '?';
  }
  if (token.size() > kMax) s += "...";
  return s + "'";
}

std::string num(double x) {
  char buf[32];
  const auto res = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, res.ptr);
}

TextScanner::TextScanner(std::string_view text)
    : begin_(text.data()), p_(text.data()), end_(text.data() + text.size()) {
  if (text.starts_with("\xEF\xBB\xBF")) p_ += 3;
}

void TextScanner::at_end() {
  // The text's last line, not the empty one after its final newline.
  line_ = cur_line_;
  if (line_ > 1 && end_ != begin_ && end_[-1] == '\n') --line_;
}

std::string_view TextScanner::next_token() {
  while (p_ != end_ && is_space(*p_)) {
    if (*p_ == '\n') ++cur_line_;
    ++p_;
  }
  if (p_ == end_) {
    at_end();
    return {};
  }
  line_ = cur_line_;
  const char* start = p_;
  while (p_ != end_ && !is_space(*p_)) ++p_;
  return {start, static_cast<std::size_t>(p_ - start)};
}

void TextScanner::skip_line() {
  while (p_ != end_ && *p_ != '\n') ++p_;
}

bool TextScanner::next_content_line(std::string_view& line) {
  while (p_ != end_) {
    const char* start = p_;
    const char* nl = static_cast<const char*>(std::memchr(p_, '\n', end_ - p_));
    const char* stop = nl ? nl : end_;
    p_ = nl ? nl + 1 : end_;
    line_ = cur_line_;
    if (nl) ++cur_line_;
    const char* hash = static_cast<const char*>(std::memchr(start, '#', stop - start));
    if (hash) stop = hash;
    while (start != stop && is_space(*start)) ++start;
    while (stop != start && is_space(stop[-1])) --stop;
    if (start != stop) {
      line = {start, static_cast<std::size_t>(stop - start)};
      return true;
    }
  }
  at_end();
  return false;
}

std::string_view LineTokens::next() {
  std::size_t i = 0;
  while (i < rest_.size() && is_space(rest_[i])) ++i;
  std::size_t j = i;
  while (j < rest_.size() && !is_space(rest_[j])) ++j;
  const std::string_view tok = rest_.substr(i, j - i);
  rest_.remove_prefix(j);
  return tok;
}

bool LineTokens::empty() const {
  for (char c : rest_)
    if (!is_space(c)) return false;
  return true;
}

void MeshBuilder::reserve(std::size_t vertices, std::size_t facets) {
  result_.mesh.vertices.reserve(vertices);
  result_.mesh.facets.reserve(facets);
}

void MeshBuilder::add_soup_facet(const Vec3& a, const Vec3& b, const Vec3& c) {
  if (is_degenerate_facet(a, b, c)) {
    ++result_.stats.facets_degenerate;
    return;
  }
  auto& v = result_.mesh.vertices;
  const auto i = static_cast<std::uint32_t>(v.size());
  v.push_back(a);
  v.push_back(b);
  v.push_back(c);
  result_.mesh.facets.push_back({i, i + 1, i + 2});
}

void MeshBuilder::add_indexed_facet(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  add_indexed_facet(a, b, c, result_.mesh.vertices);
}

void MeshBuilder::add_indexed_facet(std::uint32_t a, std::uint32_t b, std::uint32_t c,
                                    const std::vector<Vec3>& v) {
  if (is_degenerate_facet(v[a], v[b], v[c])) {
    ++result_.stats.facets_degenerate;
    return;
  }
  result_.mesh.facets.push_back({a, b, c});
}

MeshReadResult MeshBuilder::finish(const std::filesystem::path& path) {
  auto& stats = result_.stats;
  stats.facets_read = result_.mesh.facets.size();
  if (stats.facets_read == 0) {
    if (stats.facets_in_file == 0)
      throw ReadError(path, "", "empty mesh: the file holds no facets");
    throw ReadError(path, "",
                    "empty mesh: all " + std::to_string(stats.facets_in_file) +
                        " facets are degenerate (zero area)");
  }
  return std::move(result_);
}

}  // namespace ncpath::io::detail
