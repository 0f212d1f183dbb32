// The bounds the raster uses to skip facets are true upper bounds, and clustering keeps
// every facet exactly once.
#include "engine/facet_clusters.hpp"

#include <gtest/gtest.h>

#include <random>

#include "tests/support/meshes.hpp"

namespace ncpath {
namespace {

TEST(FacetClusters, EveryFacetOnceAndBoxesContainTheirFacets) {
  const FacetTable table = build_facet_table(test::random_soup(5000, 100, 30, 3, 4));
  const ClusteredFacets c = cluster_facets(table, ball_cutter(5), 16);
  ASSERT_EQ(c.facets.size(), table.facets.size());
  std::vector<int> seen(table.facets.size());
  for (const ClusterBound& cb : c.clusters) {
    ASSERT_LE(cb.count, 16u);
    for (std::uint32_t k = cb.first; k < cb.first + cb.count; ++k) {
      const FacetBound& f = c.facets[k];
      ++seen[f.facet];
      EXPECT_LE(f.top_z, cb.top_z);
      EXPECT_GE(f.x_lo, cb.x_lo);
      EXPECT_LE(f.x_hi, cb.x_hi);
      EXPECT_GE(f.y_lo, cb.y_lo);
      EXPECT_LE(f.y_hi, cb.y_hi);
      if (k > cb.first) {
        EXPECT_GE(c.facets[k - 1].top_z, f.top_z);  // highest first
      }
    }
  }
  for (int s : seen) EXPECT_EQ(s, 1);
}

// The linear tangent-plane bound is never below the kernel's answer for that facet.
TEST(FacetClusters, PlaneBoundIsAnUpperBound) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> U(-6, 6);
  for (const Cutter& c : {ball_cutter(6), flat_cutter(6), bull_nose_cutter(6, 1)}) {
    int contacts = 0;
    for (int i = 0; i < 20000; ++i) {
      PreparedFacet f;
      if (!prepare_facet({U(rng), U(rng), U(rng)}, {U(rng), U(rng), U(rng)},
                         {U(rng), U(rng), U(rng)}, f))
        continue;
      const double x = U(rng) * 0.6, y = U(rng) * 0.6;
      CutterContact best;
      if (!drop_facet(c, f, x, y, 0, best)) continue;
      ++contacts;
      const FacetBound b = facet_bound(f, c, 0);
      EXPECT_GE(b.plane_a * x + b.plane_b * y + b.plane_c, best.tip_z - 1e-12)
          << cutter_type_name(c.type);
      EXPECT_GE(b.top_z, best.tip_z);
    }
    EXPECT_GT(contacts, 5000);
  }
}

}  // namespace
}  // namespace ncpath
