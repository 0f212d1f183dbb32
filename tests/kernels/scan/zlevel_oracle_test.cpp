// Z-level contours (kernels/scan/zlevel) against independent oracles on random soups and
// terrains: contour points on the brute-force drop-cutter surface at the level, U on the left
// of every segment, point-in-contours equal to "drop >= level", bi-contact vectors at distance
// R from their elements (zlevel_test_support.hpp); the same on a real CAD part
// (datasets/cache/meshes/anchor_dense.off); the result does not depend on the candidates'
// order or repetition, nor on the pruning grid, nor on element boxes gathered beforehand.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "kernels/scan/zlevel.hpp"
#include "tests/engine/mesh_test_support.hpp"
#include "tests/kernels/scan/zlevel_test_support.hpp"

namespace ncpath {
namespace {

using namespace zlevel_test;

// ---- oracles on random meshes ----

TEST(ZLevel, RandomSoupMatchesDropCutter) {
  std::mt19937_64 rng(11);
  int checks = 0;
  for (int m = 0; m < 3; ++m) {
    const TriangleMesh mesh = random_soup(rng, 60);
    const OffsetElements el = build_offset_elements(mesh, 1.25, Coplanar::kKeep);
    Oracle o(mesh, el);
    std::uniform_real_distribution<double> rz(-3, 6);
    for (int k = 0; k < 5; ++k)
      checks += check_result(o, run(el, rz(rng)), rng, -3, -3, 23, 23, 300);
  }
  EXPECT_GT(checks, 3000);
}

TEST(ZLevel, RandomTerrainMatchesDropCutter) {
  std::mt19937_64 rng(12);
  int checks = 0;
  for (int m = 0; m < 2; ++m) {
    const TriangleMesh mesh = random_terrain(rng, 11);
    const OffsetElements el = build_offset_elements(mesh, 1.25, Coplanar::kKeep);
    Oracle o(mesh, el);
    std::uniform_real_distribution<double> rz(-1, 5.5);
    for (int k = 0; k < 5; ++k)
      checks += check_result(o, run(el, rz(rng)), rng, -3, -3, 23, 23, 300);
  }
  EXPECT_GT(checks, 3000);
}

// Integer heights on an integer grid, levels at and between them: floors exactly at the level,
// edges and vertices exactly at zc - R, coplanar neighbours, flat and collinear edges.
TEST(ZLevel, DegenerateGridTerrainMatchesDropCutter) {
  std::mt19937_64 rng(14);
  std::uniform_int_distribution<int> h(0, 3);
  TriangleMesh mesh;
  const int n = 8;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) mesh.vertices.emplace_back(2.0 * i, 2.0 * j, double(h(rng)));
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const auto a = std::uint32_t(j * n + i);
      mesh.facets.push_back({a, a + 1, a + std::uint32_t(n) + 1});
      mesh.facets.push_back({a, a + std::uint32_t(n) + 1, a + std::uint32_t(n)});
    }
  const OffsetElements el = build_offset_elements(mesh, 1.25, Coplanar::kKeep);
  Oracle o(mesh, el);
  int checks = 0;
  for (double z : {-1.25, 0.0, 0.5, 1.0, 1.75, 2.0, 3.0})
    checks += check_result(o, run(el, z), rng, -3, -3, 17, 17, 300, true);
  EXPECT_GT(checks, 2000);
}

// ---- a real part ----

// CGAL's anchor_dense (a CAD part: vertical walls in many bands, flats), fit to 200 mm in xy
// as the engine's jobs do, ball R 2.5, at levels that left open chains (regression):
//  - a wall's stacked horizontal and sloping edges shadow one line, but their directions, from
//    different end points, differ by rounding (1e-14): taken as lines crossing at that angle,
//    their pieces dropped each other in turn (-40 and the step-down levels);
//  - a sloping wall edge whose lower end lies 1e-5 mm below the ball centre's height: its
//    capsule side is its shadow line and a 4e-5 mm chord ending on it; the chord's crossing
//    with another edge's shadow (the wall's line) dropped that shadow's piece past it, which
//    runs along the shadow line, not the chord (-30.6586);
//  - a sloping wall edge's ellipse leaves its shadow line tangentially while the next edge's
//    shadow runs on; a vertex circle crossing it 2e-5 mm further on left a piece within 1e-11
//    of the wall's line, kept as shared (-62.38465574932556, a vertex's height).
TEST(ZLevel, CadPartWallsCloseEveryLoop) {
  const TriangleMesh mesh = test_meshes::load("anchor_dense");
  const OffsetElements el = build_offset_elements(mesh, 2.5, Coplanar::kKeep);
  Oracle o(mesh, el);
  std::mt19937_64 rng(15);
  for (double z : {-40.0, 30.6586, 10.6586, 0.6586, -19.3414, -30.6586, -62.38465574932556}) {
    check_result(o, run(el, z), rng, -104, -67, 104, 67, 200);
  }
}

// ---- determinism and candidates ----

TEST(ZLevel, CandidateOrderAndFilterDoNotMatter) {
  std::mt19937_64 rng(13);
  const TriangleMesh mesh = random_terrain(rng, 9);
  const OffsetElements el = build_offset_elements(mesh, 1.0, Coplanar::kKeep);
  for (double z : {0.5, 1.7, 2.9}) {
    const ZLevelResult ref = run(el, z);
    ASSERT_FALSE(ref.contours.empty());
    auto ids = all_ids(el);
    ids.insert(ids.end(), ids.begin(), ids.begin() + 40);  // repeats
    std::shuffle(ids.begin(), ids.end(), rng);
    EXPECT_TRUE(same_result(ref, zlevel_contours(el, ids, z)));
    // Only the elements that reach the level (what an engine's z-range filter passes).
    std::vector<std::uint32_t> reach;
    for (std::uint32_t id = 0; id < el.element_count(); ++id) {
      double top;
      if (id < el.facet_count()) {
        const auto t = el.offset_tri(id);
        top = std::max({t[0].z(), t[1].z(), t[2].z()});
      } else if (id < el.facet_count() + el.edge_count()) {
        const auto& e = el.edge_vertices[id - el.facet_count()];
        top = std::max(el.points[e[0]].z(), el.points[e[1]].z()) + el.radius;
      } else {
        top = el.points[el.vertex_source[id - el.facet_count() - el.edge_count()]].z() + el.radius;
      }
      if (top >= z + el.radius) reach.push_back(id);
    }
    EXPECT_TRUE(same_result(ref, zlevel_contours(el, reach, z)));
    // The element boxes gathered once (what the engine passes for all its levels).
    const ZLevelElementBoxes boxes = zlevel_element_boxes(el);
    ZLevelParams pb;
    pb.boxes = &boxes;
    EXPECT_TRUE(same_result(ref, zlevel_contours(el, reach, z, pb)));
    EXPECT_TRUE(same_result(ref, zlevel_contours(el, ids, z, pb)));
    // A different pruning grid gives the same loops (areas).
    ZLevelParams p;
    p.cell = 0.37;
    const ZLevelResult other = run(el, z, p);
    ASSERT_EQ(other.contours.size(), ref.contours.size());
    for (std::size_t i = 0; i < ref.contours.size(); ++i)
      EXPECT_NEAR(other.contours[i].area, ref.contours[i].area, 1e-9);
  }
}

}  // namespace
}  // namespace ncpath
