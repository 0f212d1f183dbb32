#pragma once
// Test helpers of the scan command tests: small OFF meshes with analytic scans (a V-groove, a
// box pocket), and the scan job's datasets read back with the HDF5 C API.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "tests/batch/output/h5_read.hpp"

namespace ncpath::scan_cli {

namespace h5 = out::test;

struct OffMesh {
  std::vector<std::array<double, 3>> v;
  std::vector<std::array<int, 3>> f;
};

// OFF keeps vertex and facet indices, so the element indices in the file can be checked.
inline void write_off(const std::filesystem::path& path, const OffMesh& m) {
  std::ofstream out(path);
  out << "OFF\n" << m.v.size() << " " << m.f.size() << " 0\n";
  for (const auto& p : m.v) out << p[0] << " " << p[1] << " " << p[2] << "\n";
  for (const auto& t : m.f) out << "3 " << t[0] << " " << t[1] << " " << t[2] << "\n";
}

// V-groove z = |x| for x in [-10, 10], y in [0, 20] (across_y: x and y swapped, z = |y|).
// Vertices 0..2 at y = 0: (-10, 10), (0, 0), (10, 10) in (x, z); 3..5 the same at y = 20.
// Facets 0, 1: the left flank (x < 0); 2, 3: the right flank. Top edges: {0, 3}, {2, 5}.
inline OffMesh groove(bool across_y) {
  OffMesh m;
  for (double y : {0.0, 20.0})
    for (double x : {-10.0, 0.0, 10.0})
      m.v.push_back(across_y ? std::array<double, 3>{y, x, std::abs(x)}
                             : std::array<double, 3>{x, y, std::abs(x)});
  m.f = {{0, 1, 4}, {0, 4, 3}, {1, 2, 5}, {1, 5, 4}};
  return m;
}

// A 40 x 40 block, top z = 10, with a square pocket [10, 30]^2 down to z = 0. Vertices: 0..3
// the outer top corners, 4..7 the pocket's top corners (10,10), (30,10), (30,30), (10,30),
// 8..11 its bottom corners. Facets: 0..7 the top, 8..15 the walls, 16, 17 the floor.
inline OffMesh box_pocket() {
  OffMesh m;
  m.v = {{0, 0, 10},  {40, 0, 10},  {40, 40, 10}, {0, 40, 10}, {10, 10, 10}, {30, 10, 10},
         {30, 30, 10}, {10, 30, 10}, {10, 10, 0},  {30, 10, 0}, {30, 30, 0},  {10, 30, 0}};
  m.f = {{0, 1, 5},  {0, 5, 4},  {1, 2, 6},  {1, 6, 5},  {2, 3, 7},  {2, 7, 6},
         {3, 0, 4},  {3, 4, 7},  {4, 5, 9},  {4, 9, 8},  {5, 6, 10}, {5, 10, 9},
         {6, 7, 11}, {6, 11, 10}, {7, 4, 8}, {7, 8, 11}, {8, 9, 10}, {8, 10, 11}};
  return m;
}

// A folder of its own per test: ctest runs the tests of a binary in parallel processes.
inline std::filesystem::path fixture_dir(const std::string& name) {
  return h5::out_dir("scan_cli_" + name);
}

using Row = std::array<double, 3>;
struct Element {
  std::int64_t kind, a, b;
};

// The cl/ and scan/ datasets of one job.
struct ScanOut {
  std::vector<double> pts;
  std::vector<std::int64_t> off;
  std::vector<std::uint8_t> kind;
  std::vector<std::size_t> cut_paths;  // cut_paths[k]: index in cl/ of the k-th cut path
  std::vector<std::int64_t> seg_path, seg_element, jun_path, jun_element1, jun_element2;
  std::vector<std::uint8_t> seg_kind, jun_kind;
  std::vector<double> seg_start, seg_end, seg_geometry, jun_position, jun_b1, jun_b2, jun_angle;

  static Row row(const std::vector<double>& v, std::size_t i) {
    return {v[3 * i], v[3 * i + 1], v[3 * i + 2]};
  }
  static Element element(const std::vector<std::int64_t>& v, std::size_t i) {
    return {v[3 * i], v[3 * i + 1], v[3 * i + 2]};
  }
  Row seg_start_of(std::size_t i) const { return row(seg_start, i); }
  Row seg_end_of(std::size_t i) const { return row(seg_end, i); }
  std::array<double, 5> seg_geometry_of(std::size_t i) const {
    std::array<double, 5> g;
    for (int c = 0; c < 5; ++c) g[c] = seg_geometry[5 * i + c];
    return g;
  }
  Element seg_element_of(std::size_t i) const { return element(seg_element, i); }
  Row jun_position_of(std::size_t i) const { return row(jun_position, i); }
  Row jun_b1_of(std::size_t i) const { return row(jun_b1, i); }
  Row jun_b2_of(std::size_t i) const { return row(jun_b2, i); }
  Element jun_element1_of(std::size_t i) const { return element(jun_element1, i); }
  Element jun_element2_of(std::size_t i) const { return element(jun_element2, i); }
};

inline ScanOut read_scan(hid_t f, const std::string& job) {
  const std::string g = "/jobs/" + job + "/";
  auto f64 = [&](const std::string& p) { return h5::read_all<double>(f, g + p, H5T_NATIVE_DOUBLE); };
  auto i64 = [&](const std::string& p) {
    return h5::read_all<std::int64_t>(f, g + p, H5T_NATIVE_INT64);
  };
  auto u8 = [&](const std::string& p) {
    return h5::read_all<std::uint8_t>(f, g + p, H5T_NATIVE_UINT8);
  };
  ScanOut s;
  s.pts = f64("cl/points");
  s.off = i64("cl/path_offsets");
  s.kind = u8("cl/path_kind");
  for (std::size_t p = 0; p < s.kind.size(); ++p)
    if (s.kind[p] == 0) s.cut_paths.push_back(p);
  s.seg_path = i64("scan/segment_path");
  s.seg_kind = u8("scan/segment_kind");
  s.seg_element = i64("scan/segment_element");
  s.seg_start = f64("scan/segment_start");
  s.seg_end = f64("scan/segment_end");
  s.seg_geometry = f64("scan/segment_geometry");
  s.jun_path = i64("scan/junction_path");
  s.jun_kind = u8("scan/junction_kind");
  s.jun_position = f64("scan/junction_position");
  s.jun_b1 = f64("scan/junction_b1");
  s.jun_b2 = f64("scan/junction_b2");
  s.jun_element1 = i64("scan/junction_element1");
  s.jun_element2 = i64("scan/junction_element2");
  s.jun_angle = f64("scan/junction_angle");
  return s;
}

// Rows whose path is k, in file order.
inline std::vector<std::size_t> rows_of(const std::vector<std::int64_t>& path, std::size_t k) {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < path.size(); ++i)
    if (path[i] == static_cast<std::int64_t>(k)) out.push_back(i);
  return out;
}

inline std::vector<hsize_t> dims(hid_t f, const std::string& path) {
  h5::Id ds(H5Dopen2(f, path.c_str(), H5P_DEFAULT), "open " + path);
  return h5::dims_of(ds);
}

// Shapes, units and descriptions of the scan datasets; paths in cutting order, each naming a
// cut path of cl/.
inline void check_shapes(hid_t f, const std::string& job, const ScanOut& s) {
  const std::string g = "/jobs/" + job + "/scan/";
  const hsize_t n = s.seg_kind.size(), m = s.jun_kind.size();
  ASSERT_GT(n, 0u);
  ASSERT_GT(m, 0u);
  const struct {
    const char* name;
    std::vector<hsize_t> shape;
    const char* unit;
  } want[] = {
      {"segment_path", {n}, ""},          {"segment_kind", {n}, ""},
      {"segment_element", {n, 3}, ""},    {"segment_start", {n, 3}, "mm"},
      {"segment_end", {n, 3}, "mm"},      {"segment_geometry", {n, 5}, ""},
      {"junction_path", {m}, ""},         {"junction_kind", {m}, ""},
      {"junction_position", {m, 3}, "mm"}, {"junction_b1", {m, 3}, ""},
      {"junction_b2", {m, 3}, ""},        {"junction_element1", {m, 3}, ""},
      {"junction_element2", {m, 3}, ""},  {"junction_angle", {m}, "rad"},
  };
  for (const auto& w : want) {
    EXPECT_EQ(dims(f, g + w.name), w.shape) << w.name;
    h5::Id ds(H5Dopen2(f, (g + w.name).c_str(), H5P_DEFAULT), w.name);
    EXPECT_TRUE(h5::has_attr(ds, "description")) << w.name;
    EXPECT_EQ(h5::has_attr(ds, "unit") ? h5::attr_str(ds, "unit") : "", w.unit) << w.name;
  }
  h5::Id kinds(H5Dopen2(f, (g + "segment_kind").c_str(), H5P_DEFAULT));
  EXPECT_NE(h5::attr_str(kinds, "description").find("6=vertical"), std::string::npos);
  for (const auto* path : {&s.seg_path, &s.jun_path}) {
    for (std::size_t i = 0; i < path->size(); ++i) {
      ASSERT_GE((*path)[i], 0);
      ASSERT_LT((*path)[i], static_cast<std::int64_t>(s.cut_paths.size()));
      if (i > 0) {
        ASSERT_LE((*path)[i - 1], (*path)[i]) << "not in cutting order at " << i;
      }
    }
  }
}

// Tip z of a segment at u from its geometry row, as docs/hdf5-schema.md describes it.
inline double segment_z(int kind, const std::array<double, 5>& g, double u) {
  if (kind == 0 || kind == 3 || kind == 5) return g[0] * u + g[1];  // z = a u + b
  if (kind == 1) return g[1] + std::sqrt(std::max(0.0, g[2] * g[2] - (u - g[0]) * (u - g[0])));
  // Ellipse, centre (g0, g1), semi-axes M = g2 along phi = g4 and m = g3: the larger root w
  // of (du c + w s)^2 / M^2 + (-du s + w c)^2 / m^2 = 1, du = u - g0.
  const double du = u - g[0], M2 = g[2] * g[2], m2 = g[3] * g[3];
  const double c = std::cos(g[4]), s = std::sin(g[4]);
  const double qa = s * s / M2 + c * c / m2;
  const double qb = 2 * du * c * s / M2 - 2 * du * s * c / m2;
  const double qc = du * du * (c * c / M2 + s * s / m2) - 1;
  return g[1] + (-qb + std::sqrt(std::max(0.0, qb * qb - 4 * qa * qc))) / (2 * qa);
}

// The statistics of one job: st[name] as a double, st.text(name) for strings, st.unit(name).
struct Stats {
  hid_t file;
  std::string job;
  std::string path(const std::string& name) const { return "/jobs/" + job + "/stats/" + name; }
  double operator[](const std::string& name) const {
    const std::vector<double> v = h5::read_all<double>(file, path(name), H5T_NATIVE_DOUBLE);
    return v.empty() ? NAN : v.front();
  }
  std::string text(const std::string& name) const {
    h5::Id ds(H5Dopen2(file, path(name).c_str(), H5P_DEFAULT), "open " + path(name));
    h5::Id type(H5Dget_type(ds));
    char* p = nullptr;
    if (H5Dread(ds, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, &p) < 0) return "?";
    std::string out = p ? p : "";
    H5free_memory(p);
    return out;
  }
  std::string unit(const std::string& name) const {
    h5::Id ds(H5Dopen2(file, path(name).c_str(), H5P_DEFAULT), "open " + path(name));
    return h5::has_attr(ds, "unit") ? h5::attr_str(ds, "unit") : std::string();
  }
};

}  // namespace ncpath::scan_cli
