// Tests kernels/mesh/condition.*: noisy planar faces come out coplanar (checked against a
// plane through three of their vertices, not the kernel's own fit), axis faces share one
// coordinate bit for bit, near-vertical walls become vertical, curved surfaces and already
// exact parts are left alone, and no vertex moves farther than stats.max_move <=
// tol::kConditionMove.
#include "kernels/mesh/condition.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <random>
#include <utility>

#include "kernels/geom/tolerance.hpp"
#include "kernels/mesh/subdivide.hpp"
#include "tests/support/meshes.hpp"

namespace ncpath {
namespace {

void add_noise(TriangleMesh& m, double e, unsigned seed) {
  std::mt19937_64 bits(seed);
  std::uniform_real_distribution<double> u(-e, e);
  for (Vec3& v : m.vertices)
    for (int k = 0; k < 3; ++k) v[k] += u(bits);
}

ConditionedMesh run(const TriangleMesh& m) { return condition_mesh(m); }

double largest_move(const TriangleMesh& a, const TriangleMesh& b) {
  double d = 0;
  for (std::size_t i = 0; i < a.vertices.size(); ++i)
    d = std::max(d, (a.vertices[i] - b.vertices[i]).norm());
  return d;
}

// Largest distance of a vertex from the plane through vertices i, j, k.
double off_plane(const TriangleMesh& m, std::uint32_t i, std::uint32_t j, std::uint32_t k) {
  const Vec3 n =
      (m.vertices[j] - m.vertices[i]).cross(m.vertices[k] - m.vertices[i]).normalized();
  double d = 0;
  for (const Vec3& v : m.vertices) d = std::max(d, std::abs(n.dot(v - m.vertices[i])));
  return d;
}

TEST(Condition, NoisySlopedPlaneBecomesOnePlane) {
  for (double noise : {1e-12, 1e-10, 1e-8, 1e-6}) {
    TriangleMesh m =
        test::height_field(12, 60, [](double x, double y) { return 5 + 0.3 * x - 0.2 * y; });
    add_noise(m, noise, 7);
    ASSERT_GT(off_plane(m, 0, 12, 168), 0.3 * noise);
    const ConditionedMesh c = run(m);
    EXPECT_EQ(c.stats.planes, 1u) << noise;
    EXPECT_EQ(c.stats.planar_facets, m.facets.size());
    EXPECT_LT(off_plane(c.mesh, 0, 12, 168), 1e-13) << noise;
    EXPECT_EQ(largest_move(m, c.mesh), c.stats.max_move);
    EXPECT_LE(c.stats.max_move, tol::kConditionMove);
    EXPECT_LE(c.stats.max_move, 4 * noise) << "moves of the order of the noise";
  }
}

// A 10 mm cube, faces split 4 x 4, vertex noise 1e-9: every face is one axis plane again,
// its vertices sharing that coordinate exactly.
TEST(Condition, NoisyBoxFacesShareOneCoordinateExactly) {
  TriangleMesh box{{Vec3(0, 0, 0), Vec3(10, 0, 0), Vec3(10, 10, 0), Vec3(0, 10, 0),
                    Vec3(0, 0, 10), Vec3(10, 0, 10), Vec3(10, 10, 10), Vec3(0, 10, 10)},
                   {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                    {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}}};
  box = subdivide_midpoint(subdivide_midpoint(box));
  add_noise(box, 1e-9, 3);
  const ConditionedMesh c = run(box);
  EXPECT_EQ(c.stats.planes, 6u);
  EXPECT_EQ(c.stats.axis_planes, 6u);
  for (const Vec3& v : c.mesh.vertices)
    for (int k = 0; k < 3; ++k) {
      if (std::abs(v[k]) < 1e-6 || std::abs(v[k] - 10) < 1e-6) {
        EXPECT_TRUE(v[k] == c.mesh.vertices[0][k] || v[k] == c.mesh.vertices[6][k])
            << k << " " << v[k];
      }
    }
  EXPECT_LE(c.stats.max_move, 3e-9);
}

// A wall leaning by 1e-9 rad (its top 1e-8 mm off its foot) becomes vertical; one leaning by
// 1e-3 rad is a real draft and stays.
TEST(Condition, NearlyVerticalWallBecomesVertical) {
  for (double lean : {1e-9, 1e-3}) {
    TriangleMesh wall;
    for (int j = 0; j <= 4; ++j)
      for (int i = 0; i <= 4; ++i) {
        const double x = 2.5 * i, z = 2.5 * j;
        wall.vertices.emplace_back(x + 0.1 * z, 3 + lean * z, z);  // along x, leaning in y
      }
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i) {
        const auto a = std::uint32_t(5 * j + i);
        wall.facets.push_back({a, a + 1, a + 6});
        wall.facets.push_back({a, a + 6, a + 5});
      }
    const ConditionedMesh c = run(wall);
    double top = -INFINITY, foot = INFINITY;
    for (const Vec3& v : c.mesh.vertices) {
      top = std::max(top, v.y());
      foot = std::min(foot, v.y());
    }
    if (lean < 1e-6) {
      EXPECT_LT(top - foot, 1e-14) << "vertical: one y for the whole wall";
      EXPECT_EQ(c.stats.axis_planes, 1u);
    } else {
      EXPECT_NEAR(top - foot, lean * 10, 1e-12) << "a draft stays";
      EXPECT_LT(c.stats.max_move, 1e-13);
    }
  }
}

// Curved surfaces bend far beyond the tolerance: nothing merges, nothing moves, also with
// noise 1e-9 on them.
TEST(Condition, CurvedSurfaceIsLeftAlone) {
  const TriangleMesh dome = test::height_field(20, 20, [](double x, double y) {
    return std::sqrt(225 - (x - 10) * (x - 10) - (y - 10) * (y - 10));
  });
  for (double noise : {0.0, 1e-9}) {
    TriangleMesh m = dome;
    add_noise(m, noise, 11);
    const ConditionedMesh c = run(m);
    EXPECT_EQ(c.stats.planes, 0u);
    EXPECT_EQ(c.stats.moved_vertices, 0u);
    EXPECT_EQ(c.mesh.vertices, m.vertices);
  }
}

// Exactly planar input (dyadic coordinates on z = 1) is already conditioned: unchanged.
TEST(Condition, ExactPlaneIsUnchanged) {
  const TriangleMesh m = test::height_field(8, 16, [](double, double) { return 1.0; });
  const ConditionedMesh c = run(m);
  EXPECT_EQ(c.stats.planes, 1u);
  EXPECT_EQ(c.mesh.vertices, m.vertices);
  EXPECT_EQ(c.stats.max_move, 0.0);
}

// Faces meeting only at a vertex (a bow tie; also what T-junctions and non-manifold edges
// leave) are one plane: grown through shared vertices, fitted together.
TEST(Condition, FacetsSharingOnlyAVertexFormOnePlane) {
  auto z = [](double x, double y) { return 0.2 * x + 0.1 * y; };
  TriangleMesh m;
  for (const auto& [x, y] : {std::pair{0.0, 0.0}, {10.0, 0.0}, {10.0, 10.0}, {20.0, 10.0},
                             {20.0, 20.0}})
    m.vertices.emplace_back(x, y, z(x, y));
  m.facets = {{0, 1, 2}, {2, 3, 4}};
  add_noise(m, 1e-9, 5);
  const ConditionedMesh c = run(m);
  EXPECT_EQ(c.stats.planes, 1u);
  EXPECT_LT(off_plane(c.mesh, 0, 1, 4), 1e-13);
}

// A vertex on no vertical facet but joined to one by an edge lying in its plane (a ruling of
// the curved surface beside a wall: anchor_dense at 12 digits) moves onto that plane, so the
// edge's shadow runs exactly along the wall's; a vertex off the plane stays.
TEST(Condition, EdgeInAWallPlaneJoinsTheWall) {
  TriangleMesh m{{Vec3(0, 0, 10), Vec3(10, 0, 10), Vec3(5, 0, 0), Vec3(7, 2e-9, 3),
                  Vec3(6, 5, 2)},
                 {{0, 1, 2}, {2, 3, 4}}};
  const ConditionedMesh c = run(m);
  EXPECT_EQ(c.mesh.vertices[3].y(), 0.0);
  EXPECT_EQ(c.mesh.vertices[3].x(), 7.0);
  EXPECT_EQ(c.mesh.vertices[4], m.vertices[4]);
  EXPECT_EQ(c.stats.max_move, 2e-9);
}

// An edge lying in a wall's plane but on no facet joined to the wall (the edge of a sloped
// ledge straight above the wall, anchor_dense with vertex noise of 1e-11 mm): its ends move
// onto the plane, so its shadow coincides with the wall's exactly; the ledge's other vertex
// stays.
TEST(Condition, DetachedEdgeInAWallPlaneJoinsTheWall) {
  TriangleMesh m{{Vec3(0, 0, 0), Vec3(10, 0, 0), Vec3(10, 0, 5), Vec3(0, 0, 5),  // the wall
                  Vec3(2, 3e-9, 8), Vec3(8, -2e-9, 8), Vec3(5, 4, 9)},           // the ledge
                 {{0, 1, 2}, {0, 2, 3}, {4, 5, 6}}};
  const ConditionedMesh c = run(m);
  EXPECT_EQ(c.mesh.vertices[4].y(), 0.0);
  EXPECT_EQ(c.mesh.vertices[5].y(), 0.0);
  EXPECT_EQ(c.mesh.vertices[4].x(), 2.0);
  EXPECT_EQ(c.mesh.vertices[6], m.vertices[6]);
  EXPECT_EQ(c.stats.max_move, 3e-9);
}

// Two pieces of one wall that share no vertex (interrupted by a fillet) get one plane, bit
// for bit: their vertices lie on the plane through three of the first piece's.
TEST(Condition, PiecesOfOneFaceGetOnePlane) {
  TriangleMesh m;
  const Vec3 along = Vec3(3, 4, 0).normalized();  // a wall through the origin, along (3, 4)
  for (const auto& [s, z] : {std::pair{0.0, 0.0}, {10.0, 0.0}, {10.0, 8.0}, {0.0, 8.0},
                             {20.0, 0.0}, {30.0, 0.0}, {30.0, 8.0}, {20.0, 8.0}})
    m.vertices.push_back(s * along + Vec3(0, 0, z));
  m.facets = {{0, 1, 2}, {0, 2, 3}, {4, 5, 6}, {4, 6, 7}};
  add_noise(m, 1e-9, 9);
  ASSERT_GT(off_plane(m, 0, 1, 2), 1e-10);
  const ConditionedMesh c = run(m);
  EXPECT_EQ(c.stats.planes, 2u);
  EXPECT_LT(off_plane(c.mesh, 0, 1, 2), 1e-13);
}

}  // namespace
}  // namespace ncpath
