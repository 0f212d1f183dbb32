// Plain OFF from a buffer holding the whole file, one item per line.
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <span>
#include <vector>

#include "batch/io/reader_support.hpp"
#include "engine/parallel.hpp"
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

// The body of an OFF file in pieces of this many bytes (whole lines), parsed in parallel.
constexpr std::size_t kOffPieceBytes = std::size_t(8) << 20;

class OffParser {
 public:
  // The whole file (parse, or parse_header then nothing else).
  OffParser(const std::filesystem::path& path, std::string_view bytes)
      : path_(path), scan_(bytes), builder_("off"), size_(bytes.size()),
        vertices_(&builder_.result().mesh.vertices) {}
  // A piece of the body (whole lines) of a file with these counts; its vertices are stored in
  // `vertices` (already sized to vertex_count), its facets in result().
  OffParser(const std::filesystem::path& path, std::string_view piece, std::uint64_t vertex_count,
            std::uint64_t face_count, std::vector<Vec3>& vertices)
      : path_(path), scan_(piece), builder_("off"), size_(piece.size()),
        vertex_count_(vertex_count), face_count_(face_count), vertices_(&vertices),
        piece_(true) {}

  // Reads the header; returns the offset of the body.
  std::size_t parse_header_only() {
    parse_header();
    return scan_.offset();
  }
  std::uint64_t vertex_count() const { return vertex_count_; }
  std::uint64_t face_count() const { return face_count_; }

  // A piece: its content lines are the file's first, first + 1, ... after the header (the
  // vertices, then the faces); parses those that are vertices, or those that are faces.
  void parse_piece_vertices(std::uint64_t first, std::uint64_t lines) {
    for (std::uint64_t g = first; g < first + lines && g < vertex_count_; ++g) parse_vertex(g);
  }
  void parse_piece_faces(std::uint64_t first, std::uint64_t lines) {
    std::string_view skipped;
    for (std::uint64_t g = first; g < first + lines; ++g) {
      if (g < vertex_count_)
        scan_.next_content_line(skipped);
      else
        parse_face(g - vertex_count_);
    }
  }
  MeshReadResult& result() { return builder_.result(); }

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
    if (piece_)
      (*vertices_)[i] = p;
    else
      vertices_->push_back(p);
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
      builder_.add_indexed_facet(face_[0], face_[1], face_[2], *vertices_);
      return;
    }
    add_polygon(f);
  }

  void add_polygon(std::uint64_t f) {
    const auto& vertices = *vertices_;
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
      builder_.add_indexed_facet(face_[t[0]], face_[t[1]], face_[t[2]], vertices);
  }

  const std::filesystem::path& path_;
  TextScanner scan_;
  MeshBuilder builder_;
  std::uint64_t size_;
  std::uint64_t vertex_count_ = 0;
  std::uint64_t face_count_ = 0;
  std::vector<Vec3>* vertices_;  // the builder's, or (a piece) the whole file's
  bool piece_ = false;
  std::vector<std::uint32_t> face_;  // scratch: the indices of the current face
  std::vector<Vec3> points_;         // scratch: its vertices
};

// Cuts `body` after the newline at or past every multiple of piece_bytes: piece k is
// [cut[k], cut[k + 1]).
std::vector<std::size_t> line_cuts(std::string_view body, std::size_t piece_bytes) {
  std::vector<std::size_t> cut = {0};
  for (std::size_t at = piece_bytes; at < body.size(); at = cut.back() + piece_bytes) {
    const std::size_t nl = body.find('\n', at);
    if (nl == std::string_view::npos || nl + 1 >= body.size()) break;
    cut.push_back(nl + 1);
  }
  cut.push_back(body.size());
  return cut;
}

// The pieces' facets in order over the shared vertices; nullopt when a piece failed or the
// file has no facets left (the whole-file parser then gives its message).
std::optional<MeshReadResult> join_off(std::vector<Vec3>& vertices,
                                       std::vector<std::optional<MeshReadResult>>& parts,
                                       std::uint64_t faces) {
  MeshReadResult out;
  out.stats.format = "off";
  std::size_t total = 0;
  for (const auto& p : parts) {
    if (!p) return std::nullopt;
    total += p->mesh.facets.size();
  }
  if (total == 0) return std::nullopt;
  out.mesh.facets.reserve(total);
  for (const auto& p : parts) {
    out.mesh.facets.insert(out.mesh.facets.end(), p->mesh.facets.begin(), p->mesh.facets.end());
    out.stats.facets_degenerate += p->stats.facets_degenerate;
    out.stats.polygons_triangulated += p->stats.polygons_triangulated;
  }
  out.mesh.vertices = std::move(vertices);
  out.stats.facets_in_file = faces;
  out.stats.facets_read = total;
  return out;
}

}  // namespace

bool off_header_counts(std::string_view bytes, std::uint64_t& vertices, std::uint64_t& faces) {
  const std::filesystem::path where("header");  // the parser keeps a reference
  try {
    OffParser head(where, bytes);
    const std::size_t body = head.parse_header_only();
    if (body == bytes.size() && !bytes.ends_with('\n')) return false;  // counts cut off
    vertices = head.vertex_count();
    faces = head.face_count();
    return true;
  } catch (const ReadError&) {
    return false;
  }
}

MeshReadResult parse_off(const std::filesystem::path& path, std::string_view bytes) {
  return parse_off_pieces(path, bytes, kOffPieceBytes);
}

MeshReadResult parse_off_pieces(const std::filesystem::path& path, std::string_view bytes,
                                std::size_t piece_bytes) {
  std::size_t body_at = 0;
  std::uint64_t nv = 0, nf = 0;
  try {
    OffParser head(path, bytes);
    body_at = head.parse_header_only();
    nv = head.vertex_count();
    nf = head.face_count();
  } catch (const ReadError&) {
    return OffParser(path, bytes).parse();  // its message
  }
  const std::string_view body = bytes.substr(body_at);
  const std::vector<std::size_t> cut = line_cuts(body, piece_bytes);
  const std::size_t pieces = cut.size() - 1;
  // One piece, or more vertices than the body has lines for: the whole-file parser.
  if (pieces == 1 || nv > body.size() / 5 + 1) return OffParser(path, bytes).parse();
  auto piece = [&](std::size_t k) { return body.substr(cut[k], cut[k + 1] - cut[k]); };
  std::vector<std::uint64_t> lines(pieces, 0), first(pieces + 1, 0);
  par::for_each(pieces, 1, [&](std::size_t k) {
    TextScanner scan(piece(k));
    std::string_view line;
    while (scan.next_content_line(line)) ++lines[k];
  });
  par::exclusive_scan(std::span<const std::uint64_t>(lines), std::span<std::uint64_t>(first));
  if (first[pieces] != nv + nf) return OffParser(path, bytes).parse();  // counts disagree
  std::vector<Vec3> vertices(nv);
  std::vector<char> ok(pieces, 1);
  par::for_each(pieces, 1, [&](std::size_t k) {
    try {
      OffParser(path, piece(k), nv, nf, vertices).parse_piece_vertices(first[k], lines[k]);
    } catch (const ReadError&) {
      ok[k] = 0;
    }
  });
  std::vector<std::optional<MeshReadResult>> parts(pieces);
  if (std::find(ok.begin(), ok.end(), 0) == ok.end())
    par::for_each(pieces, 1, [&](std::size_t k) {
      if (first[k] + lines[k] <= nv) {  // vertices only
        parts[k].emplace();
        return;
      }
      try {
        OffParser p(path, piece(k), nv, nf, vertices);
        const std::uint64_t face_lines = first[k] + lines[k] - std::max(first[k], nv);
        p.result().mesh.facets.reserve(face_lines + face_lines / 2);  // quads: two each
        p.parse_piece_faces(first[k], lines[k]);
        parts[k] = std::move(p.result());
      } catch (const ReadError&) {
      }
    });
  std::optional<MeshReadResult> out = join_off(vertices, parts, nf);
  return out ? std::move(*out) : OffParser(path, bytes).parse();
}

}  // namespace ncpath::io::detail
