// Pieces traced twice kept once (kernels/cleanup/pencil.hpp: cusp_runs, uncovered_runs,
// close_loops), on polylines whose answer is known.
#include <gtest/gtest.h>

#include <vector>

#include "kernels/cleanup/pencil.hpp"

namespace ncpath {
namespace {

std::vector<Vec3> line(double x0, double x1, double step, double y = 0) {
  std::vector<Vec3> p;
  for (double x = x0; x <= x1 + 1e-12; x += step) p.push_back(Vec3(x, y, 0));
  return p;
}

TEST(PencilRetrace, CuspRunsCutWhereAPathTurnsBack) {
  // 0 -> 4, back to 2, on to 6 (along x, offset in y by 1e-3 to keep the points apart).
  const std::vector<Vec3> z{{0, 0, 0}, {2, 0, 0}, {4, 0, 0}, {3, 0.001, 0}, {2, 0.001, 0}, {4, 0.002, 0}, {6, 0, 0}};
  const std::vector<std::vector<Vec3>> paths{z, line(0, 3, 1)};
  const std::vector<PathRun> runs = cusp_runs(paths);
  ASSERT_EQ(runs.size(), 4u);
  EXPECT_EQ(runs[0].from, 0u);
  EXPECT_EQ(runs[0].to, 2u);  // up to the first turn, sharing it
  EXPECT_EQ(runs[1].from, 2u);
  EXPECT_EQ(runs[1].to, 4u);
  EXPECT_EQ(runs[2].from, 4u);
  EXPECT_EQ(runs[2].to, 6u);
  EXPECT_EQ(runs[3].path, 1u);  // a straight path is one run
  EXPECT_EQ(runs[3].to, 3u);
}

TEST(PencilRetrace, TheShorterOfTwoOverlappingPathsKeepsWhatTheLongerMisses) {
  // [0, 10] and [8, 14] along x, 0.005 apart in y: [8, 10] is traced twice.
  const std::vector<std::vector<Vec3>> paths{line(8, 14, 0.5, 0.005), line(0, 10, 0.5)};
  const std::vector<PathRun> runs = uncovered_runs(paths, 0.02, 0.7);
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_EQ(runs[0].path, 1u);  // the longer first, whole
  EXPECT_EQ(runs[0].from, 0u);
  EXPECT_EQ(runs[0].to, 20u);
  EXPECT_EQ(runs[1].path, 0u);  // then x = 10.5 ... 14 of the shorter
  EXPECT_EQ(paths[0][runs[1].from].x(), 10.5);
  EXPECT_EQ(runs[1].to, 12u);
  // Farther apart than eps, or crossing it: nothing is covered.
  EXPECT_EQ(uncovered_runs(std::vector<std::vector<Vec3>>{line(8, 14, 0.5, 0.05), line(0, 10, 0.5)},
                           0.02, 0.7).size(), 2u);
  std::vector<Vec3> across;
  for (double y = -3; y <= 3; y += 0.5) across.push_back(Vec3(5, y, 0));
  const std::vector<PathRun> crossing =
      uncovered_runs(std::vector<std::vector<Vec3>>{across, line(0, 10, 0.5)}, 0.02, 0.7);
  ASSERT_EQ(crossing.size(), 2u);
  EXPECT_EQ(crossing[1].to - crossing[1].from + 1, across.size());
}

TEST(PencilRetrace, APathWhoseEndsMeetIsClosed) {
  // A square of side 4 with a 0.3 mm gap in its first side; an open L, and a square whose
  // gap is at a corner (the ends' directions 90 degrees apart, as merge_paths would not join
  // them either), are left open.
  const std::vector<Vec3> sq{{1, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}, {0, 0, 0}, {0.7, 0, 0}};
  std::vector<std::vector<Vec3>> paths{sq,
                                       {{0, 0, 0}, {4, 0, 0}, {4, 4, 0}},
                                       {{0.3, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}, {0, 0, 0}}};
  close_loops(paths, 1.0, 0.5);
  ASSERT_EQ(paths[0].size(), 7u);
  EXPECT_EQ(paths[0].back(), paths[0].front());
  EXPECT_EQ(paths[1].size(), 3u);
  EXPECT_EQ(paths[2].size(), 5u);
}

}  // namespace
}  // namespace ncpath
