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
    const DropIndex index(mesh, c, DropIndex::Facets::kOnDemand);
    const DropIndex stored(mesh, c, DropIndex::Facets::kPrepared);
    ASSERT_EQ(index.facet_count(), table.facets.size());
    ASSERT_EQ(index.degenerate(), table.degenerate);
    int touched = 0;
    for (int i = 0; i < points; ++i) {
      const double x = X(rng), y = Y(rng);
      const CutterContact fast = index.query(x, y);
      const CutterContact slow = drop_brute_force(table, c, x, y);
      ASSERT_EQ(fast.kind == ContactKind::kNone, slow.kind == ContactKind::kNone)
          << cutter_type_name(c.type) << " at " << x << "," << y;
      // Facets prepared on demand or stored: the same bits and the same facet.
      const CutterContact kept = stored.query(x, y);
      ASSERT_EQ(kept.kind, fast.kind);
      if (slow.kind == ContactKind::kNone) continue;
      ++touched;
      ASSERT_NEAR(fast.tip_z, slow.tip_z, 1e-9) << cutter_type_name(c.type) << " " << x << "," << y;
      ASSERT_EQ(kept.tip_z, fast.tip_z);
      ASSERT_EQ(kept.facet, fast.facet);
      // The contact's facet is the mesh's: alone, it gives that height.
      ASSERT_LT(fast.facet, mesh.facets.size());
      const auto& v = mesh.facets[fast.facet];
      PreparedFacet f;
      ASSERT_TRUE(prepare_facet(mesh.vertices[v[0]], mesh.vertices[v[1]], mesh.vertices[v[2]], f));
      CutterContact alone;
      ASSERT_TRUE(drop_facet(c, f, x, y, fast.facet, alone));
      ASSERT_EQ(alone.tip_z, fast.tip_z);
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

// Two indexes preparing facets on demand, queried in turn on one thread (their facets share
// the thread's cache, by primitive number): each still answers for its own mesh.
TEST(DropIndex, InterleavedOnDemandIndexesKeepTheirOwnFacets) {
  const TriangleMesh m1 = test::random_height_field(40, 60, 8, 11);
  const TriangleMesh m2 = test::random_height_field(40, 60, 8, 12);
  const FacetTable t1 = build_facet_table(m1), t2 = build_facet_table(m2);
  const Cutter ball = ball_cutter(5);
  const DropIndex i1(m1, ball, DropIndex::Facets::kOnDemand);
  const DropIndex i2(m2, ball, DropIndex::Facets::kOnDemand);
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> X(0, 60);
  for (int k = 0; k < 2000; ++k) {
    const double x = X(rng), y = X(rng);
    ASSERT_EQ(i1.query(x, y).tip_z, drop_brute_force(t1, ball, x, y).tip_z) << x << "," << y;
    ASSERT_EQ(i2.query(x, y).tip_z, drop_brute_force(t2, ball, x, y).tip_z) << x << "," << y;
  }
}

// Degenerate facets among the others: left out, and the contacts still name mesh facets.
TEST(DropIndex, EqualsBruteForceWithDegenerateFacets) {
  TriangleMesh mesh = test::random_soup(2000, 60, 20, 4, 5);
  const std::size_t n = mesh.facets.size();
  for (std::size_t i = 0; i < n; i += 7) {
    const auto f = mesh.facets[i];
    mesh.facets.insert(mesh.facets.begin() + static_cast<std::ptrdiff_t>(i), {f[0], f[1], f[1]});
  }
  ASSERT_GT(mesh.facets.size(), n);
  expect_index_matches_brute_force(mesh, 5000, 6);
}

// Every cutter on a tessellated hemisphere of radius S. Analytic answer for the true
// sphere: the cutter is a flat disc of radius a = R - r grown by a ball of radius r, so it
// touches the sphere grown by r: tip = S when rho <= a, else sqrt((S+r)^2 - (rho-a)^2) - r
// (ball: a = 0; flat: r = 0). The polyhedron lies inside the sphere and outside the sphere
// shrunk by its sagitta, so the drop height is bracketed by the two.
double sphere_tip(double S, const Cutter& c, double rho) {
  const double r = c.corner_radius, a = c.radius - r;
  if (rho <= a) return S;
  return std::sqrt((S + r) * (S + r) - (rho - a) * (rho - a)) - r;
}

TEST(DropIndex, EveryCutterOnHemisphereBracketedByAnalyticSpheres) {
  const double S = 30;
  const TriangleMesh mesh = test::hemisphere(S, 60, 240);
  const FacetTable table = build_facet_table(mesh);
  // Sagitta of the coarsest facet: its circumradius is at most the sum of a ring chord and
  // a meridian arc.
  const double edge = 2 * S * std::sin(M_PI / 240) + S * (M_PI / 2) / 60;
  const double sag = S - std::sqrt(S * S - edge * edge);
  for (const Cutter& c : {ball_cutter(5), flat_cutter(5), bull_nose_cutter(5, 1)}) {
    const DropIndex index(mesh, c);
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> U(-20, 20);
    for (int i = 0; i < 5000; ++i) {
      const double x = U(rng), y = U(rng), rho = std::hypot(x, y);
      const CutterContact got = index.query(x, y);
      EXPECT_LE(got.tip_z, sphere_tip(S, c, rho) + 1e-9) << cutter_type_name(c.type);
      EXPECT_GE(got.tip_z, sphere_tip(S - sag, c, rho) - 1e-9) << cutter_type_name(c.type);
    }
  }
}

// No gouge, checked by exact point-triangle distances: the ball's centre is at least R
// from every facet, and exactly R from the facet it touches.
TEST(DropIndex, BallNeverPenetratesAnyFacet) {
  const TriangleMesh mesh = test::random_height_field(30, 40, 6, 9);
  const FacetTable table = build_facet_table(mesh);
  const double R = 2.5;
  const DropIndex index(mesh, ball_cutter(2 * R));
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
    const DropIndex index(mesh, c);
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
