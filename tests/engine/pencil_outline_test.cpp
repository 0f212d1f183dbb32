// Pencil points and the part's outline (engine/pencil_outline.hpp), and a crease traced once
// however the part is turned.
//
// A plate [0, 30] x [0, 20] x [0, 3] with a block [24, 29.5] x [5, 15] x [3, 8] on it: the
// block's outer wall stands 0.5 mm inside the plate's edge x = 30. A ball of radius 2 against
// that wall (centre x = 31.5) and on the plate's top edge below it holds a bi-contact, with
// its centre beyond the plate's outline: it hangs, and is not a crease. The creases of this
// part are at the block's foot on the plate's top, every ball centre over the plate. Before
// the drive planes reached past the part's box and hanging balls were dropped, the turned
// part's pencil held the hanging path (its box reaches past x = 30 there) and the upright
// part's did not.
//
// The crease at the block's foot, the ball (radius 2) on the plate's top against the block:
// from where its centre leaves the plate (x = 30) around the corner (29.5, 5), along y = 3,
// around (24, 5), along x = 22, around (24, 15), along y = 17 and around (29.5, 15) back to
// x = 30: 2 x 5.5 + 10 + 2 (pi R / 2) + 2 R asin(0.5 / R) = 28.294 mm, one path, tip z = 3.
// Both drive-plane families follow the corner arcs past their 45-degree points; before each
// point within twice the tolerance of a longer piece was dropped, those stretches were traced
// twice (29.25 mm upright, 31.82 mm turned 37.3 degrees).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "engine/pencil.hpp"
#include "tests/engine/mesh_test_support.hpp"
#include "tests/support/random_parts.hpp"

namespace ncpath {
namespace {

TriangleMesh plate_with_block() {
  using namespace test::random_parts_detail;
  TriangleMesh part = prism(rectangle(0, 0, 30, 20), 2, 0, 3);
  append(part, prism(rectangle(24, 5, 29.5, 15), 2, 3, 8));
  return part;
}

Vec3 turned(const Vec3& v, double deg) {
  const double a = deg * std::numbers::pi / 180, c = std::cos(a), s = std::sin(a);
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y(), v.z()};
}

constexpr double kR = 2;  // ball radius, mm
constexpr double kPoses[] = {0.0, 37.3, 90.0};  // degrees about z

// The part turned by `deg`, and its pencil-cut (ball radius kR, interval 0.5, step-down 1).
struct TurnedRun {
  TriangleMesh mesh;
  PencilParams params;
  PencilResult result;
};
TurnedRun pencil_turned(double deg) {
  TurnedRun t;
  t.mesh = plate_with_block();
  for (Vec3& v : t.mesh.vertices) v = turned(v, deg);
  t.params.interval = 0.5;
  t.params.step_down = 1;
  RunControl control;
  t.result = run_pencil(t.mesh, ball_cutter(2 * kR), t.params, control);
  return t;
}

TEST(PencilOutline, ABallHangingOverTheOutlineIsNoCreaseInAnyPose) {
  for (double deg : kPoses) {
    SCOPED_TRACE("turned " + std::to_string(deg) + " degrees");
    const TurnedRun t = pencil_turned(deg);
    const PencilResult& r = t.result;
    ASSERT_FALSE(r.paths.empty());
    // Every ball centre over the plate (back in the upright frame).
    for (const auto& path : r.paths)
      for (const Vec3& q : path) {
        const Vec3 c = turned(q, -deg);
        EXPECT_GE(c.x(), -1e-6);
        EXPECT_LE(c.x(), 30 + 1e-6) << q.transpose();
        EXPECT_GE(c.y(), -1e-6);
        EXPECT_LE(c.y(), 20 + 1e-6);
      }
    EXPECT_GT(r.stats.hanging_points, 0u);
    test_meshes::expect_no_gouge(t.mesh, r.paths, kR);
  }
}

TEST(PencilOutline, TheBlocksFootIsTracedOnceInAnyPose) {
  const double expected = 2 * 5.5 + 10 + std::numbers::pi * kR + 2 * kR * std::asin(0.5 / kR);
  for (double deg : kPoses) {
    SCOPED_TRACE("turned " + std::to_string(deg) + " degrees");
    const TurnedRun t = pencil_turned(deg);
    const PencilResult& r = t.result;
    ASSERT_EQ(r.paths.size(), 1u);
    // Chords inscribed in the corner arcs (sagitta <= tolerance) and ends placed by bisection
    // to 1/128 of the interval: within 0.05 mm.
    EXPECT_NEAR(r.stats.traced_length, expected, 0.05);
    // On the plate's top, or lifted where a chord of a corner arc passes the block's edge.
    for (const Vec3& q : r.paths[0]) {
      EXPECT_GE(q.z(), 3 - 1e-9);
      EXPECT_LE(q.z(), 3 + t.params.tolerance);
    }
  }
}

}  // namespace
}  // namespace ncpath
