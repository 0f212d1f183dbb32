// Curve-based drive-plane scanning (engine/scan.hpp): the exact segments handed out
// (evaluated from their documented geometry only) equal the point drop-cutter within
// 1e-7 mm at >= 10,000 random points on real meshes (bunny00, fandisk) and random terrains;
// every sharp-concave kink that dense drop-cutter sampling sees is a junction; the CL
// polylines never lie below the drop-cutter; 1 and 2 threads give identical output.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <filesystem>
#include <random>
#include <tuple>

#include "engine/drop_index.hpp"
#include "engine/offset_elements_build.hpp"
#include "engine/parallel.hpp"
#include "engine/scan.hpp"
#include "kernels/scan/envelope.hpp"
#include "tests/engine/mesh_test_support.hpp"
#include "tests/kernels/scan/scan_test_support.hpp"

namespace ncpath {
namespace {

using test_meshes::load;
using test_meshes::terrain;

struct Collected {
  ClChunk cl;
  std::vector<ScanSegmentRecord> segments;
  std::vector<ScanJunctionRecord> junctions;
  ScanStats stats;
};

Collected scan(const TriangleMesh& mesh, const Cutter& c, const ScanParams& p) {
  Collected out;
  RunControl control;
  out.stats = run_scan(
      mesh, c, p,
      [&](const ScanChunk& ch) {
        out.cl.append(ch.cl);
        out.segments.insert(out.segments.end(), ch.segments.begin(), ch.segments.end());
        out.junctions.insert(out.junctions.end(), ch.junctions.begin(), ch.junctions.end());
      },
      control);
  return out;
}

// u (coordinate along the line) and v (the plane) of a world point of path `rec.path`.
bool along_x(const ScanSegmentRecord& s) { return s.start[1] == s.end[1]; }

// Tip z of a segment record at u, from its geometry columns (docs/hdf5-schema.md).
double record_z(const ScanSegmentRecord& s, double u) {
  const auto& g = s.geometry;
  switch (s.kind) {
    case 0:  // facet line
    case 3:  // cylinder line
    case 5:  // floor
      return g[0] * u + g[1];
    case 1: {  // sphere arc
      const double du = u - g[0];
      return g[1] + std::sqrt(std::max(0.0, g[2] * g[2] - du * du));
    }
    default: {  // ellipse: upper root of the ellipse equation in dz
      const double du = u - g[0], M = g[2], m = g[3], c = std::cos(g[4]), s2 = std::sin(g[4]);
      const double A = s2 * s2 / (M * M) + c * c / (m * m);
      const double B = 2 * du * c * s2 * (1 / (M * M) - 1 / (m * m));
      const double C = du * du * (c * c / (M * M) + s2 * s2 / (m * m)) - 1;
      return g[1] + (-B + std::sqrt(std::max(0.0, B * B - 4 * A * C))) / (2 * A);
    }
  }
}

// Random points on the exact segments against the point drop-cutter `drop(x, y)` raised to
// the floor. Returns the number of points checked.
template <class Drop>
int check_segments(const Collected& c, double floor_z, std::mt19937_64& rng, int want,
                   Drop&& drop) {
  std::uniform_real_distribution<double> u01(0, 1);
  std::uniform_int_distribution<std::size_t> pick(0, c.segments.size() - 1);
  int n = 0;
  for (int k = 0; k < 40 * want && n < want; ++k) {
    const ScanSegmentRecord& s = c.segments[pick(rng)];
    if (s.kind == kScanSegmentVertical) continue;
    const bool ax = along_x(s);
    const int iu = ax ? 0 : 1;
    const double f = u01(rng);
    double p[3];
    for (int i = 0; i < 3; ++i) p[i] = s.start[i] + f * (s.end[i] - s.start[i]);
    const double u = p[iu];
    const double z = record_z(s, u);
    const double want_z = std::max(floor_z, drop(p[0], p[1]));
    EXPECT_NEAR(z, want_z, 1e-7) << "segment kind " << int(s.kind) << " path " << s.path
                                 << " at " << p[0] << "," << p[1];
    if (std::abs(z - want_z) > 1e-7) return n;
    ++n;
  }
  return n;
}

TEST(Scan, TerrainSegmentsEqualDropCutterAndPolylinesNeverGouge) {
  std::mt19937_64 rng(5);
  const TriangleMesh mesh = terrain(rng, 15);
  const Cutter ball = ball_cutter(5);
  ScanParams p;
  p.families = ScanFamilies::kBoth;
  p.interval = 1.3;
  p.tolerance = 0.002;
  p.margin = 3;
  const Collected c = scan(mesh, ball, p);
  const FacetTable table = build_facet_table(mesh);
  auto drop = [&](double x, double y) { return drop_brute_force(table, ball, x, y).tip_z; };
  EXPECT_EQ(check_segments(c, c.stats.floor_z, rng, 4000, drop), 4000);
  // Every CL point (cuts and links): the ball there keeps at least R from every facet
  // (brute force: no gouge, also at the foot of vertical segments, where the drop-cutter
  // is higher) and, off the floor, touches or nearly touches the part.
  const double R = ball.radius;
  for (std::size_t k = 0; k < c.cl.point_count(); k += 2) {
    const double x = c.cl.xyz[3 * k], y = c.cl.xyz[3 * k + 1], z = c.cl.xyz[3 * k + 2];
    const Vec3 centre(x, y, z + R);
    double dist = INFINITY;
    for (const auto& f : mesh.facets)
      dist = std::min(dist, scan_test::point_triangle_distance(
                                centre, mesh.vertices[f[0]], mesh.vertices[f[1]],
                                mesh.vertices[f[2]]));
    ASSERT_GE(dist, R - 1e-9) << "gouge at " << x << "," << y << "," << z;
    // Lifted points (chords kept above arcs) stay within a few tolerances of touching
    // (perpendicular distance: steep arcs may lift more in z).
    if (z > c.stats.floor_z + 1e-9) {
      ASSERT_LE(dist, R + 5 * p.tolerance) << "far above at " << x << "," << y << "," << z;
    }
  }
  // Paths: cut, link, ..., cut; then a rapid; then the y family.
  EXPECT_EQ(c.stats.planes, c.stats.planes_x + c.stats.planes_y);
  std::size_t cuts = 0, rapids = 0;
  for (std::uint8_t k : c.cl.path_kinds) {
    cuts += k == std::uint8_t(PathKind::kCut);
    rapids += k == std::uint8_t(PathKind::kRapid);
  }
  EXPECT_EQ(cuts, c.stats.planes);
  EXPECT_EQ(rapids, 1u);
  // Junction vectors are unit and their angle is the one between them.
  for (const ScanJunctionRecord& j : c.junctions) {
    const Vec3 b1(j.b1[0], j.b1[1], j.b1[2]), b2(j.b2[0], j.b2[1], j.b2[2]);
    ASSERT_NEAR(b1.norm(), 1, 1e-9);
    ASSERT_NEAR(std::acos(std::clamp(b1.dot(b2), -1.0, 1.0)), j.angle, 1e-12);
  }
  EXPECT_GT(c.stats.sharp_concave, 50u);
}

TEST(Scan, OneAndTwoThreadsGiveIdenticalOutput) {
  std::mt19937_64 rng(9);
  const TriangleMesh mesh = terrain(rng, 12);
  ScanParams p;
  p.families = ScanFamilies::kBoth;
  p.interval = 0.7;
  p.chunk_planes = 5;
  Collected a, b;
  {
    par::ThreadLimit one(1);
    a = scan(mesh, ball_cutter(4), p);
  }
  {
    par::ThreadLimit two(2);
    b = scan(mesh, ball_cutter(4), p);
  }
  EXPECT_EQ(a.cl.xyz, b.cl.xyz);
  EXPECT_EQ(a.cl.contact, b.cl.contact);
  EXPECT_EQ(a.cl.path_sizes, b.cl.path_sizes);
  ASSERT_EQ(a.segments.size(), b.segments.size());
  for (std::size_t i = 0; i < a.segments.size(); ++i) {
    EXPECT_EQ(a.segments[i].geometry, b.segments[i].geometry);
    EXPECT_EQ(a.segments[i].start, b.segments[i].start);
  }
  ASSERT_EQ(a.junctions.size(), b.junctions.size());
  for (std::size_t i = 0; i < a.junctions.size(); ++i)
    EXPECT_EQ(a.junctions[i].position, b.junctions[i].position);
}

// The mesh as an STL reader gives it: three new vertices per facet.
TriangleMesh as_soup(const TriangleMesh& mesh) {
  TriangleMesh soup;
  for (const auto& f : mesh.facets) {
    const auto n = std::uint32_t(soup.vertices.size());
    for (const std::uint32_t v : f) soup.vertices.push_back(mesh.vertices[v]);
    soup.facets.push_back({n, n + 1, n + 2});
  }
  return soup;
}

// An index restricted to a few planes answers queries there exactly like the full index
// (same elements, same order) and holds only a small part of the elements.
TEST(Scan, RestrictedPlaneIndexAnswersLikeTheFullOneAtItsPlanes) {
  const TriangleMesh mesh = load("bunny00");
  const ScanElements se = build_scan_elements(mesh, 5);
  const Aabb3 box = bounding_box(mesh);
  for (int f : {0, 1}) {
    const double lo = f == 0 ? box.lo.y() : box.lo.x(), hi = f == 0 ? box.hi.y() : box.hi.x();
    const std::vector<double> at = {lo - 5, lo + 0.37 * (hi - lo), hi + 4.9999};
    const PlaneIndex small = build_plane_index(se.el[std::size_t(f)], at);
    EXPECT_LT(small.ids.size() + small.long_ids.size(),
              (se.index[std::size_t(f)].ids.size() + se.index[std::size_t(f)].long_ids.size()) / 4);
    for (const double v : at) {
      std::vector<std::uint32_t> want, got;
      se.index[std::size_t(f)].query(v, want);
      small.query(v, got);
      EXPECT_FALSE(want.empty() && v > lo && v < hi);
      EXPECT_EQ(got, want) << "family " << f << " at " << v;
    }
  }
}

// A scan of one family slices the other only along its two side planes (restricted index):
// the same output as with both families' full indexes, with the sides through the part.
TEST(Scan, OneFamilyScanEqualsTheScanWithFullIndexes) {
  const TriangleMesh mesh = as_soup(load("fandisk"));  // as read from STL: welded by the build
  const Aabb3 box = bounding_box(mesh);
  for (const ScanFamilies fam : {ScanFamilies::kX, ScanFamilies::kY}) {
    ScanParams p;
    p.families = fam;
    p.interval = 0.05 * (box.hi.x() - box.lo.x());
    const Vec3 c = 0.5 * (box.lo + box.hi), h = 0.3 * (box.hi - box.lo);
    p.rect = std::array<double, 4>{c.x() - h.x(), c.y() - h.y(), c.x() + h.x(), c.y() + h.y()};
    const Collected a = scan(mesh, ball_cutter(4), p);
    const ScanElements full = build_scan_elements(mesh, 2);
    Collected b;
    RunControl control;
    run_scan(
        full, ball_cutter(4), p,
        [&](const ScanChunk& ch) {
          b.cl.append(ch.cl);
          b.segments.insert(b.segments.end(), ch.segments.begin(), ch.segments.end());
          b.junctions.insert(b.junctions.end(), ch.junctions.begin(), ch.junctions.end());
        },
        control);
    EXPECT_GT(a.cl.path_kinds.size(), 10u);
    EXPECT_EQ(a.cl.xyz, b.cl.xyz);
    EXPECT_EQ(a.cl.path_kinds, b.cl.path_kinds);
    ASSERT_EQ(a.segments.size(), b.segments.size());
    for (std::size_t i = 0; i < a.segments.size(); ++i) {
      const ScanElementRef &ea = a.segments[i].element, &eb = b.segments[i].element;
      EXPECT_EQ(std::tie(ea.kind, ea.a, ea.b), std::tie(eb.kind, eb.a, eb.b)) << "segment " << i;
    }
    ASSERT_EQ(a.junctions.size(), b.junctions.size());
    for (std::size_t i = 0; i < a.junctions.size(); ++i) {
      const ScanElementRef &ea = a.junctions[i].element1, &eb = b.junctions[i].element1;
      EXPECT_EQ(std::tie(ea.kind, ea.a, ea.b), std::tie(eb.kind, eb.a, eb.b)) << "junction " << i;
    }
    // The sides are sliced with the elements near them only.
    const ScanElements part = build_scan_elements(
        mesh, 2, fam == ScanFamilies::kX ? std::array<std::vector<double>, 2>{{{}, {p.rect->at(0)}}}
                                         : std::array<std::vector<double>, 2>{{{p.rect->at(1)}, {}}});
    const int side = fam == ScanFamilies::kX ? 1 : 0;
    EXPECT_LT(part.el[std::size_t(side)].element_count() * 3, full.el[0].element_count());
    EXPECT_EQ(part.el[std::size_t(1 - side)].element_count(), full.el[0].element_count());
    // Elements built for other planes are refused.
    ScanParams both = p;
    both.families = ScanFamilies::kBoth;
    const ScanElements one = build_scan_elements(
        mesh, 2, fam == ScanFamilies::kX ? std::array<std::vector<double>, 2>{{{}, {0.5}}}
                                         : std::array<std::vector<double>, 2>{{{0.5}, {}}});
    EXPECT_THROW(run_scan(one, ball_cutter(4), both, [](const ScanChunk&) {}, control),
                 std::logic_error);
  }
}

// The weld's map: every vertex to the first (lowest index) of the vertices exactly equal to
// it; -0 equals 0, nearly equal vertices stay apart. Checked against a std::map.
TEST(Scan, ExactDuplicateMapSendsEachVertexToItsFirstCopy) {
  std::mt19937_64 rng(5);
  std::uniform_int_distribution<int> coord(-3, 3), pick(0, 99);
  std::vector<Vec3> v;
  for (int i = 0; i < 20000; ++i) {
    Vec3 p(coord(rng), coord(rng), coord(rng));
    if (pick(rng) == 0 && !v.empty()) p = v[std::size_t(pick(rng)) % v.size()];
    if (pick(rng) == 1) p.x() = p.x() == 0 ? -0.0 : std::nextafter(p.x(), 9.0);
    v.push_back(p);
  }
  std::map<std::array<double, 3>, std::uint32_t> first;
  std::vector<std::uint32_t> want(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) {
    const std::array<double, 3> key = {v[i].x() + 0.0, v[i].y() + 0.0, v[i].z() + 0.0};
    want[i] = first.try_emplace(key, std::uint32_t(i)).first->second;
  }
  EXPECT_LT(first.size(), v.size() / 2);  // many repeats
  EXPECT_EQ(exact_duplicate_map(v), want);
}

// The parallel build keeps one point per group of equal vertices (an STL soup: one in six)
// and still gives the sequential reference's elements for the welded mesh, element for
// element, with element_ref() naming the same mesh vertices.
TEST(Scan, CompactParallelElementsEqualTheReferenceOnTheWeldedSoup) {
  const TriangleMesh soup = as_soup(load("fandisk"));
  TriangleMesh welded = soup;
  const std::vector<std::uint32_t> rep = exact_duplicate_map(soup.vertices);
  for (auto& f : welded.facets)
    for (std::uint32_t& v : f) v = rep[v];
  const OffsetElements want = build_offset_elements(welded, 2.5);
  const OffsetElements got = build_offset_elements_parallel(soup, 2.5, false);
  EXPECT_EQ(want.points.size(), soup.vertices.size());
  EXPECT_LT(got.points.size() * 5, soup.vertices.size());
  ASSERT_EQ(got.point_source.size(), got.points.size());
  for (std::size_t k = 0; k < got.points.size(); ++k)
    ASSERT_EQ(got.points[k], soup.vertices[got.point_source[k]]);
  ASSERT_EQ(got.facet_count(), want.facet_count());
  ASSERT_EQ(got.edge_count(), want.edge_count());
  ASSERT_EQ(got.vertex_count(), want.vertex_count());
  for (std::size_t f = 0; f < got.facet_count(); ++f)
    ASSERT_EQ(got.offset_tri(f), want.offset_tri(f)) << "facet " << f;
  EXPECT_EQ(got.edge_kind, want.edge_kind);
  EXPECT_EQ(got.edge_wedge, want.edge_wedge);
  EXPECT_EQ(got.vertex_reachable, want.vertex_reachable);
  for (std::uint32_t id = 0; id < got.element_count(); ++id) {
    const ElementRef a = element_ref(got, id), b = element_ref(want, id);
    ASSERT_EQ(std::tie(a.kind, a.a, a.b), std::tie(b.kind, b.a, b.b)) << "element " << id;
  }
}

TEST(Scan, RejectsBadInput) {
  std::mt19937_64 rng(1);
  const TriangleMesh mesh = terrain(rng, 4);
  ScanParams p;
  p.interval = 0;
  EXPECT_THROW(scan(mesh, ball_cutter(5), p), std::invalid_argument);
  p.interval = 1;
  EXPECT_THROW(scan(mesh, flat_cutter(5), p), std::invalid_argument);
  p.tolerance = -1;
  EXPECT_THROW(scan(mesh, ball_cutter(5), p), std::invalid_argument);
}

// ---- real meshes ----

class ScanRealMesh : public testing::TestWithParam<const char*> {};

TEST_P(ScanRealMesh, SegmentsEqualDropCutterAndKinksAreJunctions) {
  const TriangleMesh mesh = load(GetParam());
  const Cutter ball = ball_cutter(5);
  ScanParams p;
  p.families = ScanFamilies::kBoth;
  p.interval = 10;
  const Collected c = scan(mesh, ball, p);
  const DropIndex index(mesh, ball);
  auto drop = [&](double x, double y) { return index.query(x, y).tip_z; };
  std::mt19937_64 rng(17);
  EXPECT_EQ(check_segments(c, c.stats.floor_z, rng, 10000, drop), 10000);

  // Dense drop-cutter sampling along some x lines: a kink where the slope jumps up by more
  // than 0.1 (about 6 degrees) must be a sharp-concave junction of that line.
  const double h = 0.01;
  int kinks = 0;
  for (std::size_t line = 2; line < c.stats.planes_x; line += 5) {
    const double y = c.stats.rect[1] + double(line) * p.interval;
    std::vector<double> xs;
    for (const ScanJunctionRecord& j : c.junctions)
      if (j.path == std::int64_t(line) && j.kind == std::uint8_t(JunctionKind::kSharpConcave))
        xs.push_back(j.position[0]);
    const double x0 = c.stats.rect[0], x1 = c.stats.rect[2];
    const int n = int((x1 - x0) / h);
    std::vector<double> z(n + 1);
    for (int k = 0; k <= n; ++k) z[k] = std::max(c.stats.floor_z, drop(x0 + k * h, y));
    for (int k = 1; k < n; ++k) {
      const double jump = (z[k + 1] - z[k]) / h - (z[k] - z[k - 1]) / h;
      if (jump < 0.1) continue;
      // Where the drop-cutter jumps (a wall) the kink is a pair of samples; skip if the
      // neighbour has a larger jump (count each kink once).
      const double next = k + 2 <= n ? (z[k + 2] - z[k + 1]) / h - (z[k + 1] - z[k]) / h : 0;
      if (next > jump) continue;
      const double x = x0 + k * h;
      bool found = false;
      for (double xj : xs) found = found || std::abs(xj - x) <= 2 * h;
      EXPECT_TRUE(found) << GetParam() << " kink at x " << x << " y " << y << " jump " << jump;
      ++kinks;
    }
  }
  EXPECT_GT(kinks, 5);
}

INSTANTIATE_TEST_SUITE_P(Cgal, ScanRealMesh, testing::Values("bunny00", "fandisk"));

}  // namespace
}  // namespace ncpath
