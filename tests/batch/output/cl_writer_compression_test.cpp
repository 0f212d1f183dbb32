// batch/output/chunk_appender: the writer shuffles and deflates chunks itself, in parallel,
// and writes them directly. Checked against HDF5's own filter pipeline (a second, independent
// implementation of shuffle and of the chunk layout): HDF5 decodes the chunks to the rows,
// and each stored chunk inflates to the bytes HDF5's shuffle makes of the same rows. The
// deflate strategy differs from HDF5's (faster), so the compressed bytes may differ.
#include <gtest/gtest.h>
#include <zlib.h>

#include <cstdint>
#include <vector>

#include "batch/output/cl_writer.hpp"
#include "engine/parallel.hpp"
#include "tests/batch/output/h5_read.hpp"

namespace ncpath::out {
namespace {

using test::Id;

// 200,003 rows of 3 doubles (a few chunks of 21,845 rows and a partial last one) that
// compress a little but not much: smooth coordinates with noise in the low bits.
std::vector<double> make_rows(std::size_t rows) {
  std::vector<double> v;
  std::uint64_t state = 7;
  for (std::size_t i = 0; i < 3 * rows; ++i) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    v.push_back(0.01 * static_cast<double>(i / 3) + static_cast<double>(state >> 44) * 1e-9);
  }
  return v;
}

void write_with_ncpath(const std::filesystem::path& path, const std::vector<double>& rows) {
  ClFile file(path, "0.1.0");
  ClJob job = file.begin_job("job", {"scan", "in.stl", "", "{}", "{}"});
  job.write_array("scan", "segment_start", std::span<const double>(rows), 3, "mm");
  job.append_paths(std::span<const double>(rows), std::vector<std::uint8_t>(rows.size() / 3, 3),
                   std::vector<std::uint32_t>{static_cast<std::uint32_t>(rows.size() / 3)},
                   std::vector<std::uint8_t>{0});
  job.set_status("ok", "");
  job.close();
  file.close();
}

// The same dataset written through HDF5's own filters: same shape, chunks, filters, fill.
void write_with_hdf5(const std::filesystem::path& path, const std::vector<double>& rows,
                     hsize_t chunk_rows) {
  Id file(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), "create");
  const hsize_t dims[2] = {rows.size() / 3, 3};
  const hsize_t max_dims[2] = {H5S_UNLIMITED, 3};
  const hsize_t chunk[2] = {chunk_rows, 3};
  Id space(H5Screate_simple(2, dims, max_dims));
  Id dcpl(H5Pcreate(H5P_DATASET_CREATE));
  H5Pset_chunk(dcpl, 2, chunk);
  H5Pset_shuffle(dcpl);
  H5Pset_deflate(dcpl, 1);
  const double zero = 0;
  H5Pset_fill_value(dcpl, H5T_NATIVE_DOUBLE, &zero);
  Id ds(H5Dcreate2(file, "d", H5T_IEEE_F64LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT), "dataset");
  ASSERT_GE(H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, rows.data()), 0);
}

// A zlib stream inflated (HDF5's deflate filter stores zlib streams).
std::vector<unsigned char> inflated(const std::vector<unsigned char>& packed, std::size_t bytes) {
  std::vector<unsigned char> out(bytes + 1);
  uLongf size = out.size();
  EXPECT_EQ(uncompress(out.data(), &size, packed.data(), packed.size()), Z_OK);
  out.resize(size);
  return out;
}

// The stored (filtered) bytes of every chunk of a [rows, cols] dataset.
std::vector<std::vector<unsigned char>> raw_chunks(hid_t file, const char* name) {
  Id ds(H5Dopen2(file, name, H5P_DEFAULT), name);
  const std::vector<hsize_t> dims = test::dims_of(ds);
  Id dcpl(H5Dget_create_plist(ds));
  hsize_t chunk[2] = {0, 0};
  H5Pget_chunk(dcpl, 2, chunk);
  std::vector<std::vector<unsigned char>> out;
  for (hsize_t row = 0; row < dims[0]; row += chunk[0]) {
    const hsize_t offset[2] = {row, 0};
    hsize_t bytes = 0;
    EXPECT_GE(H5Dget_chunk_storage_size(ds, offset, &bytes), 0);
    std::vector<unsigned char> buf(bytes);
    std::uint32_t mask = 1;
    EXPECT_GE(H5Dread_chunk(ds, H5P_DEFAULT, offset, &mask, buf.data()), 0);
    EXPECT_EQ(mask, 0u) << "every filter applied";
    out.push_back(std::move(buf));
  }
  return out;
}

hsize_t chunk_rows_of(hid_t file, const char* name) {
  Id ds(H5Dopen2(file, name, H5P_DEFAULT), name);
  Id dcpl(H5Dget_create_plist(ds));
  hsize_t chunk[2] = {0, 0};
  H5Pget_chunk(dcpl, 2, chunk);
  return chunk[0];
}

TEST(ClWriterCompression, ChunksInflateToTheBytesOfHdf5sOwnShuffle) {
  const std::vector<double> rows = make_rows(200003);
  const auto dir = test::out_dir("compression");
  write_with_ncpath(dir / "ncpath.h5", rows);
  Id ours = test::open_read(dir / "ncpath.h5");
  for (const char* name : {"/jobs/job/scan/segment_start", "/jobs/job/cl/points"}) {
    SCOPED_TRACE(name);
    const hsize_t chunk_rows = chunk_rows_of(ours, name);
    write_with_hdf5(dir / "hdf5.h5", rows, chunk_rows);
    Id theirs = test::open_read(dir / "hdf5.h5");
    const auto a = raw_chunks(ours, name);
    const auto b = raw_chunks(theirs, "/d");
    ASSERT_GE(a.size(), 3u);
    ASSERT_EQ(a.size(), b.size());
    const std::size_t chunk_bytes = chunk_rows * 3 * sizeof(double);
    for (std::size_t c = 0; c < a.size(); ++c) {
      const auto ours_raw = inflated(a[c], chunk_bytes);
      EXPECT_EQ(ours_raw.size(), chunk_bytes) << "chunk " << c << " is a whole chunk";
      EXPECT_EQ(ours_raw, inflated(b[c], chunk_bytes)) << "chunk " << c;
    }
    // And HDF5 decodes them back to the rows (the partial last chunk included).
    EXPECT_EQ(test::read_all<double>(ours, name, H5T_NATIVE_DOUBLE), rows);
  }
}

TEST(ClWriterCompression, SameBytesOnOneThreadAndOnAll) {
  const std::vector<double> rows = make_rows(300000);
  const auto dir = test::out_dir("compression_threads");
  {
    const par::ThreadLimit one(1);
    write_with_ncpath(dir / "one.h5", rows);
  }
  write_with_ncpath(dir / "all.h5", rows);
  EXPECT_TRUE(test::same_bytes(dir / "one.h5", dir / "all.h5"));
}

// A streamed array holds the rows appended, in order, whatever the split; misuse is refused.
TEST(ClWriterCompression, StreamedArrayHoldsTheRowsWhateverTheSplit) {
  const std::vector<double> rows = make_rows(100001);
  const auto dir = test::out_dir("streamed");
  std::vector<std::int64_t> ids;
  {
    ClFile file(dir / "streamed.h5", "0.1.0");
    ClJob job = file.begin_job("job", {"scan", "in.stl", "", "{}", "{}"});
    const ClJob::ArrayId a = job.begin_array("scan", "start", ClJob::ArrayType::kFloat64, 3, "mm");
    const ClJob::ArrayId b = job.begin_array("scan", "ids", ClJob::ArrayType::kInt64, 0);
    std::size_t at = 0;
    for (std::size_t step = 1; at < rows.size() / 3; step = step * 7 % 40000 + 1) {
      const std::size_t n = std::min(step, rows.size() / 3 - at);
      job.append_rows(a, std::span<const double>(rows).subspan(3 * at, 3 * n));
      const std::vector<std::int64_t> more(n, static_cast<std::int64_t>(at));
      job.append_rows(b, std::span<const std::int64_t>(more));
      ids.insert(ids.end(), more.begin(), more.end());
      at += n;
    }
    EXPECT_THROW(job.append_rows(a, std::span<const double>(rows).subspan(0, 2)),
                 std::invalid_argument);  // not whole rows
    EXPECT_THROW(job.append_rows(b, std::span<const double>(rows).subspan(0, 1)),
                 std::invalid_argument);  // another type
    EXPECT_THROW(job.append_rows(7, std::span<const double>(rows).subspan(0, 3)),
                 std::invalid_argument);  // no such array
    EXPECT_THROW(job.begin_array("scan", "ids", ClJob::ArrayType::kInt64, 0),
                 std::invalid_argument);
    job.set_status("ok", "");
    job.close();
    file.close();
  }
  Id f = test::open_read(dir / "streamed.h5");
  EXPECT_EQ(test::read_all<double>(f, "/jobs/job/scan/start", H5T_NATIVE_DOUBLE), rows);
  EXPECT_EQ(test::read_all<std::int64_t>(f, "/jobs/job/scan/ids", H5T_NATIVE_INT64), ids);
}

}  // namespace
}  // namespace ncpath::out
