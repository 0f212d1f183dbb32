// Plain OFF from a buffer holding the whole file, one item per line.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "batch/io/reader_support.hpp"
#include "kernels/mesh/polygon.hpp"

namespace ncpath::io::detail {
namespace {

const char* const kAxis[3] = {"x", "y", "z"};

std::string nth(std::uint64_t k) {  // 1 -> "1st", 2 -> "2nd", 12 -> "12th"
  const char* suffix = "th";
  if (k % 100 < 11 || k % 100 > 13) {
    if (k % 10 == 1) suffix = "st";
    if (k % 10 == 2) suffix = "nd";
    if (k % 10 == 3) suffix = "rd";
  }
  return std::to_string(k) + suffix;
}

class OffParser {
 public:
  OffParser(const std::filesystem::path& path, std::string_view bytes)
      : path_(path), scan_(bytes), builder_("off"), size_(bytes.size()) {}

  MeshReadResult parse() {
    parse_header();
    // A bogus header must not allocate terabytes: a vertex line takes at least 6 bytes
    // ("0 0 0\n"), a face line at least 8.
    builder_.reserve(std::min<std::uint64_t>(vertex_count_, size_ / 6),
                     std::min<std::uint64_t>(face_count_ + face_count_ / 2, size_ / 8));
    for (std::uint64_t i = 0; i < vertex_count_; ++i) parse_vertex(i);
    for (std::uint64_t f = 0; f < face_count_; ++f) parse_face(f);
    std::string_view line;
    if (scan_.next_content_line(line))
      fail("", "unexpected content after the last face: " + quote(line) + " (the header declares " +
                   std::to_string(face_count_) + " faces; is the face count wrong?)");
    builder_.result().stats.facets_in_file = face_count_;
    return builder_.finish(path_);
  }

 private:
  [[noreturn]] void fail(const std::string& what_line, const std::string& problem) {
    std::string location = "line " + std::to_string(scan_.line());
    if (!what_line.empty()) location += " (" + what_line + ")";
    throw ReadError(path_, location, problem);
  }

  // The next content line, or an "unexpected end of file" naming what was expected
  // (built only then: this runs for every line of big files).
  template <class Describe>
  LineTokens next_line(const Describe& expecting) {
    std::string_view line;
    if (!scan_.next_content_line(line)) fail("", "unexpected end of file: " + expecting());
    return LineTokens(line);
  }

  std::uint64_t count(std::string_view tok, const char* what, std::uint64_t max) {
    std::uint64_t n;
    if (tok.empty()) fail("header", std::string("bad header: the ") + what + " is missing");
    if (!parse_uint(tok, n))
      fail("header", std::string("bad header: the ") + what + " " + quote(tok) +
                         " is not a non-negative integer");
    if (n > max)
      fail("header", std::string("bad header: the ") + what + " " + std::to_string(n) +
                         " is too large (at most " + std::to_string(max) + ")");
    return n;
  }

  void parse_header() {
    LineTokens tokens = next_line([] { return std::string("expected the 'OFF' header"); });
    const std::string_view key = tokens.next();
    if (key != "OFF") {
      if (key.size() > 3 && key.ends_with("OFF"))
        fail("header", "unsupported OFF variant " + quote(key) +
                           ": only plain 'OFF' (x y z per vertex) is read");
      fail("header", "bad header: expected 'OFF', found " + quote(key));
    }
    if (tokens.empty())
      tokens = next_line([] { return std::string("expected the counts 'vertices faces edges'"); });
    const std::string_view first = tokens.next();
    if (first == "BINARY") fail("header", "binary OFF is not supported, only text OFF");
    constexpr auto kMaxIndex = std::uint64_t{std::numeric_limits<std::uint32_t>::max()};
    vertex_count_ = count(first, "vertex count", kMaxIndex);
    face_count_ = count(tokens.next(), "face count", kMaxIndex);
    const std::string_view edges = tokens.next();  // optional, unused
    std::uint64_t unused;
    if (!edges.empty() && !parse_uint(edges, unused))
      fail("header",
           "bad header: the edge count " + quote(edges) + " is not a non-negative integer");
    if (!tokens.empty())
      fail("header", "bad header: unexpected " + quote(tokens.next()) +
                         " after the counts 'vertices faces edges'");
  }

  void parse_vertex(std::uint64_t i) {
    const auto what = [i] { return "vertex index " + std::to_string(i); };
    LineTokens tokens = next_line([&] {
      return "expected " + std::to_string(vertex_count_) + " vertices, found " + std::to_string(i);
    });
    Vec3 p;
    for (int a = 0; a < 3; ++a) {
      const std::string_view tok = tokens.next();
      if (tok.empty())
        fail(what(), "vertex index " + std::to_string(i) + " has " + std::to_string(a) +
                         " coordinates, expected 3 (x y z)");
      if (!parse_double(tok, p[a]))
        fail(what(), "bad number " + quote(tok) + " for the " + kAxis[a] +
                         " coordinate of vertex index " + std::to_string(i));
      if (!std::isfinite(p[a]))
        fail(what(), "non-finite coordinate: vertex index " + std::to_string(i) + " has " +
                         kAxis[a] + " = " + std::string(tok) + ", which is not a finite number");
    }
    if (!tokens.empty())
      fail(what(), "vertex index " + std::to_string(i) + " has more than 3 values (" +
                       quote(tokens.next()) +
                       " after x y z); coloured or homogeneous OFF "
                       "variants are not supported");
    builder_.result().mesh.vertices.push_back(p);
  }

  void parse_face(std::uint64_t f) {
    const auto what = [f] { return "face " + std::to_string(f + 1); };
    LineTokens tokens = next_line([&] {
      return "expected " + std::to_string(face_count_) + " faces, found " + std::to_string(f);
    });
    const std::string_view first = tokens.next();
    std::uint64_t k;
    if (!parse_uint(first, k))
      fail(what(),
           "bad vertex count " + quote(first) + " at the start of face " + std::to_string(f + 1));
    if (k < 3)
      fail(what(), "face " + std::to_string(f + 1) + " has " + std::to_string(k) +
                       " vertices, at least 3 are needed");
    face_.clear();
    for (std::uint64_t j = 0; j < k; ++j) {
      const std::string_view tok = tokens.next();
      if (tok.empty())
        fail(what(), "face " + std::to_string(f + 1) + " declares " + std::to_string(k) +
                         " vertices but lists only " + std::to_string(j) + " indices");
      std::uint64_t index;
      if (!parse_uint(tok, index))
        fail(what(), "bad vertex index " + quote(tok) + " in face " + std::to_string(f + 1));
      if (index >= vertex_count_)
        fail(what(), "vertex index " + std::to_string(index) + " in face " + std::to_string(f + 1) +
                         " is out of range: the file has " + std::to_string(vertex_count_) +
                         " vertices (indices 0 to " + std::to_string(vertex_count_ - 1) + ")");
      face_.push_back(static_cast<std::uint32_t>(index));
    }
    // Anything left on the line is a face colour: ignored.
    if (k == 3) {
      builder_.add_indexed_facet(face_[0], face_[1], face_[2]);
      return;
    }
    add_polygon(f);
  }

  void add_polygon(std::uint64_t f) {
    const auto& vertices = builder_.result().mesh.vertices;
    points_.clear();
    for (std::uint32_t index : face_) points_.push_back(vertices[index]);
    const PolygonTriangulation tri = triangulate_convex_polygon(points_);
    auto& stats = builder_.result().stats;
    const PolygonCheck& check = tri.check;
    if (check.status == PolygonStatus::kDegenerate) {
      ++stats.facets_degenerate;  // no area: skipped like a zero-area triangle
      return;
    }
    if (!check.convex()) {
      const std::size_t n = face_.size();
      const std::size_t at = check.vertex;
      std::string where;
      if (check.status == PolygonStatus::kZeroLengthEdge)
        where = " between its " + nth(at + 1) + " and " + nth((at + 1) % n + 1) +
                " vertices (indices " + std::to_string(face_[at]) + " and " +
                std::to_string(face_[(at + 1) % n]) + ")";
      else if (check.status == PolygonStatus::kNonConvex)
        where = " at its " + nth(at + 1) + " vertex (index " + std::to_string(face_[at]) + ")";
      fail("face " + std::to_string(f + 1), "face " + std::to_string(f + 1) + " (" +
                                                std::to_string(n) + " vertices) " +
                                                polygon_status_text(check.status) + where +
                                                "; only convex polygons are triangulated");
    }
    ++stats.polygons_triangulated;
    for (const auto& t : tri.triangles)
      builder_.add_indexed_facet(face_[t[0]], face_[t[1]], face_[t[2]]);
  }

  const std::filesystem::path& path_;
  TextScanner scan_;
  MeshBuilder builder_;
  std::uint64_t size_;
  std::uint64_t vertex_count_ = 0;
  std::uint64_t face_count_ = 0;
  std::vector<std::uint32_t> face_;  // scratch: the indices of the current face
  std::vector<Vec3> points_;         // scratch: its vertices
};

}  // namespace

MeshReadResult parse_off(const std::filesystem::path& path, std::string_view bytes) {
  return OffParser(path, bytes).parse();
}

}  // namespace ncpath::io::detail
