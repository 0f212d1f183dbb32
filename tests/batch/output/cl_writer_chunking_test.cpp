// batch/output/cl_writer: the data and the file bytes do not depend on how the paths were
// split across append_paths calls, nor on when the file was written.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <thread>
#include <vector>

#include "batch/output/cl_writer.hpp"
#include "tests/batch/output/h5_read.hpp"

namespace ncpath::out {
namespace {

using test::Id;
using test::read_all;

// 70,000 paths of 0..5 points (about 175,000 points): more than one chunk of every dataset
// (points 32768 rows, contact 65536, offsets 8192, path_kind 65536).
struct Paths {
  std::vector<double> xyz;
  std::vector<std::uint8_t> contact;
  std::vector<std::uint32_t> sizes;
  std::vector<std::uint8_t> kinds;
  std::vector<std::size_t> starts;  // first point of each path
};

Paths make_paths(std::size_t n_paths) {
  Paths p;
  std::uint64_t state = 12345;
  auto next = [&state] {  // LCG, fixed seed: the same data on every run
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<std::uint32_t>(state >> 33);
  };
  std::size_t n = 0;
  for (std::size_t k = 0; k < n_paths; ++k) {
    const std::uint32_t size = next() % 6;
    p.starts.push_back(n);
    p.sizes.push_back(size);
    p.kinds.push_back(static_cast<std::uint8_t>(next() % 3));
    for (std::uint32_t i = 0; i < size; ++i, ++n) {
      p.xyz.push_back(0.001 * static_cast<double>(n));
      p.xyz.push_back(-0.5 * static_cast<double>(k));
      p.xyz.push_back(static_cast<double>(next() % 100000) * 1e-3);
      p.contact.push_back(static_cast<std::uint8_t>(next() % 4));
    }
  }
  return p;
}

// Writes paths [first, last) in one call.
void append_range(ClJob& job, const Paths& p, std::size_t first, std::size_t last) {
  const std::size_t a = first < p.starts.size() ? p.starts[first] : p.contact.size();
  const std::size_t b = last < p.starts.size() ? p.starts[last] : p.contact.size();
  job.append_paths(std::span(p.xyz).subspan(3 * a, 3 * (b - a)),
                   std::span(p.contact).subspan(a, b - a),
                   std::span(p.sizes).subspan(first, last - first),
                   std::span(p.kinds).subspan(first, last - first));
}

// Writes one job with the paths split at `cuts` (path indices, increasing).
void write_split(const std::filesystem::path& path, const Paths& p,
                 const std::vector<std::size_t>& cuts) {
  ClFile file(path, "0.1.0");
  ClJob job = file.begin_job("job", {"drop_raster", "in.stl", "", "{}", "{}"});
  std::size_t first = 0;
  for (const std::size_t cut : cuts) {
    append_range(job, p, first, cut);
    first = cut;
  }
  append_range(job, p, first, p.sizes.size());
  job.set_status("ok", "");
  job.write_stats(std::vector<StatValue>{{"points", job.points_written(), ""}});
  job.close();
  file.close();
}

TEST(ClWriterChunking, SameDataWhateverTheCallSplit) {
  const Paths p = make_paths(70000);
  const auto dir = test::out_dir("chunking");
  const auto one_call = dir / "one_call.h5";
  const auto random_calls = dir / "random_calls.h5";
  const auto per_path = dir / "per_path.h5";

  write_split(one_call, p, {});
  std::vector<std::size_t> cuts;  // random splits, some empty calls (repeated cuts)
  std::uint64_t s = 99;
  for (std::size_t at = 0; at < p.sizes.size();) {
    s = s * 6364136223846793005ULL + 1442695040888963407ULL;
    at += (s >> 40) % 3000;
    if (at < p.sizes.size()) cuts.push_back(at);
  }
  ASSERT_GT(cuts.size(), 20u);
  write_split(random_calls, p, cuts);
  std::vector<std::size_t> every_path(p.sizes.size() - 1);
  for (std::size_t k = 0; k < every_path.size(); ++k) every_path[k] = k + 1;
  write_split(per_path, p, every_path);

  // The expected offsets, from the sizes.
  std::vector<std::int64_t> offsets = {0};
  for (const std::uint32_t size : p.sizes) offsets.push_back(offsets.back() + size);

  for (const auto& path : {one_call, random_calls, per_path}) {
    SCOPED_TRACE(path.string());
    Id f = test::open_read(path);
    EXPECT_EQ(read_all<double>(f, "/jobs/job/cl/points", H5T_NATIVE_DOUBLE), p.xyz);
    EXPECT_EQ(read_all<std::uint8_t>(f, "/jobs/job/cl/contact_kind", H5T_NATIVE_UINT8), p.contact);
    EXPECT_EQ(read_all<std::int64_t>(f, "/jobs/job/cl/path_offsets", H5T_NATIVE_INT64), offsets);
    EXPECT_EQ(read_all<std::uint8_t>(f, "/jobs/job/cl/path_kind", H5T_NATIVE_UINT8), p.kinds);
    EXPECT_EQ(read_all<std::int64_t>(f, "/jobs/job/stats/points", H5T_NATIVE_INT64),
              std::vector<std::int64_t>{static_cast<std::int64_t>(p.contact.size())});
  }
  // Stronger than the contract: every chunk is written once, whole, so even the files match.
  EXPECT_TRUE(test::same_bytes(one_call, random_calls));
  EXPECT_TRUE(test::same_bytes(one_call, per_path));
}

TEST(ClWriterChunking, SameDataSameBytesAtAnotherTime) {
  const Paths p = make_paths(500);
  const auto dir = test::out_dir("determinism");
  write_split(dir / "first.h5", p, {100, 200});
  // HDF5 timestamps have a resolution of one second: make sure the clock moved on.
  std::this_thread::sleep_for(std::chrono::milliseconds(1100));
  write_split(dir / "second.h5", p, {100, 200});
  EXPECT_TRUE(test::same_bytes(dir / "first.h5", dir / "second.h5"));
}

}  // namespace
}  // namespace ncpath::out
