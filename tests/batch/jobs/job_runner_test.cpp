// The warnings an ok job carries (batch/jobs/job_runner.hpp): z-level contour chains that
// could not be closed are named with their count and statistic (none, a zero count or a
// statistic of another type give no warning); the input's guesses come first; a job without
// points says that nothing was cut and why.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "batch/jobs/job_runner.hpp"

namespace ncpath::jobs {
namespace {

using out::StatValue;

TEST(JobRunner, NoOpenChainsNoWarning) {
  EXPECT_EQ(open_chain_warning({}), "");
  EXPECT_EQ(open_chain_warning({{"levels", std::int64_t{12}, ""},
                                {"open_chains", std::int64_t{0}, ""}}),
            "");
  // Only integer counts are counts.
  EXPECT_EQ(open_chain_warning({{"open_chains", 3.0, ""}}), "");
}

TEST(JobRunner, OpenChainsAreNamedWithTheirCount) {
  const std::string z = open_chain_warning(
      {{"levels", std::int64_t{12}, ""}, {"open_chains", std::int64_t{3}, ""}});
  EXPECT_EQ(z.rfind("warning: 3 z-level contour chain(s)", 0), 0u) << z;
  EXPECT_NE(z.find("stats/open_chains"), std::string::npos) << z;
  const std::string p = open_chain_warning({{"zlevel_open_chains", std::int64_t{1}, ""}});
  EXPECT_EQ(p.rfind("warning: 1 z-level contour chain(s)", 0), 0u) << p;
  EXPECT_NE(p.find("stats/zlevel_open_chains"), std::string::npos) << p;
}

TEST(JobRunner, InputWarningsComeFirstAndOnlyAsStrings) {
  EXPECT_EQ(ok_job_warning({}), "");
  EXPECT_EQ(ok_job_warning({{"input_warning", std::int64_t{1}, ""}}), "");
  EXPECT_EQ(ok_job_warning({{"input_warning", std::string("read as mm"), ""}}),
            "warning: read as mm");
  const std::string both = ok_job_warning({{"open_chains", std::int64_t{2}, ""},
                                           {"input_warning", std::string("read as mm"), ""}});
  EXPECT_EQ(both.rfind("warning: read as mm; warning: 2 z-level", 0), 0u) << both;
}

TEST(JobRunner, NothingToCutSaysWhyForTheOperation) {
  JobSpec job;
  job.operation = Operation::kOffset;
  job.tool = flat_cutter(2);
  EXPECT_EQ(nothing_to_cut_warning(job),
            "warning: nothing to cut (0 points): the tool (diameter 2 mm, with its stock) fits "
            "in none of the profile's regions");
  job.operation = Operation::kPencil;
  EXPECT_NE(nothing_to_cut_warning(job).find("no concave crease"), std::string::npos);
}

}  // namespace
}  // namespace ncpath::jobs
