// The warning an ok job carries (batch/jobs/job_runner.hpp open_chain_warning): z-level
// contour chains that could not be closed are named with their count and statistic; none, a
// zero count or a statistic of another type give no warning.
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

}  // namespace
}  // namespace ncpath::jobs
