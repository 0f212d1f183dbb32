// pocket3d jobs in batch files: every key, the defaults (eps, delta, the profile tolerance
// that follows eps), the surface path, the ball-only tool, and bad values named by key.
#include <gtest/gtest.h>

#include "batch/jobs/job_spec.hpp"

namespace ncpath::jobs {
namespace {

JobSpec pocket3d_job(const std::string& params, const std::string& tool = "ball:12",
                     const std::string& surface = "surface = \"bottom.toml\"\n") {
  const BatchSpec b = parse_batch_text("[[job]]\noperation = \"pocket3d\"\ninput = \"p.toml\"\n" +
                                           surface + "tool = \"" + tool + "\"\n" + params,
                                       "/base/jobs", "jobs.toml");
  return b.jobs.at(0);
}

TEST(Pocket3dSpec, ParsesEveryKey) {
  const JobSpec j = pocket3d_job(
      "params = { scallop = 0.4, eps = 0.5, delta = 0.25, stock = 0.3, tolerance = 0.02, "
      "join_tolerance = 1e-3, order = \"inward\", milling = \"conventional\", clearance = 2, "
      "min_interval = 0.1 }",
      "ball:12", "surface = \"../surfaces/bottom.toml\"\n");
  ASSERT_EQ(j.error, "");
  EXPECT_EQ(j.operation, Operation::kPocket3d);
  EXPECT_EQ(j.input, "/base/jobs/p.toml");
  EXPECT_EQ(j.surface, "/base/surfaces/bottom.toml");  // relative to the batch file
  const Pocket3dJobParams& p = j.pocket3d;
  EXPECT_EQ(p.scallop, 0.4);
  EXPECT_EQ(p.eps, 0.5);
  EXPECT_EQ(p.delta, 0.25);
  EXPECT_EQ(p.stock, 0.3);
  EXPECT_EQ(p.tolerance, 0.02);
  EXPECT_EQ(p.join_tolerance, 1e-3);
  EXPECT_EQ(p.order, CutOrder::kInward);
  EXPECT_EQ(p.milling, Milling::kConventional);
  EXPECT_EQ(p.clearance, 2);
  EXPECT_EQ(p.min_interval, 0.1);
  const std::string json = params_json(j);
  for (const char* s : {"\"operation\":\"pocket3d\"", "\"surface\":\"/base/surfaces/bottom.toml\"",
                        "\"scallop\":0.4", "\"eps\":0.5", "\"delta\":0.25", "\"order\":\"inward\"",
                        "\"milling\":\"conventional\"", "\"min_interval\":0.1", "\"safe_z\":5.0"})
    EXPECT_NE(json.find(s), std::string::npos) << s << " in " << json;
}

TEST(Pocket3dSpec, DefaultsAreHundredthsOfAMillimetreAndTheToleranceFollowsEps) {
  const JobSpec j = pocket3d_job("params = { scallop = 0.05 }");
  ASSERT_EQ(j.error, "");
  EXPECT_EQ(j.pocket3d.eps, 0.01);
  EXPECT_EQ(j.pocket3d.delta, 0.01);
  EXPECT_EQ(j.pocket3d.tolerance, 0.0025);  // min(0.01, eps / 4)
  EXPECT_EQ(j.pocket3d.stock, 0);
  EXPECT_EQ(j.pocket3d.order, CutOrder::kOutward);
  EXPECT_EQ(j.pocket3d.milling, Milling::kClimb);
  EXPECT_EQ(j.pocket3d.clearance, 1);
  EXPECT_EQ(j.pocket3d.min_interval, 0);
  EXPECT_EQ(pocket3d_job("params = { scallop = 0.4, eps = 0.5 }").pocket3d.tolerance, 0.01);
  EXPECT_EQ(pocket3d_job("params = { scallop = 0.4, eps = 0.02 }").pocket3d.tolerance, 0.005);
}

TEST(Pocket3dSpec, BadValuesAreNamed) {
  auto error = [](const std::string& params, const std::string& tool = "ball:12",
                  const std::string& surface = "surface = \"b.toml\"\n") {
    const JobSpec j = pocket3d_job(params, tool, surface);
    EXPECT_EQ(j.error_status, "invalid_parameter") << params;
    return j.error;
  };
  EXPECT_NE(error("").find("'params.scallop' is required"), std::string::npos);
  EXPECT_NE(error("params = { eps = 0.5 }").find("'params.scallop' is required"),
            std::string::npos);
  EXPECT_NE(error("params = { scallop = 0.4 }", "ball:12", "").find("'surface' is required"),
            std::string::npos);
  EXPECT_NE(error("params = { scallop = 0.4 }", "flat:12").find("needs a ball-end mill"),
            std::string::npos);
  EXPECT_NE(error("params = { scallop = 0.4 }", "bull:12:2").find("got a bullnose cutter"),
            std::string::npos);
  EXPECT_NE(error("params = { scallop = 6 }").find("between 0 and the ball radius 6 mm"),
            std::string::npos);
  EXPECT_NE(error("params = { scallop = 0 }").find("scallop must be"), std::string::npos);
  EXPECT_NE(error("params = { scallop = 0.4, eps = 0 }").find("eps (plan tolerance) must be"),
            std::string::npos);
  EXPECT_NE(error("params = { scallop = 0.4, delta = -1 }").find("delta (surface tolerance)"),
            std::string::npos);
  EXPECT_NE(error("params = { scallop = 0.4, stock = -1 }").find("stock must be >= 0"),
            std::string::npos);
  EXPECT_NE(error("params = { scallop = 0.4, tolerance = 0 }").find("tolerance must be a positive"),
            std::string::npos);
  EXPECT_NE(error("params = { scallop = 0.4, clearance = -1 }").find("clearance must be >= 0"),
            std::string::npos);
  EXPECT_NE(error("params = { scallop = 0.4, min_interval = -1 }").find("min_interval must be"),
            std::string::npos);
  EXPECT_NE(error("params = { scallop = 0.4, order = \"up\" }").find("'params.order' must be"),
            std::string::npos);
  EXPECT_NE(error("params = { scallop = 0.4, depth = 2 }").find("'params.depth' is not a known"),
            std::string::npos);
  // `surface` belongs to pocket3d only.
  const BatchSpec b = parse_batch_text(
      "[[job]]\noperation = \"pocket\"\ninput = \"p.toml\"\nsurface = \"b.toml\"\n"
      "tool = \"flat:6\"\nparams = { depth = 2 }\n",
      "/base", "jobs.toml");
  EXPECT_NE(b.jobs[0].error.find("'surface' is not a known key"), std::string::npos)
      << b.jobs[0].error;
  const BatchSpec c =
      parse_batch_text("[[job]]\noperation = \"pocket4d\"\ninput = \"p\"\n", "/base", "jobs.toml");
  EXPECT_NE(c.jobs[0].error.find("\"pocket3d\""), std::string::npos);
}

}  // namespace
}  // namespace ncpath::jobs
