// The profile verifier (engine/verify_profile.*) on hand-made moves with analytic answers,
// and as the oracle of record for pocket paths: random pockets (lines, bulges, splines,
// ellipses, islands, necks, far from the origin) planned by plan_pocket must never cut into
// a wall, an island or the floor; helix entries stay within their radius.
#include "engine/verify_profile.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "engine/parallel.hpp"
#include "engine/pocket_path.hpp"
#include "tests/support/random_pockets.hpp"
#include "tests/support/shapes2d.hpp"

namespace ncpath {
namespace {

ClChunk one_path(const std::vector<Vec3>& pts, PathKind kind = PathKind::kCut) {
  ClChunk c;
  for (const Vec3& p : pts) {
    c.xyz.insert(c.xyz.end(), {p.x(), p.y(), p.z()});
    c.contact.push_back(0);
  }
  c.path_sizes.push_back(static_cast<std::uint32_t>(pts.size()));
  c.path_kinds.push_back(static_cast<std::uint8_t>(kind));
  return c;
}

// A 40 x 40 square pocket with a circular island of radius 5 at (20, 20); flat 6 mm tool,
// floor 2 mm below the top.
struct SquareCase {
  std::vector<Region> regions;
  ProfileVerifyParams prm;
  SquareCase() {
    Region r;
    r.boundary = profile_of(test::rectangle(0, 0, 40, 40, true));
    r.islands.push_back(profile_of(test::circle(Vec2(20, 20), 5, false)));
    regions = {r};
    prm.cutter = flat_cutter(6);
    prm.top = 0;
    prm.floor = -2;
    prm.rapid_limit = 0;
  }
};

TEST(VerifyProfile, AnalyticWallFloorAndRapid) {
  SquareCase sc;
  const WallSet walls = profile_walls(sc.regions, sc.prm);
  // Along the wall x = 0 at exactly R: clean, clearance 0.
  VerifyReport r = verify_profile_moves(walls, one_path({{3, 5, -2}, {3, 35, -2}}), sc.prm);
  EXPECT_EQ(r.moves, 1u);
  EXPECT_EQ(r.max_gouge, 0);
  EXPECT_NEAR(r.min_clearance, 0, 1e-12);
  // 0.01 mm closer: a 0.01 mm gouge in the wall, named.
  r = verify_profile_moves(walls, one_path({{5, 5, -2}, {2.99, 20, -2}, {5, 35, -2}}), sc.prm);
  EXPECT_NEAR(r.max_gouge, 0.01, 1e-12);
  ASSERT_EQ(r.worst.size(), 2u);  // the second move starts at the same point: same amount
  EXPECT_EQ(r.worst[0].kind, ViolationKind::kWall);
  EXPECT_EQ(r.worst[0].move, 0u);  // ties go to the lower move
  // Both ends clear of the island (R + 1 away), the middle passes 0.5 mm from its edge.
  r = verify_profile_moves(walls, one_path({{11, 25.5, -1}, {29, 25.5, -1}}), sc.prm);
  EXPECT_NEAR(r.max_gouge, 3 - 0.5, 1e-12);
  // Above the top nothing is in the way; below the floor is a gouge of the floor.
  r = verify_profile_moves(walls, one_path({{20, 20, 0.5}, {1, 1, 0.5}}), sc.prm);
  EXPECT_EQ(r.max_gouge, 0);
  r = verify_profile_moves(walls, one_path({{10, 10, -1}, {10, 12, -2.25}}), sc.prm);
  EXPECT_NEAR(r.max_gouge, 0.25, 1e-12);
  EXPECT_EQ(r.worst[0].kind, ViolationKind::kFloor);
  // A rapid that crosses the pocket below the top; a vertical retract from the floor is fine.
  r = verify_profile_moves(walls, one_path({{10, 10, 5}, {14, 10, -0.5}}, PathKind::kRapid),
                           sc.prm);
  EXPECT_EQ(r.worst[0].kind, ViolationKind::kRapid);
  EXPECT_NEAR(r.min_rapid_clearance, -0.5, 1e-12);
  r = verify_profile_moves(walls, one_path({{10, 10, -2}, {10, 10, 5}}, PathKind::kRapid), sc.prm);
  EXPECT_EQ(r.max_gouge, 0);
  r = verify_profile_moves(walls, one_path({{2, 10, -2}, {2, 10, 5}}, PathKind::kRapid), sc.prm);
  EXPECT_NEAR(r.max_gouge, 1, 1e-12);  // a retract is still a move of the tool in the pocket
}

TEST(VerifyProfile, ShallowBallSeesItsNarrowerCap) {
  SquareCase sc;
  sc.prm.cutter = ball_cutter(6);
  const WallSet walls = profile_walls(sc.regions, sc.prm);
  // Tip 0.5 mm below the top: the ball's radius at the top is sqrt(3^2 - 2.5^2).
  const double rho = std::sqrt(9 - 6.25);
  VerifyReport r = verify_profile_moves(walls, one_path({{rho, 5, -0.5}, {rho, 35, -0.5}}), sc.prm);
  EXPECT_EQ(r.max_gouge, 0);
  r = verify_profile_moves(walls, one_path({{rho - 0.1, 5, -0.5}, {rho - 0.1, 35, -0.5}}), sc.prm);
  EXPECT_NEAR(r.max_gouge, 0.1, 1e-12);
}

TEST(VerifyProfile, SameReportForAnyThreadCount) {
  SquareCase sc;
  PocketPathParams p;
  p.tool_radius = 3;
  p.stepover = 3;
  p.depth = 2;
  const PocketPath path = plan_pocket(sc.regions, p);
  const WallSet walls = profile_walls(sc.regions, sc.prm);
  VerifyReport one, two;
  {
    par::ThreadLimit limit(1);
    one = verify_profile_moves(walls, path.cl, sc.prm);
  }
  {
    par::ThreadLimit limit(2);
    two = verify_profile_moves(walls, path.cl, sc.prm);
  }
  EXPECT_EQ(one.moves, two.moves);
  EXPECT_EQ(one.min_clearance, two.min_clearance);
  EXPECT_EQ(one.max_gouge, 0);
  EXPECT_GE(one.min_clearance, 0);
  EXPECT_LT(one.min_clearance, 0.02);  // level 1 runs along the walls
}

// The helix descent of every part: the cut points strictly between the floor of the first
// pass and the feed height lie on one circle of radius <= helix radius.
double widest_entry(const PocketPath& path, double feed_z, double floor_z) {
  double widest = 0;
  std::vector<Vec2> entry;
  std::size_t start = 0;
  for (std::size_t k = 0; k < path.cl.path_sizes.size(); ++k) {
    const std::size_t n = path.cl.path_sizes[k];
    if (path.cl.path_kinds[k] == static_cast<std::uint8_t>(PathKind::kRapid)) {
      entry.clear();
    } else {
      for (std::size_t i = start; i < start + n; ++i) {
        const double z = path.cl.xyz[3 * i + 2];
        if (z < feed_z && z > floor_z)
          entry.emplace_back(path.cl.xyz[3 * i], path.cl.xyz[3 * i + 1]);
      }
      for (const Vec2& a : entry)
        for (const Vec2& b : entry) widest = std::max(widest, (a - b).norm());
    }
    start += n;
  }
  return widest;
}

// Seeds [first, first + count): NCPATH_FUZZ_SEEDS="first:count" (scripts/verify-fuzz.sh runs
// thousands), else the CI's fixed range.
std::pair<std::uint64_t, std::uint64_t> seed_range(std::uint64_t first, std::uint64_t count) {
  if (const char* env = std::getenv("NCPATH_FUZZ_SEEDS")) {
    unsigned long long a = 0, n = 0;
    if (std::sscanf(env, "%llu:%llu", &a, &n) == 2) return {a, n};
  }
  return {first, count};
}

// One random pocket through plan_pocket and the verifier: no gouge, ever; helix entries
// within their radius. Returns false when the tool does not fit (nothing to verify); counts
// the pockets entered by helices only.
bool check_random_pocket(std::uint64_t seed, int& helices) {
  const test::RandomPocketCase c = test::random_pocket_case(seed);
  const std::vector<Region>& regions = c.regions;
  const double d = c.tool_diameter;
  PocketPathParams p;
  p.tool_radius = d / 2;
  p.stepover = c.stepover;
  p.depth = 3;
  p.stepdown = seed % 3 == 0 ? 1.5 : 0;
  p.stock = seed % 5 == 0 ? 0.3 : 0;
  p.tolerance = 0.01;
  p.chordal_tolerance = 0.01;
  PocketPath path;
  try {
    path = plan_pocket(regions, p);
  } catch (const RegionTooSmall&) {
    return false;
  }
  ProfileVerifyParams v;
  v.cutter = flat_cutter(d);
  v.stock = p.stock;
  v.top = p.top;
  v.floor = p.top - p.depth;
  v.rapid_limit = p.top;
  const VerifyReport r = verify_profile_moves(profile_walls(regions, v), path.cl, v);
  EXPECT_EQ(r.max_gouge, 0) << "seed " << seed << ": " << r.message();
  if (path.stats.helix_entries > 0 && path.stats.ramp_entries == 0) {
    ++helices;
    const double floor1 = p.stepdown > 0 ? p.top - p.stepdown : p.top - p.depth;
    EXPECT_LE(widest_entry(path, p.top + p.clearance, floor1), p.tool_radius + 1e-9)
        << "seed " << seed << ": the helix (radius R/2) leaves its circle";
  }
  return true;
}

TEST(VerifyProfile, RandomPocketsNeverGouge) {
  int planned = 0, helices = 0;
  const auto [first, count] = seed_range(1, 24);
  for (std::uint64_t seed = first; seed < first + count; ++seed)
    planned += check_random_pocket(seed, helices);
  EXPECT_GE(planned, static_cast<int>(count * 3 / 4));
  EXPECT_GE(helices, static_cast<int>(count * 2 / 5));
}

// Seeds that scripts/verify-fuzz.sh found cutting through a wall or an island by millimetres
// (the offset joined corners by the offsets' own tangents, which run backwards along arcs
// turned inside out: a spike's tip closed the wrong way round, islands' loops were lost;
// spikes whose sides cross below a micrometre; arcs of 50 m radius whose crossings were
// rejected; a hooked tip's run dropped for a marginal miss), or by a few hundredths (NURBS
// walls offset by Tiller-Hanson, then as arcs).
TEST(VerifyProfile, FormerOffsetFailuresNeverGouge) {
  int helices = 0;
  for (std::uint64_t seed : {94,   100,  101,  102,  106,  121,  124,  125,  131,  144,  160,
                             178,  240,  247,  1200, 1465, 2403, 3172, 4769, 4918, 5073, 5564,
                             6478, 7606, 7688, 9751})
    EXPECT_TRUE(check_random_pocket(seed, helices)) << "seed " << seed << ": nothing planned";
}

// The one seed of 30,000 (scripts/verify-fuzz.sh, 2026-11-27) still cutting an island: its
// corner is a hook of NURBS arcs whose radii are near the tool radius, and the d-neighbourhood
// boundary there is made of vertex circles the crude loops do not follow (an island's level-1
// loop is lost, open fragments; the verifier fails the job). Swallowing inside-out arcs and
// going round their vertices' circles was tried and did not mend it; the complete fix is the
// boundary of the union of the curves' neighbourhoods. Enable when mended:
//   engine_verify_test --gtest_also_run_disabled_tests --gtest_filter=*Known*
TEST(VerifyProfile, DISABLED_KnownOffsetFailure) {
  int helices = 0;
  EXPECT_TRUE(check_random_pocket(10874, helices));
}

}  // namespace
}  // namespace ncpath

