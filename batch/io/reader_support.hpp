#pragma once
// Internal to batch/io: shared pieces of the mesh readers (whole-file input, a text scanner
// over the in-memory buffer, number parsing, the mesh builder). Not part of the public API.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "batch/io/mesh_reader.hpp"
#include "kernels/geom/vec.hpp"

namespace ncpath::io::detail {

// The whole file, or ReadError("cannot open: <reason>" / "is a directory" / "read failed").
std::string read_file_bytes(const std::filesystem::path& path);

// The whole file as read-only bytes, read once into a buffer that is not zero-filled first (a
// string of the file's size is: a 665 MB STL then took 0.8-3 s against 0.4 s for a plain read);
// a file whose size is not known (a pipe) is read as read_file_bytes does. The same errors.
// Not mapped: a file truncated while mapped would end the process (SIGBUS).
class FileBytes {
 public:
  explicit FileBytes(const std::filesystem::path& path);
  std::string_view view() const { return buf_ ? std::string_view(buf_.get(), size_) : copy_; }

 private:
  std::unique_ptr<char[]> buf_;
  std::size_t size_ = 0;
  std::string copy_;
};

// Parsers over a file already in memory; `path` is only used for messages.
MeshReadResult parse_stl(const std::filesystem::path& path, std::string_view bytes);
MeshReadResult parse_off(const std::filesystem::path& path, std::string_view bytes);
// An ASCII STL in pieces of about piece_bytes, split at 'facet' lines and parsed in parallel:
// the same result as one piece, and on any error the whole-file parser's exact message.
MeshReadResult parse_ascii_stl(const std::filesystem::path& path, std::string_view bytes,
                               std::size_t piece_bytes);
// The vertex and face counts of an OFF header at the start of `bytes` (which may hold only
// the file's beginning), read by the OFF parser itself; false when it is not a valid header
// or `bytes` ends inside it.
bool off_header_counts(std::string_view bytes, std::uint64_t& vertices, std::uint64_t& faces);
// An OFF file whose body is cut into pieces of about piece_bytes (whole lines), parsed in
// parallel: the same result as parse_off, and on any error parse_off's exact message.
MeshReadResult parse_off_pieces(const std::filesystem::path& path, std::string_view bytes,
                                std::size_t piece_bytes);

// True when the text starts (after whitespace, a UTF-8 byte order mark and, if
// allow_comments, '#' comment lines) with `keyword` followed by whitespace or the end.
bool starts_with_keyword(std::string_view bytes, std::string_view keyword, bool allow_comments);

// Number parsing of a whole token, in the "C" locale. A leading '+' is accepted; "nan",
// "inf" and overflowing literals such as 1e999 (-> inf) parse, so that the caller rejects
// them as non-finite with a better message than "bad number".
bool parse_double(std::string_view token, double& out);
bool parse_uint(std::string_view token, std::uint64_t& out);

// ASCII case-insensitive comparison with a lower-case keyword.
bool keyword_is(std::string_view token, std::string_view lower_keyword);

// A token for messages: quoted, at most 40 characters, non-printables as '?'.
std::string quote(std::string_view token);
// Shortest round-trip text of a number.
std::string num(double x);

// Whitespace-separated tokens of a text buffer, with the 1-based line of each token.
class TextScanner {
 public:
  explicit TextScanner(std::string_view text);

  // Next token of the whole text (crossing lines); empty at the end.
  std::string_view next_token();
  // Skips the rest of the current line (e.g. a solid's name).
  void skip_line();
  // Next line that has content once a '#' comment is cut off, without surrounding
  // whitespace; false at the end.
  bool next_content_line(std::string_view& line);
  // Line of the last token or content line returned; at the end, the text's last line.
  std::uint64_t line() const { return line_; }
  // Bytes of the text consumed so far.
  std::size_t offset() const { return static_cast<std::size_t>(p_ - begin_); }

 private:
  void at_end();

  const char* begin_;
  const char* p_;
  const char* end_;
  std::uint64_t line_ = 1;      // line of the last returned item
  std::uint64_t cur_line_ = 1;  // line at p_
};

// Splits one line into whitespace-separated tokens.
class LineTokens {
 public:
  explicit LineTokens(std::string_view line) : rest_(line) {}
  std::string_view next();  // empty when none left
  bool empty() const;

 private:
  std::string_view rest_;
};

// Accumulates the mesh and the statistics; drops degenerate facets.
class MeshBuilder {
 public:
  explicit MeshBuilder(std::string format) { result_.stats.format = std::move(format); }
  MeshReadResult& result() { return result_; }
  void reserve(std::size_t vertices, std::size_t facets);
  // A soup facet with three new vertices; skipped (and counted) when degenerate.
  void add_soup_facet(const Vec3& a, const Vec3& b, const Vec3& c);
  // A facet over existing vertices; skipped (and counted) when degenerate.
  void add_indexed_facet(std::uint32_t a, std::uint32_t b, std::uint32_t c);
  // The same over the vertices of another array (a piece of a file parsed in parallel).
  void add_indexed_facet(std::uint32_t a, std::uint32_t b, std::uint32_t c,
                         const std::vector<Vec3>& vertices);
  // Checks that facets are left, fills facets_read and hands the result over.
  MeshReadResult finish(const std::filesystem::path& path);

 private:
  MeshReadResult result_;
};

}  // namespace ncpath::io::detail
