// Batch files: every key is known or reported by name; per-job problems stay with the job.
#include "batch/jobs/job_spec.hpp"

#include <gtest/gtest.h>

namespace ncpath::jobs {
namespace {

BatchSpec parse(const std::string& text) { return parse_batch_text(text, "/base", "jobs.toml"); }

const char* kGood = R"(
output = "out.h5"
threads = 2
[[job]]
name = "a"
operation = "raster"
input = "part.stl"
tool = "bull:10:2"
transform = { fit_xy = 200, translate = [1, 2, 3] }
params = { interval = 0.25, step = 0.05, direction = "y", adaptive_tolerance = 0.01, rect = [0, 0, 10, 20] }
[[job]]
operation = "drop"
input = "part.off"
tool = "flat:6"
params = { points = "xy.csv" }
)";

TEST(JobSpec, ParsesEveryKeyOfAGoodBatch) {
  const BatchSpec b = parse(kGood);
  EXPECT_EQ(b.output, "/base/out.h5");
  EXPECT_EQ(b.threads, 2);
  ASSERT_EQ(b.jobs.size(), 2u);
  const JobSpec& a = b.jobs[0];
  EXPECT_EQ(a.error, "");
  EXPECT_EQ(a.name, "a");
  EXPECT_EQ(a.input, "/base/part.stl");
  EXPECT_EQ(a.tool.type, CutterType::kBullNose);
  EXPECT_EQ(a.tool.radius, 5);
  EXPECT_EQ(a.tool.corner_radius, 2);
  EXPECT_EQ(*a.transform.fit_xy_mm, 200);
  EXPECT_EQ(a.transform.translate, Vec3(1, 2, 3));
  EXPECT_EQ(a.raster.interval, 0.25);
  EXPECT_EQ(a.raster.step, 0.05);
  EXPECT_EQ(a.raster.direction, ScanDirection::kY);
  EXPECT_EQ(a.raster.adaptive_tolerance, 0.01);
  ASSERT_TRUE(a.raster.rect.has_value());
  EXPECT_EQ((*a.raster.rect)[3], 20);
  const JobSpec& d = b.jobs[1];
  EXPECT_EQ(d.error, "");
  EXPECT_EQ(d.name, "job2");
  EXPECT_EQ(d.operation, Operation::kDrop);
  EXPECT_EQ(d.points, "/base/xy.csv");
  // Defaults appear in the params JSON.
  EXPECT_NE(params_json(d).find("\"points\""), std::string::npos);
  EXPECT_NE(params_json(b.jobs[0]).find("\"min_step\":0.0"), std::string::npos);
  EXPECT_EQ(tool_json(a.tool), R"({"type":"bullnose","diameter_mm":10.0,"corner_radius_mm":2.0})");
}

std::string job_error(const std::string& job_body) {
  const BatchSpec b = parse("output = \"o.h5\"\n[[job]]\n" + job_body);
  return b.jobs.at(0).error;
}

TEST(JobSpec, BadParametersAreNamed) {
  const std::string base = "input = \"p.stl\"\n";
  EXPECT_NE(job_error(base + "tool = \"ball:-5\"").find("diameter"), std::string::npos);
  EXPECT_NE(job_error(base + "tool = \"bull:6:4\"").find("corner radius 4"), std::string::npos);
  EXPECT_NE(job_error(base + "tool = \"drill:6\"").find("tool type 'drill'"), std::string::npos);
  EXPECT_NE(job_error(base + "tool = \"ball:5\"\nparams = { step = 0 }").find("step"),
            std::string::npos);
  EXPECT_NE(job_error(base + "tool = \"ball:5\"\nparams = { intervall = 1 }")
                .find("'params.intervall' is not a known key"),
            std::string::npos);
  EXPECT_NE(job_error(base + "tool = \"ball:5\"\ncolour = 1").find("'colour' is not a known key"),
            std::string::npos);
  EXPECT_NE(job_error(base + "tool = \"ball:5\"\ntransform = { fit_xy = -1 }").find("fit_xy"),
            std::string::npos);
  EXPECT_NE(job_error(base + "tool = \"ball:5\"\nparams = { interval = \"big\" }")
                .find("'params.interval' must be a number"),
            std::string::npos);
  EXPECT_NE(job_error("tool = \"ball:5\"").find("'input' is required"), std::string::npos);
  EXPECT_NE(job_error(base + "tool = \"ball:5\"\noperation = \"drop\"").find("params.points"),
            std::string::npos);
}

TEST(JobSpec, GcodeTable) {
  const BatchSpec b = parse(R"(
[[job]]
input = "p.stl"
tool = "ball:3"
gcode = { path = "out/p.ngc", dialect = "grbl", feed = 1200, safe_z = 40 }
[[job]]
input = "p.stl"
tool = "ball:3"
gcode = { path = "q.ngc", dialect = "fanuc" }
[[job]]
input = "p.stl"
tool = "ball:3"
gcode = { path = "q.ngc", speed = 3 }
)");
  EXPECT_EQ(b.jobs[0].error, "");
  EXPECT_EQ(b.jobs[0].gcode, "/base/out/p.ngc");
  EXPECT_EQ(b.jobs[0].gcode_params.dialect, out::GcodeDialect::kGrbl);
  EXPECT_EQ(b.jobs[0].gcode_params.feed, 1200);
  EXPECT_EQ(*b.jobs[0].gcode_safe_z, 40);
  EXPECT_NE(b.jobs[1].error.find("fanuc"), std::string::npos);
  EXPECT_NE(b.jobs[2].error.find("'gcode.speed' is not a known key"), std::string::npos);
}

TEST(JobSpec, OneBadJobDoesNotSpoilTheOthers) {
  const BatchSpec b = parse(R"(
[[job]]
input = "a.stl"
tool = "ball:0"
[[job]]
input = "b.stl"
tool = "ball:3"
)");
  ASSERT_EQ(b.jobs.size(), 2u);
  EXPECT_NE(b.jobs[0].error, "");
  EXPECT_EQ(b.jobs[0].error_status, "invalid_parameter");
  EXPECT_EQ(b.jobs[1].error, "");
}

TEST(JobSpec, DuplicateNamesAreAnError) {
  const BatchSpec b = parse(
      "[[job]]\nname = \"x\"\ninput = \"a\"\ntool = \"ball:1\"\n"
      "[[job]]\nname = \"x\"\ninput = \"a\"\ntool = \"ball:1\"\n");
  EXPECT_EQ(b.jobs[0].error, "");
  EXPECT_NE(b.jobs[1].error.find("used twice"), std::string::npos);
  EXPECT_NE(b.jobs[0].name, b.jobs[1].name);  // both can still be recorded in one file
}

TEST(JobSpec, SyntaxErrorsNameFileLineAndColumn) {
  try {
    parse("output = \"o.h5\"\n[[job]]\nname = \n");
    FAIL() << "expected a parse error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("jobs.toml:3:"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parse("output = \"o.h5\"\n"), std::runtime_error);  // no jobs
  EXPECT_THROW(parse("outptu = \"o.h5\"\n[[job]]\ninput=\"a\"\ntool=\"ball:1\"\n"),
               std::runtime_error);
}

// Two jobs of a batch may run at the same time: the second naming the first's G-code file is
// refused (named), the first keeps it.
TEST(JobSpec, TwoJobsCannotWriteOneGcodeFile) {
  const std::string job = "input=\"a\"\ntool=\"ball:1\"\ngcode = { path = \"out/p.ngc\" }\n";
  const BatchSpec b = parse("[[job]]\nname = \"one\"\n" + job + "[[job]]\nname = \"two\"\n" + job +
                            "[[job]]\nname = \"three\"\ninput=\"a\"\ntool=\"ball:1\"\n"
                            "gcode = { path = \"out/../out/q.ngc\" }\n");
  ASSERT_EQ(b.jobs.size(), 3u);
  EXPECT_EQ(b.jobs[0].error, "");
  EXPECT_EQ(b.jobs[1].error_status, "invalid_parameter");
  EXPECT_NE(b.jobs[1].error.find("also job 'one'"), std::string::npos) << b.jobs[1].error;
  EXPECT_EQ(b.jobs[2].error, "");
}

// The batch's own keys: threads, concurrent_jobs and memory_limit, read or named when wrong.
TEST(JobSpec, BatchKeysAreReadOrNamed) {
  const std::string job = "[[job]]\ninput=\"a\"\ntool=\"ball:1\"\n";
  const BatchSpec b = parse("threads = 3\nconcurrent_jobs = 2\nmemory_limit = \"1.5G\"\n" + job);
  EXPECT_EQ(b.threads, 3);
  EXPECT_EQ(b.concurrent_jobs, 2);
  EXPECT_EQ(b.memory_limit, 3ull << 29);
  EXPECT_EQ(parse(job).memory_limit, 0u);  // the default, decided when the batch runs
  for (const char* bad : {"threads = -1\n", "threads = 1.5\n", "concurrent_jobs = -2\n",
                          "memory_limit = \"lots\"\n", "memory_limit = 8\n"}) {
    try {
      parse(bad + job);
      ADD_FAILURE() << bad << " was accepted";
    } catch (const std::runtime_error& e) {
      const std::string key = std::string(bad).substr(0, std::string(bad).find(' '));
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace ncpath::jobs
