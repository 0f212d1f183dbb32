// batch/output/cl_writer: layout, values and attributes read back with the plain HDF5 C API;
// error paths. Chunking invariance and byte determinism are in cl_writer_chunking_test.cpp.
#include "batch/output/cl_writer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "tests/batch/output/h5_read.hpp"

namespace ncpath::out {
namespace {

using test::attr_i64;
using test::attr_str;
using test::dims_of;
using test::Id;
using test::read_all;

JobInfo info_for(const std::string& op) {
  return {op, "parts/" + op + ".stl", std::string(64, 'a'), R"({"type":"ball","r":3})",
          R"({"step":0.5})"};
}

// Three paths (cut, link, rapid) of 2, 3 and 1 points.
const std::vector<double> kXyz = {0, 0, 1, 1, 0, 1, 1, 1, 2, 2, 1, 2, 2, 2, 2, 5, 5, 20};
const std::vector<std::uint8_t> kContact = {1, 2, 3, 3, 0, 0};
const std::vector<std::uint32_t> kSizes = {2, 3, 1};
const std::vector<std::uint8_t> kKinds = {0, 1, 2};

// Writes the two-job file used by the read-back tests.
void write_two_jobs(const std::filesystem::path& path) {
  ClFile file(path, "9.9.9-test");
  {
    ClJob job = file.begin_job("raster_a", info_for("drop_raster"));
    // Two calls: paths {0, 1} then {2}.
    job.append_paths(std::span(kXyz).first(15), std::span(kContact).first(5),
                     std::span(kSizes).first(2), std::span(kKinds).first(2));
    job.append_paths(std::span(kXyz).subspan(15), std::span(kContact).subspan(5),
                     std::span(kSizes).subspan(2), std::span(kKinds).subspan(2));
    EXPECT_EQ(job.points_written(), 6);
    EXPECT_EQ(job.paths_written(), 3);
    job.set_status("ok", "");
    const std::vector<StatValue> stats = {{"facets_read", std::int64_t{1234}, ""},
                                          {"compute_s", 0.25, "s"},
                                          {"cutter", std::string("ball"), ""}};
    job.write_stats(stats);
    job.close();
  }
  {
    ClJob job = file.begin_job("drop_b", info_for("drop_points"));
    job.set_status("invalid_input", "mesh has no facets");
  }  // closed by the destructor
  file.close();
}

TEST(ClWriter, TwoJobsReadBack) {
  const auto path = test::out_dir("two_jobs") / "two_jobs.h5";
  write_two_jobs(path);
  Id f = test::open_read(path);

  // File attributes: UTF-8 variable-length strings (h5py shows str) and an int64.
  const test::StringInfo format = test::read_string_attr(f, "format");
  EXPECT_EQ(format.value, "ncpath-cl");
  EXPECT_TRUE(format.variable);
  EXPECT_EQ(format.cset, H5T_CSET_UTF8);
  EXPECT_EQ(attr_i64(f, "format_version"), 1);
  EXPECT_EQ(attr_str(f, "ncpath_version"), "9.9.9-test");

  // Jobs are listed in creation order.
  Id jobs(H5Gopen2(f, "/jobs", H5P_DEFAULT));
  H5G_info_t ginfo;
  ASSERT_GE(H5Gget_info(jobs, &ginfo), 0);
  ASSERT_EQ(ginfo.nlinks, 2u);
  char name[64];
  H5Lget_name_by_idx(jobs, ".", H5_INDEX_CRT_ORDER, H5_ITER_INC, 0, name, sizeof name, H5P_DEFAULT);
  EXPECT_STREQ(name, "raster_a");
  H5Lget_name_by_idx(jobs, ".", H5_INDEX_CRT_ORDER, H5_ITER_INC, 1, name, sizeof name, H5P_DEFAULT);
  EXPECT_STREQ(name, "drop_b");

  // Job A: attributes.
  Id a(H5Gopen2(f, "/jobs/raster_a", H5P_DEFAULT));
  EXPECT_EQ(attr_str(a, "operation"), "drop_raster");
  EXPECT_EQ(attr_str(a, "status"), "ok");
  EXPECT_EQ(attr_str(a, "message"), "");
  EXPECT_EQ(attr_str(a, "input_path"), "parts/drop_raster.stl");
  EXPECT_EQ(attr_str(a, "input_sha256"), std::string(64, 'a'));
  EXPECT_EQ(attr_str(a, "tool"), R"({"type":"ball","r":3})");
  EXPECT_EQ(attr_str(a, "params"), R"({"step":0.5})");

  // points: float64 [6, 3], unlimited rows, chunked, shuffle + deflate.
  {
    Id ds(H5Dopen2(f, "/jobs/raster_a/cl/points", H5P_DEFAULT));
    Id type(H5Dget_type(ds));
    EXPECT_EQ(H5Tget_class(type), H5T_FLOAT);
    EXPECT_EQ(H5Tget_size(type), 8u);
    EXPECT_EQ(H5Tget_order(type), H5T_ORDER_LE);
    std::vector<hsize_t> max_dims;
    EXPECT_EQ(dims_of(ds, &max_dims), (std::vector<hsize_t>{6, 3}));
    EXPECT_EQ(max_dims, (std::vector<hsize_t>{H5S_UNLIMITED, 3}));
    EXPECT_EQ(attr_str(ds, "units"), "mm");
    EXPECT_EQ(attr_str(ds, "columns"), "x,y,z");
    Id dcpl(H5Dget_create_plist(ds));
    ASSERT_EQ(H5Pget_layout(dcpl), H5D_CHUNKED);
    hsize_t chunk[2] = {0, 0};
    ASSERT_EQ(H5Pget_chunk(dcpl, 2, chunk), 2);
    EXPECT_EQ(chunk[0], 32768u);
    EXPECT_EQ(chunk[1], 3u);
    ASSERT_EQ(H5Pget_nfilters(dcpl), 2);
    unsigned flags = 0, level = 0;
    size_t nvals = 1;
    EXPECT_EQ(H5Pget_filter2(dcpl, 0, &flags, &nvals, &level, 0, nullptr, nullptr),
              H5Z_FILTER_SHUFFLE);
    nvals = 1;
    EXPECT_EQ(H5Pget_filter2(dcpl, 1, &flags, &nvals, &level, 0, nullptr, nullptr),
              H5Z_FILTER_DEFLATE);
    EXPECT_EQ(level, 1u);
  }
  EXPECT_EQ(read_all<double>(f, "/jobs/raster_a/cl/points", H5T_NATIVE_DOUBLE), kXyz);

  // path_offsets: int64 [P + 1] starting at 0.
  {
    Id ds(H5Dopen2(f, "/jobs/raster_a/cl/path_offsets", H5P_DEFAULT));
    Id type(H5Dget_type(ds));
    EXPECT_EQ(H5Tget_class(type), H5T_INTEGER);
    EXPECT_EQ(H5Tget_size(type), 8u);
    EXPECT_EQ(H5Tget_sign(type), H5T_SGN_2);
  }
  EXPECT_EQ(read_all<std::int64_t>(f, "/jobs/raster_a/cl/path_offsets", H5T_NATIVE_INT64),
            (std::vector<std::int64_t>{0, 2, 5, 6}));

  // path_kind and contact_kind: uint8 with their enum attributes.
  for (const char* p : {"/jobs/raster_a/cl/path_kind", "/jobs/raster_a/cl/contact_kind"}) {
    Id ds(H5Dopen2(f, p, H5P_DEFAULT));
    Id type(H5Dget_type(ds));
    EXPECT_EQ(H5Tget_class(type), H5T_INTEGER) << p;
    EXPECT_EQ(H5Tget_size(type), 1u) << p;
    EXPECT_EQ(H5Tget_sign(type), H5T_SGN_NONE) << p;
  }
  {
    Id ds(H5Dopen2(f, "/jobs/raster_a/cl/path_kind", H5P_DEFAULT));
    EXPECT_EQ(attr_str(ds, "enum"), "0=cut,1=link_at_depth,2=rapid");
    Id dc(H5Dopen2(f, "/jobs/raster_a/cl/contact_kind", H5P_DEFAULT));
    EXPECT_EQ(attr_str(dc, "enum"), "0=none,1=vertex,2=edge,3=facet");
  }
  EXPECT_EQ(read_all<std::uint8_t>(f, "/jobs/raster_a/cl/path_kind", H5T_NATIVE_UINT8), kKinds);
  EXPECT_EQ(read_all<std::uint8_t>(f, "/jobs/raster_a/cl/contact_kind", H5T_NATIVE_UINT8),
            kContact);

  // Stats: one scalar dataset each, with its own type; `unit` only when given.
  {
    Id ds(H5Dopen2(f, "/jobs/raster_a/stats/facets_read", H5P_DEFAULT));
    Id type(H5Dget_type(ds));
    EXPECT_EQ(H5Tget_class(type), H5T_INTEGER);
    EXPECT_EQ(H5Tget_size(type), 8u);
    EXPECT_EQ(H5Tget_sign(type), H5T_SGN_2);
    EXPECT_TRUE(dims_of(ds).empty());  // scalar
    EXPECT_FALSE(test::has_attr(ds, "unit"));
    EXPECT_EQ(read_all<std::int64_t>(f, "/jobs/raster_a/stats/facets_read", H5T_NATIVE_INT64),
              std::vector<std::int64_t>{1234});
  }
  {
    Id ds(H5Dopen2(f, "/jobs/raster_a/stats/compute_s", H5P_DEFAULT));
    Id type(H5Dget_type(ds));
    EXPECT_EQ(H5Tget_class(type), H5T_FLOAT);
    EXPECT_EQ(attr_str(ds, "unit"), "s");
    EXPECT_EQ(read_all<double>(f, "/jobs/raster_a/stats/compute_s", H5T_NATIVE_DOUBLE),
              std::vector<double>{0.25});
  }
  {
    Id ds(H5Dopen2(f, "/jobs/raster_a/stats/cutter", H5P_DEFAULT));
    Id type(H5Dget_type(ds));
    ASSERT_EQ(H5Tget_class(type), H5T_STRING);
    EXPECT_GT(H5Tis_variable_str(type), 0);
    char* value = nullptr;
    ASSERT_GE(H5Dread(ds, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, &value), 0);
    EXPECT_STREQ(value, "ball");
    H5free_memory(value);
  }

  // Job B: no paths, so empty datasets and offsets == {0}; its own status.
  Id b(H5Gopen2(f, "/jobs/drop_b", H5P_DEFAULT));
  EXPECT_EQ(attr_str(b, "operation"), "drop_points");
  EXPECT_EQ(attr_str(b, "status"), "invalid_input");
  EXPECT_EQ(attr_str(b, "message"), "mesh has no facets");
  {
    Id ds(H5Dopen2(f, "/jobs/drop_b/cl/points", H5P_DEFAULT));
    EXPECT_EQ(dims_of(ds), (std::vector<hsize_t>{0, 3}));
  }
  EXPECT_EQ(read_all<std::int64_t>(f, "/jobs/drop_b/cl/path_offsets", H5T_NATIVE_INT64),
            std::vector<std::int64_t>{0});
  EXPECT_TRUE(read_all<std::uint8_t>(f, "/jobs/drop_b/cl/path_kind", H5T_NATIVE_UINT8).empty());
  Id stats_b(H5Gopen2(f, "/jobs/drop_b/stats", H5P_DEFAULT));
  ASSERT_GE(H5Gget_info(stats_b, &ginfo), 0);
  EXPECT_EQ(ginfo.nlinks, 0u);
}

TEST(ClWriter, StatusDefaultsToInternalErrorWhenNotSet) {
  const auto path = test::out_dir("status_default") / "status_default.h5";
  {
    ClFile file(path, "0");
    ClJob job = file.begin_job("crashed", info_for("drop_raster"));
    job.append_paths(kXyz, kContact, kSizes, kKinds);
  }  // job closed by its destructor without set_status
  Id f = test::open_read(path);
  Id g(H5Gopen2(f, "/jobs/crashed", H5P_DEFAULT));
  EXPECT_EQ(attr_str(g, "status"), "internal_error");
  EXPECT_EQ(attr_str(g, "message"), "job did not finish");
  // The buffered paths were still written at close.
  EXPECT_EQ(read_all<double>(f, "/jobs/crashed/cl/points", H5T_NATIVE_DOUBLE), kXyz);
}

TEST(ClWriter, FileClosedBeforeJobClosesTheJob) {
  const auto path = test::out_dir("file_first") / "file_first.h5";
  ClJob job = [&] {
    ClFile file(path, "0");
    ClJob j = file.begin_job("orphan", info_for("drop_raster"));
    j.append_paths(kXyz, kContact, kSizes, kKinds);
    return j;
  }();  // the ClFile is gone; the job must have been finalised with it
  EXPECT_THROW(job.append_paths(kXyz, kContact, kSizes, kKinds), std::logic_error);
  EXPECT_NO_THROW(job.close());
  Id f = test::open_read(path);
  EXPECT_EQ(read_all<std::int64_t>(f, "/jobs/orphan/cl/path_offsets", H5T_NATIVE_INT64),
            (std::vector<std::int64_t>{0, 2, 5, 6}));
  Id g(H5Gopen2(f, "/jobs/orphan", H5P_DEFAULT));
  EXPECT_EQ(attr_str(g, "status"), "internal_error");
}

TEST(ClWriter, DuplicateJobNameThrowsAndFileStaysUsable) {
  const auto path = test::out_dir("duplicate") / "duplicate.h5";
  ClFile file(path, "0");
  file.begin_job("a", info_for("x")).set_status("ok", "");
  EXPECT_THROW(file.begin_job("a", info_for("y")), std::invalid_argument);
  EXPECT_NO_THROW(file.begin_job("b", info_for("y")).close());
  file.close();
  Id f = test::open_read(path);
  Id a(H5Gopen2(f, "/jobs/a", H5P_DEFAULT));
  EXPECT_EQ(attr_str(a, "operation"), "x");  // the first job was not touched
  EXPECT_EQ(attr_str(a, "status"), "ok");
}

TEST(ClWriter, OnlyOneOpenJobAndValidNames) {
  const auto path = test::out_dir("one_open") / "one_open.h5";
  ClFile file(path, "0");
  ClJob a = file.begin_job("a", info_for("x"));
  EXPECT_THROW(file.begin_job("b", info_for("x")), std::logic_error);
  a.close();
  EXPECT_THROW(a.set_status("ok", ""), std::logic_error);  // closed
  for (const char* bad : {"", ".", "..", "a/b"}) {
    EXPECT_THROW(file.begin_job(bad, info_for("x")), std::invalid_argument) << bad;
  }
  ClJob moved_from = file.begin_job("c", info_for("x"));
  ClJob c = std::move(moved_from);
  EXPECT_THROW(moved_from.set_status("ok", ""), std::logic_error);  // NOLINT: use after move
  EXPECT_THROW(c.set_status("OK", ""), std::invalid_argument);      // not a status code
  EXPECT_NO_THROW(c.set_status("cancelled", "stopped by the user"));
}

TEST(ClWriter, UnwritablePathThrowsNamingThePath) {
  const auto dir = test::out_dir("unwritable");
  const auto plain_file = dir / "plain_file";
  std::ofstream(plain_file) << "not a directory";
  // A path below a regular file cannot be created, even by root.
  for (const auto& bad : {plain_file / "out.h5", dir / "no_such_dir" / "out.h5"}) {
    try {
      ClFile file(bad, "0");
      ADD_FAILURE() << "no exception for " << bad;
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(bad.string()), std::string::npos) << e.what();
    }
  }
}

TEST(ClWriter, BadAppendArgumentsThrowAndWriteNothing) {
  const auto path = test::out_dir("bad_args") / "bad_args.h5";
  {
    ClFile file(path, "0");
    ClJob job = file.begin_job("j", info_for("x"));
    const std::vector<std::uint32_t> wrong_sum = {2, 3, 2};
    const std::vector<std::uint8_t> bad_kind = {0, 1, 3};
    const std::vector<std::uint8_t> bad_contact = {1, 2, 3, 4, 0, 0};
    std::vector<double> nan_xyz = kXyz;
    nan_xyz[7] = std::nan("");
    EXPECT_THROW(job.append_paths(std::span(kXyz).first(17), kContact, kSizes, kKinds),
                 std::invalid_argument);
    EXPECT_THROW(job.append_paths(kXyz, kContact, wrong_sum, kKinds), std::invalid_argument);
    EXPECT_THROW(job.append_paths(kXyz, kContact, kSizes, std::span(kKinds).first(2)),
                 std::invalid_argument);
    EXPECT_THROW(job.append_paths(kXyz, kContact, kSizes, bad_kind), std::invalid_argument);
    EXPECT_THROW(job.append_paths(kXyz, bad_contact, kSizes, kKinds), std::invalid_argument);
    EXPECT_THROW(job.append_paths(nan_xyz, kContact, kSizes, kKinds), std::invalid_argument);
    EXPECT_EQ(job.points_written(), 0);
    EXPECT_EQ(job.paths_written(), 0);

    // A failing write_stats call writes none of its stats.
    const std::vector<StatValue> dup = {{"threads", std::int64_t{8}, ""},
                                        {"threads", std::int64_t{8}, ""}};
    EXPECT_THROW(job.write_stats(dup), std::invalid_argument);
    job.write_stats(std::span(dup).first(1));
    EXPECT_THROW(job.write_stats(std::span(dup).first(1)), std::invalid_argument);
  }
  Id f = test::open_read(path);
  EXPECT_EQ(read_all<std::int64_t>(f, "/jobs/j/cl/path_offsets", H5T_NATIVE_INT64),
            std::vector<std::int64_t>{0});
  EXPECT_TRUE(read_all<double>(f, "/jobs/j/cl/points", H5T_NATIVE_DOUBLE).empty());
  EXPECT_EQ(read_all<std::int64_t>(f, "/jobs/j/stats/threads", H5T_NATIVE_INT64),
            std::vector<std::int64_t>{8});
}

}  // namespace
}  // namespace ncpath::out
