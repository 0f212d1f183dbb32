// kernels/surface/surface_drop: analytic drops (inclined plane, sphere caps, a vault and a
// trough, a ball hanging over the border) and a brute-force oracle (dense samples plus local
// zoom) on random wavy bicubic surfaces with creases and concave regions tighter than the
// ball, including the check that no sample point lies inside the ball.
#include "kernels/surface/surface_drop.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "tests/kernels/surface/surface_test_util.hpp"

namespace ncpath {
namespace {

constexpr double kTol = 1e-9;

// Checks the contact's own consistency: cc on the surface at (u, v), centre = cc + R n on the
// tool axis, |n| = 1 and n_z >= 0.
void expect_consistent(const SurfaceDrop& d, const SurfaceContact& c, const Vec2& q, double r) {
  ASSERT_TRUE(c.found);
  EXPECT_NEAR((surface_point(d.surface(), c.u, c.v) - c.cc).norm(), 0, 1e-9);
  EXPECT_NEAR(c.normal.norm(), 1, 1e-9);
  EXPECT_GE(c.normal.z(), -1e-12);
  const Vec3 centre = c.cc + r * c.normal;
  EXPECT_NEAR(centre.x(), q.x(), 1e-9);
  EXPECT_NEAR(centre.y(), q.y(), 1e-9);
  EXPECT_NEAR(centre.z(), c.tip_z + r, 1e-9);
}

NurbsSurface inclined_plane(double a, double b, double c, bool rational) {
  // Bicubic 2 x 2 grid over [-50, 50]^2 on z = a x + b y + c, control points moved within the
  // plane (a non-uniform parameterisation) and, if rational, random weights.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> J(-3, 3), W(0.5, 2);
  std::vector<Vec3> ctrl;
  for (int i = 0; i < 7; ++i)
    for (int j = 0; j < 7; ++j) {
      const double x = -50 + 100.0 * i / 6 + (i % 6 ? J(rng) : 0);
      const double y = -50 + 100.0 * j / 6 + (j % 6 ? J(rng) : 0);
      ctrl.emplace_back(x, y, a * x + b * y + c);
    }
  NurbsSurface s = bezier_grid_surface(2, 2, ctrl);
  if (rational)
    for (double& w : s.weights) w = W(rng);
  return s;
}

TEST(SurfaceDrop, InclinedPlaneClosedForm) {
  // Ball on the plane z = a x + b y + c: the centre is cc + R n with n = (-a, -b, 1) / k,
  // k = sqrt(1 + a^2 + b^2), so it stands R k above the plane on the axis:
  // tip = a x + b y + c + R (k - 1).
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-30, 30);
  for (bool rational : {false, true})
    for (auto [a, b] : {std::pair{0.0, 0.0}, {0.3, -0.2}, {1.5, 0.7}}) {
      const SurfaceDrop d(inclined_plane(a, b, 2.5, rational));
      const double k = std::sqrt(1 + a * a + b * b);
      for (double r : {0.5, 3.0, 6.0})
        for (int i = 0; i < 40; ++i) {
          const Vec2 q(U(rng), U(rng));
          const SurfaceContact c = d.drop(q, r);
          EXPECT_NEAR(c.tip_z, a * q.x() + b * q.y() + 2.5 + r * (k - 1), kTol)
              << a << " " << b << " r=" << r;
          EXPECT_NEAR((c.normal - Vec3(-a, -b, 1) / k).norm(), 0, 1e-9);
          expect_consistent(d, c, q, r);
        }
    }
}

TEST(SurfaceDrop, SphereCapsConvexAndConcave) {
  // Dome of radius rho > R: the centre is at rho + R from the sphere's centre. Bowl (lower
  // hemisphere) of radius rho > R: the ball sits inside, its centre at rho - R from it.
  std::mt19937 rng(11);
  const double rho = 20, r = 6;
  const SurfaceDrop dome(test::hemisphere(rho, 1)), bowl(test::hemisphere(rho, -1));
  std::uniform_real_distribution<double> A(0, 2 * std::numbers::pi), U(0, 1);
  for (int i = 0; i < 200; ++i) {
    const double a = A(rng);
    // Dome: any axis within rho + R of the centre; include the pole region (i < 20).
    const double dr = i < 20 ? 0.01 * U(rng) : (rho + r) * 0.999 * std::sqrt(U(rng));
    const Vec2 q = dr * Vec2(std::cos(a), std::sin(a));
    SurfaceContact c = dome.drop(q, r);
    EXPECT_NEAR(c.tip_z + r, std::sqrt((rho + r) * (rho + r) - q.squaredNorm()), kTol) << dr;
    expect_consistent(dome, c, q, r);
    // Bowl: axis within rho - R of the centre (the ball touches the bowl, not its rim).
    const Vec2 qb = (rho - r) * 0.999 * std::sqrt(U(rng)) * Vec2(std::cos(a), std::sin(a));
    c = bowl.drop(qb, r);
    EXPECT_NEAR(c.tip_z + r, -std::sqrt((rho - r) * (rho - r) - qb.squaredNorm()), kTol);
    expect_consistent(bowl, c, qb, r);
  }
  // Beyond rho + R nothing is within reach.
  EXPECT_FALSE(dome.drop(Vec2(rho + r + 0.01, 0), r).found);
}

TEST(SurfaceDrop, VaultAndTroughAlongX) {
  // Cylinders of radius rho about the x axis, x in [-40, 40]: on the vault the centre is at
  // rho + R from the axis, in the trough (rho > R) at rho - R.
  std::mt19937 rng(13);
  const double rho = 9, r = 4;
  const SurfaceDrop vault(test::half_cylinder(rho, 40, 1)),
      trough(test::half_cylinder(rho, 40, -1));
  std::uniform_real_distribution<double> X(-35, 35), Y(-1, 1);
  for (int i = 0; i < 200; ++i) {
    const Vec2 q(X(rng), (rho + r) * 0.999 * Y(rng));
    SurfaceContact c = vault.drop(q, r);
    EXPECT_NEAR(c.tip_z + r, std::sqrt((rho + r) * (rho + r) - q.y() * q.y()), kTol) << q.y();
    expect_consistent(vault, c, q, r);
    const Vec2 qt(q.x(), (rho - r) * 0.999 * Y(rng));
    c = trough.drop(qt, r);
    EXPECT_NEAR(c.tip_z + r, -std::sqrt((rho - r) * (rho - r) - qt.y() * qt.y()), kTol);
    expect_consistent(trough, c, qt, r);
  }
  // A ball wider than the trough (R > rho) rests on its two rims at z = 0: the centre stands
  // sqrt(R^2 - rho^2) above them on the axis.
  const SurfaceDrop narrow(test::half_cylinder(3, 40, -1));
  const SurfaceContact c = narrow.drop(Vec2(1, 0), 5);
  EXPECT_NEAR(c.tip_z + 5, 4, kTol);
  EXPECT_NEAR(std::abs(c.cc.y()), 3, 1e-9);
}

TEST(SurfaceDrop, BallHangingOverTheBorder) {
  // Horizontal square z = 1 on [0, 10]^2. With the axis 2 mm outside the edge x = 0 the ball
  // rests on that edge: centre z = 1 + sqrt(R^2 - 4). Past R: nothing.
  std::vector<Vec3> ctrl;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) ctrl.emplace_back(10.0 * i / 3, 10.0 * j / 3, 1);
  const SurfaceDrop d(bezier_grid_surface(1, 1, ctrl));
  const double r = 6;
  SurfaceContact c = d.drop(Vec2(-2, 5), r);
  ASSERT_TRUE(c.found);
  EXPECT_NEAR(c.tip_z, 1 + std::sqrt(32.0) - r, kTol);
  EXPECT_NEAR(c.cc.x(), 0, 1e-9);
  EXPECT_NEAR(c.u, 0, 1e-9);
  expect_consistent(d, c, Vec2(-2, 5), r);
  // Diagonally off the corner (-3, -4): distance 5 to the corner.
  c = d.drop(Vec2(-3, -4), r);
  ASSERT_TRUE(c.found);
  EXPECT_NEAR(c.tip_z, 1 + std::sqrt(11.0) - r, kTol);
  EXPECT_NEAR((c.cc - Vec3(0, 0, 1)).norm(), 0, 1e-9);
  EXPECT_FALSE(d.drop(Vec2(-6.01, 5), r).found);
  EXPECT_FALSE(d.drop(Vec2(-4.3, -4.3), r).found);  // 6.08 from the corner
  EXPECT_TRUE(d.drop(Vec2(-4.2, -4.2), r).found);   // 5.94 from the corner
  // Inside, away from the border: the plane itself.
  EXPECT_NEAR(d.drop(Vec2(5, 5), 2).tip_z, 1, kTol);

  // Steep plane z = 5 x on [0, 10]^2, axis 2 mm off the edge y = 0, R = 3: the ball rests on
  // that edge near its equator. Along the edge f(x) = 5 x + sqrt(5 - (x - 5)^2), maximal at
  // x - 5 = sqrt(125 / 26).
  std::vector<Vec3> steep;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) steep.emplace_back(10.0 * i / 3, 10.0 * j / 3, 50.0 * i / 3);
  const SurfaceDrop ds(bezier_grid_surface(1, 1, steep));
  const double u = std::sqrt(125.0 / 26);
  c = ds.drop(Vec2(5, -2), 3);
  ASSERT_TRUE(c.found);
  EXPECT_NEAR(c.tip_z, 5 * (5 + u) + std::sqrt(5 - u * u) - 3, kTol);
  EXPECT_NEAR((c.cc - Vec3(5 + u, 0, 5 * (5 + u))).norm(), 0, 1e-8);
  expect_consistent(ds, c, Vec2(5, -2), 3);
}

TEST(SurfaceDrop, SteepContactOnTheBorderNearTheEquator) {
  // Regression (found by a stress run against the oracle): a steep, rational-free degree
  // (4, 3) surface; the ball hangs over the border v = 0 and touches it close to its equator,
  // where Newton on f crawls along the rim of the disc. Oracle: dense samples over the part
  // of the domain within reach, plus the local zoom.
  NurbsSurface s =
      test::make_surface(4, 3, 6, 8, {0, 0, 0, 0, 0, 1.2990519450359854, 2, 2, 2, 2, 2},
                         {0, 0, 0, 0, 1.2252985282421969, 2.0989940275887031, 3.1677097771131799,
                          4.1320444129206342, 5, 5, 5, 5});
  const double net[48][4] = {
      {-0.73912736110461763, 1.0921350027951842, 18.231107812080594, 1},
      {2.2029311713160213, 12.989101008475817, -7.9647163696313292, 1},
      {-0.98354639318000048, 21.609938891935698, -3.276831237793425, 1},
      {0.57278675626442799, 34.304507056893428, -30.323038924936643, 1},
      {-0.44625046600780716, 48.317983680619797, 16.972281000446756, 1},
      {-2.0858682405899232, 59.832512835383447, 13.433813590511809, 1},
      {-0.73773046624450156, 71.962415708257112, 33.951265529144422, 1},
      {0.9206226505959314, 85.67974989038629, 8.6310656723752377, 1},
      {14.471073476538896, 0.94999950417270063, -15.439022980718255, 1},
      {14.758983030281524, 13.670528768534112, 24.270386079166908, 1},
      {14.685240270177497, 24.197924742167778, -0.52066988535411252, 1},
      {16.626596043355484, 34.629890137317823, -5.7358864869277513, 1},
      {17.045412874567567, 47.807927975851179, -11.312070249386922, 1},
      {17.432146828381729, 59.117428573634633, 31.158047723229366, 1},
      {18.030460187387241, 72.923234729817992, -31.337588302637993, 1},
      {15.846817915254992, 82.498405334892524, -31.961518177286216, 1},
      {32.159353220812612, -0.81752451639482671, -16.687736007751571, 1},
      {35.099241943415763, 11.069522071569827, 6.4155001618861345, 1},
      {35.310734170232131, 24.925051783307005, 23.403592126122469, 1},
      {35.009531831074717, 38.284242099584546, -29.708953246997833, 1},
      {31.488709476784784, 48.176640906283673, 20.338524072831973, 1},
      {33.932006875669011, 58.713320556389426, -7.9226192960669053, 1},
      {35.657361333030686, 73.527812969657859, 9.1969143114146483, 1},
      {32.973477233888346, 81.085667772441454, -32.901307355920849, 1},
      {48.71014016582415, -2.2151967629837528, 34.671590219585994, 1},
      {50.837567581589099, 11.565980469069354, 12.379335666926513, 1},
      {50.315238826685963, 25.096694843749759, -0.57934074019353998, 1},
      {50.195375658480344, 33.44437471813783, -12.17223509810276, 1},
      {49.245540700785419, 49.196033948130534, -30.450927175097288, 1},
      {48.159189052195146, 59.349860665015719, -10.391485882411706, 1},
      {52.239241366393848, 69.105008314029902, -9.060247580562967, 1},
      {48.766687769952448, 83.9317419398634, 6.7265236773773101, 1},
      {64.557011636240446, -2.4185536269103958, 31.137236395781066, 1},
      {66.548334028696132, 13.26258603950887, -5.0276436660756847, 1},
      {68.674502542132586, 25.972677778085824, 27.559901797652095, 1},
      {67.821150689316838, 35.161449417309257, -7.6351087795254191, 1},
      {64.340210683159256, 48.066697671294982, -26.480669469570731, 1},
      {68.61861026285446, 58.312136237084779, 31.725170861510488, 1},
      {65.320642573829488, 72.761936833223089, -18.198683217516049, 1},
      {66.202953134766105, 83.03353474396998, -28.377975242817442, 1},
      {84.960623430500263, 0.50988745203698438, -25.628315162819206, 1},
      {85.764721286043724, 9.7961727916386216, -5.3218061662187521, 1},
      {84.688150427360569, 24.518021944827794, 0.82862509927307892, 1},
      {84.720930389072649, 36.584218464139582, 22.058933315720374, 1},
      {83.606469054643284, 46.795728292160462, 24.808196716154153, 1},
      {81.599868856408733, 59.040082362899533, 28.671629191553262, 1},
      {81.725322004093627, 72.281183606927044, -21.568397954399902, 1},
      {86.112918661045882, 84.990840591633983, -22.693296763889013, 1},
  };
  for (int i = 0; i < 48; ++i) {
    s.ctrl[i] = Vec3(net[i][0], net[i][1], net[i][2]);
    s.weights[i] = net[i][3];
  }
  ASSERT_EQ(validate(s), "");
  const SurfaceDrop d(s);
  const Vec2 q(47.355028994168748, -2.4091162755923516);
  const double r = 2.6618078378143046;
  auto eval = [&s](double u, double v) { return test::cox_de_boor(s, u, v); };
  const test::DropOracle<decltype(eval)> oracle(eval, 0, 2, 0, 0.5, 300);
  const SurfaceContact c = d.drop(q, r);
  ASSERT_TRUE(c.found);
  expect_consistent(d, c, q, r);
  EXPECT_NEAR(c.tip_z, oracle.drop(q, r, 0.05) - r, 1e-6);
  EXPECT_NEAR(c.v, 0, 1e-9);
}

TEST(SurfaceDrop, SteepContactInsideNearTheEquator) {
  // Regression (stress run): a steep wavy bicubic and a small ball touching a flank close to
  // its equator, where Newton on f crawls along the rim of the disc (the offset condition
  // finds the contact). Oracle over the part of the domain within reach.
  const test::BicubicGrid g =
      test::wavy_grid(5, 42.632864197651585, 13.297191566306568, 2.6702225789430458, 35);
  const SurfaceDrop d(bezier_grid_surface(5, 5, g.ctrl));
  const Vec2 q(34.075701347309668, 18.737635842729727);
  const double r = 0.69301583080676621;
  auto eval = [&g](double u, double v) { return g.point(u, v); };
  const test::DropOracle<decltype(eval)> oracle(eval, 3.7, 4.4, 1.9, 2.5, 300);
  const SurfaceContact c = d.drop(q, r);
  ASSERT_TRUE(c.found);
  expect_consistent(d, c, q, r);
  EXPECT_NEAR(c.tip_z, oracle.drop(q, r, 0.05) - r, 1e-6);
}

TEST(SurfaceDrop, InvalidSurfaceOrRadiusTouchesNothing) {
  NurbsSurface bad;
  EXPECT_FALSE(SurfaceDrop(bad).drop(Vec2(0, 0), 3).found);
  const SurfaceDrop d(test::hemisphere(5, 1));
  EXPECT_FALSE(d.drop(Vec2(0, 0), 0).found);
  EXPECT_FALSE(d.drop(Vec2(std::nan(""), 0), 1).found);
}

// Random wavy bicubic surfaces (creases at the seams, concave regions of curvature radius
// well below R) against the brute-force oracle.
void oracle_case(int patches, double size, double amp, double noise, unsigned seed, double r,
                 int queries) {
  const test::BicubicGrid g = test::wavy_grid(patches, size, amp, noise, seed);
  const NurbsSurface s = bezier_grid_surface(patches, patches, g.ctrl);
  const SurfaceDrop d(s);
  auto eval = [&g](double u, double v) { return g.point(u, v); };
  const test::DropOracle<decltype(eval)> oracle(eval, 0, patches, 0, patches, 400);
  // The surface has bowl-like places tighter than the ball (where the contact jumps between
  // two sides): some normal curvature below -1 / R.
  double min_curvature = 0;
  for (int i = 0; i <= 40; ++i)
    for (int j = 0; j <= 40; ++j) {
      const SurfacePoint sp = evaluate(s, patches * i / 40.0, patches * j / 40.0);
      min_curvature =
          std::min({min_curvature, normal_curvature(sp, 1, 0), normal_curvature(sp, 0, 1),
                    normal_curvature(sp, 1, 1), normal_curvature(sp, 1, -1)});
    }
  EXPECT_LT(min_curvature, -1 / r) << "seed " << seed;
  std::mt19937 rng(seed + 100);
  std::uniform_real_distribution<double> U(-0.1 * size, 1.1 * size);
  int found = 0;
  double worst = 0;
  for (int i = 0; i < queries; ++i) {
    const Vec2 q(U(rng), U(rng));
    const SurfaceContact c = d.drop(q, r);
    const double sample = oracle.sample_max(q, r);
    if (!c.found) {
      // Nothing within R: no sample either.
      EXPECT_EQ(sample, -std::numeric_limits<double>::infinity()) << q.transpose();
      continue;
    }
    ++found;
    expect_consistent(d, c, q, r);
    // No sample point inside the ball.
    const Vec3 centre(q.x(), q.y(), c.tip_z + r);
    EXPECT_GE(oracle.min_distance(centre), r - 1e-9) << q.transpose();
    EXPECT_LE(sample, c.tip_z + r + 1e-9) << q.transpose();
    const double expect = oracle.drop(q, r, 0.05) - r;
    EXPECT_NEAR(c.tip_z, expect, 1e-6) << q.transpose() << " seed " << seed;
    worst = std::max(worst, std::abs(c.tip_z - expect));
  }
  EXPECT_GT(found, queries / 2);
  std::printf(
      "oracle seed %u: %d drops, min curvature %.3g (1/R = %.3g), worst |tip - oracle| = "
      "%.3g mm\n",
      seed, found, min_curvature, 1 / r, worst);
}

TEST(SurfaceDrop, MatchesBruteForceOnWavyBicubics) {
  oracle_case(4, 60, 5, 3.0, 1, 6, 300);
  oracle_case(3, 40, 3, 2.0, 2, 6, 150);
  oracle_case(4, 100, 6, 6.0, 3, 6, 100);
  oracle_case(3, 30, 3, 2.0, 4, 2, 100);
  // Bumpy: strong control noise on 10 mm patches, several local maxima of f per patch.
  oracle_case(2, 20, 2, 6.0, 5, 3, 100);
  oracle_case(2, 20, 2, 6.0, 6, 10, 100);
}

}  // namespace
}  // namespace ncpath
