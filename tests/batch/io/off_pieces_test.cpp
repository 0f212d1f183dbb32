// OFF parsed in pieces in parallel (batch/io/off_reader.cpp parse_off_pieces): the same mesh
// and statistics as one piece, whatever the cuts (inside the vertices, across the switch to
// faces, among comments), and the whole-file parser's message on any error.
#include <gtest/gtest.h>

#include <random>
#include <string>

#include "batch/io/read_error.hpp"
#include "batch/io/reader_support.hpp"
#include "tests/batch/io/test_files.hpp"

namespace ncpath::io::detail {
namespace {

// A grid of (n + 1)^2 vertices; faces: triangles, convex quads, a degenerate triangle every
// 37th, colours after some faces; comments, blank lines and CRLF in between.
std::string off_text(int n) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  std::string s = "# grid\nOFF\n# counts next\n";
  const int nv = (n + 1) * (n + 1);
  std::string faces;
  int nf = 0;
  auto id = [n](int i, int j) { return std::to_string(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i, ++nf) {
      if ((i + j) % 3 == 0)
        faces += "4 " + id(i, j) + " " + id(i + 1, j) + " " + id(i + 1, j + 1) + " " +
                 id(i, j + 1) + (nf % 5 == 0 ? " 255 0 0\n" : "\n");
      else if (nf % 37 == 0)
        faces += "3 " + id(i, j) + " " + id(i, j) + " " + id(i + 1, j) + "\r\n";  // degenerate
      else
        faces += "3 " + id(i, j) + " " + id(i + 1, j) + " " + id(i + 1, j + 1) + "\n";
      if (nf % 100 == 7) faces += "\n# a comment line\n";
    }
  s += std::to_string(nv) + " " + std::to_string(nf) + " 0\n";
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      s += std::to_string(i) + " " + std::to_string(j) + " " + std::to_string(u(rng));
      s += (i + j) % 11 == 0 ? "  # tagged\n" : "\n";
    }
  return s + faces;
}

std::string error_of(const std::string& text, std::size_t piece_bytes) {
  return testing::read_error_of([&] { parse_off_pieces("p.off", text, piece_bytes); });
}

TEST(OffPieces, SameMeshAndStatisticsAsOnePiece) {
  const std::string text = off_text(40);
  const MeshReadResult whole = parse_off_pieces("p.off", text, text.size() + 1);
  ASSERT_EQ(whole.stats.facets_in_file, 1600u);
  EXPECT_GT(whole.stats.facets_degenerate, 10u);
  EXPECT_GT(whole.stats.polygons_triangulated, 400u);
  EXPECT_EQ(whole.stats.format, "off");
  for (const std::size_t piece : {std::size_t(100), std::size_t(1000), std::size_t(7000)}) {
    testing::expect_same_read(parse_off_pieces("p.off", text, piece), whole, piece);
  }
}

TEST(OffPieces, ErrorsAreTheWholeFileParsersMessages) {
  const std::string good = off_text(30);  // 961 vertices (lines 5 to 965), 900 faces
  // The text with line k (1-based) replaced.
  auto with_line = [&](std::size_t k, const std::string& line) {
    std::size_t begin = 0;
    for (std::size_t i = 1; i < k; ++i) begin = good.find('\n', begin) + 1;
    const std::size_t end = good.find('\n', begin);
    return good.substr(0, begin) + line + good.substr(end);
  };
  const std::string bad[] = {
      with_line(965, "30 30 x"),          // a bad number in the last vertex
      with_line(966, "3 0 1 99999"),      // an index out of range in the first face
      good + "3 0 1 2\n",                 // one face too many
      good.substr(0, good.size() - 40),   // cut short
      with_line(970, "5 0 1 32 31"),      // a face short of indices
      with_line(4, "962 900 0"),          // one vertex too many declared
      with_line(1200, "3 0 1 2 3 4 x y"), // a polygon with a bad colour: fine, then
  };
  for (const std::string& text : bad) {
    const std::string whole = error_of(text, text.size() + 1);
    if (&text == &bad[6]) {  // colours are ignored: no error either way
      EXPECT_EQ(whole, "");
      EXPECT_EQ(error_of(text, 100), "");
      continue;
    }
    ASSERT_NE(whole, "") << text.substr(0, 80);
    for (const std::size_t piece : {std::size_t(100), std::size_t(2000)})
      EXPECT_EQ(error_of(text, piece), whole) << piece;
  }
}

}  // namespace
}  // namespace ncpath::io::detail
