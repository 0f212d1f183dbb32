// STL writing (batch/io/stl_writer.cpp): round trips through the readers, the bytes of the
// binary layout, and write failures.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>

#include "batch/io/mesh_reader.hpp"
#include "batch/io/stl_writer.hpp"
#include "tests/batch/io/test_files.hpp"

namespace ncpath::io {
namespace {

using testing::TempDir;

// A tetrahedron with outward facets and coordinates that are not floats, plus a shared
// vertex order that differs from the facet order.
TriangleMesh tetrahedron() {
  TriangleMesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(1.1, 0, 0), Vec3(0, 2.2, 0), Vec3(0.1, 0.2, 1.0 / 3)};
  m.facets = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}};
  return m;
}

// v rounded to float32 and widened back. Through a volatile float on purpose: GCC 12.2 at -O2
// (SLP vectoriser) drops a double -> float -> double round trip of adjacent components.
double to_float(double x) {
  volatile float f = static_cast<float>(x);
  return f;
}
Vec3 as_float(const Vec3& v) { return Vec3(to_float(v.x()), to_float(v.y()), to_float(v.z())); }

std::string file_bytes(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

float float_at(const std::string& bytes, std::size_t offset) {
  float f;
  std::memcpy(&f, bytes.data() + offset, 4);
  return f;
}

TEST(StlWriterTest, BinaryRoundTripKeepsFacetsAndFloatCoordinates) {
  TempDir dir;
  const TriangleMesh m = tetrahedron();
  const auto path = dir.path() / "tet.stl";
  write_binary_stl(path, m);
  const MeshReadResult r = read_stl(path);
  EXPECT_EQ(r.stats.format, "stl-binary");
  ASSERT_EQ(r.mesh.facets.size(), m.facets.size());
  for (std::size_t f = 0; f < m.facets.size(); ++f)
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(r.mesh.vertices[r.mesh.facets[f][k]], as_float(m.vertices[m.facets[f][k]]))
          << "facet " << f << " vertex " << k;
}

TEST(StlWriterTest, BinaryLayoutHeaderCountAndNormals) {
  TempDir dir;
  const TriangleMesh m = tetrahedron();
  const auto path = dir.path() / "tet.stl";
  write_binary_stl(path, m, "my header");
  const std::string bytes = file_bytes(path);
  ASSERT_EQ(bytes.size(), 84u + 50u * 4u);
  EXPECT_EQ(bytes.substr(0, 9), "my header");
  EXPECT_EQ(bytes.substr(9, 71), std::string(71, '\0'));
  std::uint32_t count;
  std::memcpy(&count, bytes.data() + 80, 4);
  EXPECT_EQ(count, 4u);
  // Facet 1 (0, 2, 1) lies in z = 0 and is wound clockwise seen from +z: normal -z.
  EXPECT_EQ(float_at(bytes, 84), 0.0f);
  EXPECT_EQ(float_at(bytes, 88), 0.0f);
  EXPECT_EQ(float_at(bytes, 92), -1.0f);
  // Facet 2 (0, 1, 3): (1.1, 0, 0) x (0.1, 0.2, 1/3) = (0, -1.1/3, 0.22), normalised.
  const Vec3 n = Vec3(0, -1.1 / 3, 0.22).normalized();
  EXPECT_NEAR(float_at(bytes, 134), n.x(), 1e-7);
  EXPECT_NEAR(float_at(bytes, 138), n.y(), 1e-7);
  EXPECT_NEAR(float_at(bytes, 142), n.z(), 1e-7);
  EXPECT_EQ(bytes.substr(84 + 48, 2), std::string(2, '\0'));  // attribute bytes
}

TEST(StlWriterTest, LongHeaderIsCutAt80Bytes) {
  TempDir dir;
  const std::string header(100, 'h');
  const auto path = dir.path() / "h.stl";
  write_binary_stl(path, tetrahedron(), header);
  const std::string bytes = file_bytes(path);
  EXPECT_EQ(bytes.size(), 84u + 50u * 4u);
  EXPECT_EQ(bytes.substr(0, 80), std::string(80, 'h'));
}

TEST(StlWriterTest, SolidHeaderBinaryReadsBackAsBinary) {
  TempDir dir;
  const auto path = dir.path() / "s.stl";
  write_binary_stl(path, tetrahedron(), "solid tetrahedron");
  const MeshReadResult r = read_mesh(path);
  EXPECT_EQ(r.stats.format, "stl-binary");
  EXPECT_EQ(r.stats.facets_read, 4u);
}

TEST(StlWriterTest, AsciiRoundTripIsExactInDouble) {
  TempDir dir;
  const TriangleMesh m = tetrahedron();
  const auto path = dir.path() / "tet.stl";
  write_ascii_stl(path, m, "tet");
  EXPECT_EQ(file_bytes(path).substr(0, 10), "solid tet\n");
  const MeshReadResult r = read_mesh(path);
  EXPECT_EQ(r.stats.format, "stl-ascii");
  ASSERT_EQ(r.mesh.facets.size(), m.facets.size());
  for (std::size_t f = 0; f < m.facets.size(); ++f)
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(r.mesh.vertices[r.mesh.facets[f][k]], m.vertices[m.facets[f][k]]);
}

TEST(StlWriterTest, DegenerateFacetGetsZeroNormalAndIsSkippedOnReading) {
  TempDir dir;
  TriangleMesh m = tetrahedron();
  m.facets.push_back({0, 1, 1});
  const auto path = dir.path() / "d.stl";
  write_binary_stl(path, m);
  const std::string bytes = file_bytes(path);
  const std::size_t at = 84 + 50 * 4;
  EXPECT_EQ(float_at(bytes, at), 0.0f);
  EXPECT_EQ(float_at(bytes, at + 4), 0.0f);
  EXPECT_EQ(float_at(bytes, at + 8), 0.0f);
  const MeshReadResult r = read_stl(path);
  EXPECT_EQ(r.stats.facets_in_file, 5u);
  EXPECT_EQ(r.stats.facets_degenerate, 1u);
  EXPECT_EQ(r.stats.facets_read, 4u);
}

TEST(StlWriterTest, FailuresNameThePath) {
  TempDir dir;
  const auto bad = dir.path() / "no_such_dir" / "x.stl";
  try {
    write_binary_stl(bad, tetrahedron());
    ADD_FAILURE() << "expected an exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(bad.string()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("cannot open"), std::string::npos) << e.what();
  }
  EXPECT_THROW(write_ascii_stl(bad, tetrahedron()), std::runtime_error);
  TriangleMesh broken = tetrahedron();
  broken.facets.push_back({0, 1, 9});
  try {
    write_binary_stl(dir.path() / "b.stl", broken);
    ADD_FAILURE() << "expected an exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("vertex index 9 is out of range"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace ncpath::io
