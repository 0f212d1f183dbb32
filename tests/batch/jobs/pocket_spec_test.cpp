// Pocket jobs in batch files: every key, the defaults, and bad values named by key.
#include <gtest/gtest.h>

#include "batch/jobs/job_spec.hpp"

namespace ncpath::jobs {
namespace {

JobSpec pocket_job(const std::string& params, const std::string& extra = "") {
  const BatchSpec b =
      parse_batch_text("[[job]]\noperation = \"pocket\"\ninput = \"p.dxf\"\ntool = \"flat:6\"\n" +
                           params + "\n" + extra,
                       "/base", "jobs.toml");
  return b.jobs.at(0);
}

TEST(PocketSpec, ParsesEveryKey) {
  const JobSpec j = pocket_job(
      "params = { stepover = \"40%\", depth = 10, stepdown = 2, stock = 0.2, tolerance = 0.02, "
      "join_tolerance = 1e-3, order = \"inward\", milling = \"conventional\", "
      "helix_radius = 1.2, ramp_angle = 5, clearance = 2 }");
  ASSERT_EQ(j.error, "");
  EXPECT_EQ(j.operation, Operation::kPocket);
  EXPECT_EQ(j.input, "/base/p.dxf");
  const PocketParams& p = j.pocket;
  EXPECT_DOUBLE_EQ(p.stepover, 2.4);
  EXPECT_EQ(p.depth, 10);
  EXPECT_EQ(p.stepdown, 2);
  EXPECT_EQ(p.stock, 0.2);
  EXPECT_EQ(p.tolerance, 0.02);
  EXPECT_EQ(p.join_tolerance, 1e-3);
  EXPECT_EQ(p.order, CutOrder::kInward);
  EXPECT_EQ(p.milling, Milling::kConventional);
  EXPECT_EQ(p.helix_radius, 1.2);
  EXPECT_EQ(p.ramp_angle, 5);
  EXPECT_EQ(p.clearance, 2);
  const std::string json = params_json(j);
  for (const char* s :
       {"\"operation\":\"pocket\"", "\"order\":\"inward\"", "\"milling\":\"conventional\"",
        "\"ramp_angle\":5.0", "\"clearance\":2.0", "\"stepdown\":2.0", "\"helix_radius\":1.2"})
    EXPECT_NE(json.find(s), std::string::npos) << s << " in " << json;
}

// The job-level `units` key: a unit name for profile jobs (echoed in the params), refused
// with the accepted names when unknown, and refused on mesh jobs (whose files have no units).
TEST(PocketSpec, UnitsKey) {
  const JobSpec inch = pocket_job("params = { depth = 2 }", "units = \"in\"");
  ASSERT_EQ(inch.error, "");
  ASSERT_TRUE(inch.units);
  EXPECT_EQ(inch.units->name, "inch");
  EXPECT_EQ(inch.units->mm_per_unit, 25.4);
  EXPECT_NE(params_json(inch).find("\"units\":\"inch\""), std::string::npos);
  const JobSpec drawing = pocket_job("params = { depth = 2 }");
  EXPECT_FALSE(drawing.units);
  EXPECT_NE(params_json(drawing).find("\"units\":\"drawing\""), std::string::npos);
  const JobSpec bad = pocket_job("params = { depth = 2 }", "units = \"furlong\"");
  EXPECT_NE(bad.error.find("units"), std::string::npos) << bad.error;
  EXPECT_NE(bad.error.find("must be one of mm, cm"), std::string::npos) << bad.error;
  const BatchSpec mesh = parse_batch_text(
      "[[job]]\noperation = \"raster\"\ninput = \"m.stl\"\ntool = \"ball:6\"\nunits = \"inch\"\n",
      "/base", "jobs.toml");
  EXPECT_NE(mesh.jobs.at(0).error.find("applies to profile drawings"), std::string::npos)
      << mesh.jobs.at(0).error;
}

TEST(PocketSpec, DefaultsAreHalfTheDiameterOnePassAndClimbOutward) {
  const JobSpec j = pocket_job("params = { depth = 3 }");
  ASSERT_EQ(j.error, "");
  EXPECT_EQ(j.pocket.stepover, 3);  // 50% of flat:6
  EXPECT_EQ(j.pocket.stepdown, 0);
  EXPECT_EQ(j.pocket.order, CutOrder::kOutward);
  EXPECT_EQ(j.pocket.milling, Milling::kClimb);
  EXPECT_EQ(j.pocket.ramp_angle, 3);
  EXPECT_EQ(j.pocket.clearance, 1);
  EXPECT_NE(params_json(j).find("\"safe_z\":5.0"), std::string::npos);
  // The G-code table's safe height is the pocket's rapid height.
  const JobSpec g =
      pocket_job("params = { depth = 3 }", "gcode = { path = \"p.ngc\", safe_z = 12 }");
  ASSERT_EQ(g.error, "");
  EXPECT_NE(params_json(g).find("\"safe_z\":12.0"), std::string::npos);
}

TEST(PocketSpec, BadValuesAreNamed) {
  auto error = [](const std::string& params) {
    const JobSpec j = pocket_job(params);
    EXPECT_EQ(j.error_status, "invalid_parameter") << params;
    return j.error;
  };
  EXPECT_NE(error("").find("'params.depth' is required"), std::string::npos);
  EXPECT_NE(error("params = { stepover = 2 }").find("'params.depth' is required"),
            std::string::npos);
  EXPECT_NE(error("params = { depth = -1 }").find("depth must be a positive number"),
            std::string::npos);
  EXPECT_NE(error("params = { depth = 1, stepover = 0 }").find("stepover must be a positive"),
            std::string::npos);
  EXPECT_NE(error("params = { depth = 1, stepover = \"120%\" }")
                .find("stepover 7.2 mm is larger than the tool diameter 6 mm"),
            std::string::npos);
  EXPECT_NE(error("params = { depth = 1, stepdown = -1 }").find("stepdown must be >= 0"),
            std::string::npos);
  EXPECT_NE(error("params = { depth = 1, order = \"sideways\" }")
                .find("'params.order' must be \"outward\" or \"inward\""),
            std::string::npos);
  EXPECT_NE(error("params = { depth = 1, milling = \"up\" }").find("'params.milling'"),
            std::string::npos);
  EXPECT_NE(error("params = { depth = 1, ramp_angle = 0 }").find("ramp_angle must be in (0, 90)"),
            std::string::npos);
  EXPECT_NE(error("params = { depth = 1, helix_radius = -2 }").find("helix_radius must be >= 0"),
            std::string::npos);
  EXPECT_NE(error("params = { depth = 1, clearance = -1 }").find("clearance must be >= 0"),
            std::string::npos);
  EXPECT_NE(
      error("params = { depth = 1, interval = 2 }").find("'params.interval' is not a known key"),
      std::string::npos);
  EXPECT_NE(error("params = { depth = \"deep\" }").find("'params.depth' must be a number"),
            std::string::npos);
  // The operation's own name is in the list of operations.
  const BatchSpec b =
      parse_batch_text("[[job]]\noperation = \"pockets\"\ninput = \"p\"\n", "/base", "jobs.toml");
  EXPECT_NE(b.jobs[0].error.find("\"pocket\""), std::string::npos);
}

}  // namespace
}  // namespace ncpath::jobs
