// zlevel jobs in batch files: every key, the defaults, the params JSON, and bad values named by
// key: levels and step_down, exactly one of them (the tool's shape is the engine's to refuse,
// at run time: see zlevel_cli_test.cpp).
#include <gtest/gtest.h>

#include "batch/jobs/job_spec.hpp"

namespace ncpath::jobs {
namespace {

JobSpec zlevel_job(const std::string& params, const std::string& tool = "ball:6") {
  const BatchSpec b = parse_batch_text(
      "[[job]]\noperation = \"zlevel\"\ninput = \"part.off\"\ntool = \"" + tool + "\"\n" + params,
      "/base", "jobs.toml");
  return b.jobs.at(0);
}

TEST(ZLevelSpec, ParsesEveryKey) {
  const JobSpec j = zlevel_job(
      "transform = { fit_xy = 200 }\n"
      "params = { levels = [60.0, 100, -2.5], tolerance = 0.01, chunk_levels = 3 }");
  ASSERT_EQ(j.error, "");
  EXPECT_EQ(j.operation, Operation::kZLevel);
  EXPECT_STREQ(operation_name(j.operation), "zlevel");
  EXPECT_EQ(j.input, "/base/part.off");
  EXPECT_EQ(*j.transform.fit_xy_mm, 200);
  const ZLevelOpParams& p = j.zlevel;
  EXPECT_EQ(p.levels, (std::vector<double>{60, 100, -2.5}));  // as given; the engine sorts
  EXPECT_EQ(p.step_down, 0);
  EXPECT_EQ(p.tolerance, 0.01);
  EXPECT_EQ(p.chunk_levels, 3u);
  const std::string json = params_json(j);
  for (const char* s : {"\"operation\":\"zlevel\"", "\"levels\":[60.0,100.0,-2.5]",
                        "\"step_down\":null", "\"tolerance\":0.01", "\"chunk_levels\":3"})
    EXPECT_NE(json.find(s), std::string::npos) << s << " in " << json;

  const JobSpec s = zlevel_job("params = { step_down = 2.5 }");
  ASSERT_EQ(s.error, "");
  EXPECT_EQ(s.zlevel.step_down, 2.5);
  EXPECT_TRUE(s.zlevel.levels.empty());
  const std::string sj = params_json(s);
  for (const char* t : {"\"levels\":null", "\"step_down\":2.5"})
    EXPECT_NE(sj.find(t), std::string::npos) << t << " in " << sj;
}

TEST(ZLevelSpec, DefaultsAreAMicronAndFourLevelsAChunk) {
  const JobSpec j = zlevel_job("params = { levels = [1] }");
  ASSERT_EQ(j.error, "");
  EXPECT_EQ(j.zlevel.tolerance, 0.001);
  EXPECT_EQ(j.zlevel.chunk_levels, 4u);
  const std::string json = params_json(j);
  for (const char* s : {"\"tolerance\":0.001", "\"chunk_levels\":4"})
    EXPECT_NE(json.find(s), std::string::npos) << s << " in " << json;
}

TEST(ZLevelSpec, BadValuesAreNamed) {
  auto error = [](const std::string& params) {
    const JobSpec j = zlevel_job(params);
    EXPECT_EQ(j.error_status, "invalid_parameter") << params;
    return j.error;
  };
  // Exactly one of levels and step_down.
  const std::string both = error("params = { levels = [1, 2], step_down = 1 }");
  EXPECT_NE(both.find("'params.levels' and 'params.step_down' are both given: give one of them"),
            std::string::npos)
      << both;
  const std::string neither = error("params = { tolerance = 0.01 }");
  EXPECT_NE(neither.find("'params.levels' or 'params.step_down' is required for a zlevel job"),
            std::string::npos)
      << neither;
  // ... also without any params table.
  EXPECT_NE(error("").find("'params.levels' or 'params.step_down' is required"), std::string::npos);
  EXPECT_NE(error("params = { levels = [] }").find("'params.levels' must hold at least one"),
            std::string::npos);
  EXPECT_NE(error("params = { step_down = 0 }")
                .find("'params.step_down' must be a positive number of mm, got 0"),
            std::string::npos);
  EXPECT_NE(error("params = { step_down = -1 }").find("got -1"), std::string::npos);
  EXPECT_NE(error("params = { levels = 5 }").find("'params.levels' must be an array of numbers"),
            std::string::npos);
  EXPECT_NE(error("params = { levels = [1, \"2\"] }").find("'params.levels' must be an array"),
            std::string::npos);
  EXPECT_NE(error("params = { levels = [1], tolerance = 0 }")
                .find("tolerance must be a positive number of mm, got 0"),
            std::string::npos);
  EXPECT_NE(error("params = { levels = [1], chunk_levels = 0 }")
                .find("'params.chunk_levels' must be a whole"),
            std::string::npos);
  EXPECT_NE(error("params = { levels = [nan] }").find("levels must be finite"), std::string::npos);
  // Scan's keys are not zlevel's.
  EXPECT_NE(
      error("params = { levels = [1], interval = 1 }").find("'params.interval' is not a known key"),
      std::string::npos);
  // An unknown operation lists zlevel among the known ones.
  const BatchSpec b =
      parse_batch_text("[[job]]\noperation = \"z-level\"\ninput = \"p\"\n", "/base", "jobs.toml");
  EXPECT_NE(b.jobs[0].error.find("\"zlevel\""), std::string::npos) << b.jobs[0].error;
}

}  // namespace
}  // namespace ncpath::jobs
