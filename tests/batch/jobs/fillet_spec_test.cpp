// fillet jobs in batch files: every key, the defaults, the params JSON, and bad values named by
// key: a reference that is not a ball or not larger than the tool, no reference, no usable
// spacing (the tool's shape is the engine's to refuse, at run time: see fillet_cli_test.cpp).
#include <gtest/gtest.h>

#include "batch/jobs/job_spec.hpp"

namespace ncpath::jobs {
namespace {

JobSpec fillet_job(const std::string& params, const std::string& tool = "ball:3") {
  const BatchSpec b = parse_batch_text(
      "[[job]]\noperation = \"fillet\"\ninput = \"part.stl\"\ntool = \"" + tool + "\"\n" + params,
      "/base", "jobs.toml");
  return b.jobs.at(0);
}

TEST(FilletSpec, ParsesEveryKey) {
  const JobSpec j = fillet_job(
      "transform = { fit_xy = 150 }\n"
      "params = { reference = \"ball:8\", stepover = 0.3, max_passes = 12, interval = 2, "
      "step_down = 0, min_angle = 35, tolerance = 0.02, merge_distance = 3, min_length = 0.5, "
      "margin = 1.5, floor_z = -4, stock = 0.2, direction = \"conventional\" }");
  ASSERT_EQ(j.error, "");
  EXPECT_EQ(j.operation, Operation::kFillet);
  EXPECT_STREQ(operation_name(j.operation), "fillet");
  EXPECT_EQ(*j.transform.fit_xy_mm, 150);
  EXPECT_EQ(j.fillet_reference, "ball:8");
  const FilletParams& p = j.fillet;
  EXPECT_EQ(p.reference_diameter, 8);
  EXPECT_EQ(p.stepover, 0.3);
  EXPECT_EQ(p.scallop, 0.005);  // not given: the default, unused with a stepover
  EXPECT_EQ(p.max_passes, 12u);
  EXPECT_EQ(p.pencil.interval, 2);
  EXPECT_EQ(p.pencil.step_down, 0);
  EXPECT_EQ(p.pencil.min_angle_deg, 35);
  EXPECT_EQ(p.pencil.tolerance, 0.02);
  EXPECT_EQ(p.pencil.merge_distance, 3);
  EXPECT_EQ(p.pencil.min_length, 0.5);
  EXPECT_EQ(p.pencil.margin, 1.5);
  ASSERT_TRUE(p.pencil.floor_z.has_value());
  EXPECT_EQ(*p.pencil.floor_z, -4);
  // stock and direction are the fillet's own, not its reference run's.
  EXPECT_EQ(p.stock, 0.2);
  EXPECT_EQ(p.direction, CutDirection::kConventional);
  EXPECT_EQ(p.pencil.stock, 0);
  EXPECT_EQ(p.pencil.direction, CutDirection::kAny);
  // The job's pencil params (the pencil operation's) are untouched.
  EXPECT_EQ(j.pencil.interval, PencilParams{}.interval);
  const std::string json = params_json(j);
  for (const char* s :
       {"\"operation\":\"fillet\"", "\"reference\":\"ball:8\"", "\"reference_diameter\":8.0",
        "\"stepover\":0.3", "\"max_passes\":12", "\"interval\":2.0", "\"step_down\":0.0",
        "\"min_angle\":35.0", "\"tolerance\":0.02", "\"merge_distance\":3.0", "\"min_length\":0.5",
        "\"margin\":1.5", "\"floor_z\":-4.0", "\"stock\":0.2", "\"direction\":\"conventional\""})
    EXPECT_NE(json.find(s), std::string::npos) << s << " in " << json;
}

TEST(FilletSpec, DefaultsAreTheEngines) {
  const JobSpec j = fillet_job("params = { reference = \"ball:10\" }");
  ASSERT_EQ(j.error, "");
  const FilletParams& p = j.fillet;
  EXPECT_EQ(p.reference_diameter, 10);
  EXPECT_EQ(p.stepover, 0);  // 0: from the scallop height
  EXPECT_EQ(p.scallop, 0.005);
  EXPECT_EQ(p.max_passes, 64u);
  EXPECT_EQ(p.pencil.interval, 0.5);
  EXPECT_EQ(p.pencil.step_down, 1.0);
  EXPECT_EQ(p.pencil.min_angle_deg, 20);
  EXPECT_EQ(p.pencil.tolerance, 0.01);
  EXPECT_EQ(p.pencil.min_length, 1.0);
  EXPECT_FALSE(p.pencil.floor_z.has_value());
  EXPECT_EQ(p.stock, 0);
  EXPECT_EQ(p.direction, CutDirection::kAny);
  const std::string json = params_json(j);
  for (const char* s : {"\"reference\":\"ball:10\"", "\"reference_diameter\":10.0",
                        "\"stepover\":0.0", "\"scallop\":0.005", "\"max_passes\":64",
                        "\"interval\":0.5", "\"min_angle\":20.0", "\"floor_z\":null",
                        "\"stock\":0.0", "\"direction\":\"any\""})
    EXPECT_NE(json.find(s), std::string::npos) << s << " in " << json;
  // A scallop height with stepover 0 (its meaning) is fine; a larger reference of any size too.
  const JobSpec s =
      fillet_job("params = { reference = \"ball:3.5\", stepover = 0, scallop = 0.01 }");
  ASSERT_EQ(s.error, "");
  EXPECT_EQ(s.fillet.scallop, 0.01);
  EXPECT_EQ(s.fillet.reference_diameter, 3.5);
}

TEST(FilletSpec, BadValuesAreNamed) {
  auto error = [](const std::string& params, const std::string& tool = "ball:3") {
    const JobSpec j = fillet_job(params, tool);
    EXPECT_EQ(j.error_status, "invalid_parameter") << params;
    return j.error;
  };
  auto has = [](const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos
               ? ::testing::AssertionSuccess()
               : ::testing::AssertionFailure() << "'" << part << "' not in: " << text;
  };
  // The reference: a ball, larger than the tool, required.
  EXPECT_TRUE(has(error("params = { reference = \"flat:10\" }"),
                  "'params.reference' must be a ball-end mill (ball:D"));
  EXPECT_TRUE(has(error("params = { reference = \"bull:10:2\" }"),
                  "'params.reference' must be a ball-end mill"));
  EXPECT_TRUE(has(error("params = { reference = \"ball:2\" }"),
                  "'params.reference' must be a larger ball than the tool (3 mm), got 'ball:2' "
                  "(2 mm)"));
  EXPECT_TRUE(has(error("params = { reference = \"ball:3\" }"),
                  "'params.reference' must be a larger ball than the tool (3 mm)"));
  EXPECT_TRUE(has(error("params = { reference = \"ball:4\" }", "ball:6"),
                  "must be a larger ball than the tool (6 mm), got 'ball:4' (4 mm)"));
  EXPECT_TRUE(has(error("params = { reference = \"ball:x\" }"),
                  "'params.reference' is not a usable ball: tool 'ball:x' is malformed"));
  EXPECT_TRUE(has(error("params = { reference = 10 }"), "'params.reference' must be a string"));
  EXPECT_TRUE(has(error(""), "'params.reference' is required for a fillet job"));
  EXPECT_TRUE(
      has(error("params = { scallop = 0.01 }"), "'params.reference' is required for a fillet job"));
  // The spacing: a scallop height needs stepover 0; a stepover of 0 needs a scallop height.
  EXPECT_TRUE(has(error("params = { reference = \"ball:10\", scallop = 0 }"),
                  "scallop must be a positive number of mm when stepover is 0, got 0"));
  EXPECT_TRUE(has(error("params = { reference = \"ball:10\", stepover = 0, scallop = 0 }"),
                  "scallop must be a positive number of mm when stepover is 0, got 0"));
  EXPECT_TRUE(has(error("params = { reference = \"ball:10\", stepover = -1 }"),
                  "stepover must be >= 0 mm (0 = from the scallop height), got -1"));
  EXPECT_TRUE(has(error("params = { reference = \"ball:10\", stepover = 0.5, scallop = 0.01 }"),
                  "'params.scallop' is not used when 'params.stepover' is given (> 0)"));
  EXPECT_TRUE(has(error("params = { reference = \"ball:10\", max_passes = 0 }"),
                  "'params.max_passes' must be a whole number >= 1"));
  EXPECT_TRUE(has(error("params = { reference = \"ball:10\", max_passes = 2.5 }"),
                  "'params.max_passes' must be a whole number >= 1"));
  // The reference run's pencil keys, named as in a pencil job (flat: no "pencil:" prefix).
  const std::string interval = error("params = { reference = \"ball:10\", interval = 0 }");
  EXPECT_TRUE(has(interval, "interval must be a positive number of mm, got 0"));
  EXPECT_FALSE(has(interval, "pencil:"));
  EXPECT_TRUE(has(error("params = { reference = \"ball:10\", min_angle = 200 }"),
                  "min_angle must be between 0 and 180 degrees, got 200"));
  EXPECT_TRUE(has(error("params = { reference = \"ball:10\", merge_distance = -1 }"),
                  "merge_distance must be >= 0"));
  // Stock: down to (not including) minus the clean-up ball's radius (ball:3: 1.5 mm).
  EXPECT_TRUE(has(error("params = { reference = \"ball:10\", stock = -1.5 }"),
                  "stock must be greater than minus the ball radius (-1.5 mm)"));
  EXPECT_EQ(fillet_job("params = { reference = \"ball:10\", stock = -1.4 }").error, "");
  EXPECT_TRUE(has(error("params = { reference = \"ball:10\", stock = true }"),
                  "'params.stock' must be a number"));
  // Direction: any, climb or conventional, named with the allowed values.
  EXPECT_TRUE(has(error("params = { reference = \"ball:10\", direction = \"zigzag\" }"),
                  "'params.direction' must be \"any\", \"climb\" or \"conventional\", got "
                  "\"zigzag\""));
  // Field names are not keys; other operations' keys are not fillet's.
  EXPECT_TRUE(has(error("params = { reference = \"ball:10\", reference_diameter = 10 }"),
                  "'params.reference_diameter' is not a known key"));
  EXPECT_TRUE(has(error("params = { reference = \"ball:10\", families = \"x\" }"),
                  "'params.families' is not a known key"));
  // A flat or bull tool is refused when the job runs (the engine's message), not here.
  EXPECT_EQ(fillet_job("params = { reference = \"ball:10\" }", "flat:3").error, "");
  const BatchSpec b =
      parse_batch_text("[[job]]\noperation = \"filet\"\ninput = \"p\"\n", "/base", "jobs.toml");
  EXPECT_TRUE(has(b.jobs[0].error, "\"fillet\""));
}

}  // namespace
}  // namespace ncpath::jobs
