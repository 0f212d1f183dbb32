// The known inside region of the z-level kernel (kernels/scan/zlevel.hpp ZLevelInside): its
// queries against brute force on finely discretised contours (what it says lies deep inside
// does; what lies deep enough inside it finds; its depth bounds hold), and contours computed
// with it (regions deep inside a higher level's region dropped, candidates filtered by
// zlevel_filter_deep) equal to those computed without it and to the brute-force drop-cutter.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "kernels/scan/zlevel.hpp"
#include "kernels/scan/zlevel_detail.hpp"
#include "tests/engine/mesh_test_support.hpp"
#include "tests/kernels/scan/zlevel_test_support.hpp"

namespace ncpath {
namespace {

using namespace zlevel_test;

// A steep tower on a floor plate: a frustum of `rings` bands of `sectors` facets, radius 6
// at z = 0 shrinking by `draft` per mm of height up to z = 10, with a flat top. Its wall
// elements stack: at a level, those above project just inside the wall's contour.
TriangleMesh drafted_tower(int rings, int sectors, double draft) {
  TriangleMesh m;
  const double H = 10, r0 = 6;
  for (int i = 0; i <= rings; ++i) {
    const double z = H * i / rings, r = r0 - draft * z;
    for (int j = 0; j < sectors; ++j) {
      const double a = 2 * kPi * j / sectors;
      m.vertices.emplace_back(r * std::cos(a), r * std::sin(a), z);
    }
  }
  auto id = [&](int i, int j) { return std::uint32_t(i * sectors + j % sectors); };
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < sectors; ++j) {
      m.facets.push_back({id(i, j), id(i, j + 1), id(i + 1, j + 1)});
      m.facets.push_back({id(i, j), id(i + 1, j + 1), id(i + 1, j)});
    }
  const auto top = std::uint32_t(m.vertices.size());
  m.vertices.emplace_back(0, 0, H);
  for (int j = 0; j < sectors; ++j) m.facets.push_back({id(rings, j), id(rings, j + 1), top});
  const auto f = std::uint32_t(m.vertices.size());
  m.vertices.insert(m.vertices.end(), {{-12, -12, 0}, {12, -12, 0}, {12, 12, 0}, {-12, 12, 0}});
  m.facets.push_back({f, f + 1, f + 2});
  m.facets.push_back({f, f + 2, f + 3});
  return m;
}

// Contours of a and b equal up to rounding where curves are split (tol, 1e-9 mm).
void expect_same_contours(const ZLevelResult& a, const ZLevelResult& b, const char* what,
                          double tol = 1e-9) {
  ASSERT_EQ(a.contours.size(), b.contours.size()) << what;
  for (std::size_t i = 0; i < a.contours.size(); ++i) {
    const ZContour &p = a.contours[i], &q = b.contours[i];
    ASSERT_EQ(p.segs.size(), q.segs.size()) << what << " contour " << i;
    ASSERT_EQ(p.junctions.size(), q.junctions.size()) << what << " contour " << i;
    EXPECT_EQ(p.hole, q.hole);
    EXPECT_NEAR(p.area, q.area, tol) << what;
    for (std::size_t k = 0; k < p.segs.size(); ++k) {
      EXPECT_EQ(p.segs[k].kind, q.segs[k].kind) << what;
      EXPECT_EQ(p.segs[k].element, q.segs[k].element) << what;
      EXPECT_EQ(p.segs[k].shadow, q.segs[k].shadow) << what;
      EXPECT_LT((p.segs[k].a - q.segs[k].a).norm(), tol) << what;
      EXPECT_LT((p.segs[k].b - q.segs[k].b).norm(), tol) << what;
    }
    for (std::size_t k = 0; k < p.junctions.size(); ++k) {
      EXPECT_EQ(p.junctions[k].kind, q.junctions[k].kind) << what;
      EXPECT_EQ(p.junctions[k].e1, q.junctions[k].e1) << what;
      EXPECT_EQ(p.junctions[k].e2, q.junctions[k].e2) << what;
      EXPECT_LT((p.junctions[k].position - q.junctions[k].position).norm(), tol) << what;
      EXPECT_LT((p.junctions[k].b1 - q.junctions[k].b1).norm(), tol) << what;
      EXPECT_LT((p.junctions[k].b2 - q.junctions[k].b2).norm(), tol) << what;
    }
  }
}

std::vector<std::vector<Vec2>> fine_loops(const ZLevelResult& r) {
  std::vector<std::vector<Vec2>> loops;
  for (const ZContour& c : r.contours) loops.push_back(polyline(c, 1e-6));
  return loops;
}

// The loops' points, and more along their long edges (at most 0.02 mm apart).
std::vector<Vec2> loop_points(const std::vector<std::vector<Vec2>>& loops) {
  std::vector<Vec2> out;
  for (const auto& l : loops)
    for (std::size_t i = 0; i < l.size(); ++i) {
      const Vec2 &a = l[i], &b = l[(i + 1) % l.size()];
      const int n = 1 + int((b - a).norm() / 0.02);
      for (int k = 0; k < n; ++k) out.push_back(a + (b - a) * double(k) / n);
    }
  return out;
}

// Distance from x to conv(p[0, n)), n <= 3 (brute force).
double hull_distance(const Vec2& x, const Vec2* p, int n) {
  auto seg = [](const Vec2& x, const Vec2& a, const Vec2& b) {
    const Vec2 d = b - a;
    const double l2 = d.squaredNorm();
    const double t = l2 > 0 ? std::clamp((x - a).dot(d) / l2, 0.0, 1.0) : 0.0;
    return (x - (a + t * d)).norm();
  };
  if (n == 1) return (x - p[0]).norm();
  if (n == 2) return seg(x, p[0], p[1]);
  double o[3];
  for (int i = 0; i < 3; ++i) {
    const Vec2 e = p[(i + 1) % 3] - p[i], w = x - p[i];
    o[i] = e.x() * w.y() - e.y() * w.x();
  }
  if ((o[0] >= 0 && o[1] >= 0 && o[2] >= 0) || (o[0] <= 0 && o[1] <= 0 && o[2] <= 0)) return 0;
  return std::min({seg(x, p[0], p[1]), seg(x, p[1], p[2]), seg(x, p[2], p[0])});
}

// Points of conv(p[0, n)) grown by r: its corners, points along its sides and around its
// round ends, and inner points.
std::vector<Vec2> shape_samples(const Vec2* p, int n, double r) {
  std::vector<Vec2> s;
  const int k = 12;
  for (int i = 0; i < n; ++i) {
    const Vec2 &a = p[i], &b = p[(i + 1) % n];
    for (int t = 0; t < k; ++t) {
      const Vec2 q = a + (b - a) * double(t) / k;
      s.push_back(q);
      if (r > 0)
        for (int u = 0; u < k; ++u) {
          const double ang = 2 * kPi * u / k;
          s.push_back(q + r * Vec2(std::cos(ang), std::sin(ang)));
        }
    }
  }
  Vec2 c = Vec2::Zero();
  for (int i = 0; i < n; ++i) c += p[i] / n;
  for (int i = 0; i < n; ++i) s.push_back(0.5 * (c + p[i]));
  s.push_back(c);
  return s;
}

TEST(ZLevelInside, QueriesAgreeWithBruteForce) {
  std::mt19937_64 rng(21);
  const double deep = tol::kZLevelInsideDepth;
  int sound = 0, found = 0, bounds = 0;
  const TriangleMesh meshes[] = {drafted_tower(6, 24, 0.2), random_terrain(rng, 10)};
  for (const TriangleMesh& mesh : meshes) {
    const OffsetElements el = build_offset_elements(mesh, 1.25, Coplanar::kVertical);
    for (double z : {2.0, 5.5}) {
      const ZLevelResult r = run(el, z);
      ASSERT_FALSE(r.contours.empty());
      const ZLevelInside q = zlevel_inside(r, 0.7);
      ASSERT_FALSE(q.empty());
      EXPECT_EQ(q.margin, tol::kZLevelInsideMargin);
      const auto loops = fine_loops(r);
      const auto boundary = loop_points(loops);
      // Depth inside U (negative outside), from the fine loops.
      auto depth = [&](const Vec2& x) {
        const double d = dist_to_loops(loops, x);
        return inside_even_odd(loops, x) ? d : -d;
      };
      std::uniform_real_distribution<double> pos(-14, 24), len(0, 1.5), rad(0, 2);
      std::uniform_int_distribution<int> kind(1, 3);
      const double margins[] = {1e-6, 1e-3, 0.05, 0.4};
      std::uniform_int_distribution<std::size_t> on(0, boundary.size() - 1);
      for (int t = 0; t < 400; ++t) {
        const int n = kind(rng);
        Vec2 p[3];
        // Half the shapes start on the contours (hulls that cross them or run along them).
        p[0] = t % 2 ? boundary[on(rng)] : Vec2(pos(rng), pos(rng));
        for (int tries = 0; tries < 20 && t % 2 == 0 && !inside_even_odd(loops, p[0]); ++tries)
          p[0] = Vec2(pos(rng), pos(rng));
        for (int i = 1; i < n; ++i)
          p[i] = p[0] + len(rng) * Vec2(std::cos(pos(rng)), std::sin(pos(rng)));
        const double r0 = n == 3 ? 0 : rad(rng), margin = margins[t % 4];
        // Brute force: the shape's distance to the contours (over their points) and whether
        // its first point is inside.
        double clear = INFINITY;
        for (const Vec2& b : boundary) clear = std::min(clear, hull_distance(b, p, n) - r0);
        const bool in = inside_even_odd(loops, p[0]);
        const bool says = zlevel_detail::inside_contains(q, p, n, r0, margin);
        // Sound: the polygon lies inside U, so what is deep inside it is deep inside U.
        if (says) {
          EXPECT_TRUE(in) << "shape " << t << " at " << p[0].transpose();
          EXPECT_GE(clear, margin - 1e-5) << "shape " << t << " at " << p[0].transpose();
          for (const Vec2& s : shape_samples(p, n, r0)) EXPECT_GE(depth(s), margin - 1e-5);
          ++sound;
        }
        // Complete up to the polygon's chords (a quarter of the depth) and the sampling.
        if (in && clear > margin + 0.25 * deep + 0.02) {
          EXPECT_TRUE(says) << "shape " << t << " at " << p[0].transpose() << " clear " << clear;
          ++found;
        }
        // Depth bound over the hull (no radius): at least the depth of its points.
        const double limit = 0.3;
        const double bound = zlevel_detail::inside_depth_bound(q, p, n, limit);
        for (const Vec2& s : shape_samples(p, n, 0))
          EXPECT_GE(bound, std::min(limit, depth(s) - 0.25 * deep - 1e-5))
              << "hull " << t << " at " << s.transpose();
        ++bounds;
      }
    }
  }
  EXPECT_GT(sound, 200);
  EXPECT_GT(found, 200);
  EXPECT_GT(bounds, 1500);
}

// Contours at z computed with the region of a higher level (and candidates filtered against
// a still higher one, as the engine does) equal those computed from all elements; the
// regions dropped are many (the test can fail: the tower's wall stacks).
void check_pruning(const OffsetElements& el, const std::vector<double>& levels, double dz,
                   const Oracle* oracle, std::uint64_t& dropped, std::uint64_t& left_out) {
  std::mt19937_64 rng(5);
  const std::vector<std::uint32_t> all = all_ids(el);
  for (double z : levels) {
    SCOPED_TRACE(testing::Message() << "z " << z << " dz " << dz);
    const ZLevelResult plain = run(el, z);
    const ZLevelResult higher = run(el, z + dz);
    const ZLevelInside q = zlevel_inside(higher, 0.5 * el.radius);
    ASSERT_FALSE(q.empty()) << "z " << z;
    ZLevelParams kp;
    kp.inside = &q;
    const ZLevelResult with = zlevel_contours(el, all, z, kp);
    expect_same_contours(plain, with, "inside");
    dropped += with.stats.inside_regions;
    EXPECT_EQ(with.stats.open_chains, 0u);
    // Candidates filtered against the region of a level above `higher`.
    const ZLevelInside q2 = zlevel_inside(run(el, z + 2.5 * dz), 0.5 * el.radius);
    std::vector<std::uint32_t> filtered;
    zlevel_filter_deep(el, all, q2, filtered);
    left_out += all.size() - filtered.size();
    const ZLevelResult fewer = zlevel_contours(el, filtered, z, kp);
    expect_same_contours(plain, fewer, "filtered");
    if (oracle) check_result(*oracle, with, rng, -14, -14, 14, 14, 100);
  }
}

TEST(ZLevelInside, DraftedTowerSameContoursWithFewerRegions) {
  const TriangleMesh mesh = drafted_tower(40, 48, 0.05);
  const OffsetElements el = build_offset_elements(mesh, 1.25, Coplanar::kVertical);
  const Oracle o(mesh, el);
  std::uint64_t dropped = 0, left_out = 0;
  check_pruning(el, {1.0, 3.3, 6.1}, 1.0, &o, dropped, left_out);
  check_pruning(el, {2.2, 4.0}, 0.3, nullptr, dropped, left_out);
  EXPECT_GT(dropped, 1000u);
  EXPECT_GT(left_out, 1000u);
}

TEST(ZLevelInside, TerrainAndHemisphereSameContours) {
  std::mt19937_64 rng(22);
  std::uint64_t dropped = 0, left_out = 0;
  {
    const TriangleMesh mesh = random_terrain(rng, 14);
    const OffsetElements el = build_offset_elements(mesh, 1.25, Coplanar::kVertical);
    const Oracle o(mesh, el);
    check_pruning(el, {0.5, 1.5, 2.5}, 0.7, &o, dropped, left_out);
  }
  {
    const TriangleMesh mesh = scan_test::uv_hemisphere(8, 24, 48, Vec3(0, 0, 0));
    const OffsetElements el = build_offset_elements(mesh, 1.25, Coplanar::kVertical);
    check_pruning(el, {0.3, 2.0, 5.0}, 1.0, nullptr, dropped, left_out);
  }
  EXPECT_GT(dropped, 100u);
  EXPECT_GT(left_out, 100u);
}

// CGAL's anchor_dense (a CAD part with walls in many bands, float-free OFF) fit to 200 mm as
// the jobs do, ball R 2.5: the levels of CadPartWallsCloseEveryLoop and others.
TEST(ZLevelInside, CadPartSameContours) {
  const TriangleMesh mesh = test_meshes::load("anchor_dense");
  const OffsetElements el = build_offset_elements(mesh, 2.5, Coplanar::kVertical);
  std::uint64_t dropped = 0, left_out = 0;
  check_pruning(el, {-40.0, -19.3414, 0.6586, 30.6586, -62.38465574932556}, 1.0, nullptr, dropped,
                left_out);
  EXPECT_GT(dropped, 1000u);
  EXPECT_GT(left_out, 1000u);
}

// A closed box [lo, hi], facets facing out.
void add_box(TriangleMesh& m, const Vec3& lo, const Vec3& hi) {
  const auto b = std::uint32_t(m.vertices.size());
  for (int k = 0; k < 8; ++k)
    m.vertices.emplace_back(k & 1 ? hi.x() : lo.x(), k & 2 ? hi.y() : lo.y(),
                            k & 4 ? hi.z() : lo.z());
  const std::uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                     {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    m.facets.push_back({b + q[0], b + q[1], b + q[2]});
    m.facets.push_back({b + q[0], b + q[2], b + q[3]});
  }
}

// A mushroom on a plate: cap 60 x 60 (z 30 to 40) on a stem 10 x 10 (z 4 to 31) on a base
// 80 x 80 (z 0 to 5), ball R 2.5. Between the cap's offset bottom (z 27.5) and the base's top
// (7.5) every element lies above the ball centre, or its region is empty: U is the cap's
// square grown by R, the same at every level: with the higher level's region known inside,
// the kernel gives that square again, its segments shadows and its contact vectors
// horizontal. Lower, the base's top face reaches the level and U grows.
TEST(ZLevelInside, UnderAnOverhangTheHigherContoursComeBack) {
  TriangleMesh mesh;
  add_box(mesh, Vec3(-30, -30, 30), Vec3(30, 30, 40));
  add_box(mesh, Vec3(-5, -5, 4), Vec3(5, 5, 31));
  add_box(mesh, Vec3(-40, -40, 0), Vec3(40, 40, 5));
  const double R = 2.5;
  const OffsetElements el = build_offset_elements(mesh, R, Coplanar::kVertical);
  const std::vector<std::uint32_t> all = all_ids(el);
  const ZLevelResult higher = run(el, 20);  // tip z; the centre at 22.5
  ASSERT_EQ(higher.contours.size(), 1u);
  EXPECT_NEAR(higher.contours[0].area, 60 * 60 + 4 * 60 * R + kPi * R * R, 1e-9);
  const ZLevelInside q = zlevel_inside(higher, 0.5 * R);
  ZLevelParams kp;
  kp.inside = &q;
  for (double z : {15.0, 5.1}) {  // the centre at 17.5 and 7.6
    const ZLevelResult known = zlevel_contours(el, all, z, kp);
    expect_same_contours(run(el, z), known, "known");
    ASSERT_EQ(known.contours.size(), 1u);
    EXPECT_NEAR(known.contours[0].area, higher.contours[0].area, 1e-9);
    for (const ZJunction& j : known.contours[0].junctions) {
      EXPECT_EQ(j.position.z(), z);
      EXPECT_EQ(j.b1.z(), 0.0);  // shadows: the contact lies on the vertical below the cap
    }
    for (const ContourSeg& s : known.contours[0].segs) EXPECT_TRUE(s.shadow);
  }
  // The centre at 5.5: the base's top face (offset to 7.5) and its edges' capsules (radius
  // sqrt(R^2 - 0.5^2)) make U.
  const ZLevelResult grown = zlevel_contours(el, all, 3, kp);
  expect_same_contours(run(el, 3), grown, "grown");
  ASSERT_EQ(grown.contours.size(), 1u);
  const double r = std::sqrt(R * R - 0.25);
  EXPECT_NEAR(grown.contours[0].area, 80 * 80 + 4 * 80 * r + kPi * r * r, 1e-9);
}

// The mushroom with a post on each side of the plate (x 31 to 36 and -36 to -31, y -3 to 3, z
// 4 to 20), outside the cap's square: at the centre 17.5 their tops (offset to 22.5) and top
// edges make U the cap's square grown by R with a rounded rectangle on each side. With the
// higher level's region known inside, the posts change U, and the level gives the same
// contours as without that region.
TEST(ZLevelInside, ChangesNearAFewElementsAreComputed) {
  TriangleMesh mesh;
  add_box(mesh, Vec3(-30, -30, 30), Vec3(30, 30, 40));
  add_box(mesh, Vec3(-5, -5, 4), Vec3(5, 5, 31));
  add_box(mesh, Vec3(-40, -40, 0), Vec3(40, 40, 5));
  add_box(mesh, Vec3(31, -3, 4), Vec3(36, 3, 20));
  add_box(mesh, Vec3(-36, -3, 4), Vec3(-31, 3, 20));
  const double R = 2.5;
  const OffsetElements el = build_offset_elements(mesh, R, Coplanar::kVertical);
  const ZLevelElementBoxes boxes = zlevel_element_boxes(el);
  const std::vector<std::uint32_t> all = all_ids(el);
  const ZLevelResult higher = run(el, 21);  // the centre at 23.5: the posts lie below
  ASSERT_EQ(higher.contours.size(), 1u);
  const double square = 60 * 60 + 4 * 60 * R + kPi * R * R;
  EXPECT_NEAR(higher.contours[0].area, square, 1e-9);
  const ZLevelInside q = zlevel_inside(higher, 0.5 * R);
  ZLevelParams kp;
  kp.inside = &q;
  kp.boxes = &boxes;
  const ZLevelResult known = zlevel_contours(el, all, 15, kp);
  EXPECT_EQ(known.stats.open_chains, 0u);
  // Where a wall's line meets its corner's circle at a tangent, the kernel places the joint
  // to ~sqrt(rounding): 3.4e-7 mm here at the cap's corners.
  expect_same_contours(run(el, 15), known, "known", 1e-6);
  ASSERT_EQ(known.contours.size(), 1u);
  // Each post's rectangle grown by R less the part inside the square (x within 32.5).
  const double post = 5 * 6 + 2 * R * (5 + 6) + kPi * R * R;
  const double overlap = 1.5 * 11 + R * 6 + kPi * R * R / 2;
  EXPECT_NEAR(known.contours[0].area, square + 2 * (post - overlap), 1e-9);
  int concave = 0;
  for (const ZJunction& j : known.contours[0].junctions) {
    EXPECT_EQ(j.position.z(), 15.0);
    concave += j.kind == JunctionKind::kSharpConcave;
  }
  EXPECT_EQ(concave, 4);  // where the posts' sides meet the square's
}

TEST(ZLevelInside, OpenChainsGiveNoRegion) {
  ZLevelResult r;
  ZContour c;
  ContourSeg s;
  s.a = Vec2(0, 0);
  s.b = Vec2(1, 0);
  c.segs = {s, s, s};
  c.segs[1].a = Vec2(1, 0);
  c.segs[1].b = Vec2(0, 1);
  c.segs[2].a = Vec2(0, 1);
  c.segs[2].b = Vec2(0, 0);
  r.contours.push_back(c);
  EXPECT_FALSE(zlevel_inside(r, 0.5).empty());
  EXPECT_EQ(zlevel_inside(r, 0.5).margin, tol::kZLevelInsideMargin);
  r.stats.open_chains = 1;
  EXPECT_TRUE(zlevel_inside(r, 0.5).empty());
}

}  // namespace
}  // namespace ncpath
