// Tests kernels/mesh/subdivide.*: counts against a brute-force edge set, exact midpoints
// (dyadic coordinates make 0.5 * (a + b) exact), area and winding preserved per facet,
// closed stays closed, determinism and input-not-modified.
#include "kernels/mesh/subdivide.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cstdint>
#include <limits>
#include <map>
#include <utility>

namespace ncpath {
namespace {

using Edge = std::pair<std::uint32_t, std::uint32_t>;

Edge edge(std::uint32_t u, std::uint32_t v) { return {std::min(u, v), std::max(u, v)}; }

// Brute-force oracle: undirected edge -> number of facets using it.
std::map<Edge, int> edge_use(const TriangleMesh& m) {
  std::map<Edge, int> use;
  for (const auto& f : m.facets)
    for (int k = 0; k < 3; ++k) ++use[edge(f[k], f[(k + 1) % 3])];
  return use;
}

Vec3 doubled_normal(const TriangleMesh& m, const std::array<std::uint32_t, 3>& f) {
  const Vec3& a = m.vertices[f[0]];
  return (m.vertices[f[1]] - a).cross(m.vertices[f[2]] - a);
}

double area(const TriangleMesh& m) {
  double sum = 0.0;
  for (const auto& f : m.facets) sum += 0.5 * doubled_normal(m, f).norm();
  return sum;
}

// Closed, outward-wound, integer coordinates: V=4, E=6, F=4.
TriangleMesh tetrahedron() {
  return {{Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(0, 4, 0), Vec3(0, 0, 4)},
          {{{0, 2, 1}}, {{0, 1, 3}}, {{0, 3, 2}}, {{1, 2, 3}}}};
}

// Closed unit-ish box, two facets a side, outward: V=8, E=18, F=12.
TriangleMesh box() {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i)
    m.vertices.emplace_back(i & 1 ? 2 : -2, i & 2 ? 1 : -1, i & 4 ? 3 : 0);
  m.facets = {{{0, 2, 1}}, {{1, 2, 3}}, {{4, 5, 6}}, {{5, 7, 6}}, {{0, 1, 4}}, {{1, 5, 4}},
              {{2, 6, 3}}, {{3, 6, 7}}, {{0, 4, 2}}, {{2, 4, 6}}, {{1, 3, 5}}, {{3, 7, 5}}};
  return m;
}

// Open: two facets sharing edge {1, 2}, plus an unreferenced vertex 4. V=5, E=5, F=2.
TriangleMesh open_strip() {
  return {{Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 2, 0), Vec3(2, 2, 1), Vec3(9, 9, 9)},
          {{{0, 1, 2}}, {{1, 3, 2}}}};
}

TEST(SubdivideMidpoint, FacetsTimesFourVerticesPlusEdges) {
  for (const TriangleMesh& m : {tetrahedron(), box(), open_strip()}) {
    const TriangleMesh s = subdivide_midpoint(m);
    EXPECT_EQ(s.facets.size(), 4 * m.facets.size());
    EXPECT_EQ(s.vertices.size(), m.vertices.size() + edge_use(m).size());
  }
  // The known counts, not just the oracle: tetrahedron 4+6, box 8+18, strip 5+5.
  EXPECT_EQ(subdivide_midpoint(tetrahedron()).vertices.size(), 10u);
  EXPECT_EQ(subdivide_midpoint(box()).vertices.size(), 26u);
  EXPECT_EQ(subdivide_midpoint(open_strip()).vertices.size(), 10u);
}

TEST(SubdivideMidpoint, ClosedStaysClosedAndEulerIsKept) {
  for (const TriangleMesh& m : {tetrahedron(), box()}) {
    const TriangleMesh s = subdivide_midpoint(subdivide_midpoint(m));
    const auto use = edge_use(s);
    for (const auto& [e, n] : use) EXPECT_EQ(n, 2) << e.first << "-" << e.second;
    const long chi = static_cast<long>(s.vertices.size()) - static_cast<long>(use.size()) +
                     static_cast<long>(s.facets.size());
    EXPECT_EQ(chi, 2);  // genus 0
    EXPECT_EQ(s.facets.size(), 16 * m.facets.size());
  }
}

TEST(SubdivideMidpoint, KeepsCornersAndPlacesExactMidpoints) {
  for (const TriangleMesh& m : {tetrahedron(), box(), open_strip()}) {
    const TriangleMesh s = subdivide_midpoint(m);
    for (std::size_t i = 0; i < m.vertices.size(); ++i) EXPECT_EQ(s.vertices[i], m.vertices[i]);
    for (std::size_t i = 0; i < m.facets.size(); ++i) {
      const auto& f = m.facets[i];
      const Vec3 &a = m.vertices[f[0]], &b = m.vertices[f[1]], &c = m.vertices[f[2]];
      const auto &c0 = s.facets[4 * i], &c1 = s.facets[4 * i + 1], &c2 = s.facets[4 * i + 2],
                 &c3 = s.facets[4 * i + 3];
      EXPECT_EQ(c0[0], f[0]);
      EXPECT_EQ(c1[1], f[1]);
      EXPECT_EQ(c2[2], f[2]);
      // Integer inputs: halves are exact, so compare with ==.
      EXPECT_EQ(s.vertices[c3[0]], Vec3((a + b) / 2));
      EXPECT_EQ(s.vertices[c3[1]], Vec3((b + c) / 2));
      EXPECT_EQ(s.vertices[c3[2]], Vec3((c + a) / 2));
      EXPECT_EQ(c0[1], c3[0]);
      EXPECT_EQ(c0[2], c3[2]);
      EXPECT_EQ(c1[0], c3[0]);
      EXPECT_EQ(c1[2], c3[1]);
      EXPECT_EQ(c2[0], c3[2]);
      EXPECT_EQ(c2[1], c3[1]);
    }
  }
}

TEST(SubdivideMidpoint, SharedEdgeGetsOneMidpoint) {
  const TriangleMesh s = subdivide_midpoint(open_strip());
  // Facet 0 edge bc = {1,2} is facet 1 edge ca = {2,1}.
  EXPECT_EQ(s.facets[3][1], s.facets[7][2]);
  EXPECT_EQ(s.vertices[s.facets[3][1]], Vec3(1, 1, 0));
  // First-appearance numbering: facet 0's ab, bc, ca, then facet 1's ab, bc.
  EXPECT_EQ(s.facets[3][0], 5u);
  EXPECT_EQ(s.facets[3][1], 6u);
  EXPECT_EQ(s.facets[3][2], 7u);
  EXPECT_EQ(s.facets[7][0], 8u);
  EXPECT_EQ(s.facets[7][1], 9u);
}

TEST(SubdivideMidpoint, NonManifoldEdgeGetsOneMidpoint) {
  // Three facets on edge {0, 1}.
  TriangleMesh m{{Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 2, 0), Vec3(0, 0, 2), Vec3(0, -2, 0)},
                 {{{0, 1, 2}}, {{1, 0, 3}}, {{0, 1, 4}}}};
  const TriangleMesh s = subdivide_midpoint(m);
  EXPECT_EQ(s.vertices.size(), m.vertices.size() + edge_use(m).size());
  EXPECT_EQ(s.facets[3][0], s.facets[7][0]);
  EXPECT_EQ(s.facets[3][0], s.facets[11][0]);
}

TEST(SubdivideMidpoint, AreaAndWindingPreserved) {
  TriangleMesh m = box();
  // Non-dyadic coordinates: area holds to rounding, not exactly.
  for (Vec3& p : m.vertices) p = Vec3(p.x() * 0.1 + 0.3, p.y() / 3.0, p.z() * 1.7);
  const TriangleMesh s = subdivide_midpoint(m);
  EXPECT_NEAR(area(s), area(m), 1e-14 * area(m));
  for (std::size_t i = 0; i < m.facets.size(); ++i) {
    const Vec3 n = doubled_normal(m, m.facets[i]);
    for (int k = 0; k < 4; ++k) {
      const Vec3 nk = doubled_normal(s, s.facets[4 * i + k]);
      // Each child is the parent scaled by 1/2 (about a corner or, for 4i+3, rotated by
      // pi in-plane): same normal direction, a quarter of the area.
      EXPECT_NEAR(nk.norm(), 0.25 * n.norm(), 1e-14 * n.norm());
      EXPECT_GT(nk.dot(n), 0.0);
    }
  }
}

TEST(SubdivideMidpoint, DeterministicAndInputUntouched) {
  const TriangleMesh original = box();
  TriangleMesh input = box();
  const TriangleMesh a = subdivide_midpoint(input);
  const TriangleMesh b = subdivide_midpoint(input);
  EXPECT_EQ(input.vertices, original.vertices);
  EXPECT_EQ(input.facets, original.facets);
  EXPECT_EQ(a.vertices, b.vertices);
  EXPECT_EQ(a.facets, b.facets);
}

TEST(SubdivideMidpoint, EmptyMeshKeepsVertices) {
  TriangleMesh m{{Vec3(1, 2, 3)}, {}};
  const TriangleMesh s = subdivide_midpoint(m);
  EXPECT_TRUE(s.facets.empty());
  ASSERT_EQ(s.vertices.size(), 1u);
  EXPECT_EQ(s.vertices[0], Vec3(1, 2, 3));
}

TEST(SubdivideMidpoint, FitsGuardsIndexOverflow) {
  constexpr std::size_t kMax = std::numeric_limits<std::uint32_t>::max();
  EXPECT_TRUE(subdivide_midpoint_fits(44460, 88928));
  EXPECT_TRUE(subdivide_midpoint_fits(0, kMax / 4));
  EXPECT_FALSE(subdivide_midpoint_fits(0, kMax / 4 + 1));
  EXPECT_TRUE(subdivide_midpoint_fits(kMax - 3 * 1000, 1000));
  EXPECT_FALSE(subdivide_midpoint_fits(kMax - 3 * 1000 + 1, 1000));
}

}  // namespace
}  // namespace ncpath

namespace ncpath {
namespace {

// Regular octahedron, outward: every vertex has valence 4, every edge two facets.
TriangleMesh octahedron() {
  TriangleMesh m;
  m.vertices = {Vec3(1, 0, 0), Vec3(-1, 0, 0), Vec3(0, 1, 0),
                Vec3(0, -1, 0), Vec3(0, 0, 1), Vec3(0, 0, -1)};
  m.facets = {{{0, 2, 4}}, {{2, 1, 4}}, {{1, 3, 4}}, {{3, 0, 4}},
              {{2, 0, 5}}, {{1, 2, 5}}, {{3, 1, 5}}, {{0, 3, 5}}};
  return m;
}

// Loop's rules by hand on the octahedron: valence 4, beta = (5/8 - (3/8)^2) / 4 = 31/256, so
// (1, 0, 0) goes to (1 - 4 beta) (1, 0, 0) + beta (sum of its 4 neighbours = 0) =
// (33/64, 0, 0); the edge point of {(1,0,0), (0,1,0)} is 3/8 (1, 1, 0) + 1/8 ((0,0,1) +
// (0,0,-1)) = (3/8, 3/8, 0).
TEST(SubdivideLoop, OctahedronByHand) {
  const TriangleMesh m = octahedron();
  const TriangleMesh l = subdivide_loop(m);
  const TriangleMesh mid = subdivide_midpoint(m);
  ASSERT_EQ(l.facets, mid.facets);  // the same topology and numbering
  ASSERT_EQ(l.vertices.size(), mid.vertices.size());
  for (int k = 0; k < 6; ++k)
    EXPECT_NEAR((l.vertices[k] - 33.0 / 64 * m.vertices[k]).norm(), 0, 1e-15) << k;
  for (std::size_t v = 6; v < l.vertices.size(); ++v) {
    // Every edge of the octahedron joins two unit vectors on different axes: its Loop point
    // is 3/8 of their sum (the opposite corners cancel).
    EXPECT_NEAR((l.vertices[v] - 0.75 * mid.vertices[v]).norm(), 0, 1e-15) << v;
  }
}

// On a plane, a regular grid (valence 6 inside) is reproduced by the vertex rule (beta =
// 1/16, the ring sums to 6 v) and every point stays in the plane; boundary edges are creases
// (midpoints) and the boundary vertices with two crease edges move to 3/4 v + 1/8 (ends),
// which on a straight border is v again.
TEST(SubdivideLoop, FlatRegularGridStaysPutAndFlat) {
  TriangleMesh m;
  const int n = 6;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) m.vertices.emplace_back(i + 0.5 * j, 0.8660254037844386 * j, 2);
  const auto id = [&](int i, int j) { return static_cast<std::uint32_t>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      m.facets.push_back({{id(i, j), id(i + 1, j), id(i, j + 1)}});
      m.facets.push_back({{id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)}});
    }
  const TriangleMesh l = subdivide_loop(m);
  for (const Vec3& p : l.vertices) EXPECT_NEAR(p.z(), 2, 1e-12);
  for (int j = 1; j < n; ++j)
    for (int i = 1; i < n; ++i)
      EXPECT_NEAR((l.vertices[id(i, j)] - m.vertices[id(i, j)]).norm(), 0, 1e-12) << i << "," << j;
  // Vertices inside a straight border keep their place (3/4 v + 1/8 (v - t) + 1/8 (v + t));
  // the grid's corners, whose two border edges turn, do not.
  for (int i = 1; i < n; ++i)
    EXPECT_NEAR((l.vertices[id(i, 0)] - m.vertices[id(i, 0)]).norm(), 0, 1e-12) << i;
}

// A sphere-like closed mesh shrinks towards its limit surface and every vertex moves: no two
// facets of the result are coplanar (what makes Loop meshes scan-like); the closed mesh stays
// closed with F' = 4F; the same input gives the same bytes.
TEST(SubdivideLoop, ClosedMeshEveryVertexMovesNoCoplanarNeighbours) {
  const TriangleMesh once = subdivide_loop(octahedron());
  const TriangleMesh twice = subdivide_loop(once);
  EXPECT_EQ(twice.facets.size(), 4 * once.facets.size());
  for (const auto& [e, uses] : edge_use(twice)) EXPECT_EQ(uses, 2);
  for (std::size_t v = 0; v < once.vertices.size(); ++v)
    EXPECT_GT((twice.vertices[v] - once.vertices[v]).norm(), 1e-6) << v;
  // Neighbouring facets (sharing an edge) are never coplanar.
  std::map<Edge, std::vector<std::size_t>> by_edge;
  for (std::size_t f = 0; f < twice.facets.size(); ++f)
    for (int k = 0; k < 3; ++k)
      by_edge[edge(twice.facets[f][k], twice.facets[f][(k + 1) % 3])].push_back(f);
  for (const auto& [e, fs] : by_edge) {
    const Vec3 a = doubled_normal(twice, twice.facets[fs[0]]).normalized();
    const Vec3 b = doubled_normal(twice, twice.facets[fs[1]]).normalized();
    EXPECT_GT(a.cross(b).norm(), 1e-6);
  }
  const TriangleMesh again = subdivide_loop(subdivide_loop(octahedron()));
  EXPECT_EQ(again.vertices, twice.vertices);
}

}  // namespace
}  // namespace ncpath
