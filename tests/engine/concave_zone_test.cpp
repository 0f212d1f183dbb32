// The concave zone (engine/concave_zone.hpp): a conservative screen for where a ball can
// touch a mesh at two points whose normals are min_angle apart. Oracles: analytic parts (a
// convex sphere has no such place, a V-groove has its bi-contact centres on its bisector),
// the z-levels of the whole mesh (every sharp-concave junction whose contacts lie on the part
// and whose angle reaches the threshold must lie in the zone, on CAD and scanned meshes and
// on the representation variants), and the z-levels sliced to the zone (the same junctions
// there, to rounding, as the whole mesh's).
#include "engine/concave_zone.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <tuple>
#include <vector>

#include "engine/mesh_distance.hpp"
#include "engine/offset_elements_build.hpp"
#include "engine/pencil.hpp"
#include "engine/zlevel.hpp"
#include "kernels/mesh/subdivide.hpp"
#include "kernels/scan/envelope.hpp"
#include "tests/engine/mesh_test_support.hpp"
#include "tests/support/meshes.hpp"
#include "tests/support/representation_variants.hpp"

namespace ncpath {
namespace {

constexpr double kDeg = std::numbers::pi / 180;

// A sphere of radius r (an octahedron subdivided `levels` times, vertices pushed out),
// wound outward.
TriangleMesh sphere(double r, int levels) {
  TriangleMesh m;
  m.vertices = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  m.facets = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
              {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (int k = 0; k < levels; ++k) m = subdivide_midpoint(m);
  for (Vec3& v : m.vertices) v = r * v.normalized();
  return m;
}

// A closed V-groove block: the top is z = |x| tan(slope) over [-w, w] x [0, len] on an n x n
// grid, the sides and bottom (z = -depth, a fan around its centre) close it, wound outward.
TriangleMesh groove_block(double slope, double w, double len, int n, double depth) {
  TriangleMesh m;
  auto top = [&](double x) { return std::abs(x) * std::tan(slope); };
  auto id = [n](int i, int j) { return std::uint32_t(j * (n + 1) + i); };
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = -w + 2 * w * i / n, y = len * j / n;
      m.vertices.emplace_back(x, y, top(x));
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      m.facets.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.facets.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  // The rim of the top walled down to the bottom, closed by a fan around its centre.
  test::close_grid(m, n, -depth, 0, 0.5 * len);
  return m;
}

// An axis-aligned box [lo, hi], its faces subdivided `levels` times (small facets, so that
// only its edges' and corners' own balls hold the centres of balls resting on them), wound
// outward, appended to m.
void add_box(TriangleMesh& m, const Vec3& lo, const Vec3& hi, int levels) {
  TriangleMesh b;
  for (int k = 0; k < 8; ++k)
    b.vertices.emplace_back(k & 1 ? hi.x() : lo.x(), k & 2 ? hi.y() : lo.y(),
                            k & 4 ? hi.z() : lo.z());
  b.facets = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
              {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  for (int k = 0; k < levels; ++k) b = subdivide_midpoint(b);
  const auto base = std::uint32_t(m.vertices.size());
  m.vertices.insert(m.vertices.end(), b.vertices.begin(), b.vertices.end());
  for (const auto& f : b.facets) m.facets.push_back({base + f[0], base + f[1], base + f[2]});
}

TEST(ConcaveZone, ConvexSphereHasNone) {
  const TriangleMesh m = sphere(30, 4);
  const ConcaveZone z = concave_zone(m, 2.5, 20 * kDeg, 0.01);
  EXPECT_GT(z.elements, m.facets.size());
  EXPECT_TRUE(z.balls.empty());
  EXPECT_EQ(z.keep_facets, 0u);
  EXPECT_FALSE(z.holds(Vec3(0, 0, 32.5)));
}

TEST(ConcaveZone, HoldsTheCentresOfAVGroove) {
  // Slopes 30 degrees: a ball of radius R on both flanks has its centre at x = 0,
  // z = R / cos(30), and a bi-contact angle of 60 degrees.
  const double R = 2.5, slope = 30 * kDeg;
  const TriangleMesh m = groove_block(slope, 20, 40, 40, 5);
  const ConcaveZone z = concave_zone(m, R, 20 * kDeg, 0.01);
  for (double y = 5; y <= 35; y += 0.7) EXPECT_TRUE(z.holds(Vec3(0, y, R / std::cos(slope)))) << y;
  // A ball on one flank, far from the groove and the block's edges, touches once.
  const Vec3 n(-std::sin(slope), 0, std::cos(slope));
  EXPECT_FALSE(z.holds(Vec3(-10, 20, 10 * std::tan(slope)) + R * n));
  // Kept: the groove's neighbourhood, not the whole top.
  EXPECT_GT(z.keep_facets, 0u);
  EXPECT_LT(z.keep_facets, m.facets.size());
}

void expect_zone_holds_bicontacts(const TriangleMesh& m, double R, double min_angle,
                                  const std::string& what);

// A ball dropped between two blocks 2 mm apart rests on their top edges (edge contacts only,
// normals 47 degrees apart); between two blocks set corner to corner, on their corners.
TEST(ConcaveZone, HoldsBallsRestingOnEdgesAndCorners) {
  const double R = 2.5;
  TriangleMesh m;
  add_box(m, Vec3(0, 0, 0), Vec3(10, 10, 10), 4);
  add_box(m, Vec3(12, 0, 0), Vec3(22, 10, 10), 4);
  add_box(m, Vec3(11.5, 11.5, 0), Vec3(21.5, 21.5, 10), 4);
  const ConcaveZone z = concave_zone(m, R, 20 * kDeg, 0.01);
  for (double y = 1; y <= 9; y += 0.5)
    EXPECT_TRUE(z.holds(Vec3(11, y, 10 + std::sqrt(R * R - 1)))) << "edges, y " << y;
  const double half = 0.75 * std::sqrt(2.0);  // half the corners' distance
  EXPECT_TRUE(z.holds(Vec3(10.75, 10.75, 10 + std::sqrt(R * R - half * half)))) << "corners";
  expect_zone_holds_bicontacts(m, R, 20 * kDeg, "blocks");
}

// The part as the pencil slices it: welded and conditioned.
TriangleMesh conditioned(const TriangleMesh& m) { return condition_for_slicing(m).mesh; }

struct Junction {
  std::uint8_t kind;
  std::array<double, 3> position, b1, b2;
  std::array<std::int64_t, 6> elements;
  auto key() const { return std::tie(kind, position, b1, b2, elements); }
  bool operator<(const Junction& o) const { return key() < o.key(); }
  bool operator==(const Junction& o) const { return key() == o.key(); }
};

// The same crossing found from other pieces of the curves (the sliced part splits them
// elsewhere) may differ in its last bits (mm).
constexpr double kSplitRounding = 1e-9;

// Sorted by kind, elements, then position (to a micrometre, so that rounding does not reorder).
std::vector<Junction> junctions(const TriangleMesh& m, double R, const ConcaveZone* zone) {
  ZLevelOpParams p;
  p.step_down = 1;
  p.tolerance = 0.01;
  p.condition = false;
  p.zone = zone;
  std::vector<Junction> out;
  RunControl control;
  const ZLevelOpStats st = run_zlevel(
      m, ball_cutter(2 * R), p,
      [&](const ZLevelChunk& ch) {
        for (const ZLevelJunctionRecord& j : ch.junctions)
          out.push_back({j.kind,
                         j.position,
                         j.b1,
                         j.b2,
                         {j.element1.kind, j.element1.a, j.element1.b, j.element2.kind,
                          j.element2.a, j.element2.b}});
      },
      control);
  EXPECT_EQ(st.open_chains, 0u);
  auto key = [](const Junction& j) {
    return std::make_tuple(j.kind, j.elements, std::lround(j.position[0] * 1e3),
                           std::lround(j.position[1] * 1e3), std::lround(j.position[2] * 1e3));
  };
  std::sort(out.begin(), out.end(), [&](const Junction& a, const Junction& b) {
    return key(a) != key(b) ? key(a) < key(b) : a < b;
  });
  return out;
}

Vec3 centre_of(const Junction& j, double R) {
  return Vec3(j.position[0], j.position[1], j.position[2] + R);
}

// Every sharp-concave junction of the whole mesh's z-levels that the pencil would keep
// (angle >= min_angle, both contacts within the tolerance of the part) lies in the zone.
void expect_zone_holds_bicontacts(const TriangleMesh& m, double R, double min_angle,
                                  const std::string& what) {
  const double tol = 0.01;
  const ConcaveZone zone = concave_zone(m, R, min_angle, tol);
  const MeshDistance distance(m);
  std::size_t checked = 0;
  for (const Junction& j : junctions(m, R, nullptr)) {
    if (j.kind != std::uint8_t(JunctionKind::kSharpConcave)) continue;
    const Vec3 b1(j.b1[0], j.b1[1], j.b1[2]), b2(j.b2[0], j.b2[1], j.b2[2]);
    if (std::atan2(b1.cross(b2).norm(), b1.dot(b2)) < min_angle) continue;
    const Vec3 c = centre_of(j, R);
    if (distance.closest(c - R * b1, tol).distance > tol ||
        distance.closest(c - R * b2, tol).distance > tol)
      continue;
    ++checked;
    EXPECT_TRUE(zone.holds(c)) << what << ": bi-contact centre " << c.transpose();
  }
  EXPECT_GT(checked, 0u) << what;
}

TEST(ConcaveZone, HoldsEveryPencilBiContactOfRealMeshes) {
  for (const char* name : {"fandisk", "anchor_dense", "bunny00"})
    expect_zone_holds_bicontacts(conditioned(test_meshes::load(name)), 2.5, 20 * kDeg, name);
}

// An open height field (both sides count, its rim's edges and vertices have unknown normals).
TEST(ConcaveZone, HoldsEveryPencilBiContactOfAnOpenTerrain) {
  for (unsigned seed : {3u, 4u}) {
    std::mt19937_64 rng(seed);
    expect_zone_holds_bicontacts(conditioned(test_meshes::terrain(rng, 30)), 2.5, 20 * kDeg,
                                 "terrain seed " + std::to_string(seed));
  }
}

TEST(ConcaveZone, HoldsEveryPencilBiContactOfTheVariants) {
  const TriangleMesh part = test_meshes::load("anchor_dense");
  for (const auto& [label, apply] : test::representation_variants()) {
    if (label != "float32" && label != "digits 6" && label != "digits 12" &&
        label != "noise 1e-11 seed 1" && label != "noise 1e-07 seed 2" && label != "turn 37.3" &&
        label != "reversed")
      continue;
    TriangleMesh m = part;
    apply(m);
    expect_zone_holds_bicontacts(conditioned(m), 2.5, 20 * kDeg, "anchor_dense " + label);
  }
}

TEST(ConcaveZone, HoldsEveryPencilBiContactAtOtherRadiiAndAngles) {
  const TriangleMesh m = conditioned(test_meshes::load("fandisk"));
  for (const auto& [R, deg] : {std::pair{1.0, 10.0}, std::pair{6.0, 45.0}})
    expect_zone_holds_bicontacts(
        m, R, deg * kDeg, "fandisk R " + std::to_string(R) + " angle " + std::to_string(deg));
}

// Sliced to the zone, the z-levels give the whole mesh's junctions inside it (the same
// elements and kinds, positions and vectors to rounding).
TEST(ConcaveZone, SlicedZLevelsHaveTheWholeMeshsJunctionsInside) {
  for (const char* name : {"fandisk", "anchor_dense"}) {
    const TriangleMesh m = conditioned(test_meshes::load(name));
    const double R = 2.5;
    const ConcaveZone zone = concave_zone(m, R, 20 * kDeg, 0.01);
    ASSERT_LT(zone.keep_facets, m.facets.size()) << name;
    std::vector<Junction> whole;
    for (const Junction& j : junctions(m, R, nullptr))
      if (zone.holds(centre_of(j, R))) whole.push_back(j);
    const std::vector<Junction> sliced = junctions(m, R, &zone);
    EXPECT_GT(whole.size(), 0u) << name;
    ASSERT_EQ(whole.size(), sliced.size()) << name;
    for (std::size_t k = 0; k < whole.size(); ++k) {
      const Junction &a = whole[k], &b = sliced[k];
      ASSERT_EQ(a.kind, b.kind) << name << " junction " << k;
      ASSERT_EQ(a.elements, b.elements) << name << " junction " << k;
      for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(a.position[i], b.position[i], kSplitRounding) << name << " junction " << k;
        EXPECT_NEAR(a.b1[i], b.b1[i], kSplitRounding) << name << " junction " << k;
        EXPECT_NEAR(a.b2[i], b.b2[i], kSplitRounding) << name << " junction " << k;
      }
    }
  }
}

// A convex part has an empty zone: nothing to slice, no pencil point, and no error.
TEST(ConcaveZone, PencilOfAConvexPartSlicesNothing) {
  const TriangleMesh m = sphere(30, 4);
  PencilParams p;
  p.zone_max_share = 1;
  RunControl control;
  const PencilResult r = run_pencil(m, ball_cutter(5), p, control);
  EXPECT_EQ(r.stats.sliced_facets, 0u);
  EXPECT_TRUE(r.points.empty());
  EXPECT_TRUE(r.paths.empty());
}

// The pencil-cut gives the same paths and points whether its z-levels slice the zone or the
// whole part (PencilParams::zone_max_share 1 and 0), to rounding.
TEST(ConcaveZone, PencilIsTheSameSlicedOrWhole) {
  for (const char* name : {"anchor_dense", "bunny00"}) {
    const TriangleMesh m = test_meshes::load(name);
    PencilParams p;
    RunControl control;
    p.zone_max_share = 0;
    const PencilResult whole = run_pencil(m, ball_cutter(5), p, control);
    p.zone_max_share = 1;
    const PencilResult sliced = run_pencil(m, ball_cutter(5), p, control);
    EXPECT_EQ(whole.stats.sliced_facets, m.facets.size()) << name;
    EXPECT_LT(sliced.stats.sliced_facets, m.facets.size()) << name;
    ASSERT_EQ(whole.paths.size(), sliced.paths.size()) << name;
    for (std::size_t i = 0; i < whole.paths.size(); ++i) {
      ASSERT_EQ(whole.paths[i].size(), sliced.paths[i].size()) << name << " path " << i;
      for (std::size_t k = 0; k < whole.paths[i].size(); ++k)
        EXPECT_LE((whole.paths[i][k] - sliced.paths[i][k]).norm(), kSplitRounding) << name;
    }
    // The sliced run's paths keep the ball clear of the part as given (brute force; on bunny00
    // its first three paths, for time).
    const std::size_t n = std::string(name) == "bunny00" ? 3 : sliced.paths.size();
    test_meshes::expect_no_gouge(
        m,
        {sliced.paths.begin(),
         sliced.paths.begin() + std::ptrdiff_t(std::min(n, sliced.paths.size()))},
        2.5);
    ASSERT_EQ(whole.points.size(), sliced.points.size()) << name;
    for (std::size_t k = 0; k < whole.points.size(); ++k) {
      EXPECT_LE((whole.points[k].position - sliced.points[k].position).norm(), kSplitRounding);
      EXPECT_EQ(whole.points[k].kept, sliced.points[k].kept) << name << " point " << k;
    }
  }
}

}  // namespace
}  // namespace ncpath
