// The batch's file in batch order whatever order jobs end in (batch/jobs/ordered_output.hpp):
// jobs begun and finished out of order land in order, each with exactly what it wrote,
// copied from its spool file, which is removed; the first job in order writes straight in.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "batch/jobs/ordered_output.hpp"
#include "tests/batch/output/h5_read.hpp"

namespace ncpath::jobs {
namespace {

namespace h5 = out::test;

// Job k's paths: k + 1 points on one path, x = 100 k + i; a statistic and a streamed table.
void write_job(out::ClJob& cl, int k) {
  std::vector<double> xyz;
  for (int i = 0; i <= k; ++i) xyz.insert(xyz.end(), {100.0 * k + i, 1.0, 2.0});
  const std::vector<std::uint8_t> contact(k + 1, out::kContactFacet);
  cl.append_paths(xyz, contact, std::vector<std::uint32_t>{std::uint32_t(k + 1)},
                  std::vector<std::uint8_t>{0});
  const auto id = cl.begin_array("extra", "rows", out::ClJob::ArrayType::kInt64, 2);
  const std::vector<std::int64_t> rows = {k, -k, 2 * k, 7};
  cl.append_rows(id, rows);
  cl.set_status("ok", "job " + std::to_string(k));
  const std::vector<out::StatValue> stats = {{"zeta", std::int64_t{k}, ""},
                                             {"alpha", 0.5 * k, "mm"}};
  cl.write_stats(stats);
}

std::vector<std::string> job_names(hid_t f) {
  std::vector<std::string> names;
  h5::Id jobs(H5Gopen2(f, "jobs", H5P_DEFAULT));
  hsize_t idx = 0;
  H5Literate(
      jobs, H5_INDEX_CRT_ORDER, H5_ITER_INC, &idx,
      [](hid_t, const char* name, const H5L_info_t*, void* data) {
        static_cast<std::vector<std::string>*>(data)->push_back(name);
        return 0;
      },
      &names);
  return names;
}

TEST(OrderedOutput, JobsEndingOutOfOrderLandInBatchOrder) {
  const auto dir = h5::out_dir("OrderedOutput_Order");
  {
    out::ClFile file(dir / "all.h5", "test");
    OrderedOutput output(file, 4);
    out::ClJob j1 = output.begin(1, "one", {});
    out::ClJob j0 = output.begin(0, "zero", {});  // first in order: straight into the file
    out::ClJob j2 = output.begin(2, "two", {});
    EXPECT_TRUE(std::filesystem::exists(output.spool_path(1)));
    EXPECT_FALSE(std::filesystem::exists(output.spool_path(0)));
    write_job(j2, 2);
    j2.close();
    output.finished(2);
    write_job(j1, 1);
    j1.close();
    output.finished(1);
    EXPECT_TRUE(std::filesystem::exists(output.spool_path(1)));  // waits for job 0
    write_job(j0, 0);
    j0.close();
    output.finished(0);
    EXPECT_FALSE(std::filesystem::exists(output.spool_path(1)));
    EXPECT_FALSE(std::filesystem::exists(output.spool_path(2)));
    out::ClJob j3 = output.begin(3, "three", {});  // every earlier job is in: straight in
    EXPECT_FALSE(std::filesystem::exists(output.spool_path(3)));
    write_job(j3, 3);
    j3.close();
    output.finished(3);
    EXPECT_EQ(output.spooled(), 2u);
    file.close();
  }
  // The same jobs written one after another, straight into a file of their own.
  {
    out::ClFile file(dir / "seq.h5", "test");
    const char* names[] = {"zero", "one", "two", "three"};
    for (int k = 0; k < 4; ++k) {
      out::ClJob cl = file.begin_job(names[k], {});
      write_job(cl, k);
    }
    file.close();
  }
  h5::Id f = h5::open_read(dir / "all.h5");
  EXPECT_EQ(job_names(f), (std::vector<std::string>{"zero", "one", "two", "three"}));
  EXPECT_TRUE(h5::same_content(dir / "all.h5", dir / "seq.h5", [](const std::string&) {
    return false;
  }));
  EXPECT_EQ(h5::read_all<double>(f, "/jobs/two/cl/points", H5T_NATIVE_DOUBLE),
            (std::vector<double>{200, 1, 2, 201, 1, 2, 202, 1, 2}));
}

TEST(OrderedOutput, CopyingRefusesWhatItCannotDo) {
  const auto dir = h5::out_dir("OrderedOutput_Copy");
  {
    out::ClFile spool(dir / "spool.h5", "test");
    out::ClJob cl = spool.begin_job("a", {});
    write_job(cl, 1);
  }
  out::ClFile file(dir / "f.h5", "test");
  EXPECT_THROW(file.copy_job(dir / "spool.h5", "b"), std::invalid_argument);  // not there
  {
    out::ClJob open = file.begin_job("x", {});
    EXPECT_THROW(file.copy_job(dir / "spool.h5", "a"), std::logic_error);  // a job is open
  }
  file.copy_job(dir / "spool.h5", "a");
  EXPECT_THROW(file.copy_job(dir / "spool.h5", "a"), std::invalid_argument);  // twice
  EXPECT_THROW(file.copy_job(dir / "missing.h5", "a"), std::runtime_error);
  file.close();
}

}  // namespace
}  // namespace ncpath::jobs
