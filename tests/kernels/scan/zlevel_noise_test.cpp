// Z-level contours (kernels/scan/zlevel.hpp) of a square prism whose walls are stored with
// noise, as a CAD part in float coordinates is: the wall vertices lie up to `noise` off the
// wall planes, so a wall's stacked edges differ in direction by ~noise / (column width) and
// their capsule sides (shadow lines) are nearly coincident, tangent to one corner circle at
// points R x (that angle) apart, and converge to within 1e-11 mm of each other there.
// Regressions: joints on a corner's circle were lost where the coincident trimming kept
// another stacked vertex's circle (gaps of ~R noise / width, open chains); a clip line
// leaving its joint at a grazing angle to a shadow line, or a sloping edge's shadow ending
// beside another's, left the other line unsplit (open chains at noise 1e-6).
//
// Oracles are analytic. The walls lie within `noise` of the square's, so at a level whose
// ball centre is between the prism's floor and top, U lies between the square offset by
// R - noise and by R + noise: each contour point is at distance R +- noise from the square,
// and the area is that of the square offset by R, L^2 + 4 L R + pi R^2, within the area
// between the offsets, 4 L noise + pi (2 R noise + noise^2).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

#include "kernels/mesh/offset_elements.hpp"
#include "kernels/scan/zlevel.hpp"

namespace ncpath {
namespace {

constexpr double kL = 20, kH = 20, kR = 2.5;
// mm: the kernel's own tolerances (boundary 1e-11, links between pieces) and rounding.
constexpr double kSlack = 1e-9;

// Square prism [0, L]^2 x [0, H]: each side cut into `cols` columns and `rows` rows of two
// triangles, top and bottom fans. Wall vertices other than the corners and the top and bottom
// rings are pushed along the wall's normal by noise * u, u uniform in [-1, 1) (from the raw
// bits: the same on every platform).
TriangleMesh noisy_prism(double noise, int rows, int cols, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  auto uniform = [&] { return double(rng() >> 11) * 0x1.0p-52 - 1.0; };
  const Vec2 corner[4] = {{0, 0}, {kL, 0}, {kL, kL}, {0, kL}};
  std::vector<Vec2> ring;
  for (int s = 0; s < 4; ++s)
    for (int k = 0; k < cols; ++k)
      ring.push_back(corner[s] + (corner[(s + 1) % 4] - corner[s]) * (double(k) / cols));
  const auto n = std::uint32_t(ring.size());
  TriangleMesh m;
  for (int r = 0; r <= rows; ++r)
    for (std::uint32_t i = 0; i < n; ++i) {
      Vec2 p = ring[i];
      if (i % cols != 0 && r > 0 && r < rows) {
        const Vec2 d = (corner[(i / cols + 1) % 4] - corner[i / cols]).normalized();
        p += noise * uniform() * Vec2(d.y(), -d.x());
      }
      m.vertices.emplace_back(p.x(), p.y(), kH * r / rows);
    }
  auto vid = [&](int r, std::uint32_t i) { return std::uint32_t(r) * n + i % n; };
  for (int r = 0; r < rows; ++r)
    for (std::uint32_t i = 0; i < n; ++i) {
      m.facets.push_back({vid(r, i), vid(r, i + 1), vid(r + 1, i + 1)});
      m.facets.push_back({vid(r, i), vid(r + 1, i + 1), vid(r + 1, i)});
    }
  const auto top = std::uint32_t(m.vertices.size());
  m.vertices.emplace_back(kL / 2, kL / 2, kH);
  m.vertices.emplace_back(kL / 2, kL / 2, 0);
  for (std::uint32_t i = 0; i < n; ++i) {
    m.facets.push_back({vid(rows, i), vid(rows, i + 1), top});
    m.facets.push_back({vid(0, i + 1), vid(0, i), top + 1});
  }
  return m;
}

// Distance from p to the square [0, L]^2 (0 inside).
double square_distance(const Vec2& p) {
  const double dx = std::max({0.0, -p.x(), p.x() - kL});
  const double dy = std::max({0.0, -p.y(), p.y() - kL});
  return std::hypot(dx, dy);
}

void check_prism(double noise, int rows, int cols, std::uint64_t seed) {
  const TriangleMesh mesh = noisy_prism(noise, rows, cols, seed);
  const OffsetElements el = build_offset_elements(mesh, kR, Coplanar::kVertical);
  std::vector<std::uint32_t> ids(el.element_count());
  for (std::uint32_t i = 0; i < ids.size(); ++i) ids[i] = i;
  const double pi = std::numbers::pi;
  const double area = kL * kL + 4 * kL * kR + pi * kR * kR;
  const double area_tol = 4 * kL * noise + pi * (2 * kR * noise + noise * noise) + kSlack;
  // 20 levels whose ball centre z + R lies in (0, H), off the rows' heights.
  for (int k = 0; k < 20; ++k) {
    const double z = 0.5 + 0.85 * k;
    const ZLevelResult r = zlevel_contours(el, ids, z);
    SCOPED_TRACE(testing::Message() << "noise " << noise << " rows " << rows << " cols " << cols
                                    << " seed " << seed << " z " << z);
    EXPECT_EQ(r.stats.open_chains, 0u);
    ASSERT_EQ(r.contours.size(), 1u);
    const ZContour& c = r.contours[0];
    EXPECT_FALSE(c.hole);
    EXPECT_NEAR(c.area, area, area_tol);
    for (const ZJunction& j : c.junctions)
      EXPECT_NEAR(square_distance(Vec2(j.position.x(), j.position.y())), kR, noise + kSlack)
          << "junction at (" << j.position.x() << ", " << j.position.y() << ")";
    for (const ContourSeg& s : c.segs)
      for (double f : {0.0, 0.25, 0.5, 0.75})
        EXPECT_NEAR(square_distance(seg_point(s, f)), kR, noise + kSlack)
            << contour_seg_kind_name(s.kind) << " of element " << s.element << " at " << f;
  }
}

// Noise from the float rounding of a CAD wall (1e-6) up to 1e-3 mm (directions ~2e-4 rad
// apart over 5 mm columns; the repair radius covered gaps R x that angle up to 1e-4 mm only).
TEST(ZLevelNoise, NoisyPrismWallsGiveOneOffsetSquare) {
  for (double noise : {1e-6, 1e-5, 1e-4, 3e-4, 1e-3})
    for (std::uint64_t seed : {1u, 2u}) check_prism(noise, 8, 4, seed);
}

// Seeds and subdivisions where a line ended within 1e-11 mm of another that ran on unsplit
// (the clip line of a wall facet leaving its joint at a grazing angle to a shadow line; a
// sloping edge's shadow ending where it turns into its ellipse beside the next edge's).
TEST(ZLevelNoise, LineEndingOnANearlyCoincidentLineSplitsIt) {
  check_prism(1e-6, 5, 3, 4);
  check_prism(1e-6, 12, 6, 3);
  check_prism(1e-7, 8, 4, 1);
}

}  // namespace
}  // namespace ncpath
