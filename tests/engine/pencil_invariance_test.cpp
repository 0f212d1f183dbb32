// Representation invariance of the pencil-cut and its z-levels (issue 17, item 1): the same
// part written the ways exporters write it (float32, 6-17 significant digits, vertex noise
// 1e-13..1e-7 mm, turned about z by an arbitrary angle, 1 m from the origin, facets
// reversed) gives 0 open z-level chains, a traced length within 1 % and a path count within
// 10 % of the full-precision run. Oracles independent of the pencil code: every pencil point's
// bi-contact angle recomputed by brute force from the part as given (the directions from the
// facets' closest points to the ball centre), and the brute-force no-gouge check of the paths
// against the part as given (not the conditioned one). The fillet-cut, which follows the
// pencil paths, likewise.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "engine/fillet.hpp"
#include "engine/parallel.hpp"
#include "engine/pencil.hpp"
#include "kernels/mesh/closest_point.hpp"
#include "tests/engine/mesh_test_support.hpp"
#include "tests/support/representation_variants.hpp"

namespace ncpath {
namespace {

// Largest angle between the directions from the part's contacts to the ball centre c: the
// closest points of facets within R + reach of c (brute force over all facets).
double brute_bicontact_angle(const TriangleMesh& m, const Vec3& c, double R, double reach) {
  std::vector<Vec3> dirs;
  for (const auto& f : m.facets) {
    const Vec3 &a = m.vertices[f[0]], &b = m.vertices[f[1]], &d = m.vertices[f[2]];
    if ((b - a).cross(d - a).squaredNorm() == 0) continue;
    Vec3 q;
    if (point_triangle_closest(c, a, b, d, q) <= R + reach) dirs.push_back((c - q).normalized());
  }
  double best = 0;
  for (std::size_t i = 0; i < dirs.size(); ++i)
    for (std::size_t j = i + 1; j < dirs.size(); ++j)
      best = std::max(best, std::acos(std::clamp(dirs[i].dot(dirs[j]), -1.0, 1.0)));
  return best;
}

// The oracles on one run: every 25th pencil point's angle seen on the part as given
// (contacts within the job's tolerance and the conditioning's move), and no gouge.
void expect_sound(const TriangleMesh& m, const PencilResult& r, const PencilParams& p, double R) {
  EXPECT_LE(r.stats.condition.max_move, tol::kConditionMove);
  const double min_angle = p.min_angle_deg * std::numbers::pi / 180;
  const double reach = p.tolerance + r.stats.condition.max_move;
  for (std::size_t k = 0; k < r.points.size(); k += 25) {
    const Vec3 centre = r.points[k].position + Vec3(0, 0, R);
    EXPECT_GE(brute_bicontact_angle(m, centre, R, reach), min_angle - 1e-3)
        << "point " << k << " family " << int(r.points[k].family) << " angle "
        << r.points[k].angle << " at " << r.points[k].position.transpose();
  }
  test_meshes::expect_no_gouge(m, r.paths, R);
}

// What a mesh must meet beyond 0 open chains and the oracles: the bars (length within
// 1 %, paths within 10 %), loosened only where the tracing is known to fall short, each
// loosening measured (docs/performance.md) and named here.
struct Bars {
  double length = 0.01;       // relative
  double turn_length = 0.01;  // relative, for the turned part
  int path_slack = 0;         // paths either way beyond 10 % (a piece split off or joined)
};

void expect_invariant(const std::string& name, const Bars& bars,
                      const std::vector<std::string>& only = {}) {
  const TriangleMesh mesh = test_meshes::load(name);
  const Cutter ball = ball_cutter(5);  // diameter 5 mm
  const double R = ball.radius;
  const PencilParams p;  // interval 0.5, step-down 1, 20 degrees, tolerance 0.01
  RunControl control;
  const PencilResult full = run_pencil(mesh, ball, p, control);
  ASSERT_EQ(full.stats.zlevel_open_chains, 0u);
  ASSERT_GT(full.stats.paths, 0u);
  expect_sound(mesh, full, p, R);
  for (const auto& [label, change] : test::representation_variants()) {
    if (!only.empty() && std::find(only.begin(), only.end(), label) == only.end()) continue;
    SCOPED_TRACE(name + ", " + label);
    TriangleMesh m = mesh;
    change(m);
    const PencilResult r = run_pencil(m, ball, p, control);
    EXPECT_EQ(r.stats.zlevel_open_chains, 0u);
    const bool turned = label.starts_with("turn");
    EXPECT_NEAR(r.stats.traced_length / full.stats.traced_length, 1.0,
                turned ? bars.turn_length : bars.length);
    const double paths = double(full.stats.paths);
    EXPECT_NEAR(double(r.stats.paths), paths, 0.1 * paths + bars.path_slack + 1e-9);
    expect_sound(m, r, p, R);
  }
}

TEST(PencilInvariance, FandiskCad) {
  // Turned, the drive planes cross the part elsewhere: a 1.3 mm piece 2 mm beyond a path's
  // end is bridged in one pose and not the other. Turned, 2.4 % longer: upright, a chain ends
  // where its crease turns (bi-contact angle 80 degrees at (5.6, 55.5, 75.0)); turned, the
  // 3.7 mm that follow (80 fading to 21 degrees) are traced. (Before the lift away from both
  // contacts, both poses lost that stretch to split chords.)
  expect_invariant("fandisk", {.turn_length = 0.03, .path_slack = 1});
}

TEST(PencilInvariance, AnchorDenseCad) {
  // 6 to 8 paths (8 at full precision): beside one 371.7 mm path, pieces of 1.0 to 4.0 mm
  // that a lifted chord splits off or not (the `leave` threshold meets rounding) and pieces of
  // 1.0 to 1.2 mm kept or dropped by min_length (1 mm); turned, the traced length is 1.8 %
  // longer.
  expect_invariant("anchor_dense", {.turn_length = 0.02, .path_slack = 2});
}

TEST(PencilInvariance, Bunny00Scan) {
  // A scan: 2.8 s a run, so the number formats and noise levels most often met. Turned, the
  // traced length is 5.3 % longer (drive planes sample the soft creases elsewhere: 179.9 mm
  // against 170.7 mm with a 5 mm ball). Before stretches traced twice were kept once, both
  // poses carried such stretches (20.2 mm upright, 13.8 mm turned), which hid the difference
  // (turned 1.4 % longer then).
  expect_invariant("bunny00", {.turn_length = 0.06},
                   {"float32", "digits 12", "noise 1e-09 seed 1", "turn 37.3", "far"});
}

// The conditioning runs its passes in parallel: on a part it changes (fandisk with noise 1e-9,
// 462 planar clusters), 1 and 2 threads give the same paths and pencil points, bit for bit.
TEST(PencilInvariance, OneAndTwoThreadsGiveIdenticalPathsOnANoisyPart) {
  TriangleMesh mesh = test_meshes::load("fandisk");
  for (const auto& [label, change] : test::representation_variants())
    if (label == "noise 1e-09 seed 1") change(mesh);
  const PencilParams p;
  RunControl control;
  PencilResult one, two;
  {
    par::ThreadLimit limit(1);
    one = run_pencil(mesh, ball_cutter(5), p, control);
  }
  {
    par::ThreadLimit limit(2);
    two = run_pencil(mesh, ball_cutter(5), p, control);
  }
  EXPECT_GT(one.stats.condition.planes, 100u);
  EXPECT_EQ(one.paths, two.paths);
  ASSERT_EQ(one.points.size(), two.points.size());
  for (std::size_t k = 0; k < one.points.size(); ++k)
    EXPECT_EQ(one.points[k].position, two.points[k].position) << k;
}

// The fillet-cut follows the reference ball's pencil paths (the same conditioned slicing): its
// passes must not depend on the representation either. Ball 2 mm after a 10 mm reference
// (the demo's job); every 20th pass point checked for gouges by brute force.
TEST(FilletInvariance, FandiskCad) {
  const TriangleMesh mesh = test_meshes::load("fandisk");
  const Cutter ball = ball_cutter(2);
  const FilletParams p;
  RunControl control;
  const FilletResult full = run_fillet(mesh, ball, p, control);
  ASSERT_GT(full.stats.passes, 0u);
  for (const auto& [label, change] : test::representation_variants()) {
    if (label != "float32" && label != "digits 12" && label != "noise 1e-09 seed 1" &&
        label != "far" && label != "turn 37.3")
      continue;
    SCOPED_TRACE("fandisk fillet, " + label);
    TriangleMesh m = mesh;
    change(m);
    const FilletResult r = run_fillet(m, ball, p, control);
    EXPECT_EQ(r.stats.pencil.zlevel_open_chains, 0u);
    const bool turned = label.starts_with("turn");
    const double ratio = r.stats.cut_length / full.stats.cut_length;
    if (turned) {
      // The passes follow the reference pencil, whose turned length is within 3 % of the
      // upright one (PencilInvariance.FandiskCad): 2.1 % less cut turned (15,503 mm against
      // 15,833), 246.1 mm of reference path upright against 242.7 turned. (While the drive
      // planes stopped at the part's box, the turned pose cut 19 % more.)
      EXPECT_NEAR(ratio, 1.0, 0.03);
    } else {
      EXPECT_NEAR(ratio, 1.0, 0.01);
    }
    // Turned, the reference pencil paths split differently (fandisk: 130 passes against 260
    // over the same length): the pass count follows the pencil's pieces, not the fillets.
    const double passes = double(full.stats.passes);
    if (!turned) {
      EXPECT_NEAR(double(r.stats.passes), passes, 0.1 * passes + 1e-9);
    }
    std::vector<std::vector<Vec3>> sample;
    for (std::size_t k = 0; k < r.paths.size(); ++k)
      if (r.kinds[k] == PathKind::kCut)
        for (std::size_t i = 0; i < r.paths[k].size(); i += 20) sample.push_back({r.paths[k][i]});
    test_meshes::expect_no_gouge(m, sample, ball.radius);
  }
}

}  // namespace
}  // namespace ncpath
