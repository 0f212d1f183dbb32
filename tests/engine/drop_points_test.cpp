#include "engine/drop_points.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "engine/drop_index.hpp"
#include "tests/support/meshes.hpp"

namespace ncpath {
namespace {

TEST(DropPoints, SameOrderAndMissesAreFlaggedNotInvented) {
  const TriangleMesh mesh = test::height_field(10, 20, [](double x, double) { return 0.1 * x; });
  const std::vector<double> xy = {5, 5, 100, 100, 10, 3, -50, 0, 19, 19};
  const std::vector<std::uint32_t> paths = {3, 2};
  ClChunk got;
  RunControl control;
  const DropPointsStats st = run_drop_points(
      mesh, ball_cutter(2), xy, paths, [&](const ClChunk& c) { got.append(c); }, control);
  EXPECT_EQ(st.points, 5u);
  EXPECT_EQ(st.no_contact, 2u);
  EXPECT_EQ(got.path_sizes, paths);
  const FacetTable table = build_facet_table(mesh);
  for (int k = 0; k < 5; ++k) {
    EXPECT_EQ(got.xyz[3 * k], xy[2 * k]);
    EXPECT_EQ(got.xyz[3 * k + 1], xy[2 * k + 1]);
    const CutterContact bf = drop_brute_force(table, ball_cutter(2), xy[2 * k], xy[2 * k + 1]);
    if (bf.kind == ContactKind::kNone) {
      EXPECT_TRUE(std::isnan(got.xyz[3 * k + 2]));
      EXPECT_EQ(got.contact[k], 0);
    } else {
      EXPECT_NEAR(got.xyz[3 * k + 2], bf.tip_z, 1e-9);
      EXPECT_NE(got.contact[k], 0);
    }
  }
  // Analytic: plane z = 0.1 x, ball R = 1: tip = z + R / cos(a) - R.
  EXPECT_NEAR(got.xyz[2], 0.5 + std::sqrt(1.01) - 1, 1e-9);
}

}  // namespace
}  // namespace ncpath
