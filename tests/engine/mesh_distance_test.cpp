// MeshDistance against independent oracles: a brute-force closest point (its own point-
// triangle routine, solved through the plane's Gram system rather than edge sign tests), a
// Lipschitz-certified bisection for march(), and analytic planes and spheres.
#include "engine/mesh_distance.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "engine/parallel.hpp"
#include "kernels/geom/tolerance.hpp"
#include "tests/engine/mesh_test_support.hpp"
#include "tests/support/meshes.hpp"

namespace ncpath {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// ---- Oracles -------------------------------------------------------------------------------

// Long double (64-bit mantissa) so that the oracle's rounding is far below the tolerance
// even on slivers, where the normal equations below are ill-conditioned.
using L = long double;
using VL = Eigen::Matrix<long double, 3, 1>;

L oracle_segment(const VL& p, const VL& a, const VL& b) {
  const VL e = b - a;
  const L t = std::clamp((p - a).dot(e) / e.dot(e), L(0), L(1));
  return (p - (a + t * e)).norm();
}

// Minimise |a + u e0 + v e1 - p| over the triangle: the unconstrained minimiser from the
// 2x2 normal equations when it lies inside, else the best of the three sides.
double oracle_triangle(const Vec3& pd, const Vec3& ad, const Vec3& bd, const Vec3& cd) {
  const VL p = pd.cast<L>(), a = ad.cast<L>(), b = bd.cast<L>(), c = cd.cast<L>();
  const VL e0 = b - a, e1 = c - a, w = p - a;
  const L g00 = e0.dot(e0), g01 = e0.dot(e1), g11 = e1.dot(e1);
  const L r0 = e0.dot(w), r1 = e1.dot(w);
  const L det = g00 * g11 - g01 * g01;
  const L u = (g11 * r0 - g01 * r1) / det, v = (g00 * r1 - g01 * r0) / det;
  if (u >= 0 && v >= 0 && u + v <= 1) return double((p - (a + u * e0 + v * e1)).norm());
  return double(
      std::min({oracle_segment(p, a, b), oracle_segment(p, b, c), oracle_segment(p, c, a)}));
}

bool degenerate(const TriangleMesh& m, std::size_t i) {
  const Vec3 &a = m.vertices[m.facets[i][0]], &b = m.vertices[m.facets[i][1]],
             &c = m.vertices[m.facets[i][2]];
  return !((b - a).cross(c - a).norm() >= tol::kDegenerateArea2);
}

double oracle_facet_distance(const TriangleMesh& m, std::size_t i, const Vec3& p) {
  return oracle_triangle(p, m.vertices[m.facets[i][0]], m.vertices[m.facets[i][1]],
                         m.vertices[m.facets[i][2]]);
}

// Brute force over every non-degenerate facet. A facet lies within rho of its centroid, so
// one whose centroid is farther than best + rho (+ a margin for rounding) cannot be closer:
// that bound only saves time on the real mesh.
class Oracle {
 public:
  explicit Oracle(const TriangleMesh& m) : m_(m) {
    for (std::size_t i = 0; i < m.facets.size(); ++i) {
      if (degenerate(m, i)) continue;
      const Vec3 &a = m.vertices[m.facets[i][0]], &b = m.vertices[m.facets[i][1]],
                 &c = m.vertices[m.facets[i][2]];
      const Vec3 g = (a + b + c) / 3;
      facets_.push_back({i, g, std::max({(a - g).norm(), (b - g).norm(), (c - g).norm()})});
    }
  }
  double distance(const Vec3& p) const {
    double best = kInf;
    for (const F& f : facets_)
      if ((p - f.centre).norm() - f.rho <= best + 1e-9 * (1 + best))
        best = std::min(best, oracle_facet_distance(m_, f.index, p));
    return best;
  }

 private:
  struct F {
    std::size_t index;
    Vec3 centre;
    double rho;
  };
  const TriangleMesh& m_;
  std::vector<F> facets_;
};

// First s in [0, s_max] where dist(o + s d) <= r, by bisection certified with the Lipschitz
// bound: on [a, b] the distance is at least (g(a) + g(b) - (b - a)) / 2 above r. Intervals
// that cannot be certified are halved down to `resolution`; nullopt when all of [0, s_max]
// is certified free.
std::optional<double> oracle_march(const Oracle& oracle, const Vec3& o, const Vec3& d, double r,
                                   double s_max, double resolution = 1e-11) {
  auto g = [&](double s) { return oracle.distance(o + s * d) - r; };
  struct Span {
    double a, b, ga, gb;
  };
  std::vector<Span> stack{{0, s_max, g(0), g(s_max)}};  // top = earliest span
  while (!stack.empty()) {
    const Span sp = stack.back();
    stack.pop_back();
    if (sp.ga <= 0) return sp.a;
    if ((sp.ga + sp.gb - (sp.b - sp.a)) / 2 > 0) continue;
    if (sp.b - sp.a < resolution) return sp.a;
    const double mid = 0.5 * (sp.a + sp.b), gm = g(mid);
    stack.push_back({mid, sp.b, gm, sp.gb});
    stack.push_back({sp.a, mid, sp.ga, gm});
  }
  return std::nullopt;
}

// ---- Query points --------------------------------------------------------------------------

// Inside and around the box, far and very far, near the surface (offsets from 1e-9 to 1 mm
// off a random facet point) and on it (vertices, edge midpoints, facet points).
std::vector<Vec3> query_points(const TriangleMesh& m, int count, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> U(0, 1), D(-1, 1), E(-9, 0);
  const Aabb3 box = bounding_box(m);
  const Vec3 mid = 0.5 * (box.lo + box.hi), half = 0.5 * (box.hi - box.lo);
  const double size = (box.hi - box.lo).norm();
  std::uniform_int_distribution<std::size_t> F(0, m.facets.size() - 1);
  std::vector<Vec3> pts;
  for (int i = 0; i < count; ++i) {
    const Vec3 r3{D(rng), D(rng), D(rng)};
    const auto& f = m.facets[F(rng)];
    const Vec3 &a = m.vertices[f[0]], &b = m.vertices[f[1]], &c = m.vertices[f[2]];
    double u = U(rng), v = U(rng);
    if (u + v > 1) u = 1 - u, v = 1 - v;
    const Vec3 on = a + u * (b - a) + v * (c - a);
    switch (i % 10) {
      case 0:
      case 1:
      case 2:
        pts.push_back(mid + (1.1 * half).cwiseProduct(r3));
        break;
      case 3:
      case 4:
        pts.push_back(mid + 3 * size * r3);
        break;
      case 5:
        pts.push_back(mid + 100 * size * r3);
        break;
      case 6:
      case 7:
      case 8:
        pts.push_back(on + std::pow(10.0, E(rng)) * r3.normalized());
        break;
      default: {
        const int k = static_cast<int>(U(rng) * 3);
        pts.push_back(k == 0 ? on : k == 1 ? a : 0.5 * (b + c));
      }
    }
  }
  return pts;
}

// Distances are compared within 1e-12 relative, but never tighter than 1e-12 mm: a point on
// the surface has distance 0 up to the rounding of its coordinates (~1e-14 mm at 200 mm).
double tol12(double d) { return 1e-12 * std::max(d, 1.0); }

void expect_closest_matches_brute_force(const TriangleMesh& m, const std::vector<Vec3>& pts) {
  const MeshDistance index(m);
  const Oracle oracle(m);
  std::vector<double> brute(pts.size());
  par::for_each(pts.size(), 16, [&](std::size_t i) { brute[i] = oracle.distance(pts[i]); });
  int far = 0, near = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const Vec3& p = pts[i];
    const MeshDistance::Closest c = index.closest(p);
    ASSERT_LT(c.facet, m.facets.size()) << i;
    ASSERT_FALSE(degenerate(m, c.facet)) << i;
    ASSERT_NEAR(c.distance, brute[i], tol12(brute[i])) << "point " << i;
    // The point is on the reported facet, at the reported distance, and that facet is
    // (one of) the closest.
    EXPECT_LE(oracle_facet_distance(m, c.facet, c.point), tol12(brute[i])) << i;
    EXPECT_NEAR((p - c.point).norm(), c.distance, tol12(c.distance)) << i;
    EXPECT_NEAR(oracle_facet_distance(m, c.facet, p), brute[i], tol12(brute[i])) << i;
    far += brute[i] > 10;
    near += brute[i] < 1e-3;
  }
  EXPECT_GT(far, static_cast<int>(pts.size()) / 5);
  EXPECT_GT(near, static_cast<int>(pts.size()) / 5);
}

// A random soup with degenerate triangles (repeated and collinear vertices) mixed in, so
// that reported indices must skip them correctly.
TriangleMesh soup_with_degenerates(int count, unsigned seed) {
  TriangleMesh m = test::random_soup(count, 60, 20, 4, seed);
  const auto nv = static_cast<std::uint32_t>(m.vertices.size());
  m.vertices.push_back(Vec3{0, 0, 0});
  m.vertices.push_back(Vec3{1, 2, 3});
  m.vertices.push_back(Vec3{2, 4, 6});
  for (std::size_t k = 0; k < m.facets.size(); k += 97) {
    m.facets.insert(m.facets.begin() + k, {nv, nv + 1, nv + 2});  // collinear, exactly
    m.facets.insert(m.facets.begin() + k, {5, 5, 6});             // repeated vertex
  }
  return m;
}

// ---- closest() -----------------------------------------------------------------------------

TEST(MeshDistance, ClosestEqualsBruteForceOnRandomSoups) {
  for (unsigned seed : {1u, 2u}) {
    const TriangleMesh m = soup_with_degenerates(2000, seed);
    const MeshDistance index(m);
    std::uint64_t degenerates = 0;
    for (std::size_t i = 0; i < m.facets.size(); ++i) degenerates += degenerate(m, i);
    EXPECT_GT(degenerates, 40u);
    EXPECT_EQ(index.skipped(), degenerates);
    EXPECT_EQ(index.facet_count(), m.facets.size() - degenerates);
    expect_closest_matches_brute_force(m, query_points(m, 5000, 10 + seed));
  }
}

// The BVH only prunes: the answer is bitwise the one of a scan over all facets with the
// index's own point-triangle routine (lowest index among equal distances).
void expect_closest_is_the_scan_bitwise(const TriangleMesh& m, const std::vector<Vec3>& pts) {
  const MeshDistance index(m);
  std::vector<MeshDistance::Closest> scan(pts.size());
  par::for_each(pts.size(), 16, [&](std::size_t i) {
    for (std::size_t k = 0; k < m.facets.size(); ++k) {
      if (degenerate(m, k)) continue;
      Vec3 q;
      const double d =
          point_triangle_closest(pts[i], m.vertices[m.facets[k][0]], m.vertices[m.facets[k][1]],
                                 m.vertices[m.facets[k][2]], q);
      if (d < scan[i].distance) scan[i] = {d, q, static_cast<std::uint32_t>(k)};
    }
  });
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const MeshDistance::Closest c = index.closest(pts[i]);
    ASSERT_EQ(c.distance, scan[i].distance) << i;
    ASSERT_EQ(c.facet, scan[i].facet) << i;
    ASSERT_EQ(c.point, scan[i].point) << i;
  }
}

TEST(MeshDistance, ClosestIsTheFullScanBitwise) {
  const TriangleMesh soup = soup_with_degenerates(2000, 5);
  expect_closest_is_the_scan_bitwise(soup, query_points(soup, 5000, 6));
  const TriangleMesh bunny = test_meshes::load("bunny00");
  expect_closest_is_the_scan_bitwise(bunny, query_points(bunny, 600, 7));
}

TEST(MeshDistance, ClosestEqualsBruteForceOnBunny) {
  const TriangleMesh m = test_meshes::load("bunny00");
  expect_closest_matches_brute_force(m, query_points(m, 5000, 7));
}

TEST(MeshDistance, MaxDistanceIsRespectedAndInclusive) {
  const TriangleMesh m = soup_with_degenerates(1000, 3);
  const MeshDistance index(m);
  for (const Vec3& p : query_points(m, 3000, 4)) {
    const MeshDistance::Closest full = index.closest(p);
    const MeshDistance::Closest at = index.closest(p, full.distance);
    EXPECT_EQ(at.distance, full.distance);
    EXPECT_EQ(at.facet, full.facet);
    EXPECT_EQ(index.closest(p, 2 * full.distance + 1).facet, full.facet);
    if (full.distance > 0) {
      const MeshDistance::Closest below = index.closest(p, std::nextafter(full.distance, 0.0));
      EXPECT_EQ(below.distance, kInf);
      EXPECT_EQ(below.facet, MeshDistance::kNoFacet);
      EXPECT_EQ(index.closest(p, 0.5 * full.distance).facet, MeshDistance::kNoFacet);
    }
  }
}

// Equal distances: the lowest facet index wins, whatever order Embree visits them in.
TEST(MeshDistance, TiesGoToTheLowestFacetIndex) {
  // A cone fan under a point straight above its apex: every facet's closest point is the
  // apex, at exactly the same distance.
  TriangleMesh cone;
  cone.vertices.emplace_back(0, 0, 10);
  const int k = 64;
  for (int i = 0; i < k; ++i)
    cone.vertices.emplace_back(10 * std::cos(2 * M_PI * i / k), 10 * std::sin(2 * M_PI * i / k), 0);
  for (int i = 0; i < k; ++i)
    cone.facets.push_back({std::uint32_t(1 + i), std::uint32_t(1 + (i + 1) % k), 0});
  for (int rotate : {0, 17, 40}) {
    TriangleMesh m = cone;
    std::rotate(m.facets.begin(), m.facets.begin() + rotate, m.facets.end());
    const MeshDistance index(m);
    const MeshDistance::Closest c = index.closest(Vec3{0, 0, 25});
    EXPECT_EQ(c.distance, 15);
    EXPECT_EQ(c.point, Vec3(0, 0, 10));
    EXPECT_EQ(c.facet, 0u) << "rotation " << rotate;
  }
  // Duplicated facets (same vertex order, so bitwise-equal distances): the first copy.
  TriangleMesh soup = test::random_soup(300, 60, 20, 4, 8);
  const std::size_t n = soup.facets.size();
  for (std::size_t i = 0; i < n; ++i) soup.facets.push_back(soup.facets[i]);
  std::reverse(soup.facets.begin(), soup.facets.end());  // copies at i and 2n - 1 - i
  const MeshDistance index(soup);
  for (const Vec3& p : query_points(soup, 2000, 9)) {
    const MeshDistance::Closest c = index.closest(p);
    ASSERT_LT(c.facet, n) << "a later duplicate was reported";
  }
}

TEST(MeshDistance, EmptyAndAllDegenerateMeshes) {
  TriangleMesh m;
  EXPECT_EQ(MeshDistance(m).closest(Vec3::Zero()).distance, kInf);
  m.vertices = {Vec3{0, 0, 0}, Vec3{1, 1, 1}, Vec3{2, 2, 2}};
  m.facets = {{0, 1, 2}, {0, 0, 1}};
  const MeshDistance index(m);
  EXPECT_EQ(index.skipped(), 2u);
  EXPECT_EQ(index.closest(Vec3::Zero()).facet, MeshDistance::kNoFacet);
  EXPECT_FALSE(index.march(Vec3{0, 0, 5}, Vec3{0, 0, -1}, 1, 100).has_value());
}

// ---- march() -------------------------------------------------------------------------------

// A flat grid at z = 0 over [-1000, 1000]^2 (6.7 mm cells: gaps of 20 and 100 mm are crossed
// by sphere-tracing steps, smaller ones by exact windows); a ray from height h descending at
// angle a reaches height r (first contact of a ball of radius r) at s = (h - r) / sin(a).
// Includes grazing angles where plain sphere tracing would need ~1/a steps per decade of
// accuracy.
TEST(MeshDistance, MarchOnAPlaneMatchesTheAnalyticContact) {
  const TriangleMesh plane = test::height_field(300, 2000, [](double, double) { return 0.0; });
  TriangleMesh m = plane;
  for (Vec3& v : m.vertices) v -= Vec3{1000, 1000, 0};
  const MeshDistance index(m);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> U(-100, 100), Phi(0, 2 * M_PI);
  int checked = 0;
  for (double deg : {90.0, 60.0, 30.0, 10.0, 1.0, 0.1, 0.01})
    for (double r : {0.0, 0.5, 3.0})
      for (double gap : {0.05, 1.0, 20.0, 100.0}) {
        const double a = deg * M_PI / 180, phi = Phi(rng);
        const double expected = gap / std::sin(a);
        if (expected * std::cos(a) > 700) continue;  // would leave the plane
        const Vec3 o{U(rng), U(rng), r + gap};
        const Vec3 d{std::cos(a) * std::cos(phi), std::cos(a) * std::sin(phi), -std::sin(a)};
        const std::optional<double> s = index.march(o, d, r, 5000);
        ASSERT_TRUE(s.has_value()) << deg << " " << r << " " << gap;
        EXPECT_NEAR(*s, expected, 1e-9) << deg << " deg, r " << r << ", gap " << gap;
        // s_max just short of / just past the contact.
        EXPECT_FALSE(index.march(o, d, r, expected * (1 - 1e-9) - 1e-9).has_value());
        EXPECT_TRUE(index.march(o, d, r, expected * (1 + 1e-9) + 1e-9).has_value());
        ++checked;
      }
  EXPECT_GT(checked, 50);
  // Parallel to the plane just above contact height, and climbing away: no contact (and
  // no endless crawl).
  for (double r : {0.0, 2.0}) {
    EXPECT_FALSE(index.march(Vec3{-900, 3, r + 1e-7}, Vec3{1, 0, 0}, r, kInf).has_value());
    EXPECT_FALSE(index.march(Vec3{0, 0, r + 1}, Vec3{0.6, 0, 0.8}, r, kInf).has_value());
  }
  // Already touching at the origin: 0.
  EXPECT_EQ(index.march(Vec3{0, 0, 2}, Vec3{1, 0, 0}, 2, 100), 0.0);
}

// A UV sphere of radius S with vertices on the sphere: the polyhedron lies inside the sphere
// and contains the sphere of radius S - sag, so a ball of radius r first touches it between
// the entries of the centre line into the spheres of radius S + r and S - sag + r.
TEST(MeshDistance, MarchOnASphereIsBracketedByAnalyticSpheres) {
  const double S = 30;
  const int rings = 90, segments = 180;
  TriangleMesh m;
  m.vertices.emplace_back(0, 0, S);
  for (int i = 1; i < rings; ++i)
    for (int k = 0; k < segments; ++k) {
      const double th = M_PI * i / rings, ph = 2 * M_PI * k / segments;
      m.vertices.emplace_back(S * std::sin(th) * std::cos(ph), S * std::sin(th) * std::sin(ph),
                              S * std::cos(th));
    }
  m.vertices.emplace_back(0, 0, -S);
  auto at = [&](int i, int k) { return std::uint32_t(1 + (i - 1) * segments + k % segments); };
  const auto south = std::uint32_t(m.vertices.size() - 1);
  for (int k = 0; k < segments; ++k) {
    m.facets.push_back({0, at(1, k), at(1, k + 1)});
    m.facets.push_back({south, at(rings - 1, k + 1), at(rings - 1, k)});
  }
  for (int i = 1; i + 1 < rings; ++i)
    for (int k = 0; k < segments; ++k) {
      m.facets.push_back({at(i, k), at(i + 1, k), at(i + 1, k + 1)});
      m.facets.push_back({at(i, k), at(i + 1, k + 1), at(i, k + 1)});
    }
  double inner = S;  // distance from the centre to the nearest facet plane
  for (const auto& f : m.facets) {
    const Vec3 &a = m.vertices[f[0]], &b = m.vertices[f[1]], &c = m.vertices[f[2]];
    const Vec3 n = (b - a).cross(c - a).normalized();
    inner = std::min(inner, std::abs(n.dot(a)));
  }
  ASSERT_LT(S - inner, 0.05);
  const MeshDistance index(m);
  // Entry of o + t d into the sphere of radius R about the origin, if any.
  auto entry = [](const Vec3& o, const Vec3& d, double R) -> std::optional<double> {
    const double b = o.dot(d), disc = b * b - (o.squaredNorm() - R * R);
    if (disc < 0) return std::nullopt;
    return -b - std::sqrt(disc);
  };
  std::mt19937_64 rng(12);
  std::normal_distribution<double> N(0, 1);
  std::uniform_real_distribution<double> Dist(45, 100), Aim(0, 45), R(0, 5);
  int hits = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vec3 o = Dist(rng) * Vec3{N(rng), N(rng), N(rng)}.normalized();
    const Vec3 target = Aim(rng) * Vec3{N(rng), N(rng), N(rng)}.normalized();
    const Vec3 d = (target - o).normalized();
    const double r = (i % 4 == 0) ? 0.0 : R(rng);
    const std::optional<double> s = index.march(o, d, r, 1000);
    const std::optional<double> first = entry(o, d, S + r), sure = entry(o, d, inner + r);
    if (!first) {
      EXPECT_FALSE(s.has_value()) << i;
      continue;
    }
    if (sure) {
      ASSERT_TRUE(s.has_value()) << i;
    }
    if (!s) continue;
    ++hits;
    EXPECT_GE(*s, *first - 1e-9) << i;
    if (sure) {
      EXPECT_LE(*s, *sure + 1e-9) << i;
    }
    EXPECT_NEAR(index.closest(o + *s * d).distance, r, 1e-9) << i;
  }
  EXPECT_GT(hits, 1000);
}

TEST(MeshDistance, MarchEqualsCertifiedBisectionOnRandomSoups) {
  for (unsigned seed : {21u, 22u}) {
    const TriangleMesh m = soup_with_degenerates(150, seed);
    const MeshDistance index(m);
    const Oracle oracle(m);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> X(-10, 70), Z(-10, 30), R(0, 3);
    std::normal_distribution<double> N(0, 1);
    int hits = 0, rays = 0;
    while (rays < 300) {
      const Vec3 o{X(rng), X(rng), Z(rng)};
      const double r = (rays % 5 == 0) ? 0.0 : R(rng);
      if (oracle.distance(o) <= r + 1e-3) continue;
      const Vec3 d = Vec3{N(rng), N(rng), N(rng)}.normalized();
      ++rays;
      const std::optional<double> s = index.march(o, d, r, 80);
      const std::optional<double> want = oracle_march(oracle, o, d, r, 80);
      ASSERT_EQ(s.has_value(), want.has_value()) << "ray " << rays;
      if (!want) continue;
      ++hits;
      EXPECT_NEAR(*s, *want, 1e-9) << "ray " << rays;
      EXPECT_NEAR(oracle.distance(o + *s * d), r, 1e-9) << "ray " << rays;
    }
    EXPECT_GT(hits, 50);
  }
}

// On the bunny: every contact touches (distance r at s) and nothing earlier is closer than r
// at the sampled points before it.
TEST(MeshDistance, MarchOnBunnyTouchesAndDoesNotPassThrough) {
  const TriangleMesh m = test_meshes::load("bunny00");
  const MeshDistance index(m);
  const Aabb3 box = bounding_box(m);
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<double> U(0, 1), R(0, 4);
  std::normal_distribution<double> N(0, 1);
  int hits = 0;
  for (int i = 0; i < 500; ++i) {
    const Vec3 t{U(rng), U(rng), U(rng)};
    const Vec3 target = box.lo + (box.hi - box.lo).cwiseProduct(t);
    const Vec3 o = target + 300 * Vec3{N(rng), N(rng), N(rng)}.normalized();
    const Vec3 d = (target - o).normalized();
    const double r = R(rng);
    const std::optional<double> s = index.march(o, d, r, 1000);
    if (!s) continue;
    ++hits;
    EXPECT_NEAR(index.closest(o + *s * d).distance, r, 1e-9) << i;
    for (int k = 0; k < 200; ++k) {
      const double sk = *s * k / 200;
      ASSERT_GT(index.closest(o + sk * d).distance, r - 1e-9) << i << " at " << sk;
    }
  }
  EXPECT_GT(hits, 200);
}

// ---- Threads -------------------------------------------------------------------------------

TEST(MeshDistance, OneAndTwoThreadsGiveIdenticalBytes) {
  const TriangleMesh m = test_meshes::load("bunny00");
  const MeshDistance index(m);
  const std::vector<Vec3> pts = query_points(m, 4000, 41);
  struct Out {
    MeshDistance::Closest c;
    double s;
  };
  auto run = [&](int threads) {
    par::ThreadLimit limit(threads);
    std::vector<Out> out(pts.size());
    const Vec3 centre = 0.5 * (bounding_box(m).lo + bounding_box(m).hi);
    par::for_each(pts.size(), 8, [&](std::size_t i) {
      out[i].c = index.closest(pts[i]);
      const Vec3 o = pts[i] + Vec3{0, 0, 250};
      out[i].s = index.march(o, (centre - o).normalized(), 1.5, 600).value_or(-1);
    });
    return out;
  };
  const std::vector<Out> one = run(1), two = run(2);
  for (std::size_t i = 0; i < pts.size(); ++i) {
    ASSERT_EQ(std::memcmp(&one[i].c.distance, &two[i].c.distance, sizeof(double)), 0) << i;
    ASSERT_EQ(std::memcmp(one[i].c.point.data(), two[i].c.point.data(), 3 * sizeof(double)), 0);
    ASSERT_EQ(one[i].c.facet, two[i].c.facet) << i;
    ASSERT_EQ(std::memcmp(&one[i].s, &two[i].s, sizeof(double)), 0) << i;
  }
}

}  // namespace
}  // namespace ncpath
