// Z-level contours with Coplanar::kVertical elements (kernels/mesh/offset_elements.hpp): the
// inner edges and vertices of vertical coplanar regions (a wall split into many triangles,
// whose edges all project onto the wall's line) are dropped, and the contours are those of
// the elements kept in full (Coplanar::kKeep).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "kernels/mesh/offset_elements.hpp"
#include "kernels/mesh/subdivide.hpp"
#include "kernels/scan/zlevel.hpp"
#include "tests/kernels/scan/scan_test_support.hpp"

namespace ncpath {
namespace {

std::vector<std::uint32_t> every_id(const OffsetElements& el) {
  std::vector<std::uint32_t> ids(el.element_count());
  for (std::uint32_t i = 0; i < ids.size(); ++i) ids[i] = i;
  return ids;
}

std::size_t reachable_edges(const OffsetElements& el) {
  std::size_t n = 0;
  for (std::size_t e = 0; e < el.edge_count(); ++e) n += element_reachable(el, el.edge_id(e));
  return n;
}

double segment_distance(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 d = b - a;
  const double l2 = d.squaredNorm();
  const double t = l2 > 0 ? std::clamp((p - a).dot(d) / l2, 0.0, 1.0) : 0.0;
  return (p - (a + t * d)).norm();
}

// Largest distance from a point of one result's contours (discretised within 1e-6) to the
// other's contours (discretised likewise).
double one_sided(const ZLevelResult& a, const ZLevelResult& b) {
  std::vector<std::vector<Vec2>> lb;
  for (const ZContour& c : b.contours) {
    std::vector<Vec2> pts;
    for (const ContourSeg& s : c.segs) discretise(s, 1e-6, pts);
    pts.push_back(pts.front());
    lb.push_back(std::move(pts));
  }
  double worst = 0;
  for (const ZContour& c : a.contours) {
    std::vector<Vec2> pts;
    for (const ContourSeg& s : c.segs) discretise(s, 1e-6, pts);
    for (const Vec2& p : pts) {
      double best = std::numeric_limits<double>::infinity();
      for (const auto& l : lb)
        for (std::size_t i = 0; i + 1 < l.size(); ++i)
          best = std::min(best, segment_distance(p, l[i], l[i + 1]));
      worst = std::max(worst, best);
    }
  }
  return worst;
}

// The box pocket (plate 20 x 20 at z = 3 with a 10 x 10 pocket of floor z = 0), its faces
// split twice into four: walls of 16 coplanar triangles each, tilted off the axes so that no
// wall edge is axis-aligned.
TEST(ZLevelWalls, SplitWallsGiveTheSameContoursWithFewerElements) {
  TriangleMesh m = subdivide_midpoint(subdivide_midpoint(scan_test::box_pocket()));
  const double c = std::cos(0.37), s = std::sin(0.37);
  for (Vec3& p : m.vertices) p = Vec3(c * p.x() - s * p.y(), s * p.x() + c * p.y(), p.z());
  for (double R : {0.75, 2.0}) {
    const OffsetElements keep = build_offset_elements(m, R, Coplanar::kKeep);
    const OffsetElements vert = build_offset_elements(m, R, Coplanar::kVertical);
    // Only the pocket's 4 walls are vertical (the plate has no outer walls); each wall is 2
    // triangles split twice, 32 triangles with 16 boundary edges: (3 * 32 - 16) / 2 = 40
    // inner edges.
    EXPECT_EQ(reachable_edges(keep) - reachable_edges(vert), 4u * 40u) << "R " << R;
    // Non-vertical facets keep their own offset triangles (no normal is shared).
    for (std::size_t f = 0; f < keep.facet_count(); ++f)
      ASSERT_EQ(keep.facet_normal[f], vert.facet_normal[f]);
    for (double z : {-0.5 * R, 0.0, 0.7, 1.5, 2.999, 3.0, 3.0 + 0.5 * R}) {
      SCOPED_TRACE("R " + std::to_string(R) + " z " + std::to_string(z));
      const ZLevelResult a = zlevel_contours(keep, every_id(keep), z);
      const ZLevelResult b = zlevel_contours(vert, every_id(vert), z);
      EXPECT_EQ(a.stats.open_chains, 0u);
      EXPECT_EQ(b.stats.open_chains, 0u);
      ASSERT_EQ(a.contours.size(), b.contours.size());
      for (std::size_t k = 0; k < a.contours.size(); ++k) {
        EXPECT_EQ(a.contours[k].hole, b.contours[k].hole);
        EXPECT_NEAR(a.contours[k].area, b.contours[k].area, 1e-9);
      }
      EXPECT_LE(one_sided(a, b), 3e-6);
      EXPECT_LE(one_sided(b, a), 3e-6);
    }
  }
}

}  // namespace
}  // namespace ncpath
