// scan jobs in batch files: every key, the defaults, the params JSON, and bad values named by
// key (the tool's shape is the engine's to refuse, at run time: see scan_cli_test.cpp).
#include <gtest/gtest.h>

#include "batch/jobs/job_spec.hpp"

namespace ncpath::jobs {
namespace {

JobSpec scan_job(const std::string& params, const std::string& tool = "ball:6") {
  const BatchSpec b = parse_batch_text(
      "[[job]]\noperation = \"scan\"\ninput = \"part.stl\"\ntool = \"" + tool + "\"\n" + params,
      "/base", "jobs.toml");
  return b.jobs.at(0);
}

TEST(ScanSpec, ParsesEveryKey) {
  const JobSpec j = scan_job(
      "transform = { fit_xy = 200 }\n"
      "params = { families = \"both\", interval = 2, tolerance = 0.01, margin = 3, "
      "rect = [-1, -2, 30, 40], floor_z = -5, chunk_planes = 7 }");
  ASSERT_EQ(j.error, "");
  EXPECT_EQ(j.operation, Operation::kScan);
  EXPECT_STREQ(operation_name(j.operation), "scan");
  EXPECT_EQ(j.input, "/base/part.stl");
  EXPECT_EQ(*j.transform.fit_xy_mm, 200);
  const ScanParams& p = j.scan;
  EXPECT_EQ(p.families, ScanFamilies::kBoth);
  EXPECT_EQ(p.interval, 2);
  EXPECT_EQ(p.tolerance, 0.01);
  EXPECT_EQ(p.margin, 3);
  ASSERT_TRUE(p.rect.has_value());
  EXPECT_EQ(*p.rect, (std::array<double, 4>{-1, -2, 30, 40}));
  ASSERT_TRUE(p.floor_z.has_value());
  EXPECT_EQ(*p.floor_z, -5);
  EXPECT_EQ(p.chunk_planes, 7u);
  const std::string json = params_json(j);
  for (const char* s : {"\"operation\":\"scan\"", "\"families\":\"both\"", "\"interval\":2.0",
                        "\"tolerance\":0.01", "\"margin\":3.0", "\"rect\":[-1.0,-2.0,30.0,40.0]",
                        "\"floor_z\":-5.0", "\"chunk_planes\":7"})
    EXPECT_NE(json.find(s), std::string::npos) << s << " in " << json;
  EXPECT_EQ(scan_job("params = { families = \"y\" }").scan.families, ScanFamilies::kY);
}

TEST(ScanSpec, DefaultsAreXLinesHalfAMillimetreApartWithinAMicron) {
  const JobSpec j = scan_job("");
  ASSERT_EQ(j.error, "");
  EXPECT_EQ(j.scan.families, ScanFamilies::kX);
  EXPECT_EQ(j.scan.interval, 0.5);
  EXPECT_EQ(j.scan.tolerance, 0.001);
  EXPECT_EQ(j.scan.margin, 0);
  EXPECT_FALSE(j.scan.rect.has_value());
  EXPECT_FALSE(j.scan.floor_z.has_value());
  // Defaults are written out, unset optionals as null.
  const std::string json = params_json(j);
  for (const char* s : {"\"families\":\"x\"", "\"interval\":0.5", "\"tolerance\":0.001",
                        "\"rect\":null", "\"floor_z\":null"})
    EXPECT_NE(json.find(s), std::string::npos) << s << " in " << json;
}

TEST(ScanSpec, BadValuesAreNamed) {
  auto error = [](const std::string& params) {
    const JobSpec j = scan_job(params);
    EXPECT_EQ(j.error_status, "invalid_parameter") << params;
    return j.error;
  };
  EXPECT_NE(error("params = { interval = 0 }").find("interval must be a positive number"),
            std::string::npos);
  EXPECT_NE(error("params = { interval = -1 }").find("got -1"), std::string::npos);
  EXPECT_NE(error("params = { tolerance = 0 }").find("tolerance must be a positive number"),
            std::string::npos);
  EXPECT_NE(error("params = { margin = -2 }").find("margin must be >= 0"), std::string::npos);
  EXPECT_NE(error("params = { rect = [10, 0, 0, 10] }").find("rect must be"), std::string::npos);
  EXPECT_NE(error("params = { rect = [0, 0, 10] }").find("'params.rect' must be an array of 4"),
            std::string::npos);
  const std::string families = error("params = { families = \"z\" }");
  EXPECT_NE(families.find("'params.families' must be \"x\", \"y\" or \"both\", got \"z\""),
            std::string::npos)
      << families;
  EXPECT_NE(error("params = { families = 1 }").find("'params.families' must be a string"),
            std::string::npos);
  EXPECT_NE(error("params = { chunk_planes = 0 }").find("'params.chunk_planes' must be a whole"),
            std::string::npos);
  // Raster's keys are not scan's.
  EXPECT_NE(error("params = { step = 0.1 }").find("'params.step' is not a known key"),
            std::string::npos);
  EXPECT_NE(error("params = { direction = \"x\" }").find("'params.direction' is not a known"),
            std::string::npos);
  // An unknown operation lists scan among the known ones.
  const BatchSpec b =
      parse_batch_text("[[job]]\noperation = \"scann\"\ninput = \"p\"\n", "/base", "jobs.toml");
  EXPECT_NE(b.jobs[0].error.find("\"scan\""), std::string::npos) << b.jobs[0].error;
}

}  // namespace
}  // namespace ncpath::jobs
