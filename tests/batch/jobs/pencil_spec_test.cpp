// pencil jobs in batch files: every key, the defaults, the params JSON, and bad values named by
// key (the tool's shape is the engine's to refuse, at run time: see pencil_cli_test.cpp).
#include <gtest/gtest.h>

#include "batch/jobs/job_spec.hpp"

namespace ncpath::jobs {
namespace {

JobSpec pencil_job(const std::string& params, const std::string& tool = "ball:6") {
  const BatchSpec b = parse_batch_text(
      "[[job]]\noperation = \"pencil\"\ninput = \"part.stl\"\ntool = \"" + tool + "\"\n" + params,
      "/base", "jobs.toml");
  return b.jobs.at(0);
}

TEST(PencilSpec, ParsesEveryKey) {
  const JobSpec j = pencil_job(
      "transform = { fit_xy = 150 }\n"
      "params = { interval = 2, step_down = 0, min_angle = 35, tolerance = 0.02, "
      "merge_distance = 3, min_length = 0.5, margin = 1.5, floor_z = -4, stock = 0.25, "
      "direction = \"climb\" }");
  ASSERT_EQ(j.error, "");
  EXPECT_EQ(j.operation, Operation::kPencil);
  EXPECT_STREQ(operation_name(j.operation), "pencil");
  EXPECT_EQ(*j.transform.fit_xy_mm, 150);
  const PencilParams& p = j.pencil;
  EXPECT_EQ(p.interval, 2);
  EXPECT_EQ(p.step_down, 0);
  EXPECT_EQ(p.min_angle_deg, 35);
  EXPECT_EQ(p.tolerance, 0.02);
  EXPECT_EQ(p.merge_distance, 3);
  EXPECT_EQ(p.min_length, 0.5);
  EXPECT_EQ(p.margin, 1.5);
  ASSERT_TRUE(p.floor_z.has_value());
  EXPECT_EQ(*p.floor_z, -4);
  EXPECT_EQ(p.stock, 0.25);
  EXPECT_EQ(p.direction, CutDirection::kClimb);
  const std::string json = params_json(j);
  for (const char* s : {"\"operation\":\"pencil\"", "\"interval\":2.0", "\"step_down\":0.0",
                        "\"min_angle\":35.0", "\"tolerance\":0.02", "\"merge_distance\":3.0",
                        "\"min_length\":0.5", "\"margin\":1.5", "\"floor_z\":-4.0",
                        "\"stock\":0.25", "\"direction\":\"climb\""})
    EXPECT_NE(json.find(s), std::string::npos) << s << " in " << json;
}

TEST(PencilSpec, DefaultsAreTheEnginesWithTwentyDegrees) {
  const JobSpec j = pencil_job("");
  ASSERT_EQ(j.error, "");
  const PencilParams& p = j.pencil;
  EXPECT_EQ(p.interval, 0.5);
  EXPECT_EQ(p.step_down, 1.0);
  EXPECT_EQ(p.min_angle_deg, 20);
  EXPECT_EQ(p.tolerance, 0.01);
  EXPECT_EQ(p.merge_distance, 0);  // 0: twice the interval
  EXPECT_EQ(p.min_length, 1.0);
  EXPECT_EQ(p.margin, 0);
  EXPECT_FALSE(p.floor_z.has_value());
  EXPECT_EQ(p.stock, 0);
  EXPECT_EQ(p.direction, CutDirection::kAny);
  const std::string json = params_json(j);
  for (const char* s :
       {"\"interval\":0.5", "\"step_down\":1.0", "\"min_angle\":20.0", "\"tolerance\":0.01",
        "\"merge_distance\":0.0", "\"min_length\":1.0", "\"floor_z\":null", "\"stock\":0.0",
        "\"direction\":\"any\""})
    EXPECT_NE(json.find(s), std::string::npos) << s << " in " << json;
}

TEST(PencilSpec, BadValuesAreNamed) {
  auto error = [](const std::string& params) {
    const JobSpec j = pencil_job(params);
    EXPECT_EQ(j.error_status, "invalid_parameter") << params;
    return j.error;
  };
  EXPECT_NE(error("params = { min_angle = 0 }")
                .find("min_angle must be between 0 and 180 degrees, got 0"),
            std::string::npos);
  EXPECT_NE(error("params = { min_angle = 200 }").find("min_angle must be between 0 and 180"),
            std::string::npos);
  EXPECT_NE(error("params = { interval = 0 }").find("interval must be a positive number of mm"),
            std::string::npos);
  EXPECT_NE(error("params = { tolerance = -1 }").find("tolerance must be a positive number"),
            std::string::npos);
  EXPECT_NE(error("params = { step_down = -1 }").find("step_down must be >= 0 mm"),
            std::string::npos);
  EXPECT_NE(error("params = { merge_distance = -1 }").find("merge_distance must be >= 0"),
            std::string::npos);
  EXPECT_NE(error("params = { min_length = -1 }").find("min_length must be >= 0"),
            std::string::npos);
  EXPECT_NE(error("params = { margin = -1 }").find("margin must be >= 0"), std::string::npos);
  EXPECT_NE(error("params = { min_angle = \"20\" }").find("'params.min_angle' must be a number"),
            std::string::npos);
  // Stock: down to (not including) minus the ball's radius (ball:6, 3 mm); a number.
  EXPECT_NE(error("params = { stock = -3 }")
                .find("stock must be greater than minus the ball radius (-3 mm)"),
            std::string::npos);
  EXPECT_NE(error("params = { stock = -4.5 }").find("got -4.5"), std::string::npos);
  EXPECT_NE(error("params = { stock = \"0.2\" }").find("'params.stock' must be a number"),
            std::string::npos);
  EXPECT_EQ(pencil_job("params = { stock = -2.9 }").error, "");
  // With a flat tool the engine refuses the job when it runs (not a ball), not the stock here.
  EXPECT_EQ(pencil_job("params = { stock = -4 }", "flat:6").error, "");
  // Direction: any, climb or conventional, named with the allowed values.
  EXPECT_NE(error("params = { direction = \"down\" }")
                .find("'params.direction' must be \"any\", \"climb\" or \"conventional\", "
                      "got \"down\""),
            std::string::npos);
  EXPECT_NE(error("params = { direction = \"Climb\" }").find("'params.direction' must be"),
            std::string::npos);
  EXPECT_NE(error("params = { direction = 1 }").find("'params.direction' must be a string"),
            std::string::npos);
  EXPECT_EQ(pencil_job("params = { direction = \"conventional\" }").pencil.direction,
            CutDirection::kConventional);
  // The struct's field name is not a key; scan's keys are not pencil's.
  EXPECT_NE(
      error("params = { min_angle_deg = 20 }").find("'params.min_angle_deg' is not a known key"),
      std::string::npos);
  EXPECT_NE(error("params = { families = \"x\" }").find("'params.families' is not a known key"),
            std::string::npos);
  const BatchSpec b =
      parse_batch_text("[[job]]\noperation = \"pencill\"\ninput = \"p\"\n", "/base", "jobs.toml");
  EXPECT_NE(b.jobs[0].error.find("\"pencil\""), std::string::npos) << b.jobs[0].error;
}

}  // namespace
}  // namespace ncpath::jobs
