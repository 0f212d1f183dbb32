// One job split into bands and joined (batch/jobs/split_job.hpp), without MPI: the bands run
// as one-job batches one after another, as ranks would run them. The oracle is the same job
// run whole: the joined job must have its datasets and attributes, its status, and every
// statistic other than times equal to it. Synthetic bands check what a real raster seldom
// shows: a gouge in a later band is reported with its job-wide move and path, a band that
// failed fails the job, and statistics the merge does not know are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <variant>
#include <vector>

#include "batch/io/stl_writer.hpp"
#include "batch/jobs/job_verify.hpp"
#include "batch/jobs/split_job.hpp"
#include "batch/output/cl_reader.hpp"
#include "tests/batch/output/h5_read.hpp"
#include "tests/support/meshes.hpp"

namespace ncpath::jobs {
namespace {

namespace h5 = out::test;
using out::StatValue;

bool statistic(const std::string& path) { return path.find("/stats/") != std::string::npos; }

// A raster job over a hemisphere standing on the floor (floor points, steep chords that the
// chord guard lifts) with small chunks, so that bands end inside the whole run's chunks.
JobSpec raster_job(const std::filesystem::path& dir) {
  io::write_binary_stl(dir / "part.stl", test::hemisphere(12, 10, 24));
  JobSpec job;
  job.name = "dome";
  job.operation = Operation::kRaster;
  job.input = dir / "part.stl";
  job.tool_text = "ball:4";
  EXPECT_EQ(parse_tool(job.tool_text, job.tool), "");
  job.raster.interval = 0.4;
  job.raster.step = 0.1;
  job.raster.margin = 3;
  job.raster.chunk_lines = 5;
  return job;
}

JobOutcome run_into(const JobSpec& job, const std::filesystem::path& out) {
  BatchSpec batch;
  batch.output = out;
  batch.threads = 1;
  batch.jobs = {job};
  return run_batch(batch, BatchObserver{}).at(0);
}

// Runs the bands of `job` one after another and joins them into `out`.
JobOutcome split_run(const JobSpec& job, std::uint32_t n, const std::filesystem::path& dir,
                     const std::filesystem::path& out) {
  std::vector<Band> bands;
  for (std::uint32_t b = 0; b < n; ++b) {
    const auto file = dir / ("band" + std::to_string(b) + ".h5");
    bands.push_back({file, run_into(band_job(job, b, n), file), static_cast<int>(b % 3)});
  }
  // As the batch runners write it.
  const std::string version =
      h5::read_string_attr(h5::open_read(bands[0].file), "ncpath_version").value;
  out::ClFile file(out, version);
  file.mark_batch(1, false);
  const JobOutcome o = join_bands(file, job, bands, 1.5);
  file.mark_batch(1, true);
  file.close();
  return o;
}

JobOutcome outcome(const std::string& status, const std::string& message = "") {
  JobOutcome o;
  o.name = "j";
  o.status = status;
  o.message = message;
  return o;
}

const StatValue* find(const std::vector<StatValue>& stats, const std::string& name) {
  for (const StatValue& s : stats)
    if (s.name == name) return &s;
  return nullptr;
}

TEST(SplitJob, BandsJoinedAreTheWholeJob) {
  const auto dir = h5::out_dir("split_bands");
  const JobSpec job = raster_job(dir);
  ASSERT_TRUE(splittable(job));
  const JobOutcome whole = run_into(job, dir / "whole.h5");
  ASSERT_EQ(whole.status, "ok") << whole.message;
  const std::vector<StatValue> ws = out::read_stats(dir / "whole.h5", job.name);
  ASSERT_GT(std::get<std::int64_t>(find(ws, "chord_guard_lifted")->value), 0);
  ASSERT_GT(std::get<std::int64_t>(find(ws, "floor_points")->value), 0);
  // 76 lines in 38 strips of 2: 50 bands leave some bands empty.
  for (std::uint32_t n : {1u, 2u, 3u, 7u, 50u}) {
    SCOPED_TRACE(testing::Message() << n << " bands");
    const auto joined = dir / ("joined" + std::to_string(n) + ".h5");
    const JobOutcome o = split_run(job, n, dir, joined);
    EXPECT_EQ(o.status, "ok") << o.message;
    EXPECT_EQ(o.points, whole.points);
    EXPECT_TRUE(h5::same_content(dir / "whole.h5", joined, statistic));
    const std::vector<StatValue> js = out::read_stats(joined, job.name);
    for (const StatValue& w : ws) {
      SCOPED_TRACE(w.name);
      const StatValue* j = find(js, w.name);
      ASSERT_NE(j, nullptr);
      if (w.unit == "s" || w.unit == "1/s" || w.name == "peak_rss_bytes") continue;
      EXPECT_TRUE(j->value == w.value);
    }
    EXPECT_EQ(std::get<std::int64_t>(find(js, "mpi_bands")->value), std::int64_t(n));
    // The wall time before the join, and the join's.
    EXPECT_EQ(std::get<double>(find(js, "total_s")->value),
              1.5 + std::get<double>(find(js, "mpi_join_s")->value));
  }
}

// A band's CL file as a rank writes it: strips of `strips[k]` paths, each path of `points`
// points along x at y = y0 + path, and a verifier report with one violation of `amount` mm
// at move `move`.
void write_band(const std::filesystem::path& file, const std::vector<std::int64_t>& strips,
                int points, double y0, std::uint64_t move, double amount) {
  int paths = 0;
  for (const std::int64_t n : strips) paths += static_cast<int>(n);
  out::ClFile f(file, "test");
  out::ClJob cl = f.begin_job("j", out::JobInfo{"raster", "in.stl", "ab", "{}", "{}"});
  ClChunk c;
  for (int p = 0; p < paths; ++p) {
    for (int i = 0; i < points; ++i) {
      c.xyz.insert(c.xyz.end(), {double(i), y0 + p, 1.0});
      c.contact.push_back(out::kContactFacet);
    }
    c.path_sizes.push_back(static_cast<std::uint32_t>(points));
    c.path_kinds.push_back(static_cast<std::uint8_t>(PathKind::kCut));
  }
  cl.append_paths(c.xyz, c.contact, c.path_sizes, c.path_kinds);
  VerifyReport r;
  r.moves = static_cast<std::uint64_t>(paths * (points - 1));
  const auto path = static_cast<std::uint32_t>(move / (points - 1));
  r.add({move, path, Vec3(0, y0 + path, 1), Vec3(1, y0 + path, 1), amount, ViolationKind::kMesh});
  write_verify_worst(cl, r);
  cl.write_array("band", "strip_paths", strips, 0);
  cl.set_status("failed_verification", "band-local message");
  const std::vector<StatValue> stats = {{"points", std::int64_t{paths * points}, ""},
                                        {"verify_moves", static_cast<std::int64_t>(r.moves), ""},
                                        {"verify_max_gouge", r.max_gouge, "mm"},
                                        {"verify_min_clearance", 0.5 - y0 / 100, "mm"},
                                        {"compute_s", 0.25, "s"},
                                        {"facets_used", std::int64_t{12}, ""}};
  cl.write_stats(stats);
  cl.close();
  f.close();
}

TEST(SplitJob, AGougeInALaterBandIsNumberedJobWide) {
  const auto dir = h5::out_dir("split_gouge");
  // Paths of 5 points (4 moves). The job's strips: band 0's first (2 paths), band 1's (2),
  // band 0's second (1). Band 0's 0.02 mm gouge at its move 9 (its path 2) is the job's move
  // 17 on path 4; band 1's 0.05 mm gouge at its move 2 (its path 0) is the job's move 10 on
  // path 2.
  write_band(dir / "b0.h5", {2, 1}, 5, 0, 9, 0.02);
  write_band(dir / "b1.h5", {2}, 5, 10, 2, 0.05);
  JobSpec job;
  job.name = "j";
  const std::vector<Band> bands = {{dir / "b0.h5", outcome("failed_verification"), 0},
                                   {dir / "b1.h5", outcome("failed_verification"), 1}};
  out::ClFile file(dir / "joined.h5", "test");
  const JobOutcome o = join_bands(file, job, bands, 2.0);
  file.close();
  EXPECT_EQ(o.status, "failed_verification");
  EXPECT_EQ(o.message.rfind("failed verification: move 10 (path 2, (0, 10, 1) -> (1, 10, 1))", 0),
            0u)
      << o.message;
  const auto worst = out::read_float64_array(dir / "joined.h5", "j", "verify/worst");
  ASSERT_TRUE(worst);
  const std::vector<VerifyViolation> v = violations_from_rows(worst->data);
  ASSERT_EQ(v.size(), 2u);
  EXPECT_EQ(v[0].move, 10u);
  EXPECT_EQ(v[0].path, 2u);
  EXPECT_EQ(v[0].amount, 0.05);
  EXPECT_EQ(v[1].move, 17u);
  EXPECT_EQ(v[1].path, 4u);
  // The paths themselves in that order: y of the job's paths 0 to 4.
  std::vector<double> y;
  out::read_paths(dir / "joined.h5", "j", [&](const ClChunk& c) {
    std::size_t i = 0;
    for (const std::uint32_t n : c.path_sizes) {
      y.push_back(c.xyz[3 * i + 1]);
      i += n;
    }
  });
  EXPECT_EQ(y, (std::vector<double>{0, 1, 10, 11, 2}));
  const std::vector<StatValue> s = out::read_stats(dir / "joined.h5", "j");
  EXPECT_EQ(std::get<std::int64_t>(find(s, "points")->value), 25);
  EXPECT_EQ(std::get<std::int64_t>(find(s, "verify_moves")->value), 20);
  EXPECT_EQ(std::get<double>(find(s, "verify_max_gouge")->value), 0.05);
  EXPECT_EQ(std::get<double>(find(s, "verify_min_clearance")->value), 0.4);
  EXPECT_EQ(std::get<double>(find(s, "compute_s")->value), 0.5);
  EXPECT_EQ(std::get<std::string>(find(s, "mpi_band_ranks")->value), "0 1");
}

TEST(SplitJob, AFailedBandFailsTheJob) {
  const auto dir = h5::out_dir("split_failed");
  write_band(dir / "b0.h5", {2}, 3, 0, 1, 0.0);
  JobSpec job;
  job.name = "j";
  const std::vector<Band> bands = {{dir / "b0.h5", outcome("ok"), 0},
                                   {dir / "b1.h5", outcome("out_of_memory", "ran out"), 2}};
  out::ClFile file(dir / "joined.h5", "test");
  const JobOutcome o = join_bands(file, job, bands, 2.0);
  file.close();
  EXPECT_EQ(o.status, "out_of_memory");
  EXPECT_EQ(o.message, "ran out (band 1 of 2, rank 2)");
  EXPECT_EQ(out::read_jobs(dir / "joined.h5").at(0).status, "out_of_memory");
}

TEST(SplitJob, StatisticsWithoutARuleMustAgree) {
  const std::vector<StatValue> a = {{"facets_used", std::int64_t{5}, ""},
                                    {"lines", std::int64_t{3}, ""},
                                    {"max_lift", 0.5, "mm"}};
  std::vector<StatValue> b = a;
  EXPECT_EQ(std::get<std::int64_t>(merge_band_stats({a, b})[1].value), 6);
  b[2].value = 0.25;  // not a known maximum: the bands must agree
  EXPECT_THROW(merge_band_stats({a, b}), std::logic_error);
  b = a;
  b[0].value = std::int64_t{6};
  EXPECT_THROW(merge_band_stats({a, b}), std::logic_error);
  b = {a[1], a[0], a[2]};
  EXPECT_THROW(merge_band_stats({a, b}), std::logic_error);
}

TEST(SplitJob, OnlyRasterJobsWithoutGcodeOrSamplingSplit) {
  JobSpec job;
  job.operation = Operation::kRaster;
  EXPECT_TRUE(splittable(job));
  job.verify = VerifyMode::kSample;
  EXPECT_FALSE(splittable(job));
  job.verify = VerifyMode::kOff;
  EXPECT_TRUE(splittable(job));
  job.gcode = "a.ngc";
  EXPECT_FALSE(splittable(job));
  job.gcode.clear();
  job.operation = Operation::kScan;
  EXPECT_FALSE(splittable(job));
}

}  // namespace
}  // namespace ncpath::jobs
