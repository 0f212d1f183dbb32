// Random pockets (tests/support/random_pockets.hpp) and their DXF round trip through
// batch/io/dxf_reader.*, plus the glyph and CAD pocket files in datasets/pockets/.
//
// The checks here do not reuse the generator's helpers: lengths and areas come from exact
// line/arc formulas and Gauss-Legendre quadrature on the NURBS, samples from point_at /
// nurbs_point at fixed parameter steps, and chain_and_nest is a second, independent judge of
// closure, crossings and nesting.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "batch/io/dxf_reader.hpp"
#include "kernels/curves/nurbs.hpp"
#include "kernels/pocket/chain.hpp"
#include "tests/batch/io/test_files.hpp"
#include "tests/support/random_pockets_dxf.hpp"

namespace ncpath::test {
namespace {

constexpr int kSeeds = 200;
constexpr double kRoundTripRel = 1e-6;  // relative length / area agreement after the DXF trip
constexpr double kSampleStep = 0.1;     // mm between check samples
constexpr double kGapSlack = 5e-3;      // mm: sampling error allowed in the gap check

double cross(const Vec2& u, const Vec2& v) { return u.x() * v.y() - u.y() * v.x(); }

struct Gauss {
  std::vector<double> x, w;  // nodes and weights on [-1, 1]
};

// Gauss-Legendre rule of order n (Newton on the Legendre recurrence).
Gauss gauss_legendre(int n) {
  Gauss g;
  for (int i = 1; i <= n; ++i) {
    double x = std::cos(std::numbers::pi * (i - 0.25) / (n + 0.5)), dp = 1;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1, p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
        p0 = p1, p1 = p2;
      }
      dp = n * (x * p1 - p0) / (x * x - 1);
      const double dx = p1 / dp;
      x -= dx;
      if (std::abs(dx) < 1e-16) break;
    }
    g.x.push_back(x);
    g.w.push_back(2 / ((1 - x * x) * dp * dp));
  }
  return g;
}

// Signed sweep of an arc from its end points and turn, radians.
double arc_sweep(const Seg2& s) {
  double phi = std::atan2(cross(s.a - s.c, s.b - s.c), (s.a - s.c).dot(s.b - s.c));
  if (s.kind == SegKind::kArcCcw && phi <= 0) phi += 2 * std::numbers::pi;
  if (s.kind == SegKind::kArcCw && phi >= 0) phi -= 2 * std::numbers::pi;
  return phi;
}

struct Measure {
  double length = 0;  // mm
  double area = 0;    // mm^2, signed: > 0 counter-clockwise
};

// Exact for lines and arcs, 16-point Gauss on 8 pieces of every knot span for NURBS. Areas
// about o (a point near the loop) so that far-away loops lose no digits.
Measure measure(const Profile& p, const Vec2& o) {
  static const Gauss g = gauss_legendre(16);
  double len = 0, area2 = 0;
  for (const ProfileCurve& pc : p.curves) {
    const Seg2& s = pc.seg;
    if (pc.nurbs >= 0) {
      const Nurbs2& n = p.nurbs[pc.nurbs];
      for (std::size_t k = 0; k + 1 < n.knots.size(); ++k) {
        if (!(n.knots[k] < n.knots[k + 1])) continue;
        const int pieces = 8;
        const double h = (n.knots[k + 1] - n.knots[k]) / pieces;
        for (int j = 0; j < pieces; ++j)
          for (std::size_t q = 0; q < g.x.size(); ++q) {
            const double t = n.knots[k] + h * (j + 0.5 * (1 + g.x[q]));
            Vec2 d0, d1, d2;
            nurbs_derivatives(n, t, d0, d1, d2);
            len += 0.5 * h * g.w[q] * d1.norm();
            area2 += 0.5 * h * g.w[q] * cross(d0 - o, d1);
          }
      }
    } else if (s.is_arc()) {
      const double th = arc_sweep(s), r = (s.a - s.c).norm();
      len += r * std::abs(th);
      area2 += cross(s.a - o, s.b - o) + r * r * (th - std::sin(th));
    } else {
      len += (s.b - s.a).norm();
      area2 += cross(s.a - o, s.b - o);
    }
  }
  return {len, area2 / 2};
}

// Closed polygon of points at most ~kSampleStep apart along the loop (first not repeated).
std::vector<Vec2> samples(const Profile& p) {
  std::vector<Vec2> out;
  for (const ProfileCurve& pc : p.curves) {
    if (pc.nurbs >= 0) {
      const Nurbs2& n = p.nurbs[pc.nurbs];
      Profile one;
      one.nurbs = {n};
      one.curves = {pc};
      one.curves[0].nurbs = 0;
      // Parameter steps are not arc-length steps: twice as many as the length asks for.
      const int m =
          std::clamp(static_cast<int>(2 * measure(one, n.ctrl[0]).length / kSampleStep), 16, 20000);
      for (int i = 0; i < m; ++i)
        out.push_back(nurbs_point(n, nurbs_t0(n) + (nurbs_t1(n) - nurbs_t0(n)) * i / m));
    } else {
      const double len = pc.seg.is_arc()
                             ? (pc.seg.a - pc.seg.c).norm() * std::abs(arc_sweep(pc.seg))
                             : (pc.seg.b - pc.seg.a).norm();
      const int m =
          pc.seg.is_arc() ? std::clamp(static_cast<int>(len / kSampleStep), 16, 20000) : 1;
      for (int i = 0; i < m; ++i) out.push_back(point_at(pc.seg, static_cast<double>(i) / m));
    }
  }
  return out;
}

bool inside(const std::vector<Vec2>& poly, const Vec2& q) {
  int winding = 0;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Vec2& a = poly[i];
    const Vec2& b = poly[(i + 1) % poly.size()];
    if (a.y() <= q.y()) {
      if (b.y() > q.y() && cross(b - a, q - a) > 0) ++winding;
    } else if (b.y() <= q.y() && cross(b - a, q - a) < 0) {
      --winding;
    }
  }
  return winding != 0;
}

double seg_point_distance(const Vec2& a, const Vec2& b, const Vec2& q) {
  const Vec2 ab = b - a;
  const double t = std::clamp((q - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (a + t * ab - q).norm();
}

// Smallest distance from any point of `pts` to the closed polygon `poly`, searched only out to
// `limit` (returns limit when nothing is closer): a uniform grid of cell size `limit` holds
// every edge in the cells its box grown by `limit` meets, so one cell per point suffices.
double min_distance(const std::vector<Vec2>& poly, const std::vector<Vec2>& pts, double limit) {
  const double cell = limit;
  std::map<std::pair<long, long>, std::vector<int>> grid;
  auto key = [&](double x, double y) {
    return std::make_pair(static_cast<long>(std::floor(x / cell)),
                          static_cast<long>(std::floor(y / cell)));
  };
  for (int i = 0; i < static_cast<int>(poly.size()); ++i) {
    const Vec2& a = poly[i];
    const Vec2& b = poly[(i + 1) % poly.size()];
    const auto lo = key(std::min(a.x(), b.x()) - limit, std::min(a.y(), b.y()) - limit);
    const auto hi = key(std::max(a.x(), b.x()) + limit, std::max(a.y(), b.y()) + limit);
    for (long x = lo.first; x <= hi.first; ++x)
      for (long y = lo.second; y <= hi.second; ++y) grid[{x, y}].push_back(i);
  }
  double best = limit;
  for (const Vec2& q : pts) {
    auto it = grid.find(key(q.x(), q.y()));
    if (it == grid.end()) continue;
    for (int i : it->second)
      best = std::min(best, seg_point_distance(poly[i], poly[(i + 1) % poly.size()], q));
  }
  return best;
}

// The region's curves as one soup, for chain_and_nest.
void soup_of(const Region& r, std::vector<ProfileCurve>& curves, std::vector<Nurbs2>& nurbs) {
  auto add = [&](const Profile& p) {
    for (ProfileCurve pc : p.curves) {
      if (pc.nurbs >= 0) {
        nurbs.push_back(p.nurbs[pc.nurbs]);
        pc.nurbs = static_cast<std::int32_t>(nurbs.size() - 1);
      }
      curves.push_back(pc);
    }
  };
  add(r.boundary);
  for (const Profile& isl : r.islands) add(isl);
}

// Everything wrong with a region, one problem per line ("" when valid). gap: the least
// distance (mm) islands must keep from the boundary and from each other.
std::string region_problems(const Region& r, double gap) {
  std::string out;
  auto loop_problems = [&](const Profile& p, const std::string& name, bool want_ccw) {
    if (p.curves.empty()) return out += name + ": no curves\n", void();
    for (std::size_t i = 0; i < p.curves.size(); ++i) {
      const ProfileCurve& pc = p.curves[i];
      const ProfileCurve& next = p.curves[(i + 1) % p.curves.size()];
      if (pc.seg.b != next.seg.a)
        out += name + ": not closed after curve " + std::to_string(i) + "\n";
      if (pc.nurbs >= 0) {
        if (pc.nurbs >= static_cast<int>(p.nurbs.size())) {
          out += name + ": bad nurbs index\n";
          continue;
        }
        const Nurbs2& n = p.nurbs[pc.nurbs];
        if (const std::string v = validate(n); !v.empty()) out += name + ": " + v + "\n";
        if (n.ctrl.front() != pc.seg.a || n.ctrl.back() != pc.seg.b)
          out += name + ": nurbs ends differ from seg ends\n";
      } else if (pc.seg.is_arc()) {
        const double ra = (pc.seg.a - pc.seg.c).norm(), rb = (pc.seg.b - pc.seg.c).norm();
        if (std::abs(ra - rb) > 1e-9 * (1 + ra) || std::abs(ra - pc.seg.r) > 1e-9 * (1 + ra))
          out += name + ": arc ends not on its circle\n";
      }
    }
    const double area = measure(p, p.curves[0].seg.a).area;
    if ((area > 0) != want_ccw)
      out += name + ": wrong orientation (signed area " + std::to_string(area) + ")\n";
  };
  loop_problems(r.boundary, "boundary", false);
  for (std::size_t i = 0; i < r.islands.size(); ++i)
    loop_problems(r.islands[i], "island " + std::to_string(i), true);
  if (!out.empty()) return out;

  // Islands inside the boundary, outside each other, and at least `gap` away.
  const std::vector<Vec2> wall = samples(r.boundary);
  std::vector<std::vector<Vec2>> isl;
  for (const Profile& p : r.islands) isl.push_back(samples(p));
  for (std::size_t i = 0; i < isl.size(); ++i) {
    const std::string name = "island " + std::to_string(i);
    if (!std::all_of(isl[i].begin(), isl[i].end(), [&](const Vec2& q) { return inside(wall, q); }))
      out += name + ": outside the boundary\n";
    const double dw = min_distance(wall, isl[i], gap + 1);
    if (dw < gap - kGapSlack) out += name + ": " + std::to_string(dw) + " mm from the wall\n";
    for (std::size_t j = 0; j < isl.size(); ++j) {
      if (j == i) continue;
      if (std::any_of(isl[i].begin(), isl[i].end(),
                      [&](const Vec2& q) { return inside(isl[j], q); }))
        out += name + ": inside island " + std::to_string(j) + "\n";
      if (j > i) {
        const double dj = min_distance(isl[j], isl[i], gap + 1);
        if (dj < gap - kGapSlack)
          out += name + ": " + std::to_string(dj) + " mm from island " + std::to_string(j) + "\n";
      }
    }
  }
  // The library's chaining is an independent judge of closure, crossings and nesting.
  std::vector<ProfileCurve> curves;
  std::vector<Nurbs2> nurbs;
  soup_of(r, curves, nurbs);
  const ChainResult c = chain_and_nest(curves, nurbs, {}, 0.0);
  if (!c.error.empty())
    out += "chain_and_nest: " + c.error + "\n";
  else if (c.regions.size() != 1 || c.regions[0].islands.size() != r.islands.size())
    out += "chain_and_nest: " + std::to_string(c.regions.size()) + " regions\n";
  return out;
}

std::string relative_mismatch(const std::string& what, double a, double b) {
  if (std::abs(a - b) <= kRoundTripRel * std::max(std::abs(a), std::abs(b))) return "";
  return what + ": " + std::to_string(a) + " vs " + std::to_string(b) + "\n";
}

// Reads the DXF text back and compares it with the region ("" when the same): one region,
// same island and curve counts, same length and signed area per loop within kRoundTripRel.
std::string round_trip_problems(const Region& r, const std::string& dxf,
                                const io::testing::TempDir& dir, const std::string& name,
                                const std::string& units = "mm") {
  io::ProfileSoup soup;
  try {
    soup = io::read_dxf(dir.write(name, dxf));
    if (soup.units.name != units || soup.units_from != io::kUnitsFromInsunits)
      return "read in " + soup.units.name + " from " + soup.units_from + ", not " + units + "\n";
  } catch (const io::ReadError& e) {
    return std::string("read_dxf: ") + e.what() + "\n";
  }
  std::string out;
  if (!soup.warnings.empty()) out += "warning: " + soup.warnings[0] + "\n";
  if (soup.zero_length_dropped != 0) out += "zero-length entities dropped\n";
  const ChainResult c = chain_and_nest(soup.curves, soup.nurbs, soup.sources);
  if (!c.error.empty()) return out + "chain_and_nest: " + c.error + "\n";
  if (c.regions.size() != 1) return out + std::to_string(c.regions.size()) + " regions\n";
  const Region& back = c.regions[0];
  if (back.islands.size() != r.islands.size()) return out + "island count differs\n";
  std::size_t n0 = r.boundary.curves.size(), n1 = back.boundary.curves.size();
  for (const Profile& p : r.islands) n0 += p.curves.size();
  for (const Profile& p : back.islands) n1 += p.curves.size();
  if (n0 != n1) out += "curve count " + std::to_string(n0) + " vs " + std::to_string(n1) + "\n";

  const Vec2 o = r.boundary.curves[0].seg.a;
  const Measure b0 = measure(r.boundary, o), b1 = measure(back.boundary, o);
  out += relative_mismatch("boundary length", b0.length, b1.length);
  out += relative_mismatch("boundary area", b0.area, b1.area);
  auto island_measures = [&](const Region& x) {
    std::vector<std::pair<double, double>> m;  // (area, length), sorted
    for (const Profile& p : x.islands) {
      const Measure q = measure(p, o);
      m.push_back({q.area, q.length});
    }
    std::sort(m.begin(), m.end());
    return m;
  };
  const auto i0 = island_measures(r), i1 = island_measures(back);
  double len0 = b0.length, len1 = b1.length;
  for (std::size_t i = 0; i < i0.size(); ++i) {
    out += relative_mismatch("island area", i0[i].first, i1[i].first);
    out += relative_mismatch("island length", i0[i].second, i1[i].second);
    len0 += i0[i].second, len1 += i1[i].second;
  }
  out += relative_mismatch("total length", len0, len1);
  return out;
}

std::uint64_t shuffle_seed_of(std::uint64_t seed) { return seed * 0x9E3779B97F4A7C15ull + 7; }

TEST(RandomPocket, TwoHundredSeedsAreValidRegions) {
  for (std::uint64_t seed = 0; seed < kSeeds; ++seed) {
    RandomPocketInfo info;
    const std::vector<Region> regions = random_pocket(seed, {}, &info);
    ASSERT_EQ(regions.size(), 1u) << "seed " << seed;
    EXPECT_EQ(region_problems(regions[0], info.gap), "") << "seed " << seed;
  }
}

TEST(RandomPocket, TwoHundredSeedsSurviveTheDxfRoundTrip) {
  const io::testing::TempDir dir;
  for (std::uint64_t seed = 0; seed < kSeeds; ++seed) {
    const std::vector<Region> regions = random_pocket(seed);
    const std::string dxf = region_to_dxf(regions, shuffle_seed_of(seed));
    EXPECT_EQ(round_trip_problems(regions[0], dxf, dir, "seed.dxf"), "") << "seed " << seed;
  }
}

// The same pockets drawn in other units ($INSUNITS) read back as the same mm: the reader
// multiplies by the unit's size, here from the DXF reference's table as written below (not
// the reader's table).
TEST(RandomPocket, SeedsDrawnInOtherUnitsReadBackInMm) {
  struct Unit {
    const char* name;
    DxfUnits dxf;
  };
  const Unit units[] = {{"inch", {1, 25.4}},      {"foot", {2, 12 * 25.4}},
                        {"cm", {5, 10}},           {"m", {6, 1000}},
                        {"mil", {9, 0.0254}},      {"yard", {10, 36 * 25.4}},
                        {"micron", {13, 1e-3}},    {"dm", {14, 100}},
                        {"us_survey_foot", {21, 1200.0 / 3937 * 1000}}};
  const io::testing::TempDir dir;
  for (std::uint64_t seed = 0; seed < kSeeds; ++seed) {
    const Unit& u = units[seed % std::size(units)];
    const std::vector<Region> regions = random_pocket(seed);
    const std::string dxf = region_to_dxf(regions, shuffle_seed_of(seed), u.dxf);
    EXPECT_EQ(round_trip_problems(regions[0], dxf, dir, "seed.dxf", u.name), "")
        << "seed " << seed << " in " << u.name;
  }
}

TEST(RandomPocket, SameSeedSameBytes) {
  for (std::uint64_t seed : {0u, 1u, 57u, 199u}) {
    const std::string a = region_to_dxf(random_pocket(seed), 5);
    EXPECT_EQ(a, region_to_dxf(random_pocket(seed), 5)) << "seed " << seed;
    EXPECT_NE(a, region_to_dxf(random_pocket(seed + 1), 5)) << "seed " << seed;
    EXPECT_NE(a, region_to_dxf(random_pocket(seed), 6)) << "seed " << seed;  // order differs
  }
}

// The seeds cover what the generator promises (a generator stuck in one corner would pass
// the validity tests above).
TEST(RandomPocket, SeedsCoverEveryKind) {
  std::set<int> island_counts;
  std::set<double> gaps;
  std::map<std::string, int> seen;
  const RandomPocketOptions opt;
  for (std::uint64_t seed = 0; seed < kSeeds; ++seed) {
    RandomPocketInfo info;
    const Region r = random_pocket(seed, opt, &info)[0];
    island_counts.insert(static_cast<int>(r.islands.size()));
    gaps.insert(info.gap);
    ++seen[info.kind == RandomPocketKind::kStar ? "star" : "dumbbell"];
    if (info.kind == RandomPocketKind::kStar) {
      EXPECT_GE(info.samples, 5);
      EXPECT_LE(info.samples, 24);
    } else {
      EXPECT_GE(info.neck_width, 1.2 * opt.tool_diameter) << "seed " << seed;
      EXPECT_LE(info.neck_width, 3 * opt.tool_diameter) << "seed " << seed;
    }
    if (info.offset.cwiseAbs().maxCoeff() > 1e3) ++seen["far"];
    if (info.rotation != 0) ++seen["rotated"];
    EXPECT_LE(static_cast<int>(r.islands.size()), opt.max_islands);
    // The extent in the generator's frame (placement undone) is the size, which is in range.
    EXPECT_GE(info.size, opt.min_size);
    EXPECT_LE(info.size, opt.max_size);
    const double c = std::cos(info.rotation), s = std::sin(info.rotation);
    Vec2 lo = Vec2::Constant(INFINITY), hi = -lo;
    for (const Vec2& p : samples(r.boundary)) {
      const Vec2 d = p - info.offset;
      const Vec2 local(c * d.x() + s * d.y(), -s * d.x() + c * d.y());
      lo = lo.cwiseMin(local), hi = hi.cwiseMax(local);
    }
    const double extent = (hi - lo).maxCoeff();
    EXPECT_NEAR(extent, info.size, 1e-3 * info.size) << "seed " << seed;
    auto count_curves = [&](const Profile& p) {
      for (const ProfileCurve& pc : p.curves) {
        if (pc.nurbs >= 0) {
          const Nurbs2& n = p.nurbs[pc.nurbs];
          const bool rational =
              std::any_of(n.weights.begin(), n.weights.end(), [](double w) { return w != 1; });
          ++seen[n.degree == 3 ? (rational ? "rational cubic" : "cubic") : "quadratic (ellipse)"];
        } else {
          ++seen[pc.seg.kind == SegKind::kLine ? "line" : "arc"];
        }
      }
    };
    count_curves(r.boundary);
    for (const Profile& p : r.islands) count_curves(p);
    if (!r.islands.empty()) {
      const std::vector<Vec2> wall = samples(r.boundary);
      for (const Profile& p : r.islands)
        if (min_distance(wall, samples(p), 1) < 0.1) {
          ++seen["island within 0.1 mm of the wall"];
          break;
        }
    }
    const std::string dxf = region_to_dxf({r}, shuffle_seed_of(seed));
    if (dxf.find("\n230\n-1.0\n") != std::string::npos) ++seen["ARC with extrusion -Z"];
    if (dxf.find("\n  0\nCIRCLE\n") != std::string::npos) ++seen["CIRCLE"];
  }
  EXPECT_EQ(island_counts, (std::set<int>{0, 1, 2, 3, 4}));
  EXPECT_EQ(gaps, (std::set<double>{0.05, 0.5, 3}));
  for (const char* k :
       {"star", "dumbbell", "far", "rotated", "cubic", "rational cubic", "quadratic (ellipse)",
        "line", "arc", "island within 0.1 mm of the wall", "ARC with extrusion -Z", "CIRCLE"})
    EXPECT_GE(seen[k], 3) << k;
}

// The checks above can fail: broken copies of a valid region are caught.
TEST(RandomPocket, ChecksCatchBrokenRegions) {
  // A seed with islands, one of them made of arcs.
  std::uint64_t seed = 0;
  RandomPocketInfo info;
  Region r;
  for (;; ++seed) {
    r = random_pocket(seed, {}, &info)[0];
    if (r.islands.size() >= 2) break;
  }
  ASSERT_EQ(region_problems(r, info.gap), "");

  Region reversed_boundary = r;
  reversed_boundary.boundary = random_pocket_detail::reversed_profile(r.boundary);
  EXPECT_NE(region_problems(reversed_boundary, info.gap).find("wrong orientation"),
            std::string::npos);

  Region open = r;
  open.boundary.curves[1].seg.a += Vec2(1e-9, 0);
  EXPECT_NE(region_problems(open, info.gap).find("not closed after curve 0"), std::string::npos);

  Region outside = r;
  random_pocket_detail::map_profile(outside.islands[0],
                                    [](const Vec2& p) -> Vec2 { return p + Vec2(500, 0); });
  EXPECT_NE(region_problems(outside, info.gap).find("island 0: outside the boundary"),
            std::string::npos);

  Region twice = r;
  twice.islands.push_back(r.islands[0]);
  EXPECT_NE(region_problems(twice, info.gap), "");

  // Demanding a wider gap than the islands keep fails.
  EXPECT_NE(region_problems(r, info.gap + 50).find("mm from"), std::string::npos);

  // DXF: the first entity missing; a geometry 1e-5 larger.
  const io::testing::TempDir dir;
  const std::string dxf = region_to_dxf({r}, 1);
  ASSERT_EQ(round_trip_problems(r, dxf, dir, "ok.dxf"), "");
  const std::size_t second = dxf.find("\n  0\n", dxf.find("ENTITIES"));
  const std::size_t third = dxf.find("\n  0\n", second + 1);
  const std::string missing = dxf.substr(0, second) + dxf.substr(third);
  EXPECT_NE(round_trip_problems(r, missing, dir, "missing.dxf"), "");
  Region grown = r;
  random_pocket_detail::map_profile(grown.boundary,
                                    [](const Vec2& p) -> Vec2 { return p * (1 + 1e-5); });
  for (Profile& p : grown.islands)
    random_pocket_detail::map_profile(p, [](const Vec2& p) -> Vec2 { return p * (1 + 1e-5); });
  const std::string grown_dxf = region_to_dxf({grown}, 1);
  const std::string e = round_trip_problems(r, grown_dxf, dir, "grown.dxf");
  EXPECT_NE(e.find("boundary length"), std::string::npos) << e;
}

// The hand-made glyph and CAD pockets of datasets/pockets/ read and chain as intended.
TEST(DatasetPockets, GlyphAndCadDxfsChain) {
  const std::map<std::string, std::size_t> islands = {
      {"glyph_eight.dxf", 2}, {"glyph_percent.dxf", 3}, {"glyph_g.dxf", 0}, {"bracket.dxf", 4}};
  for (const auto& [file, n] : islands) {
    const io::ProfileSoup s =
        io::read_dxf(std::filesystem::path(NCPATH_SOURCE_DIR) / "datasets/pockets" / file);
    EXPECT_TRUE(s.warnings.empty()) << file;
    const ChainResult c = chain_and_nest(s.curves, s.nurbs, s.sources);
    ASSERT_EQ(c.error, "") << file;
    ASSERT_EQ(c.regions.size(), 1u) << file;
    EXPECT_EQ(c.regions[0].islands.size(), n) << file;
    EXPECT_EQ(region_problems(c.regions[0], 0.5), "") << file;
  }
}

}  // namespace
}  // namespace ncpath::test
