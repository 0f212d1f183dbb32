// STL reading (batch/io/stl_reader.cpp through the public read_stl / read_mesh): binary and
// ASCII, detection, and every malformed-input message.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "batch/io/mesh_reader.hpp"
#include "engine/parallel.hpp"
#include "tests/batch/io/test_files.hpp"

namespace ncpath::io {
namespace {

using testing::binary_stl;
using testing::expect_read_error;
using testing::raw_facet;
using testing::RawFacet;
using testing::TempDir;

const RawFacet kUnitTri = raw_facet({0, 0, 0}, {1, 0, 0}, {0, 1, 0});

TEST(StlReaderTest, MissingFileNamesFileAndReason) {
  TempDir dir;
  const auto path = dir.path() / "nope.stl";
  expect_read_error([&] { read_stl(path); },
                    {path.string(), "cannot open", "No such file or directory"});
  expect_read_error([&] { read_mesh(path); }, {"nope.stl", "cannot open"});
}

TEST(StlReaderTest, DirectoryIsNotAFile) {
  TempDir dir;
  expect_read_error([&] { read_stl(dir.path()); }, {dir.path().string(), "is a directory"});
}

TEST(StlReaderTest, EmptyFile) {
  TempDir dir;
  const auto path = dir.write("empty.stl", "");
  expect_read_error([&] { read_stl(path); }, {"empty.stl", "empty file (0 bytes)"});
}

TEST(StlReaderTest, ShortFileThatIsNeitherFormat) {
  TempDir dir;
  const auto path = dir.write("junk.stl", "hello");
  expect_read_error([&] { read_stl(path); }, {"junk.stl", "not an STL file", "5 bytes"});
}

TEST(StlReaderTest, BinaryReadsFloatsWidenedToDouble) {
  TempDir dir;
  const auto path = dir.write(
      "a.stl", binary_stl("ncpath test",
                          {raw_facet({0.1f, 0.2f, 0.3f}, {1, 0, 0}, {0, 1, -7.5f}), kUnitTri}));
  const MeshReadResult r = read_stl(path);
  EXPECT_EQ(r.stats.format, "stl-binary");
  EXPECT_EQ(r.stats.facets_in_file, 2u);
  EXPECT_EQ(r.stats.facets_read, 2u);
  EXPECT_EQ(r.stats.facets_degenerate, 0u);
  ASSERT_EQ(r.mesh.vertices.size(), 6u);  // a soup: 3 vertices per facet
  ASSERT_EQ(r.mesh.facets.size(), 2u);
  // float32 widened exactly: 0.1f is not 0.1.
  EXPECT_EQ(r.mesh.vertices[0].x(), static_cast<double>(0.1f));
  EXPECT_NE(r.mesh.vertices[0].x(), 0.1);
  EXPECT_EQ(r.mesh.vertices[0].z(), static_cast<double>(0.3f));
  EXPECT_EQ(r.mesh.vertices[2], Vec3(0, 1, -7.5));
  EXPECT_EQ(r.mesh.facets[1], (std::array<std::uint32_t, 3>{3, 4, 5}));
  EXPECT_EQ(r.mesh.vertices[r.mesh.facets[1][1]], Vec3(1, 0, 0));
}

TEST(StlReaderTest, BinaryWithSolidHeaderReadsAsBinary) {
  TempDir dir;
  const auto path = dir.write(
      "solid.stl",
      binary_stl("solid looks like ascii\nfacet normal 0 0 1\n", {kUnitTri, kUnitTri, kUnitTri}));
  const MeshReadResult r = read_stl(path);
  EXPECT_EQ(r.stats.format, "stl-binary");
  EXPECT_EQ(r.stats.facets_read, 3u);
  EXPECT_EQ(r.mesh.vertices[4], Vec3(1, 0, 0));
  EXPECT_EQ(read_mesh(path).stats.format, "stl-binary");
}

TEST(StlReaderTest, BinaryWithSolidHeaderAndBadCountIsABinaryError) {
  TempDir dir;
  const auto path =
      dir.write("solid.stl", binary_stl("solid x", {kUnitTri, kUnitTri}, std::uint32_t{3}));
  // Not parsed as ASCII (that would complain about syntax): reported as a truncated binary.
  expect_read_error([&] { read_stl(path); },
                    {"solid.stl", "byte 184 (facet 3)", "truncated file", "3 facets"});
}

TEST(StlReaderTest, BinaryTruncatedInsideAFacet) {
  TempDir dir;
  std::string bytes = binary_stl("h", {kUnitTri, kUnitTri, kUnitTri});
  bytes.resize(84 + 50 * 2 + 12);  // 196 bytes: facet 3 has only 12 of its 50 bytes
  const auto path = dir.write("bunny.stl", bytes);
  expect_read_error([&] { read_stl(path); },
                    {"bunny.stl: byte 184 (facet 3): truncated file: expected 50 bytes for "
                     "facet 3, 12 left",
                     "3 facets", "234 bytes", "196 bytes"});
}

TEST(StlReaderTest, BinaryTruncatedAtAFacetBoundary) {
  TempDir dir;
  const auto path =
      dir.write("cut.stl", binary_stl("h", {kUnitTri, kUnitTri, kUnitTri}, std::uint32_t{5}));
  expect_read_error([&] { read_stl(path); },
                    {"cut.stl", "byte 234 (facet 4)", "truncated file", "ends after facet 3",
                     "5 facets", "334 bytes", "234 bytes"});
}

TEST(StlReaderTest, BinaryCountSmallerThanTheFileSays) {
  TempDir dir;
  const auto path =
      dir.write("long.stl", binary_stl("h", {kUnitTri, kUnitTri, kUnitTri}, std::uint32_t{2}));
  expect_read_error([&] { read_stl(path); },
                    {"long.stl", "byte 80 (facet count)", "disagrees with the file size",
                     "2 facets", "184 bytes", "234 bytes", "50 bytes too many"});
}

TEST(StlReaderTest, BinaryNonFiniteCoordinateNamesFacetAndVertex) {
  TempDir dir;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const auto p1 = dir.write(
      "nan.stl", binary_stl("h", {kUnitTri, raw_facet({0, 0, 0}, {1, 0, 0}, {0, 1, nan})}));
  // Facet 2 starts at byte 134; its third vertex's z is float 11 of the facet: 134 + 44.
  expect_read_error([&] { read_stl(p1); },
                    {"nan.stl", "byte 178 (facet 2)", "non-finite", "vertex 3", "z = nan"});
  const auto p2 =
      dir.write("inf.stl", binary_stl("h", {raw_facet({0, -inf, 0}, {1, 0, 0}, {0, 1, 0})}));
  expect_read_error([&] { read_stl(p2); },
                    {"inf.stl", "byte 100 (facet 1)", "vertex 1", "y = -inf"});
}

TEST(StlReaderTest, BinaryNonFiniteNormalIsIgnored) {
  TempDir dir;
  RawFacet f = kUnitTri;
  f[0] = f[1] = f[2] = std::numeric_limits<float>::quiet_NaN();
  const auto path = dir.write("n.stl", binary_stl("h", {f}));
  EXPECT_EQ(read_stl(path).stats.facets_read, 1u);
}

TEST(StlReaderTest, DegenerateFacetsAreSkippedAndCounted) {
  TempDir dir;
  const auto path = dir.write(
      "deg.stl",
      binary_stl("h", {kUnitTri, raw_facet({0, 0, 0}, {0, 0, 0}, {1, 1, 1}),  // repeated vertex
                       raw_facet({0, 0, 0}, {1, 1, 1}, {2, 2, 2}),            // collinear
                       raw_facet({5, 0, 0}, {6, 0, 0}, {5, 0, 1})}));
  const MeshReadResult r = read_stl(path);
  EXPECT_EQ(r.stats.facets_in_file, 4u);
  EXPECT_EQ(r.stats.facets_degenerate, 2u);
  EXPECT_EQ(r.stats.facets_read, 2u);
  ASSERT_EQ(r.mesh.facets.size(), 2u);
  EXPECT_EQ(r.mesh.vertices[r.mesh.facets[1][0]], Vec3(5, 0, 0));  // the 4th facet, kept
}

// 200,000 facets (binary facets are parsed in chunks of 65,536, in parallel): degenerate ones
// on both sides of the chunk boundaries and at random are skipped, the others kept in file
// order, each facet's vertices as written (the generator's list, not a second reader); the
// same with 1 and 2 threads. A non-finite coordinate in the third chunk and one in the second
// report the second's, as a serial reader meets it first.
TEST(StlReaderTest, BinaryChunksKeepFileOrderAndTheFirstError) {
  TempDir dir;
  std::vector<RawFacet> facets;
  std::vector<std::array<float, 3>> expected;  // first vertex of each kept facet
  std::uint64_t degenerate = 0;
  for (std::uint32_t f = 0; f < 200000; ++f) {
    const float x = float(f % 1000), y = float(f / 1000);
    const bool flat = f % 65536 == 0 || f % 65536 == 65535 || f % 997 == 3;
    facets.push_back(flat ? raw_facet({x, y, 0}, {x + 1, y, 0}, {x + 2, y, 0})
                          : raw_facet({x, y, 1}, {x + 1, y, 1}, {x, y + 1, 1}));
    if (flat)
      ++degenerate;
    else
      expected.push_back({x, y, 1});
  }
  const auto path = dir.write("many.stl", binary_stl("h", facets));
  MeshReadResult one, two;
  {
    par::ThreadLimit limit(1);
    one = read_stl(path);
  }
  {
    par::ThreadLimit limit(2);
    two = read_stl(path);
  }
  EXPECT_EQ(one.stats.facets_degenerate, degenerate);
  ASSERT_EQ(one.mesh.facets.size(), expected.size());
  for (std::size_t k = 0; k < expected.size(); ++k) {
    const auto& f = one.mesh.facets[k];
    ASSERT_EQ(f, (std::array<std::uint32_t, 3>{3 * std::uint32_t(k), 3 * std::uint32_t(k) + 1,
                                               3 * std::uint32_t(k) + 2}));
    ASSERT_EQ(one.mesh.vertices[f[0]], Vec3(expected[k][0], expected[k][1], expected[k][2]));
    ASSERT_EQ(one.mesh.vertices[f[2]], Vec3(expected[k][0], expected[k][1] + 1, 1));
  }
  EXPECT_EQ(one.mesh.vertices, two.mesh.vertices);
  EXPECT_EQ(one.mesh.facets, two.mesh.facets);

  facets[150000][5] = std::numeric_limits<float>::infinity();  // chunk 3, vertex 1 z
  facets[70000][9] = std::numeric_limits<float>::quiet_NaN();  // chunk 2, vertex 3 x
  const auto bad = dir.write("bad.stl", binary_stl("h", facets));
  // Facet 70,001 starts at byte 84 + 50 * 70,000; its third vertex's x is its float 9: + 36.
  expect_read_error([&] { read_stl(bad); },
                    {"byte 3500120 (facet 70001)", "non-finite", "vertex 3", "x = nan"});
}

TEST(StlReaderTest, NoFacetsLeftIsAnError) {
  TempDir dir;
  const auto p1 = dir.write("zero.stl", binary_stl("h", {}));
  expect_read_error([&] { read_stl(p1); }, {"zero.stl", "empty mesh", "no facets"});
  const auto p2 =
      dir.write("flat.stl", binary_stl("h", {raw_facet({0, 0, 0}, {1, 0, 0}, {2, 0, 0}),
                                             raw_facet({1, 1, 1}, {1, 1, 1}, {1, 1, 1})}));
  expect_read_error([&] { read_stl(p2); },
                    {"flat.stl", "empty mesh", "all 2 facets", "degenerate"});
  const auto p3 = dir.write("none.stl", "solid x\nendsolid x\n");
  expect_read_error([&] { read_stl(p3); }, {"none.stl", "empty mesh"});
}

constexpr const char* kAsciiTwoSolids =
    "solid part one\n"
    "  facet normal 0 0 1\n"
    "    outer loop\n"
    "      vertex 0 0 0\n"
    "      vertex 1 0 0\n"
    "      vertex 0 1 0\n"
    "    endloop\n"
    "  endfacet\n"
    "endsolid part one\n"
    "SOLID second\r\n"
    "FACET NORMAL nan nan nan\r\n"
    "OUTER LOOP\r\n"
    "VERTEX +1.5e+1 -2.25 0.1\r\n"
    "VERTEX 3 4 5\r\n"
    "VERTEX 1e-3 .5 7\r\n"
    "ENDLOOP\r\n"
    "ENDFACET\r\n"
    "ENDSOLID second\r\n";

TEST(StlReaderTest, AsciiParsesInDoublePrecision) {
  TempDir dir;
  const auto path = dir.write("two.stl", kAsciiTwoSolids);
  const MeshReadResult r = read_stl(path);
  EXPECT_EQ(r.stats.format, "stl-ascii");
  EXPECT_EQ(r.stats.facets_in_file, 2u);
  EXPECT_EQ(r.stats.facets_read, 2u);
  ASSERT_EQ(r.mesh.vertices.size(), 6u);
  EXPECT_EQ(r.mesh.vertices[1], Vec3(1, 0, 0));
  EXPECT_EQ(r.mesh.vertices[3], Vec3(15, -2.25, 0.1));  // 0.1 in double, not float
  EXPECT_EQ(r.mesh.vertices[5], Vec3(0.001, 0.5, 7));
  EXPECT_EQ(read_mesh(path).stats.format, "stl-ascii");
}

// ASCII STL with one facet whose loop body is `loop` (lines 4 on).
std::string ascii_facet(const std::string& loop, const std::string& tail = "endsolid t\n") {
  return "solid t\n"               // line 1
         "  facet normal 0 0 1\n"  // line 2
         "    outer loop\n" +      // line 3
         loop +
         "    endloop\n  endfacet\n" + tail;
}

TEST(StlReaderTest, AsciiMissingVertexKeyword) {
  TempDir dir;
  const auto path = dir.write("a.stl", ascii_facet("vertex 0 0 0\n1 0 0\nvertex 0 1 0\n"));
  expect_read_error([&] { read_stl(path); },
                    {"a.stl: line 5: ", "expected 'vertex' or 'endloop' in facet 1, found '1'"});
}

TEST(StlReaderTest, AsciiTooFewVerticesInLoop) {
  TempDir dir;
  const auto path = dir.write("a.stl", ascii_facet("vertex 0 0 0\nvertex 1 0 0\n"));
  expect_read_error([&] { read_stl(path); },
                    {"a.stl: line 6: ", "facet 1 has 2 vertices in its loop, expected 3"});
}

TEST(StlReaderTest, AsciiTooManyVerticesInLoop) {
  TempDir dir;
  const auto path =
      dir.write("a.stl", ascii_facet("vertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nvertex 1 1 0\n"));
  expect_read_error([&] { read_stl(path); },
                    {"a.stl: line 7: ", "facet 1 has more than 3 vertices"});
}

TEST(StlReaderTest, AsciiUnterminatedSolid) {
  TempDir dir;
  const auto path = dir.write(
      "a.stl", ascii_facet("vertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n", "  facet normal 0 0 1\n"));
  expect_read_error(
      [&] { read_stl(path); },
      {"a.stl: line 9: ", "unterminated solid (started at line 1)", "'endsolid' is missing"});
}

TEST(StlReaderTest, AsciiBadNumber) {
  TempDir dir;
  const auto path =
      dir.write("a.stl", ascii_facet("vertex 0 0 0\nvertex 1 0.0.1 0\nvertex 0 1 0\n"));
  expect_read_error(
      [&] { read_stl(path); },
      {"a.stl: line 5: ", "bad number '0.0.1' for the y coordinate of vertex 2 in facet 1"});
  const auto p2 = dir.write("b.stl", ascii_facet("vertex 0 0\nvertex 1 0 0\nvertex 0 1 0\n"));
  expect_read_error([&] { read_stl(p2); },
                    {"b.stl: line 5: ", "bad number 'vertex' for the z coordinate of vertex 1"});
  const auto p3 = dir.write("c.stl", "solid t\n facet normal 0 x 1\n");
  expect_read_error([&] { read_stl(p3); },
                    {"c.stl: line 2: ", "bad number 'x' for the normal's y in facet 1"});
}

TEST(StlReaderTest, AsciiNonFiniteCoordinate) {
  TempDir dir;
  const auto path = dir.write("a.stl", ascii_facet("vertex 0 0 0\nvertex 1 0 0\nvertex 0 nan 0\n"));
  expect_read_error([&] { read_stl(path); },
                    {"a.stl: line 6: ", "non-finite coordinate in facet 1: vertex 3 has y = nan"});
  const auto p2 = dir.write("b.stl", ascii_facet("vertex -inf 0 0\nvertex 1 0 0\nvertex 0 1 0\n"));
  expect_read_error([&] { read_stl(p2); }, {"b.stl: line 4: ", "vertex 1 has x = -inf"});
  // Overflowing literals are non-finite, not "bad numbers"; underflowing ones are tiny.
  const auto p3 = dir.write("c.stl", ascii_facet("vertex 0 0 0\nvertex 1 0 0\nvertex 0 1 1e999\n"));
  expect_read_error([&] { read_stl(p3); },
                    {"c.stl: line 6: ", "vertex 3 has z = 1e999, which is not a finite number"});
  const auto p4 =
      dir.write("d.stl", ascii_facet("vertex 0 0 1e-400\nvertex 1 0 0\nvertex 0 1 0\n"));
  const MeshReadResult r = read_stl(p4);
  EXPECT_GE(r.mesh.vertices[0].z(), 0.0);
  EXPECT_LT(r.mesh.vertices[0].z(), 1e-300);
}

TEST(StlReaderTest, AsciiMissingEndfacetAndTrailingGarbage) {
  TempDir dir;
  const auto p1 = dir.write("a.stl",
                            "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                            "vertex 0 1 0\nendloop\nfacet normal 0 0 1\n");
  expect_read_error(
      [&] { read_stl(p1); },
      {"a.stl: line 8: ", "expected 'endfacet' after 'endloop' in facet 1, found 'facet'"});
  const auto p2 = dir.write(
      "b.stl", ascii_facet("vertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n", "endsolid t\nhello\n"));
  expect_read_error([&] { read_stl(p2); },
                    {"b.stl: line 10: ", "unexpected 'hello' after 'endsolid'"});
}

}  // namespace
}  // namespace ncpath::io
