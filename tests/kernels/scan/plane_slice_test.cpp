// Offset elements and drive-plane slicing (kernels/mesh/offset_elements, kernels/scan/
// plane_slice): analytic cases, every piece point at distance R from its element (oracles
// written here, independent of the kernels), and the upper envelope of all pieces equal to
// the point drop-cutter (kernels/cutters/drop_cutter.hpp) with a ball.
#include "kernels/scan/plane_slice.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "kernels/cutters/drop_cutter.hpp"
#include "kernels/mesh/offset_elements.hpp"
#include "tests/kernels/scan/scan_test_support.hpp"

namespace ncpath {
namespace {

using namespace scan_test;

void check_mesh(const TriangleMesh& mesh, std::mt19937_64& rng, int planes, int xs_per_plane,
                int& drop_checks) {
  const double R = 1.25;
  const OffsetElements el = build_offset_elements(mesh, R);
  const auto facets = prepare_all(mesh);
  const Cutter ball = ball_cutter(2 * R);
  std::uniform_real_distribution<double> ry(-1, 21), rx(-1.5, 21.5), u01(0, 1);
  int piece_checks = 0;
  for (int k = 0; k < planes; ++k) {
    const double y0 = ry(rng);
    // Whole pieces on even planes, trimmed ones on odd planes: both envelopes are the
    // drop-cutter.
    const auto pieces = slice_all(el, y0, k % 2 == 1);
    ASSERT_FALSE(pieces.empty());
    for (const SlicePiece& pc : pieces) {
      ASSERT_LE(pc.x0, pc.x1);
      for (int s = 0; s < 3; ++s) {
        const double x = pc.x0 + (pc.x1 - pc.x0) * (s == 0 ? 0.0 : s == 1 ? 1.0 : u01(rng));
        const PieceContact c = piece_contact(pc, x);
        ASSERT_NEAR(c.centre.z(), tip_z(pc, x) + R, 1e-12);
        EXPECT_NEAR(element_distance(el, mesh, pc.element, c.centre), R, kDistTol)
            << piece_kind_name(pc.kind) << " element " << pc.element << " x " << x;
        // The contact point is on the element and the normal is the unit vector to the centre.
        EXPECT_NEAR(element_distance(el, mesh, pc.element, c.cc), 0, kDistTol);
        EXPECT_NEAR(c.normal.norm(), 1, 1e-12);
        EXPECT_LT((c.cc + R * c.normal - c.centre).norm(), kDistTol);
        ++piece_checks;
      }
    }
    for (int s = 0; s < xs_per_plane; ++s) {
      const double x = rx(rng);
      const double want = drop_all(ball, facets, x, y0);
      const double got = envelope_tip(pieces, x);
      if (std::isinf(want)) {
        EXPECT_TRUE(std::isinf(got) && got < 0) << "x " << x << " y " << y0;
      } else {
        EXPECT_NEAR(got, want, kDropTol) << "x " << x << " y " << y0;
      }
      ++drop_checks;
    }
  }
  EXPECT_GT(piece_checks, 1000);
}

TEST(PlaneSlice, RandomSoupMatchesDistanceAndDropCutter) {
  std::mt19937_64 rng(5);
  int drop_checks = 0;
  for (int m = 0; m < 3; ++m) check_mesh(random_soup(rng, 300), rng, 12, 60, drop_checks);
  EXPECT_GE(drop_checks, 2000);
}

TEST(PlaneSlice, RandomTerrainMatchesDistanceAndDropCutter) {
  std::mt19937_64 rng(55);
  int drop_checks = 0;
  for (int m = 0; m < 2; ++m) check_mesh(random_terrain(rng, 13), rng, 12, 90, drop_checks);
  EXPECT_GE(drop_checks, 2000);
}

// ---- analytic cases ----

TriangleMesh one_triangle(const Vec3& a, const Vec3& b, const Vec3& c) {
  return TriangleMesh{{a, b, c}, {{0, 1, 2}}};
}

TEST(OffsetElements, OpenSingleFacet) {
  const auto mesh = one_triangle({0, 0, 1}, {10, 0, 1}, {0, 10, 2});
  const OffsetElements el = build_offset_elements(mesh, 2);
  ASSERT_EQ(el.facet_count(), 1u);
  ASSERT_EQ(el.edge_count(), 3u);
  ASSERT_EQ(el.vertex_count(), 3u);
  EXPECT_EQ(el.element_count(), 7u);
  EXPECT_EQ(el.edge_id(0), 1u);
  EXPECT_EQ(el.vertex_id(0), 4u);
  for (std::size_t e = 0; e < 3; ++e) {
    EXPECT_EQ(el.edge_kind[e], EdgeKind::kBoundary);
    EXPECT_EQ(el.edge_facet_count[e], 1u);
  }
  // Offset triangle: source + R n, n upward.
  const Vec3 n = Vec3(0, -10, 100).normalized();
  EXPECT_LT((el.facet_normal[0] - n).norm(), 1e-15);
  EXPECT_LT((el.offset_tri(0)[1] - (Vec3(10, 0, 1) + 2 * n)).norm(), 1e-14);
}

TEST(OffsetElements, DownwardWindingGivesUpwardNormal) {
  const auto mesh = one_triangle({0, 0, 0}, {0, 10, 0}, {10, 0, 0});  // clockwise from above
  const OffsetElements el = build_offset_elements(mesh, 1);
  ASSERT_EQ(el.facet_count(), 1u);
  EXPECT_EQ(el.facet_normal[0], Vec3(0, 0, 1));
  EXPECT_EQ(el.offset_tri(0)[0], Vec3(0, 0, 1));
}

TEST(OffsetElements, DegenerateFacetContributesNothing) {
  TriangleMesh mesh{{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 1, 3}}};
  const OffsetElements el = build_offset_elements(mesh, 1);
  EXPECT_EQ(el.facet_count(), 1u);
  EXPECT_EQ(el.facet_source[0], 1u);
  EXPECT_EQ(el.edge_count(), 3u);
  EXPECT_EQ(el.vertex_count(), 3u);  // vertex 2 only belongs to the degenerate facet
}

// Two facets on the x axis edge (0,0,0)-(10,0,0), the second at y < 0 with height s*|y|.
EdgeKind kind_of_hinge(double s) {
  TriangleMesh mesh{{{0, 0, 0}, {10, 0, 0}, {5, 8, 0}, {5, -8, 8 * s}}, {{0, 1, 2}, {1, 0, 3}}};
  const OffsetElements el = build_offset_elements(mesh, 1);
  for (std::size_t e = 0; e < el.edge_count(); ++e)
    if (el.edge_vertices[e] == std::array<std::uint32_t, 2>{0, 1}) {
      EXPECT_EQ(el.edge_facet_count[e], 2u);
      return el.edge_kind[e];
    }
  ADD_FAILURE() << "hinge edge missing";
  return EdgeKind::kBoundary;
}

TEST(OffsetElements, EdgeKinds) {
  EXPECT_EQ(kind_of_hinge(0.5), EdgeKind::kConcave);
  EXPECT_EQ(kind_of_hinge(-0.5), EdgeKind::kConvex);
  EXPECT_EQ(kind_of_hinge(0), EdgeKind::kFlat);
  TriangleMesh fan{{{0, 0, 0}, {10, 0, 0}, {5, 8, 0}, {5, -8, 1}, {5, 0, 9}},
                   {{0, 1, 2}, {0, 1, 3}, {0, 1, 4}}};
  const OffsetElements el = build_offset_elements(fan, 1);
  EXPECT_EQ(el.edge_count(), 7u);
  EXPECT_EQ(el.edge_kind[0], EdgeKind::kNonManifold);
  EXPECT_EQ(el.edge_facet_count[0], 3u);
}

TEST(PlaneSlice, HorizontalFacetGivesPlaneHeight) {
  const auto mesh = one_triangle({-100, -100, 3.5}, {100, -100, 3.5}, {0, 100, 3.5});
  const double R = 2;
  const OffsetElements el = build_offset_elements(mesh, R);
  const auto pieces = slice_all(el, 7);
  int facet_pieces = 0;
  for (const SlicePiece& pc : pieces)
    if (pc.kind == PieceKind::kFacetLine) {
      ++facet_pieces;
      EXPECT_NEAR(pc.x0, -46.5, 1e-12);  // the triangle's width at y = 7
      EXPECT_NEAR(pc.x1, 46.5, 1e-12);
      double slope, intercept;
      ASSERT_TRUE(line_of(pc, slope, intercept));
      EXPECT_EQ(slope, 0);
      EXPECT_DOUBLE_EQ(intercept, 3.5 + R);
      EXPECT_DOUBLE_EQ(tip_z(pc, 12.25), 3.5);
      EXPECT_EQ(piece_contact(pc, 1).normal, Vec3(0, 0, 1));
    }
  EXPECT_EQ(facet_pieces, 1);
  for (double x : {-40.0, 0.0, 33.0}) EXPECT_DOUBLE_EQ(envelope_tip(pieces, x), 3.5);
}

TEST(PlaneSlice, SphereThroughCentreIsHalfCircle) {
  const auto mesh = one_triangle({1, 2, 3}, {11, 2, 3}, {1, 12, 3});
  const double R = 1.5;
  const OffsetElements el = build_offset_elements(mesh, R);
  const auto pieces = slice_all(el, 12);  // through vertex (1, 12, 3) only
  const SlicePiece* arc = nullptr;
  for (const SlicePiece& pc : pieces)
    if (pc.kind == PieceKind::kSphereArc) {
      EXPECT_EQ(arc, nullptr);
      arc = &pc;
    }
  ASSERT_NE(arc, nullptr);
  EXPECT_DOUBLE_EQ(arc->x0, 1 - R);
  EXPECT_DOUBLE_EQ(arc->x1, 1 + R);
  for (double dx : {-1.5, -1.0, 0.0, 0.3, 1.4999, 1.5})
    EXPECT_NEAR(centre_z(*arc, 1 + dx), 3 + std::sqrt(R * R - dx * dx), 1e-12);
  const PieceContact c = piece_contact(*arc, 1 + 0.9);
  EXPECT_LT((c.normal - Vec3(0.9, 0, 1.2) / 1.5).norm(), 1e-14);
  // A plane at distance 0.9 from the vertex: circle of radius 1.2.
  for (const SlicePiece& pc : slice_all(el, 12.9)) {
    if (pc.kind == PieceKind::kSphereArc) {
      EXPECT_NEAR(pc.x1 - pc.x0, 2.4, 1e-12);
    }
  }
}

// An edge along x at height 4, the drive plane at distance d from it: the cylinder gives
// the line z = 4 + sqrt(R^2 - d^2) over exactly the edge's x range, its caps pushed out by
// tol::kTrimExtend along the edge.
TEST(PlaneSlice, CylinderParallelToPlaneIsLine) {
  const auto mesh = one_triangle({0, 0, 4}, {10, 0, 4}, {5, -6, -20});
  const double R = 2, d = 1.2;
  const OffsetElements el = build_offset_elements(mesh, R);
  int lines = 0;
  for (const SlicePiece& pc : slice_all(el, d))
    if (pc.kind == PieceKind::kCylinderLine) {
      ++lines;
      EXPECT_NEAR(pc.x0, -tol::kTrimExtend, 1e-12);
      EXPECT_NEAR(pc.x1, 10 + tol::kTrimExtend, 1e-12);
      double slope, intercept;
      ASSERT_TRUE(line_of(pc, slope, intercept));
      EXPECT_NEAR(slope, 0, 1e-15);
      EXPECT_NEAR(intercept, 4 + 1.6, 1e-12);
      EXPECT_NEAR(centre_z(pc, 3.3), 5.6, 1e-12);
    }
  EXPECT_EQ(lines, 1);
}

// An edge along y: the section is the circle of radius R around the edge's trace.
TEST(PlaneSlice, CylinderPerpendicularToPlaneIsCircle) {
  const auto mesh = one_triangle({2, 0, 1}, {2, 10, 1}, {-5, 5, -30});
  const double R = 1;
  const OffsetElements el = build_offset_elements(mesh, R);
  int circles = 0;
  for (const SlicePiece& pc : slice_all(el, 4))
    if (pc.kind == PieceKind::kCylinderCircle) {
      ++circles;
      EXPECT_DOUBLE_EQ(pc.x0, 1);
      EXPECT_DOUBLE_EQ(pc.x1, 3);
      EXPECT_NEAR(centre_z(pc, 2.6), 1 + 0.8, 1e-12);
      SectionEllipse e;
      ASSERT_TRUE(ellipse_of(pc, e));
      EXPECT_DOUBLE_EQ(e.major, 1);
      EXPECT_EQ(e.centre, Vec2(2, 1));
    }
  EXPECT_EQ(circles, 1);
}

// A horizontal diagonal edge (45 degrees to the plane): an elliptic arc whose points satisfy
// the ellipse equation of ellipse_of (semi-axes R sqrt(2) along the edge, R vertically).
TEST(PlaneSlice, DiagonalCylinderIsEllipse) {
  const auto mesh = one_triangle({0, 0, 2}, {10, 10, 2}, {10, 0, -40});
  const double R = 1;
  const OffsetElements el = build_offset_elements(mesh, R);
  int ellipses = 0;
  for (const SlicePiece& pc : slice_all(el, 5))
    if (pc.kind == PieceKind::kCylinderEllipse && std::abs(pc.dir.x() - pc.dir.y()) < 1e-15) {
      ++ellipses;
      SectionEllipse e;
      ASSERT_TRUE(ellipse_of(pc, e));
      EXPECT_NEAR(e.centre.x(), 5, 1e-12);
      EXPECT_NEAR(e.centre.y(), 2, 1e-12);
      EXPECT_NEAR(e.major, std::sqrt(2.0), 1e-12);
      EXPECT_NEAR(e.minor, 1, 0);
      EXPECT_NEAR(pc.x0, 5 - std::sqrt(2.0), 1e-12);  // the whole upper half of the ellipse
      EXPECT_NEAR(pc.x1, 5 + std::sqrt(2.0), 1e-12);
      for (double x : {4.0, 5.0, 5.7, 6.4}) {
        const double dx = x - 5, dz = centre_z(pc, x) - 2;
        EXPECT_NEAR(dx * dx / 2 + dz * dz, 1, 1e-12);
        EXPECT_GE(dz, 0);
      }
    }
  EXPECT_EQ(ellipses, 1);
}

// Near its end the diagonal edge's cylinder is cut by the end plane: the piece stops where
// the section meets the plane through the end perpendicular to the edge.
TEST(PlaneSlice, CylinderClippedAtEdgeEnd) {
  const auto mesh = one_triangle({0, 0, 2}, {10, 10, 2}, {10, 0, -40});
  const OffsetElements el = build_offset_elements(mesh, 1);
  for (const SlicePiece& pc : slice_all(el, 9.5))
    if (pc.kind == PieceKind::kCylinderEllipse && std::abs(pc.dir.x() - pc.dir.y()) < 1e-15) {
      // End plane x + y = 20 (pushed out by tol::kTrimExtend along the edge, i.e. x + y =
      // 20 + sqrt(2) kTrimExtend) at y = 9.5: x <= 10.5 + sqrt(2) kTrimExtend.
      EXPECT_NEAR(pc.x1, 10.5 + std::sqrt(2.0) * tol::kTrimExtend, 1e-12);
      EXPECT_NEAR(pc.x0, 9.5 - std::sqrt(2.0), 1e-12);
    }
}

TEST(PlaneSlice, SplitRangesGiveTheSamePieces) {
  std::mt19937_64 rng(9);
  const TriangleMesh mesh = random_terrain(rng, 6);
  const OffsetElements el = build_offset_elements(mesh, 0.8);
  const auto all = slice_all(el, 7.3, true);
  std::vector<SlicePiece> split;
  const auto n = std::uint32_t(el.element_count());
  for (std::uint32_t b = 0; b < n; b += 7) slice_elements(el, 7.3, b, std::min(n, b + 7), split);
  // Trimming removes pieces: fewer than the whole ones, none longer.
  EXPECT_LT(all.size() + 5, slice_all(el, 7.3, false).size());
  ASSERT_EQ(all.size(), split.size());
  for (std::size_t i = 0; i < all.size(); ++i) {
    EXPECT_EQ(all[i].element, split[i].element);
    EXPECT_EQ(all[i].x0, split[i].x0);
    EXPECT_EQ(all[i].x1, split[i].x1);
  }
}

TEST(PlaneSlice, TrimmedPiecesLieWithinTheElementsYReach) {
  // element_y_reach bounds the planes that get a trimmed piece: every element that gives
  // one in a plane must reach that plane; and the reach is not the whole +-R band.
  std::mt19937_64 rng(31);
  for (const TriangleMesh& mesh : {random_terrain(rng, 9), random_soup(rng, 60)}) {
    const OffsetElements el = build_offset_elements(mesh, 1.1);
    std::uniform_real_distribution<double> ry(-1, 21);
    int pieces = 0, narrower = 0;
    for (std::uint32_t id = 0; id < el.element_count(); ++id) {
      double lo = 0, hi = 0;
      const bool reach = element_y_reach(el, id, lo, hi);
      if (id >= el.facet_count() && reach && hi - lo < 2 * 1.1 - 1e-6) ++narrower;
      for (int k = 0; k < 30; ++k) {
        const double y0 = ry(rng);
        std::vector<SlicePiece> out;
        slice_elements(el, y0, id, id + 1, out, true);
        if (!element_reachable(el, id)) continue;
        for (const SlicePiece& pc : out) {
          ASSERT_TRUE(reach) << "element " << id;
          EXPECT_GE(y0, lo) << "element " << id;
          EXPECT_LE(y0, hi) << "element " << id;
          ++pieces;
          (void)pc;
        }
      }
    }
    EXPECT_GT(pieces, 300);
    EXPECT_GT(narrower, 20);
  }
}

}  // namespace
}  // namespace ncpath
