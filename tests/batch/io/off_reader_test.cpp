// OFF reading (batch/io/off_reader.cpp through read_off / read_mesh): polygons, comments,
// and every malformed-input message.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <charconv>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "batch/io/mesh_reader.hpp"
#include "tests/batch/io/test_files.hpp"

namespace ncpath::io {
namespace {

using testing::expect_read_error;
using testing::TempDir;

double total_area(const TriangleMesh& m) {
  double a = 0;
  for (const auto& f : m.facets)
    a += 0.5 *
         (m.vertices[f[1]] - m.vertices[f[0]]).cross(m.vertices[f[2]] - m.vertices[f[0]]).norm();
  return a;
}

Vec3 tri_normal(const TriangleMesh& m, const std::array<std::uint32_t, 3>& f) {
  return (m.vertices[f[1]] - m.vertices[f[0]]).cross(m.vertices[f[2]] - m.vertices[f[0]]);
}

std::string exact(double x) {  // shortest round-trip text
  char buf[32];
  return std::string(buf, std::to_chars(buf, buf + sizeof buf, x).ptr);
}

constexpr const char* kCube =
    "# a unit cube with outward quads\n"
    "OFF\n"
    "8 6 12\n"
    "\n"
    "0 0 0\n"
    "1 0 0\n"
    "1 1 0\n"
    "0 1 0   # comment after a vertex\n"
    "0 0 1\n"
    "1 0 1\n"
    "\t1 1 1\n"
    "0 1 1\n"
    "4 0 3 2 1\n"
    "4 4 5 6 7\n"
    "\n"
    "4 0 1 5 4\n"
    "4 1 2 6 5\n"
    "4 2 3 7 6\n"
    "4 3 0 4 7\n"
    "# trailing comment\n\n";

TEST(OffReaderTest, CubeQuadsAreTriangulatedWithTheirWinding) {
  TempDir dir;
  const auto path = dir.write("cube.off", kCube);
  const MeshReadResult r = read_off(path);
  EXPECT_EQ(r.stats.format, "off");
  EXPECT_EQ(r.stats.facets_in_file, 6u);
  EXPECT_EQ(r.stats.polygons_triangulated, 6u);
  EXPECT_EQ(r.stats.facets_read, 12u);  // 6 quads x 2
  EXPECT_EQ(r.stats.facets_degenerate, 0u);
  EXPECT_EQ(r.mesh.vertices.size(), 8u);
  EXPECT_EQ(r.mesh.vertices[6], Vec3(1, 1, 1));
  EXPECT_NEAR(total_area(r.mesh), 6.0, 1e-14);
  // The quads are outward; every triangle must be too.
  for (const auto& f : r.mesh.facets) {
    const Vec3 centroid =
        (r.mesh.vertices[f[0]] + r.mesh.vertices[f[1]] + r.mesh.vertices[f[2]]) / 3;
    EXPECT_GT(tri_normal(r.mesh, f).dot(centroid - Vec3(0.5, 0.5, 0.5)), 0);
  }
}

// Regular k-gons of circumradius 1 in the plane z = 2, face vertices in CCW order.
std::string regular_polygons_off(const std::vector<int>& sides) {
  std::string verts, faces;
  int total = 0;
  for (int k : sides) total += k;
  int base = 0;
  for (int k : sides) {
    faces += std::to_string(k);
    for (int i = 0; i < k; ++i) {
      const double t = 2 * std::numbers::pi * i / k;
      verts += exact(std::cos(t) + 3 * base) + " " + exact(std::sin(t)) + " 2\n";
      faces += ' ';
      faces += std::to_string(base + i);
    }
    faces += "\n";
    base += k;
  }
  return "OFF " + std::to_string(total) + " " + std::to_string(sides.size()) + " 0\n" + verts +
         faces;
}

TEST(OffReaderTest, PentagonsAndHexagonsGiveKMinus2TrianglesEach) {
  TempDir dir;
  const auto path = dir.write("polys.off", regular_polygons_off({5, 6, 5, 3, 8}));
  const MeshReadResult r = read_off(path);
  EXPECT_EQ(r.stats.facets_in_file, 5u);
  EXPECT_EQ(r.stats.polygons_triangulated, 4u);  // the triangle is not a polygon to split
  EXPECT_EQ(r.stats.facets_read, 3u + 4u + 3u + 1u + 6u);
  // Area of a regular k-gon of circumradius 1: k/2 sin(2 pi / k).
  double expected = 0;
  for (int k : {5, 6, 5, 3, 8}) expected += 0.5 * k * std::sin(2 * std::numbers::pi / k);
  EXPECT_NEAR(total_area(r.mesh), expected, 1e-12);
  for (const auto& f : r.mesh.facets) EXPECT_GT(tri_normal(r.mesh, f).z(), 0);  // CCW kept
}

TEST(OffReaderTest, CountsOnTheHeaderLineAndFaceColoursIgnored) {
  TempDir dir;
  const auto path = dir.write("c.off", "OFF 3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 255 0 0\n");
  const MeshReadResult r = read_off(path);
  ASSERT_EQ(r.mesh.facets.size(), 1u);
  EXPECT_EQ(r.mesh.facets[0], (std::array<std::uint32_t, 3>{0, 1, 2}));
}

TEST(OffReaderTest, ReadMeshPicksOffByExtensionOrContent) {
  TempDir dir;
  EXPECT_EQ(read_mesh(dir.write("CUBE.OFF", kCube)).stats.format, "off");
  EXPECT_EQ(read_mesh(dir.write("cube.mesh", kCube)).stats.format, "off");  // '#' then OFF
  // An OFF error through read_mesh is an OFF message, not an STL one.
  expect_read_error([&] { read_mesh(dir.write("bad.off", "OFX\n")); },
                    {"bad.off: line 1 (header): ", "expected 'OFF'"});
}

TEST(OffReaderTest, BadHeader) {
  TempDir dir;
  expect_read_error([&] { read_off(dir.write("a.off", "\n# c\nOFX\n3 1 0\n")); },
                    {"a.off: line 3 (header): ", "bad header: expected 'OFF', found 'OFX'"});
  expect_read_error([&] { read_off(dir.write("b.off", "COFF\n3 1 0\n")); },
                    {"b.off: line 1 (header): ", "unsupported OFF variant 'COFF'"});
  expect_read_error([&] { read_off(dir.write("c.off", "OFF\n3 x 0\n")); },
                    {"c.off: line 2 (header): ", "face count 'x' is not a non-negative integer"});
  expect_read_error([&] { read_off(dir.write("d.off", "OFF\n-3 1 0\n")); },
                    {"d.off: line 2 (header): ", "vertex count '-3' is not a non-negative"});
  expect_read_error([&] { read_off(dir.write("e.off", "OFF\n3\n")); },
                    {"e.off: line 2 (header): ", "face count is missing"});
  expect_read_error([&] { read_off(dir.write("f.off", "OFF\n3 1 0 7\n")); },
                    {"f.off: line 2 (header): ", "unexpected '7' after the counts"});
  expect_read_error([&] { read_off(dir.write("g.off", "# nothing\n")); },
                    {"g.off: line 1: ", "unexpected end of file: expected the 'OFF' header"});
}

// Lines: 1 OFF, 2 counts, 3-6 vertices, 7 the face under test.
std::string square_with_face(const std::string& face, const std::string& tail = "") {
  return "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n" + face + "\n" + tail;
}

TEST(OffReaderTest, VertexIndexOutOfRange) {
  TempDir dir;
  const auto path = dir.write("a.off", square_with_face("3 0 1 7"));
  expect_read_error([&] { read_off(path); },
                    {"a.off: line 7 (face 1): ", "vertex index 7 in face 1 is out of range",
                     "4 vertices (indices 0 to 3)"});
}

TEST(OffReaderTest, FaceWithFewerThanThreeVertices) {
  TempDir dir;
  expect_read_error([&] { read_off(dir.write("a.off", square_with_face("2 0 1"))); },
                    {"a.off: line 7 (face 1): ", "face 1 has 2 vertices, at least 3 are needed"});
  expect_read_error([&] { read_off(dir.write("b.off", square_with_face("4 0 1 2"))); },
                    {"b.off: line 7 (face 1): ", "declares 4 vertices but lists only 3 indices"});
  expect_read_error([&] { read_off(dir.write("c.off", square_with_face("3 0 1 x"))); },
                    {"c.off: line 7 (face 1): ", "bad vertex index 'x' in face 1"});
  expect_read_error([&] { read_off(dir.write("d.off", square_with_face("three 0 1 2"))); },
                    {"d.off: line 7 (face 1): ", "bad vertex count 'three'"});
}

TEST(OffReaderTest, NonConvexPolygonIsRejectedWithItsLine) {
  TempDir dir;
  // A dart: the 4th vertex (0.5, 1) is a notch.
  const auto path = dir.write("dart.off",
                              "OFF\n4 2 0\n0 0 0\n2 1 0\n0 2 0\n0.5 1 0\n"
                              "3 0 1 2\n"
                              "4 0 1 2 3\n");
  expect_read_error([&] { read_off(path); },
                    {"dart.off: line 8 (face 2): ", "face 2 (4 vertices) is not convex",
                     "at its 4th vertex (index 3)", "only convex polygons are triangulated"});
}

TEST(OffReaderTest, StarPolygonIsRejected) {
  TempDir dir;
  std::string off = "OFF\n5 1 0\n";
  for (int i = 0; i < 5; ++i) {
    const double t = std::numbers::pi / 2 + 4 * std::numbers::pi * i / 5;  // 144 deg steps
    off += exact(std::cos(t)) + " " + exact(std::sin(t)) + " 0\n";
  }
  off += "5 0 1 2 3 4\n";
  expect_read_error([&] { read_off(dir.write("star.off", off)); },
                    {"star.off: line 8 (face 1): ", "is self-intersecting"});
}

TEST(OffReaderTest, ZeroLengthEdgeInAPolygonIsRejected) {
  TempDir dir;
  expect_read_error([&] { read_off(dir.write("a.off", square_with_face("4 0 1 1 2"))); },
                    {"a.off: line 7 (face 1): ", "has a zero-length edge",
                     "between its 2nd and 3rd vertices (indices 1 and 1)"});
}

TEST(OffReaderTest, DegenerateFacesAreSkippedAndCounted) {
  TempDir dir;
  // Face 1 repeats a vertex, face 3 is a quad on a line, faces 2 and 4 are fine.
  const auto path = dir.write("deg.off",
                              "OFF\n6 4 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n2 0 0\n3 0 0\n"
                              "3 0 0 1\n"
                              "3 0 1 2\n"
                              "4 0 1 4 5\n"
                              "4 0 1 2 3\n");
  const MeshReadResult r = read_off(path);
  EXPECT_EQ(r.stats.facets_in_file, 4u);
  EXPECT_EQ(r.stats.facets_degenerate, 2u);
  EXPECT_EQ(r.stats.polygons_triangulated, 1u);
  EXPECT_EQ(r.stats.facets_read, 3u);
  EXPECT_NEAR(total_area(r.mesh), 1.5, 1e-15);
}

TEST(OffReaderTest, BadVertexLines) {
  TempDir dir;
  expect_read_error(
      [&] { read_off(dir.write("a.off", "OFF\n3 1 0\n0 0 0\n1 abc 0\n0 1 0\n3 0 1 2\n")); },
      {"a.off: line 4 (vertex index 1): ",
       "bad number 'abc' for the y coordinate of vertex index 1"});
  expect_read_error(
      [&] { read_off(dir.write("b.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 nan\n3 0 1 2\n")); },
      {"b.off: line 5 (vertex index 2): ", "non-finite coordinate", "z = nan"});
  expect_read_error(
      [&] { read_off(dir.write("e.off", "OFF\n3 1 0\n-1e500 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")); },
      {"e.off: line 3 (vertex index 0): ", "x = -1e500, which is not a finite number"});
  expect_read_error(
      [&] { read_off(dir.write("c.off", "OFF\n3 1 0\n0 0\n1 0 0\n0 1 0\n3 0 1 2\n")); },
      {"c.off: line 3 (vertex index 0): ", "has 2 coordinates, expected 3"});
  expect_read_error(
      [&] { read_off(dir.write("d.off", "OFF\n3 1 0\n0 0 0 1\n1 0 0\n0 1 0\n3 0 1 2\n")); },
      {"d.off: line 3 (vertex index 0): ", "more than 3 values ('1' after x y z)"});
}

TEST(OffReaderTest, UnexpectedEndOfFile) {
  TempDir dir;
  expect_read_error([&] { read_off(dir.write("a.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n")); },
                    {"a.off: line 4: ", "unexpected end of file: expected 4 vertices, found 2"});
  expect_read_error(
      [&] { read_off(dir.write("c.off", "OFF\n4 3 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n")); },
      {"c.off: line 7: ", "unexpected end of file: expected 3 faces, found 1"});
}

TEST(OffReaderTest, TrailingContentAfterTheLastFace) {
  TempDir dir;
  const auto path = dir.write("a.off", square_with_face("3 0 1 2", "\n# fine\n3 0 2 3\n"));
  expect_read_error([&] { read_off(path); },
                    {"a.off: line 10: ", "unexpected content after the last face: '3 0 2 3'",
                     "declares 1 faces"});
}

TEST(OffReaderTest, NoFacesIsAnEmptyMesh) {
  TempDir dir;
  expect_read_error([&] { read_off(dir.write("a.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n")); },
                    {"a.off: ", "empty mesh: the file holds no facets"});
}

}  // namespace
}  // namespace ncpath::io
