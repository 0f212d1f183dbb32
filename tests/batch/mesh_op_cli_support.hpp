#pragma once
// Test helpers of the zlevel and pencil command tests: a plate with a box pocket (analytic
// z-level contours), and the zlevel/ and pencil/ datasets of a job read back with the HDF5 C
// API. The V-groove, the OFF writer and the statistics reader are the scan tests'.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "tests/batch/output/h5_read.hpp"
#include "tests/batch/scan_cli_support.hpp"

namespace ncpath::mesh_op_cli {

namespace h5 = out::test;
using scan_cli::OffMesh;
using scan_cli::Row;

// A 20 x 20 plate [-10, 10]^2, top z = 3, with a 10 x 10 pocket [-5, 5]^2 down to a floor at
// z = 0, vertical walls; an open surface (no sides or bottom). Vertices: 0..3 the plate's
// corners (-10,-10), (10,-10), (10,10), (-10,10); 4..7 the pocket's rim corners (-5,-5),
// (5,-5), (5,5), (-5,5); 8..11 the floor corners below them. Facets: 0..7 the top, 8, 9 the
// floor, 10..17 the walls.
inline OffMesh plate_pocket() {
  OffMesh m;
  const double o = 10, i = 5, top = 3;
  m.v = {{-o, -o, top}, {o, -o, top}, {o, o, top}, {-o, o, top}, {-i, -i, top}, {i, -i, top},
         {i, i, top},   {-i, i, top}, {-i, -i, 0}, {i, -i, 0},   {i, i, 0},     {-i, i, 0}};
  m.f = {{0, 1, 5},  {0, 5, 4},  {1, 2, 6},  {1, 6, 5},   {2, 3, 7}, {2, 7, 6},
         {3, 0, 4},  {3, 4, 7},  {8, 9, 10}, {8, 10, 11}, {4, 5, 9}, {4, 9, 8},
         {5, 6, 10}, {5, 10, 9}, {6, 7, 11}, {6, 11, 10}, {7, 4, 8}, {7, 8, 11}};
  return m;
}

inline std::vector<double> f64(hid_t f, const std::string& path) {
  return h5::read_all<double>(f, path, H5T_NATIVE_DOUBLE);
}
inline std::vector<std::int64_t> i64(hid_t f, const std::string& path) {
  return h5::read_all<std::int64_t>(f, path, H5T_NATIVE_INT64);
}
inline std::vector<std::uint8_t> u8(hid_t f, const std::string& path) {
  return h5::read_all<std::uint8_t>(f, path, H5T_NATIVE_UINT8);
}

inline Row row(const std::vector<double>& v, std::size_t i) {
  return {v[3 * i], v[3 * i + 1], v[3 * i + 2]};
}

// cl/ of one job.
struct ClOut {
  std::vector<double> pts;
  std::vector<std::int64_t> off;
  std::vector<std::uint8_t> kind, contact;
  std::vector<std::size_t> cut_paths;  // cut_paths[k]: index in cl/ of the k-th cut path
  Row point(std::size_t i) const { return row(pts, i); }
};

inline ClOut read_cl(hid_t f, const std::string& job) {
  const std::string g = "/jobs/" + job + "/cl/";
  ClOut c;
  c.pts = f64(f, g + "points");
  c.off = i64(f, g + "path_offsets");
  c.kind = u8(f, g + "path_kind");
  c.contact = u8(f, g + "contact_kind");
  for (std::size_t p = 0; p < c.kind.size(); ++p)
    if (c.kind[p] == 0) c.cut_paths.push_back(p);
  return c;
}

// The zlevel/ datasets of one job.
struct ZLevelOut {
  std::vector<std::int64_t> seg_path, seg_element, jun_path, jun_element1, jun_element2;
  std::vector<std::uint8_t> seg_kind, seg_shadow, jun_kind, contour_hole;
  std::vector<double> seg_start, seg_end, seg_geometry, jun_position, jun_b1, jun_b2, jun_angle;
  std::vector<double> contour_level;

  std::array<double, 7> geometry(std::size_t i) const {
    std::array<double, 7> g;
    for (int c = 0; c < 7; ++c) g[c] = seg_geometry[7 * i + c];
    return g;
  }
};

inline ZLevelOut read_zlevel(hid_t f, const std::string& job) {
  const std::string g = "/jobs/" + job + "/zlevel/";
  ZLevelOut z;
  z.seg_path = i64(f, g + "segment_path");
  z.seg_kind = u8(f, g + "segment_kind");
  z.seg_shadow = u8(f, g + "segment_shadow");
  z.seg_element = i64(f, g + "segment_element");
  z.seg_start = f64(f, g + "segment_start");
  z.seg_end = f64(f, g + "segment_end");
  z.seg_geometry = f64(f, g + "segment_geometry");
  z.jun_path = i64(f, g + "junction_path");
  z.jun_kind = u8(f, g + "junction_kind");
  z.jun_position = f64(f, g + "junction_position");
  z.jun_b1 = f64(f, g + "junction_b1");
  z.jun_b2 = f64(f, g + "junction_b2");
  z.jun_element1 = i64(f, g + "junction_element1");
  z.jun_element2 = i64(f, g + "junction_element2");
  z.jun_angle = f64(f, g + "junction_angle");
  z.contour_level = f64(f, g + "contour_level");
  z.contour_hole = u8(f, g + "contour_hole");
  return z;
}

// Point of an arc segment at parameter t from its geometry row, as docs/hdf5-schema.md
// describes it: centre + r1 cos t axis + r2 sin t perp(axis), axis at angle g4 from +x.
inline std::array<double, 2> arc_point(const std::array<double, 7>& g, double t) {
  const double ax = std::cos(g[4]), ay = std::sin(g[4]);  // perp(axis) = (-ay, ax)
  return {g[0] + g[2] * std::cos(t) * ax - g[3] * std::sin(t) * ay,
          g[1] + g[2] * std::cos(t) * ay + g[3] * std::sin(t) * ax};
}

// The pencil/ datasets of one job.
struct PencilOut {
  std::vector<double> position, b1, b2, angle;
  std::vector<std::uint8_t> family, kept;
};

inline PencilOut read_pencil(hid_t f, const std::string& job) {
  const std::string g = "/jobs/" + job + "/pencil/";
  PencilOut p;
  p.position = f64(f, g + "point_position");
  p.b1 = f64(f, g + "point_b1");
  p.b2 = f64(f, g + "point_b2");
  p.angle = f64(f, g + "point_angle");
  p.family = u8(f, g + "point_family");
  p.kept = u8(f, g + "point_kept");
  return p;
}

// Shape, unit and description of dataset `name` of a job's group.
inline void expect_dataset(hid_t f, const std::string& path, std::vector<hsize_t> shape,
                           const std::string& unit) {
  EXPECT_EQ(scan_cli::dims(f, path), shape) << path;
  h5::Id ds(H5Dopen2(f, path.c_str(), H5P_DEFAULT), path);
  EXPECT_TRUE(h5::has_attr(ds, "description")) << path;
  EXPECT_EQ(h5::has_attr(ds, "unit") ? h5::attr_str(ds, "unit") : "", unit) << path;
}

}  // namespace ncpath::mesh_op_cli
