// The Embree-accelerated drop equals the brute-force scan, and never gouges.
#include "engine/drop_index.hpp"

#include <gtest/gtest.h>

#include <random>

#include "tests/support/meshes.hpp"
#include "tests/support/oracle.hpp"

namespace ncpath {
namespace {

const Cutter kCutters[] = {ball_cutter(5), flat_cutter(5), bull_nose_cutter(5, 1)};

void expect_index_matches_brute_force(const TriangleMesh& mesh, int points, unsigned seed) {
  const FacetTable table = build_facet_table(mesh);
  std::mt19937_64 rng(seed);
  const Aabb3 box = table.box;
  std::uniform_real_distribution<double> X(box.lo.x() - 3, box.hi.x() + 3);
  std::uniform_real_distribution<double> Y(box.lo.y() - 3, box.hi.y() + 3);
  for (const Cutter& c : kCutters) {
    const DropIndex index(table, c);
    int touched = 0;
    for (int i = 0; i < points; ++i) {
      const double x = X(rng), y = Y(rng);
      const CutterContact fast = index.query(x, y);
      const CutterContact slow = drop_brute_force(table, c, x, y);
      ASSERT_EQ(fast.kind == ContactKind::kNone, slow.kind == ContactKind::kNone)
          << cutter_type_name(c.type) << " at " << x << "," << y;
      if (slow.kind == ContactKind::kNone) continue;
      ++touched;
      ASSERT_NEAR(fast.tip_z, slow.tip_z, 1e-9) << cutter_type_name(c.type) << " " << x << ","
                                                << y;
    }
    EXPECT_GT(touched, points / 2);
  }
}

TEST(DropIndex, EqualsBruteForceOnRandomHeightField) {
  expect_index_matches_brute_force(test::random_height_field(40, 60, 8, 1), 10000, 2);
}

TEST(DropIndex, EqualsBruteForceOnRandomSoup) {
  expect_index_matches_brute_force(test::random_soup(3000, 60, 20, 4, 3), 10000, 4);
}

// Ball on a tessellated hemisphere of radius S: the exact answer for the true sphere is
// sqrt((S+R)^2 - rho^2) - R; the polyhedron lies inside the sphere and outside the sphere
// shrunk by its sagitta, so the drop height is bracketed by the two.
TEST(DropIndex, BallOnHemisphereBracketedByAnalyticSpheres) {
  const double S = 30, R = 2.5;
  const TriangleMesh mesh = test::hemisphere(S, 60, 240);
  const FacetTable table = build_facet_table(mesh);
  const DropIndex index(table, ball_cutter(2 * R));
  // Sagitta of the coarsest facet: circumradius of the largest triangle bounds it.
  const double edge = 2 * S * std::sin(M_PI / 240) * 1.0 + S * (M_PI / 2) / 60;
  const double sag = S - std::sqrt(S * S - edge * edge);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> U(-20, 20);
  for (int i = 0; i < 5000; ++i) {
    const double x = U(rng), y = U(rng), rho = std::hypot(x, y);
    const CutterContact c = index.query(x, y);
    const double upper = std::sqrt((S + R) * (S + R) - rho * rho) - R;
    const double lower = std::sqrt((S - sag + R) * (S - sag + R) - rho * rho) - R;
    EXPECT_LE(c.tip_z, upper + 1e-9);
    EXPECT_GE(c.tip_z, lower - 1e-9);
  }
}

// No gouge, checked by exact point-triangle distances: the ball's centre is at least R
// from every facet, and exactly R from the facet it touches.
TEST(DropIndex, BallNeverPenetratesAnyFacet) {
  const TriangleMesh mesh = test::random_height_field(30, 40, 6, 9);
  const FacetTable table = build_facet_table(mesh);
  const double R = 2.5;
  const DropIndex index(table, ball_cutter(2 * R));
  std::mt19937_64 rng(6);
  std::uniform_real_distribution<double> U(0, 40);
  for (int i = 0; i < 2000; ++i) {
    const double x = U(rng), y = U(rng);
    const CutterContact c = index.query(x, y);
    ASSERT_NE(c.kind, ContactKind::kNone);
    const Vec3 centre{x, y, c.tip_z + R};
    double nearest = 1e300;
    for (const PreparedFacet& f : table.facets)
      nearest = std::min(nearest, test::point_triangle_distance(centre, f.p[0], f.p[1], f.p[2]));
    EXPECT_NEAR(nearest, R, 1e-9);
  }
}

// No gouge for the flat and bull-nose cutters: no point of any facet asks for a higher tip
// (vertices, golden-section edges and interior samples of every facet in reach).
TEST(DropIndex, FlatAndBullNeverGouge) {
  const TriangleMesh mesh = test::random_height_field(16, 30, 6, 12);
  const FacetTable table = build_facet_table(mesh);
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> U(0, 30);
  for (const Cutter& c : {flat_cutter(5), bull_nose_cutter(5, 1)}) {
    const DropIndex index(table, c);
    for (int i = 0; i < 300; ++i) {
      const double x = U(rng), y = U(rng);
      const CutterContact got = index.query(x, y);
      double need = -1e300;
      for (const PreparedFacet& f : table.facets)
        need = std::max(need, test::tip_lower_bound(c.radius, c.corner_radius, f.p[0], f.p[1],
                                                    f.p[2], x, y, 12));
      EXPECT_GE(got.tip_z, need - 1e-9) << cutter_type_name(c.type);
      // And it is not too high: its contact point lies on a facet and touches the tool.
      double on_mesh = 1e300;
      for (const PreparedFacet& f : table.facets)
        on_mesh = std::min(on_mesh, test::point_triangle_distance(got.cc, f.p[0], f.p[1], f.p[2]));
      EXPECT_LT(on_mesh, 1e-9);
      EXPECT_NEAR(test::tip_for_point(c.radius, c.corner_radius, got.cc, x, y), got.tip_z, 1e-9);
    }
  }
}

}  // namespace
}  // namespace ncpath
