// reachable() (engine/surface_check.hpp), on planes whose answers are known: a ball touching
// a steep wall sideways is reachable; the same ball 1.8e-4 mm lower, 1.5e-7 mm into the wall,
// is not (the case a fillet-cut of anchor_dense met, which the neighbours' deficit missed);
// a ball touching a wall that leans over it is not (the shank's space is taken); on a floor,
// on it and not below it.
#include "engine/surface_check.hpp"

#include <gtest/gtest.h>

#include <cmath>


namespace ncpath {
namespace {

constexpr double kR = 1.5;  // ball:3

// The wall through the y axis at z = 0 whose normal (cos b, 0, sin b) leans its face up by b
// (b < 0: it leans over), from z = 0 to 10 and y = -50 to 50.
TriangleMesh wall(double b) {
  TriangleMesh m;
  const double dx = -10 * std::tan(b);  // where the wall's top is in x
  m.vertices = {Vec3(0, -50, 0), Vec3(0, 50, 0), Vec3(dx, 50, 10), Vec3(dx, -50, 10)};
  m.facets = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

struct Probe {
  explicit Probe(const TriangleMesh& m)
      : mesh(m), index(mesh, ball_cutter(2 * kR)), distance(mesh),
        part{index, distance, kR, -100, 10} {}
  TriangleMesh mesh;
  DropIndex index;
  MeshDistance distance;
  PartProbe part;
};

// The tip of the ball touching the wall with normal n at height z of the wall (y = 0).
Vec3 touching(double b, double z) {
  const Vec3 n(std::cos(b), 0, std::sin(b));
  const Vec3 on_wall(-z * std::tan(b), 0, z);
  return on_wall + kR * n - Vec3(0, 0, kR);
}

TEST(Reachable, BallTouchingASteepWallSidewaysButNotInIt) {
  const double b = 8.4e-4;  // the wall is 89.95 degrees steep
  const Probe p(wall(b));
  const Vec3 q = touching(b, 5);
  EXPECT_TRUE(reachable(p.part, q));
  // 1.8e-4 mm lower the ball is 1.8e-4 sin(b) = 1.5e-7 mm in the wall.
  const Vec3 low = q - Vec3(0, 0, 1.8e-4);
  EXPECT_NEAR(kR - p.distance.closest(low + Vec3(0, 0, kR)).distance, 1.8e-4 * std::sin(b), 1e-12);
  EXPECT_FALSE(reachable(p.part, low));
  // The drop-cutter there is 1.8e-4 mm higher (the tool from above stops on the wall).
  EXPECT_NEAR(p.index.query(low.x(), low.y()).tip_z - low.z(), 1.8e-4, 1e-9);
  // Anything above the touching ball is reachable.
  EXPECT_TRUE(reachable(p.part, q + Vec3(0, 0, 1e-3)));
  EXPECT_TRUE(reachable(p.part, q + Vec3(0.5, 0, 0)));
}

TEST(Reachable, BallUnderAWallThatLeansOverIt) {
  const double b = -0.05;  // leans 2.9 degrees over the ball's side
  const Probe p(wall(b));
  const Vec3 q = touching(b, 5);
  EXPECT_NEAR(p.distance.closest(q + Vec3(0, 0, kR)).distance, kR, 1e-12);  // it touches only
  EXPECT_FALSE(reachable(p.part, q));  // but the shank's space above it is the wall's
  // Far enough out, the ball clears the wall's top edge all the way up.
  EXPECT_TRUE(reachable(p.part, q + Vec3(10 * std::tan(-b) + 0.01, 0, 0)));
}

TEST(Reachable, OnAFloorNotBelowIt) {
  TriangleMesh floor;
  floor.vertices = {Vec3(-50, -50, 0), Vec3(50, -50, 0), Vec3(50, 50, 0), Vec3(-50, 50, 0)};
  floor.facets = {{0, 1, 2}, {0, 2, 3}};
  const Probe p(floor);
  EXPECT_TRUE(reachable(p.part, Vec3(1, 2, 0)));
  EXPECT_FALSE(reachable(p.part, Vec3(1, 2, -1e-6)));
  PartProbe high = p.part;
  high.floor_z = 1;  // the tool touches nothing below z = 1
  EXPECT_FALSE(reachable(high, Vec3(1, 2, 0.5)));
}

}  // namespace
}  // namespace ncpath
