// batch/cli/progress_bar: the time left, extrapolated at the pace so far.
#include <gtest/gtest.h>

#include "batch/cli/progress_bar.hpp"

namespace ncpath::cli {
namespace {

TEST(ProgressBar, EtaExtrapolatesThePaceSoFar) {
  EXPECT_EQ(eta_text(10, 1, 4), "ETA 30s");      // 10 s a unit, 3 left
  EXPECT_EQ(eta_text(30, 1, 4), "ETA 1m30s");
  EXPECT_EQ(eta_text(3600, 1, 3), "ETA 2h00m");
  EXPECT_EQ(eta_text(2, 50, 100), "ETA 2s");
  EXPECT_EQ(eta_text(5, 0, 10), "");              // no pace yet
  EXPECT_EQ(eta_text(5, 10, 10), "");             // done
}

}  // namespace
}  // namespace ncpath::cli
