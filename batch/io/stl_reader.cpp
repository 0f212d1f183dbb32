// STL, binary and ASCII, from a buffer holding the whole file.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "batch/io/reader_support.hpp"
#include "engine/parallel.hpp"
#include "kernels/mesh/mesh_transform.hpp"

namespace ncpath::io::detail {
namespace {

static_assert(std::endian::native == std::endian::little,
              "the binary STL reader assumes a little-endian host");
static_assert(std::numeric_limits<float>::is_iec559);

constexpr std::uint64_t kHeaderBytes = 80;
constexpr std::uint64_t kFirstFacet = 84;  // header + uint32 facet count
constexpr std::uint64_t kFacetBytes = 50;  // normal, 3 vertices (12 float32) + uint16
// A soup mesh has 3 vertices per facet, indexed with uint32.
constexpr std::uint64_t kMaxSoupFacets = std::numeric_limits<std::uint32_t>::max() / 3;
// ASCII files are parsed in pieces of about this size in parallel, split at 'facet' lines
// (the pieces depend on the bytes only, not on the thread count).
constexpr std::size_t kAsciiPieceBytes = std::size_t(8) << 20;

const char* const kAxis[3] = {"x", "y", "z"};

std::string ordinal_vertex(int k) { return "vertex " + std::to_string(k + 1); }

std::uint32_t load_u32(const char* p) {
  std::uint32_t v;
  std::memcpy(&v, p, 4);
  return v;
}

std::string byte_at(std::uint64_t offset, std::uint64_t facet_index) {
  return "byte " + std::to_string(offset) + " (facet " + std::to_string(facet_index + 1) + ")";
}

// Looks like text: no control characters other than whitespace in the first kilobyte. A
// binary STL's facet count alone (bytes 80-83) nearly always holds a zero byte.
bool looks_like_text(std::string_view bytes) {
  const std::size_t n = std::min<std::size_t>(bytes.size(), 1024);
  for (std::size_t i = 0; i < n; ++i) {
    const unsigned char c = static_cast<unsigned char>(bytes[i]);
    if (c < 0x20 && c != '\t' && c != '\n' && c != '\r' && c != '\v' && c != '\f') return false;
    if (c == 0x7F) return false;
  }
  return true;
}

// Binary facets are parsed in chunks of this many, in parallel (the chunks depend on the
// facet count only, so the result does not depend on the thread count).
constexpr std::uint64_t kBinaryChunkFacets = 1 << 16;

// Facet f's three vertices; false (and the first bad coordinate's index 0-8 in `bad`) when
// one is not finite.
bool load_facet(const char* facets, std::uint64_t f, Vec3 v[3], int& bad) {
  float xyz[9];
  std::memcpy(xyz, facets + f * kFacetBytes + 12, sizeof xyz);  // skip the normal
  for (int i = 0; i < 9; ++i) {
    if (!std::isfinite(xyz[i])) {
      bad = i;
      return false;
    }
    v[i / 3][i % 3] = xyz[i];
  }
  return true;
}

// Binary facets [c kBinaryChunkFacets, (c + 1) kBinaryChunkFacets) clipped to `count`.
struct FacetChunk {
  std::uint64_t begin, end;
  FacetChunk(std::size_t c, std::uint64_t count)
      : begin(c * kBinaryChunkFacets), end(std::min(count, (c + 1) * kBinaryChunkFacets)) {}
};

// ReadError for facet f's coordinate i (0-8), which is not finite.
[[noreturn]] void throw_non_finite(const std::filesystem::path& path, const char* facets,
                                   std::uint64_t f, int i) {
  const std::uint64_t at = f * kFacetBytes + 12 + 4 * std::uint64_t(i);
  float x;
  std::memcpy(&x, facets + at, 4);
  throw ReadError(path, byte_at(kFirstFacet + at, f),
                  "non-finite coordinate in facet " + std::to_string(f + 1) + ": " +
                      ordinal_vertex(i / 3) + " has " + kAxis[i % 3] + " = " + num(x));
}

// The soup of `count` binary facets: a first pass per chunk finds non-finite coordinates
// and counts the facets kept (degenerate ones are skipped, as MeshBuilder does), a second
// writes each chunk's facets at its offset. File order, and the first error in file order,
// whatever the threads.
MeshReadResult binary_facets(const std::filesystem::path& path, const char* facets,
                             std::uint64_t count) {
  const std::uint64_t chunks = (count + kBinaryChunkFacets - 1) / kBinaryChunkFacets;
  std::vector<std::uint64_t> offset(chunks + 1, 0), first_bad(chunks, count);
  std::vector<int> bad_coord(chunks, 0);
  par::for_each(chunks, 1, [&](std::size_t c) {
    const FacetChunk ch(c, count);
    Vec3 v[3];
    for (std::uint64_t f = ch.begin; f < ch.end; ++f) {
      if (!load_facet(facets, f, v, bad_coord[c])) {
        first_bad[c] = f;
        return;
      }
      offset[c + 1] += !is_degenerate_facet(v[0], v[1], v[2]);
    }
  });
  for (std::uint64_t c = 0; c < chunks; ++c)
    if (first_bad[c] != count) throw_non_finite(path, facets, first_bad[c], bad_coord[c]);
  for (std::uint64_t c = 0; c < chunks; ++c) offset[c + 1] += offset[c];
  MeshBuilder builder("stl-binary");
  MeshReadResult& out = builder.result();
  out.stats.facets_in_file = count;
  out.stats.facets_degenerate = count - offset[chunks];
  out.mesh.vertices.resize(3 * offset[chunks]);  // Eigen vectors: not initialised
  out.mesh.facets.resize(offset[chunks]);
  par::for_each(chunks, 1, [&](std::size_t c) {
    const FacetChunk ch(c, count);
    auto at = static_cast<std::uint32_t>(offset[c]);
    Vec3 v[3];
    int bad = 0;
    for (std::uint64_t f = ch.begin; f < ch.end; ++f) {
      load_facet(facets, f, v, bad);
      if (is_degenerate_facet(v[0], v[1], v[2])) continue;
      for (int k = 0; k < 3; ++k) out.mesh.vertices[3 * at + k] = v[k];
      out.mesh.facets[at] = {3 * at, 3 * at + 1, 3 * at + 2};
      ++at;
    }
  });
  return builder.finish(path);
}

MeshReadResult parse_binary(const std::filesystem::path& path, std::string_view bytes) {
  const std::uint64_t size = bytes.size();
  const std::uint64_t count = load_u32(bytes.data() + kHeaderBytes);
  const std::uint64_t expected = kFirstFacet + kFacetBytes * count;
  const std::string declares = "the header declares " + std::to_string(count) +
                               " facets (84 + 50 * " + std::to_string(count) + " = " +
                               std::to_string(expected) + " bytes), the file has " +
                               std::to_string(size) + " bytes";
  if (size < expected) {
    const std::uint64_t complete = (size - kFirstFacet) / kFacetBytes;
    const std::uint64_t left = (size - kFirstFacet) % kFacetBytes;
    const std::uint64_t at = kFirstFacet + complete * kFacetBytes;
    if (left != 0)
      throw ReadError(path, byte_at(at, complete),
                      "truncated file: expected 50 bytes for facet " +
                          std::to_string(complete + 1) + ", " + std::to_string(left) + " left (" +
                          declares + ")");
    throw ReadError(
        path, byte_at(at, complete),
        "truncated file: it ends after facet " + std::to_string(complete) + " (" + declares + ")");
  }
  if (size > expected) {
    throw ReadError(path, "byte 80 (facet count)",
                    "facet count disagrees with the file size: " + declares + ", " +
                        std::to_string(size - expected) + " bytes too many");
  }
  if (count > kMaxSoupFacets)
    throw ReadError(path, "byte 80 (facet count)",
                    std::to_string(count) + " facets are too many (at most " +
                        std::to_string(kMaxSoupFacets) + " with 32-bit vertex indices)");

  return binary_facets(path, bytes.data() + kFirstFacet, count);
}

// ASCII STL: solid / facet normal / outer loop / 3 x vertex / endloop / endfacet /
// endsolid, keywords in any case, several solids in a row allowed.
class AsciiStlParser {
 public:
  AsciiStlParser(const std::filesystem::path& path, std::string_view bytes)
      : path_(path), scan_(bytes), builder_("stl-ascii") {
    // About 250 bytes per facet in typical exporters' output.
    const std::size_t guess = std::min<std::size_t>(bytes.size() / 250 + 16, kMaxSoupFacets);
    builder_.reserve(3 * guess, guess);
  }

  // Parses a piece of the file that starts inside a solid at a 'facet' line (or at the file's
  // start, then outside any solid): facets, 'endsolid' and 'solid' lines, in any number.
  // Returns whether the piece ends inside a solid; throws ReadError on anything else (the
  // caller then parses the whole file in one go for the exact message).
  bool parse_piece(bool in_solid) {
    for (std::string_view tok = scan_.next_token(); !tok.empty(); tok = scan_.next_token()) {
      if (in_solid && keyword_is(tok, "facet")) {
        parse_facet();
      } else if (in_solid && keyword_is(tok, "endsolid")) {
        scan_.skip_line();
        in_solid = false;
      } else if (!in_solid && keyword_is(tok, "solid")) {
        scan_.skip_line();
        in_solid = true;
      } else {
        fail("unexpected " + quote(tok));
      }
    }
    return in_solid;
  }
  std::uint64_t facets() const { return facets_; }
  MeshReadResult& result() { return builder_.result(); }

  MeshReadResult parse() {
    std::string_view tok = scan_.next_token();
    if (!keyword_is(tok, "solid")) fail("expected 'solid' at the start, found " + quote(tok));
    while (!tok.empty()) {
      if (!keyword_is(tok, "solid"))
        fail("unexpected " + quote(tok) +
             " after 'endsolid' (expected the end of the file "
             "or another 'solid')");
      parse_solid();
      tok = scan_.next_token();
    }
    builder_.result().stats.facets_in_file = facets_;
    return builder_.finish(path_);
  }

 private:
  [[noreturn]] void fail(const std::string& problem) {
    throw ReadError(path_, "line " + std::to_string(scan_.line()), problem);
  }

  std::string facet_name() const { return "facet " + std::to_string(facets_); }
  std::string in_facet() const { return "in " + facet_name(); }

  // What the next token should be, for messages: vertex -1 is the facet normal.
  std::string describe(int vertex, int axis) const {
    if (vertex < 0) return std::string("the normal's ") + kAxis[axis] + " " + in_facet();
    return std::string("the ") + kAxis[axis] + " coordinate of " + ordinal_vertex(vertex) + " " +
           in_facet();
  }

  // Next token; the end of the file inside a solid is an unterminated solid. Messages are
  // only built on failure: this runs for every token of big files.
  template <class Describe>
  std::string_view need_described(const Describe& expecting) {
    const std::string_view tok = scan_.next_token();
    if (tok.empty())
      fail("unterminated solid (started at line " + std::to_string(solid_line_) +
           "): the file ends where " + expecting() + " was expected, 'endsolid' is missing");
    return tok;
  }
  std::string_view need(const char* expecting) {
    return need_described([expecting] { return std::string(expecting); });
  }

  void expect(const char* keyword, const char* after) {
    const std::string_view tok =
        need_described([keyword] { return "'" + std::string(keyword) + "'"; });
    if (!keyword_is(tok, keyword))
      fail("expected '" + std::string(keyword) + "' after '" + after + "' " + in_facet() +
           ", found " + quote(tok));
  }

  // A vertex coordinate must be finite; the normal (vertex -1) is only checked for syntax.
  double coordinate(int vertex, int axis) {
    const std::string_view tok = need_described([&] { return describe(vertex, axis); });
    double x;
    if (!parse_double(tok, x)) fail("bad number " + quote(tok) + " for " + describe(vertex, axis));
    if (vertex >= 0 && !std::isfinite(x))
      fail("non-finite coordinate in " + facet_name() + ": " + ordinal_vertex(vertex) + " has " +
           kAxis[axis] + " = " + std::string(tok) + ", which is not a finite number");
    return x;
  }

  void parse_solid() {
    solid_line_ = scan_.line();
    scan_.skip_line();  // the solid's name
    for (;;) {
      const std::string_view tok = need("'facet' or 'endsolid'");
      if (keyword_is(tok, "endsolid")) {
        scan_.skip_line();
        return;
      }
      if (!keyword_is(tok, "facet")) fail("expected 'facet' or 'endsolid', found " + quote(tok));
      parse_facet();
    }
  }

  void parse_facet() {
    ++facets_;
    if (facets_ > kMaxSoupFacets)
      fail("too many facets (at most " + std::to_string(kMaxSoupFacets) +
           " with 32-bit vertex indices)");
    std::string_view tok = need("'normal' or 'outer'");
    if (keyword_is(tok, "normal")) {
      // Parsed for syntax only: the normal is recomputed downstream, and exporters write
      // nan normals for degenerate facets.
      for (int a = 0; a < 3; ++a) coordinate(-1, a);
      tok = need("'outer'");
    }
    if (!keyword_is(tok, "outer"))
      fail("expected 'outer loop' " + in_facet() + ", found " + quote(tok));
    expect("loop", "outer");
    Vec3 v[3];
    int count = 0;
    for (;;) {
      tok = need("'vertex' or 'endloop'");
      if (keyword_is(tok, "endloop")) break;
      if (!keyword_is(tok, "vertex"))
        fail("expected 'vertex' or 'endloop' " + in_facet() + ", found " + quote(tok));
      if (count == 3) fail(facet_name() + " has more than 3 vertices in its loop");
      for (int a = 0; a < 3; ++a) v[count][a] = coordinate(count, a);
      ++count;
    }
    if (count != 3)
      fail(facet_name() + " has " + std::to_string(count) + " vertices in its loop, expected 3");
    expect("endfacet", "endloop");
    builder_.add_soup_facet(v[0], v[1], v[2]);
  }

  const std::filesystem::path& path_;
  TextScanner scan_;
  MeshBuilder builder_;
  std::uint64_t facets_ = 0;
  std::uint64_t solid_line_ = 1;
};

// Start of the first line at or after `from` whose first token is 'facet' (any case), or
// bytes.size().
std::size_t next_facet_line(std::string_view bytes, std::size_t from) {
  std::size_t p = bytes.find('\n', from == 0 ? 0 : from - 1);
  while (p != std::string_view::npos) {
    std::size_t q = p + 1;
    while (q < bytes.size() && (bytes[q] == ' ' || bytes[q] == '\t' || bytes[q] == '\r')) ++q;
    if (q + 5 < bytes.size() && keyword_is(bytes.substr(q, 5), "facet") &&
        (bytes[q + 5] == ' ' || bytes[q + 5] == '\t' || bytes[q + 5] == '\r' ||
         bytes[q + 5] == '\n'))
      return p + 1;
    p = bytes.find('\n', q);
  }
  return bytes.size();
}

// The pieces' facets in file order, as one soup (what the whole-file parser builds).
MeshReadResult join_pieces(std::vector<MeshReadResult>& parts, std::uint64_t facets_in_file) {
  MeshReadResult out = std::move(parts[0]);
  for (std::size_t k = 1; k < parts.size(); ++k) {
    auto& v = out.mesh.vertices;
    const auto base = static_cast<std::uint32_t>(v.size());
    v.insert(v.end(), parts[k].mesh.vertices.begin(), parts[k].mesh.vertices.end());
    for (const auto& f : parts[k].mesh.facets)
      out.mesh.facets.push_back({f[0] + base, f[1] + base, f[2] + base});
    out.stats.facets_degenerate += parts[k].stats.facets_degenerate;
  }
  out.stats.facets_in_file = facets_in_file;
  return out;
}

}  // namespace

MeshReadResult parse_ascii_stl(const std::filesystem::path& path, std::string_view bytes,
                               std::size_t piece_bytes) {
  std::vector<std::size_t> cut = {0};
  for (std::size_t at = piece_bytes; at < bytes.size(); at = cut.back() + piece_bytes) {
    const std::size_t next = next_facet_line(bytes, at);
    if (next >= bytes.size()) break;
    cut.push_back(next);
  }
  cut.push_back(bytes.size());
  const std::size_t pieces = cut.size() - 1;
  if (pieces == 1) return AsciiStlParser(path, bytes).parse();
  std::vector<MeshReadResult> parts(pieces);
  std::vector<std::uint64_t> facets(pieces, 0);
  std::vector<char> ends_in_solid(pieces, 0), ok(pieces, 0);
  par::for_each(pieces, 1, [&](std::size_t k) {
    try {
      AsciiStlParser piece(path, bytes.substr(cut[k], cut[k + 1] - cut[k]));
      ends_in_solid[k] = piece.parse_piece(k > 0);
      facets[k] = piece.facets();
      parts[k] = std::move(piece.result());
      ok[k] = 1;
    } catch (const ReadError&) {  // reported below by the whole-file parser
    }
  });
  bool joined = ok[pieces - 1] && !ends_in_solid[pieces - 1];
  std::uint64_t total = 0;
  for (std::size_t k = 0; k < pieces; ++k) {
    joined = joined && ok[k] && (k + 1 == pieces || ends_in_solid[k]);
    total += facets[k];
  }
  // Anything but a clean split (an error, a piece ending outside a solid before a 'facet'
  // line, too many facets): the whole-file parser gives the exact message or result.
  if (!joined || total > kMaxSoupFacets || !starts_with_keyword(bytes, "solid", false))
    return AsciiStlParser(path, bytes).parse();
  MeshReadResult out = join_pieces(parts, total);
  out.stats.facets_read = out.mesh.facets.size();
  if (out.stats.facets_read == 0) return AsciiStlParser(path, bytes).parse();  // its message
  return out;
}

MeshReadResult parse_stl(const std::filesystem::path& path, std::string_view bytes) {
  if (bytes.empty()) throw ReadError(path, "", "empty file (0 bytes): not an STL file");
  if (bytes.size() >= kFirstFacet &&
      kFirstFacet + kFacetBytes * load_u32(bytes.data() + kHeaderBytes) == bytes.size())
    return parse_binary(path, bytes);  // size-consistent: binary, whatever the header says
  if (starts_with_keyword(bytes, "solid", false) && looks_like_text(bytes))
    return parse_ascii_stl(path, bytes, kAsciiPieceBytes);
  if (bytes.size() < kFirstFacet)
    throw ReadError(path, "",
                    "not an STL file: " + std::to_string(bytes.size()) +
                        " bytes are too few for a binary STL (at least 84) and it is not an "
                        "ASCII STL (text starting with 'solid')");
  return parse_binary(path, bytes);  // reports the count/size mismatch
}

}  // namespace ncpath::io::detail
