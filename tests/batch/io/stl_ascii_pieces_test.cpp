// ASCII STL parsed in pieces in parallel (batch/io/stl_reader.cpp parse_ascii_stl): the same
// mesh and statistics as one piece, and the whole-file parser's message on any error.
#include <gtest/gtest.h>

#include <random>
#include <string>

#include "batch/io/read_error.hpp"
#include "batch/io/reader_support.hpp"
#include "tests/batch/io/test_files.hpp"

namespace ncpath::io::detail {
namespace {

// Three solids of mixed case, indentation, CRLF lines and degenerate facets.
std::string ascii_stl(int facets_per_solid) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-50, 50);
  std::string s;
  for (int solid = 0; solid < 3; ++solid) {
    const std::string nl = solid == 1 ? "\r\n" : "\n";
    s += (solid == 2 ? "SOLID facet_named_part" : "solid part") + nl;
    for (int f = 0; f < facets_per_solid; ++f) {
      s += (f % 7 == 0 ? "  FACET NORMAL 0 0 1" : "facet normal 0 0 0") + nl + "outer loop" + nl;
      const double x = u(rng), y = u(rng), z = u(rng);
      for (int k = 0; k < 3; ++k) {
        const bool degenerate = f % 50 == 3;
        s += "  vertex " + std::to_string(x + (degenerate ? 0 : k == 1)) + " " +
             std::to_string(y + (degenerate ? 0 : k == 2)) + " " + std::to_string(z + 0.1 * k) +
             nl;
      }
      s += "endloop" + nl + "endfacet" + nl;
    }
    s += "endsolid part" + nl;
  }
  return s;
}

std::string error_of(const std::string& text, std::size_t piece_bytes) {
  return testing::read_error_of([&] { parse_ascii_stl("p.stl", text, piece_bytes); });
}

TEST(StlAsciiPieces, SameMeshAndStatisticsAsOnePiece) {
  const std::string text = ascii_stl(700);
  const MeshReadResult whole = parse_ascii_stl("p.stl", text, text.size() + 1);
  ASSERT_EQ(whole.stats.facets_in_file, 2100u);
  EXPECT_GT(whole.stats.facets_degenerate, 30u);
  for (const std::size_t piece : {std::size_t(1000), std::size_t(4096), std::size_t(50000)}) {
    testing::expect_same_read(parse_ascii_stl("p.stl", text, piece), whole, piece);
  }
}

TEST(StlAsciiPieces, ErrorsAreTheWholeFileParsersMessages) {
  const std::string good = ascii_stl(400);
  const std::size_t mid = good.find("vertex", good.size() / 2);
  std::string bad_number = good;
  bad_number.replace(mid + 7, 1, "x");
  std::string facet_outside = good;  // a facet after 'endsolid' without a new 'solid'
  facet_outside.replace(facet_outside.find("SOLID facet_named_part"), 22, "  comment line");
  std::string unterminated = good.substr(0, good.rfind("endsolid"));
  for (const std::string* text : {&bad_number, &facet_outside, &unterminated}) {
    const std::string whole = error_of(*text, text->size() + 1);
    ASSERT_NE(whole, "");
    EXPECT_NE(whole.find("line "), std::string::npos) << whole;
    EXPECT_EQ(error_of(*text, 2000), whole);
  }
}

}  // namespace
}  // namespace ncpath::io::detail
