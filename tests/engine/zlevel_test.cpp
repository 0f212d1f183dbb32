// Z-level contouring (engine/zlevel.hpp): on each contour the point drop-cutter equals the
// level (the tool touches there) and just outside it is below; the polylines never gouge
// (brute-force distance from the ball to the mesh) and stay within the tolerance; levels
// from a step-down; 1 and 2 threads give identical output; bad input is named.
#include "engine/zlevel.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "engine/drop_index.hpp"
#include "engine/parallel.hpp"
#include "kernels/geom/tolerance.hpp"
#include "kernels/mesh/subdivide.hpp"
#include "kernels/scan/envelope.hpp"
#include "tests/engine/mesh_test_support.hpp"
#include "tests/kernels/scan/scan_test_support.hpp"

namespace ncpath {
namespace {

struct Collected {
  ClChunk cl;
  std::vector<ZLevelSegmentRecord> segments;
  std::vector<ZLevelJunctionRecord> junctions;
  std::vector<double> level;
  ZLevelOpStats stats;
};

Collected contour(const TriangleMesh& mesh, const Cutter& c, const ZLevelOpParams& p) {
  Collected out;
  RunControl control;
  out.stats = run_zlevel(
      mesh, c, p,
      [&](const ZLevelChunk& ch) {
        out.cl.append(ch.cl);
        out.segments.insert(out.segments.end(), ch.segments.begin(), ch.segments.end());
        out.junctions.insert(out.junctions.end(), ch.junctions.begin(), ch.junctions.end());
        out.level.insert(out.level.end(), ch.contour_level.begin(), ch.contour_level.end());
      },
      control);
  return out;
}

// Point of a segment record at fraction f, from its geometry columns (docs/hdf5-schema.md).
Vec2 record_point(const ZLevelSegmentRecord& s, double f) {
  const Vec2 a(s.start[0], s.start[1]), b(s.end[0], s.end[1]);
  if (s.kind == 0) return a + f * (b - a);
  const auto& g = s.geometry;
  const Vec2 c(g[0], g[1]), ax(std::cos(g[4]), std::sin(g[4])), perp(-ax.y(), ax.x());
  const double t = g[5] + f * (g[6] - g[5]);
  return c + g[2] * std::cos(t) * ax + g[3] * std::sin(t) * perp;
}

// On every segment: drop-cutter = level (or, where the part has a wall or overhang and the
// drop-cutter jumps there, above the level on the left and below it on the right); just
// right of the segment (outside U) it is below the level. Returns points checked.
// exact = false: the contours of a conditioned mesh (ZLevelOpParams::condition, the ball grown
// by its largest vertex move) against the part as given: on-contour points only never above
// the level (the tool keeps clear), by at most the grown radius' worth below it on slopes.
template <class Drop>
int check_on_contours(const Collected& c, Drop&& drop, std::mt19937_64& rng, int want,
                      bool exact = true) {
  std::uniform_real_distribution<double> u01(0.05, 0.95);
  std::uniform_int_distribution<std::size_t> pick(0, c.segments.size() - 1);
  int n = 0;
  for (int k = 0; k < 20 * want && n < want; ++k) {
    const ZLevelSegmentRecord& s = c.segments[pick(rng)];
    const double z = s.start[2];
    const double f = u01(rng);
    const Vec2 p = record_point(s, f);
    const Vec2 tangent = record_point(s, f + 1e-4) - record_point(s, f - 1e-4);
    if (!(tangent.norm() > 0)) continue;
    const Vec2 right = Vec2(tangent.y(), -tangent.x()).normalized();
    const Vec2 out = p + 1e-4 * right, in = p - 1e-4 * right;
    const double d = drop(p.x(), p.y());
    if (s.shadow) {
      EXPECT_GE(drop(in.x(), in.y()), z - 1e-7) << "shadow segment, inside";
    } else if (exact) {
      EXPECT_NEAR(d, z, 1e-7) << "segment kind " << int(s.kind) << " at " << p.x() << ","
                              << p.y();
    } else {
      EXPECT_LE(d, z + 1e-7) << "segment kind " << int(s.kind) << " at " << p.x() << ","
                             << p.y();
    }
    EXPECT_LT(drop(out.x(), out.y()), z) << "outside at " << out.x() << "," << out.y();
    ++n;
  }
  return n;
}

TEST(ZLevel, TerrainContoursTouchTheLevelAndNeverGouge) {
  std::mt19937_64 rng(3);
  const TriangleMesh mesh = test_meshes::terrain(rng, 13);
  const Cutter ball = ball_cutter(5);
  ZLevelOpParams p;
  p.step_down = 0.7;
  p.tolerance = 0.002;
  const Collected c = contour(mesh, ball, p);
  // Levels top - k step above the bottom.
  EXPECT_EQ(c.stats.levels,
            std::size_t(std::ceil((c.stats.top_z - c.stats.bottom_z) / p.step_down)) - 1);
  EXPECT_EQ(c.stats.open_chains, 0u);
  EXPECT_GT(c.stats.contours, 5u);
  const FacetTable table = build_facet_table(mesh);
  auto drop = [&](double x, double y) { return drop_brute_force(table, ball, x, y).tip_z; };
  EXPECT_EQ(check_on_contours(c, drop, rng, 3000), 3000);
  // Polylines: distance from the ball centre to the mesh at least R, and at most R plus a
  // few tolerances where the ball touches.
  const double R = ball.radius;
  std::size_t k = 0;
  for (std::size_t i = 0; i < c.cl.path_sizes.size(); ++i) {
    for (std::uint32_t j = 0; j < c.cl.path_sizes[i]; ++j, ++k) {
      if (k % 3 != 0) continue;
      const Vec3 centre(c.cl.xyz[3 * k], c.cl.xyz[3 * k + 1], c.cl.xyz[3 * k + 2] + R);
      double dist = INFINITY;
      for (const auto& f : mesh.facets)
        dist = std::min(dist, scan_test::point_triangle_distance(
                                  centre, mesh.vertices[f[0]], mesh.vertices[f[1]],
                                  mesh.vertices[f[2]]));
      ASSERT_GE(dist, R - 1e-9) << "gouge at " << centre.transpose();
      // Beside a wall or under an overhang (drop-cutter above the level) the ball passes
      // the part without touching it; elsewhere it touches within the tolerance.
      double near = -INFINITY;
      for (double dx : {-0.01, 0.0, 0.01})
        for (double dy : {-0.01, 0.0, 0.01})
          near = std::max(near, drop(centre.x() + dx, centre.y() + dy));
      if (near <= centre.z() - R + 1e-6) {
        ASSERT_LE(dist, R + 3 * p.tolerance) << "far at " << centre.transpose();
      }
    }
  }
  // Paths: a cut per contour, a rapid before every contour but the first.
  std::size_t cuts = 0;
  for (std::uint8_t kind : c.cl.path_kinds) cuts += kind == std::uint8_t(PathKind::kCut);
  EXPECT_EQ(cuts, c.stats.contours);
  EXPECT_EQ(c.level.size(), c.stats.contours);
  for (const ZLevelJunctionRecord& j : c.junctions) {
    const Vec3 b1(j.b1[0], j.b1[1], j.b1[2]);
    ASSERT_NEAR(b1.norm(), 1, 1e-9);
  }
}

TEST(ZLevel, OneAndTwoThreadsGiveIdenticalOutput) {
  std::mt19937_64 rng(8);
  const TriangleMesh mesh = test_meshes::terrain(rng, 10);
  ZLevelOpParams p;
  p.step_down = 0.5;
  p.chunk_levels = 2;
  Collected a, b;
  {
    par::ThreadLimit one(1);
    a = contour(mesh, ball_cutter(4), p);
  }
  {
    par::ThreadLimit two(2);
    b = contour(mesh, ball_cutter(4), p);
  }
  EXPECT_EQ(a.cl.xyz, b.cl.xyz);
  EXPECT_EQ(a.cl.path_sizes, b.cl.path_sizes);
  ASSERT_EQ(a.segments.size(), b.segments.size());
  for (std::size_t i = 0; i < a.segments.size(); ++i) {
    EXPECT_EQ(a.segments[i].path, b.segments[i].path);
    EXPECT_EQ(a.segments[i].geometry, b.segments[i].geometry);
  }
}

// Levels after the first chunk use the region of the previous chunk's last level (regions and
// candidates deep inside it left out, kernels/scan/zlevel.hpp ZLevelInside): with one level a
// chunk (every level but the first uses the level above) the contours equal those of one chunk
// for all levels (none does), up to rounding where curves are split; fewer candidates.
TEST(ZLevel, KnownInsideRegionGivesTheSameContours) {
  const TriangleMesh mesh = test_meshes::load("anchor_dense");
  ZLevelOpParams p;
  p.step_down = 4;
  p.chunk_levels = 1000;
  const Collected plain = contour(mesh, ball_cutter(5), p);
  p.chunk_levels = 1;
  const Collected chained = contour(mesh, ball_cutter(5), p);
  EXPECT_EQ(plain.stats.open_chains, 0u);
  EXPECT_EQ(chained.stats.open_chains, 0u);
  EXPECT_LT(chained.stats.candidates, plain.stats.candidates / 2);
  EXPECT_EQ(plain.level, chained.level);
  ASSERT_EQ(plain.segments.size(), chained.segments.size());
  for (std::size_t i = 0; i < plain.segments.size(); ++i) {
    const ZLevelSegmentRecord &a = plain.segments[i], &b = chained.segments[i];
    EXPECT_EQ(a.path, b.path);
    EXPECT_EQ(a.kind, b.kind);
    EXPECT_EQ(a.element.kind, b.element.kind);
    EXPECT_EQ(a.element.a, b.element.a);
    EXPECT_EQ(a.element.b, b.element.b);
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(a.start[k], b.start[k], 1e-9) << "segment " << i;
      EXPECT_NEAR(a.end[k], b.end[k], 1e-9) << "segment " << i;
    }
  }
  ASSERT_EQ(plain.junctions.size(), chained.junctions.size());
  for (std::size_t i = 0; i < plain.junctions.size(); ++i) {
    const ZLevelJunctionRecord &a = plain.junctions[i], &b = chained.junctions[i];
    EXPECT_EQ(a.kind, b.kind);
    EXPECT_EQ(a.element1.a, b.element1.a);
    EXPECT_EQ(a.element2.a, b.element2.a);
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(a.position[k], b.position[k], 1e-9);
      EXPECT_NEAR(a.b1[k], b.b1[k], 1e-9);
      EXPECT_NEAR(a.b2[k], b.b2[k], 1e-9);
    }
  }
}

TEST(ZLevel, RejectsBadInput) {
  std::mt19937_64 rng(1);
  const TriangleMesh mesh = test_meshes::terrain(rng, 4);
  ZLevelOpParams p;
  EXPECT_THROW(contour(mesh, ball_cutter(5), p), std::invalid_argument);  // no levels
  p.step_down = 1;
  p.levels = {2};
  EXPECT_THROW(contour(mesh, ball_cutter(5), p), std::invalid_argument);  // both
  p.levels.clear();
  EXPECT_THROW(contour(mesh, flat_cutter(5), p), std::invalid_argument);
}

TEST(ZLevel, BunnyContoursTouchTheLevel) {
  const TriangleMesh mesh = test_meshes::load("bunny00");
  const Cutter ball = ball_cutter(5);
  ZLevelOpParams p;
  const Aabb3 box = bounding_box(mesh);
  for (double f : {0.2, 0.5, 0.8}) p.levels.push_back(box.lo.z() + f * (box.hi.z() - box.lo.z()));
  const DropIndex index(mesh, ball);
  auto drop = [&](double x, double y) { return index.query(x, y).tip_z; };
  for (const bool condition : {false, true}) {
    p.condition = condition;
    const Collected c = contour(mesh, ball, p);
    EXPECT_EQ(c.stats.open_chains, 0u);
    // bunny00 has a few nearly coplanar facet pairs: the conditioning moves their vertices.
    EXPECT_EQ(c.stats.condition.max_move > 0, condition);
    EXPECT_LE(c.stats.condition.max_move, tol::kConditionMove);
    std::mt19937_64 rng(4);
    EXPECT_EQ(check_on_contours(c, drop, rng, 3000, !condition), 3000);
  }
}

// anchor_dense with every coordinate moved by up to 1e-11 mm (the draw of the first
// ncpath_pencil_invariance: uniform from the top 53 bits of mt19937_64, seed 17): the edge of
// a ledge lies in the plane of a wall below it without being joined to it; unless the
// conditioning puts it on that plane exactly, its shadow runs 1e-10 mm beside the wall's and
// 63 levels kept a duplicate piece that closed no contour. Same contours as the part as given.
TEST(ZLevel, NoisyCadPartClosesEveryContour) {
  const TriangleMesh mesh = test_meshes::load("anchor_dense");
  TriangleMesh noisy = mesh;
  std::mt19937_64 bits(17);
  for (Vec3& v : noisy.vertices)
    for (int i = 0; i < 3; ++i) v[i] += 1e-11 * (2 * double(bits() >> 11) * 0x1.0p-53 - 1);
  ZLevelOpParams p;
  p.step_down = 1;
  const Collected given = contour(mesh, ball_cutter(5), p), moved = contour(noisy, ball_cutter(5), p);
  EXPECT_EQ(given.stats.open_chains, 0u);
  EXPECT_EQ(moved.stats.open_chains, 0u);
  EXPECT_EQ(moved.stats.contours, given.stats.contours);
  EXPECT_EQ(moved.stats.segments, given.stats.segments);
}

// anchor_dense midpoint-subdivided three times and stored in float32 in its own units (extent
// 1), as datasets/make-large-mesh.sh writes anchor_large (486,272 facets), then fit to 200 mm:
// the rounding (up to 6e-6 mm, above the conditioning's plane tolerance when this was written:
// 3e-6), so the walls'
// stacked edges stay ~1e-5 rad apart and their shadows and corner circles nearly coincide
// (before the planar map of the pieces, kernels/scan/zlevel_map.hpp, 31 chains stayed open
// here at 1 mm steps without a repair pass).
TEST(ZLevel, SubdividedFloat32CadPartClosesEveryContour) {
  const std::filesystem::path path =
      std::filesystem::path(NCPATH_SOURCE_DIR) / "datasets/cache/meshes/anchor_dense.off";
  io::MeshReadResult r = io::read_mesh(path);
  TriangleMesh mesh = std::move(r.mesh);
  for (int k = 0; k < 3; ++k) mesh = subdivide_midpoint(mesh);
  for (Vec3& v : mesh.vertices)
    for (int i = 0; i < 3; ++i) v[i] = double(float(v[i]));
  MeshTransform t;
  t.fit_xy_mm = 200;
  ASSERT_TRUE(apply_transform(t, mesh).ok());
  const Cutter ball = ball_cutter(5);
  ZLevelOpParams p;
  p.step_down = 1;
  const Collected c = contour(mesh, ball, p);
  EXPECT_EQ(c.stats.levels, 171u);
  EXPECT_EQ(c.stats.open_chains, 0u);
  const DropIndex index(mesh, ball);
  auto drop = [&](double x, double y) { return index.query(x, y).tip_z; };
  std::mt19937_64 rng(5);
  EXPECT_EQ(check_on_contours(c, drop, rng, 2000, false), 2000);
}

}  // namespace
}  // namespace ncpath
