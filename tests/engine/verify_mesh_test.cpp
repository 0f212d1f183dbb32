// Mesh verifier (engine/verify_mesh.*): analytic paths over a V-groove (touching, lowered,
// rapids above it), the culling and grid against a brute-force scan of every facet with the
// kernel, 1 vs 2 threads and chunked vs whole, and the bunny (real mesh): raster points
// from the drop-cutter raster touch exactly, and the throughput of a raster job. The chord
// guard (engine/chord_guard.hpp) on a fine raster: shallow cuts cleared by raising points,
// deep ones by lift-overs, every move clean by the verifier and by the drop-cutter; its
// checks handed to the verifier give the report of checking every move, and a check whose
// move has changed is not used.
#include "engine/verify_mesh.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>

#include "engine/chord_guard.hpp"
#include "engine/drop_index.hpp"
#include "engine/facet_table.hpp"
#include "engine/parallel.hpp"
#include "engine/raster.hpp"
#include "tests/engine/mesh_test_support.hpp"
#include "tests/support/meshes.hpp"

namespace ncpath {
namespace {

constexpr double kR = 3, kSlope = 0.5, kGroove = 20;

// V-groove along y at x = 20: z = 0.5 |x - 20| over [0, 40]^2, planar flanks split into a grid
// whose lines include x = 20. A ball on a flank touches the plane: tip = drop(x) below.
TriangleMesh groove() {
  return test::height_field(40, 40,
                            [](double x, double) { return kSlope * std::abs(x - kGroove); });
}
double drop(double x) {
  return kSlope * std::abs(x - kGroove) + kR * (std::sqrt(1 + kSlope * kSlope) - 1);
}

struct Paths {
  ClChunk chunk;
  void add(const std::vector<Vec3>& points, PathKind kind) {
    for (const Vec3& p : points) {
      chunk.xyz.insert(chunk.xyz.end(), {p.x(), p.y(), p.z()});
      chunk.contact.push_back(0);
    }
    chunk.path_sizes.push_back(static_cast<std::uint32_t>(points.size()));
    chunk.path_kinds.push_back(static_cast<std::uint8_t>(kind));
  }
};

// Along the groove bottom (both flanks touched), then across it (one flank, then the other;
// the drop height is linear on each side and the kink is a path point).
std::vector<std::vector<Vec3>> touching_paths() {
  std::vector<Vec3> along, across;
  for (double y = 5; y <= 35; y += 2.5) along.emplace_back(kGroove, y, drop(kGroove));
  for (double x : {5.0, 12.5, 20.0, 27.5, 35.0}) across.emplace_back(x, 20, drop(x));
  return {along, across};
}

MeshVerifyReport verify(const MeshVerifier& v, const ClChunk& c, MeshVerifyParams p = {}) {
  return verify_moves(v, ball_cutter(2 * kR), c, p);
}

TEST(VerifyMesh, TouchingPathHasNoGouge) {
  const MeshVerifier verifier(groove());
  Paths p;
  for (const auto& path : touching_paths()) p.add(path, PathKind::kCut);
  const MeshVerifyReport r = verify(verifier, p.chunk);
  EXPECT_TRUE(r.error.empty()) << r.error;
  EXPECT_EQ(r.moves, 12u + 4u);
  EXPECT_EQ(r.gouging_moves, 0u);
  EXPECT_EQ(r.max_gouge, 0);
  EXPECT_TRUE(r.worst.empty());
  EXPECT_GT(r.candidates, 50u);  // planar flanks: every facet is dismissed by its plane
}

TEST(VerifyMesh, LoweredPathGougesByTheDrop) {
  const MeshVerifier verifier(groove());
  auto paths = touching_paths();
  for (auto& path : paths)
    for (Vec3& q : path) q.z() -= 0.2;
  paths[0][6].z() -= 0.3;  // 0.5 below at one point: moves 5 and 6 gouge most
  Paths p;
  for (const auto& path : paths) p.add(path, PathKind::kCut);
  const MeshVerifyReport r = verify(verifier, p.chunk);
  EXPECT_EQ(r.gouging_moves, r.moves);
  EXPECT_NEAR(r.max_gouge, 0.5, 1e-6);
  ASSERT_EQ(r.worst.size(), 8u);
  EXPECT_NEAR(r.worst[0].amount, 0.5, 1e-6);
  EXPECT_NEAR(r.worst[1].amount, 0.5, 1e-6);
  EXPECT_EQ(std::min(r.worst[0].move, r.worst[1].move), 5u);
  EXPECT_EQ(std::max(r.worst[0].move, r.worst[1].move), 6u);
  EXPECT_EQ(r.worst[0].path, 0u);
  for (std::size_t i = 2; i < r.worst.size(); ++i) EXPECT_NEAR(r.worst[i].amount, 0.2, 1e-6);
  // The facet named lies under the deepest point (within the ball's reach).
  const TriangleMesh mesh = groove();
  const Vec3 deep = paths[0][6];
  for (std::uint32_t v : mesh.facets[r.worst[0].facet])
    EXPECT_LT(std::hypot(mesh.vertices[v].x() - deep.x(), mesh.vertices[v].y() - deep.y()),
              kR + 1.5);

  // Lowered by 0.2 only: every move gouges 0.2.
  for (Vec3& q : paths[0]) q.z() = drop(kGroove) - 0.2;
  Paths even;
  even.add(paths[0], PathKind::kCut);
  const MeshVerifyReport e = verify(verifier, even.chunk);
  EXPECT_NEAR(e.max_gouge, 0.2, 1e-6);
  for (const MoveViolation& w : e.worst) EXPECT_NEAR(w.amount, 0.2, 1e-6);
}

// Rapid at tip height h above the groove bottom: the ball centre is h + R above it, at
// (h + R) / sqrt(1 + k^2) from each flank.
TEST(VerifyMesh, RapidClearanceAboveTheGroove) {
  const MeshVerifier verifier(groove());
  const double h = 5;
  Paths p;
  p.add(touching_paths()[1], PathKind::kCut);
  p.add({{kGroove, 10, 50}, {kGroove, 30, 50}}, PathKind::kRapid);  // nothing within the cap
  p.add({{kGroove, 10, h}, {kGroove, 30, h}}, PathKind::kRapid);
  p.add({{kGroove, 30, 8}, {kGroove, 30, 50}}, PathKind::kRapid);  // 6.34 mm at its start
  MeshVerifyParams params;
  params.safe_clearance = 5;
  params.stock = 0.5;
  const MeshVerifyReport r = verify(verifier, p.chunk, params);
  const double expected = (h + kR) / std::sqrt(1 + kSlope * kSlope) - kR - params.stock;
  EXPECT_EQ(r.rapid_moves, 3u);
  EXPECT_NEAR(r.min_rapid_clearance, expected, 1e-9);
  EXPECT_EQ(r.closest_rapid.move, 4u + 1u);
  EXPECT_EQ(r.closest_rapid.path, 2u);
  EXPECT_EQ(r.unsafe_rapids, 1u);
  // The cut path touches the flanks without stock: the ball grown by s clears a flank of
  // slope k raised by s sqrt(1 + k^2).
  EXPECT_NEAR(r.max_gouge, params.stock * std::sqrt(1 + kSlope * kSlope), 1e-6);

  Paths high;
  high.add({{kGroove, 10, 50}, {kGroove, 30, 50}}, PathKind::kRapid);
  EXPECT_EQ(verify(verifier, high.chunk).min_rapid_clearance, 10);  // the cap
}

// Random moves over a random terrain, for every cutter: the verifier's gouge and clearance
// equal a scan of every facet with the kernel (the culling and the grid lose nothing).
TEST(VerifyMesh, EqualsBruteForceOverAllFacets) {
  const TriangleMesh mesh = test::random_height_field(24, 40, 6, 5);
  const MeshVerifier verifier(mesh);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> X(-3, 43), Z(2, 9), D(-3, 3);
  const Cutter cutters[] = {ball_cutter(6), flat_cutter(5), bull_nose_cutter(8, 1.5)};
  int gouging = 0;
  for (const Cutter& c : cutters) {
    const SweptTool tool{c, 20, 0.1};
    for (int i = 0; i < 150; ++i) {
      const Vec3 p0{X(rng), X(rng), Z(rng)};
      const Vec3 p1 = p0 + Vec3(D(rng), D(rng), 0.3 * D(rng));
      const double floor = 1e-6, cap = 4;
      const MeshVerifier::MoveCheck got = verifier.check_move(tool, p0, p1, floor, cap);
      double gouge = 0, clearance = INFINITY;
      for (const auto& f : mesh.facets) {
        const Vec3 &a = mesh.vertices[f[0]], &b = mesh.vertices[f[1]], &d = mesh.vertices[f[2]];
        gouge = std::max(gouge, swept_gouge(tool, p0, p1, a, b, d));
        clearance = std::min(clearance, swept_gap(tool, p0, p1, a, b, d));
      }
      EXPECT_NEAR(got.gouge, gouge > floor ? gouge : 0, 3e-9) << cutter_type_name(c.type) << i;
      // Bounds and GJK agree to rounding where the bound is exact (plane contacts).
      if (clearance < cap - 1e-9) {
        EXPECT_NEAR(got.clearance, clearance, 1e-12) << cutter_type_name(c.type) << i;
      } else if (clearance > cap + 1e-9) {
        EXPECT_EQ(got.clearance, INFINITY) << cutter_type_name(c.type) << i;
      }
      gouging += gouge > floor;
    }
  }
  EXPECT_GT(gouging, 100);
}

// Facets that start far outside a move's box and reach into it (a sliver along y whose first
// grid cell is rows below the query, one along x whose first cell is columns to its left)
// are found, beside a floor of small facets that keeps the grid's cells small: the gouge
// equals the scan of every facet, about the 1 mm the slivers stand above the tip.
TEST(VerifyMesh, LongFacetsReachingIntoTheQueryAreFound) {
  TriangleMesh mesh = test::height_field(100, 50, [](double, double) { return 0.0; });
  auto add = [&](const Vec3& a, const Vec3& b, const Vec3& c) {
    const auto n = static_cast<std::uint32_t>(mesh.vertices.size());
    mesh.vertices.insert(mesh.vertices.end(), {a, b, c});
    mesh.facets.push_back({n, n + 1, n + 2});
  };
  add(Vec3(25, -100, 5), Vec3(25.2, -100, 5), Vec3(25.1, 100, 5));  // along y, from far below
  add(Vec3(-100, 25, 5), Vec3(-100, 25.2, 5), Vec3(100, 25.1, 5));  // along x, from far left
  const MeshVerifier verifier(mesh);
  const SweptTool tool{ball_cutter(2 * kR), 20, 0};
  const std::pair<Vec3, Vec3> moves[] = {{Vec3(20, 40, 4), Vec3(30, 40, 4)},
                                         {Vec3(40, 20, 4), Vec3(40, 30, 4)}};
  for (const auto& [p0, p1] : moves) {
    double gouge = 0;
    for (const auto& f : mesh.facets)
      gouge = std::max(gouge, swept_gouge(tool, p0, p1, mesh.vertices[f[0]],
                                          mesh.vertices[f[1]], mesh.vertices[f[2]]));
    const MeshVerifier::MoveCheck got = verifier.check_move(tool, p0, p1, 1e-6, 0);
    EXPECT_GT(gouge, 0.9);
    EXPECT_NEAR(got.gouge, gouge, 3e-9) << p0.transpose() << " -> " << p1.transpose();
  }
}

void expect_same_check(const MeshVerifier::MoveCheck& got, const MeshVerifier::MoveCheck& want,
                       const std::string& what) {
  EXPECT_EQ(got.gouge, want.gouge) << what;
  EXPECT_EQ(got.gouge_facet, want.gouge_facet) << what;
  EXPECT_EQ(got.clearance, want.clearance) << what;
  EXPECT_EQ(got.clearance_facet, want.clearance_facet) << what;
  EXPECT_EQ(got.gjk_calls, want.gjk_calls) << what;
}

// Paths of short moves (a raster's, a pencil's) share one walk of the grid per group of
// moves: each move's check must still be the one it gets alone, bit for bit, whatever it
// is grouped with: random walks over a random terrain, with steps from 0.05 mm to 4 mm (one
// group to many), climbs and drops, points sunk into the part, three cutters with stock,
// gouge floors and rapid caps; the same moves as unconnected pairs in another order.
TEST(VerifyMesh, PathChecksEqualSingleMoveChecks) {
  const TriangleMesh mesh = test::random_height_field(40, 40, 5, 21);
  const MeshVerifier verifier(mesh);
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> X(2, 38), U(-1, 1), Z(0, 8);
  const Cutter cutters[] = {ball_cutter(6), flat_cutter(5), bull_nose_cutter(8, 1.5)};
  int gouging = 0, groups_of_many = 0;
  for (const Cutter& c : cutters) {
    const SweptTool tool{c, 20, 0.2};
    for (double step : {0.05, 0.3, 4.0}) {
      for (const double floor : {1e-6, 0.05}) {
        for (const double cap : {0.0, 3.0}) {
          std::vector<Vec3> tips{{X(rng), X(rng), Z(rng)}};
          for (int i = 0; i < 120; ++i)
            tips.push_back(tips.back() + Vec3(step * U(rng), step * U(rng), 0.5 * step * U(rng)));
          std::vector<MeshVerifier::MoveCheck> path(tips.size() - 1);
          verifier.check_path(tool, tips.data(), tips.size(), floor, cap, path.data());
          // Unconnected: every other move, reversed order.
          std::vector<Vec3> from, to;
          for (std::size_t k = path.size(); k-- > 0;)
            if (k % 2 == 0) {
              from.push_back(tips[k]);
              to.push_back(tips[k + 1]);
            }
          std::vector<MeshVerifier::MoveCheck> pairs(from.size());
          verifier.check_moves(tool, from.data(), to.data(), from.size(), floor, cap, pairs.data());
          for (std::size_t k = 0; k < path.size(); ++k) {
            const std::string what = std::string(cutter_type_name(c.type)) + " step " +
                                     std::to_string(step) + " move " + std::to_string(k);
            const MeshVerifier::MoveCheck alone =
                verifier.check_move(tool, tips[k], tips[k + 1], floor, cap);
            expect_same_check(path[k], alone, what);
            if (k % 2 == 0) expect_same_check(pairs[pairs.size() - 1 - k / 2], alone, what);
            gouging += alone.gouge > 0;
          }
          groups_of_many += step < 1;
        }
      }
    }
  }
  EXPECT_GT(gouging, 500);
  EXPECT_GT(groups_of_many, 0);
}

// kDecide says what kMeasure says about each move (a gouge above the floor or not), as +inf
// or 0, and still measures rapids' clearances.
TEST(VerifyMesh, DecidingAGougeAgreesWithMeasuringIt) {
  const TriangleMesh mesh = test::random_height_field(30, 40, 5, 9);
  const MeshVerifier verifier(mesh);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> X(2, 38), U(-1, 1), Z(1, 7);
  int yes = 0, no = 0;
  for (const Cutter& c : {ball_cutter(6), flat_cutter(5), bull_nose_cutter(8, 1.5)}) {
    const SweptTool tool{c, 20, 0.1};
    for (const double cap : {0.0, 2.0}) {
      std::vector<Vec3> tips{{X(rng), X(rng), Z(rng)}};
      for (int i = 0; i < 300; ++i)
        tips.push_back(tips.back() + Vec3(0.2 * U(rng), 0.2 * U(rng), 0.1 * U(rng)));
      std::vector<MeshVerifier::MoveCheck> measured(tips.size() - 1), decided(tips.size() - 1);
      verifier.check_path(tool, tips.data(), tips.size(), 1e-6, cap, measured.data());
      verifier.check_path(tool, tips.data(), tips.size(), 1e-6, cap, decided.data(),
                          MoveCheckMode::kDecide);
      for (std::size_t k = 0; k < measured.size(); ++k) {
        EXPECT_EQ(decided[k].gouge, measured[k].gouge > 0 ? INFINITY : 0.0) << k;
        if (cap > 0) {
          EXPECT_EQ(decided[k].clearance, measured[k].clearance) << k;
        }
        (measured[k].gouge > 0 ? yes : no) += 1;
      }
    }
  }
  EXPECT_GT(yes, 100);
  EXPECT_GT(no, 100);
}

// A long job over a random terrain with many gouges: 1 thread, 2 threads and two chunks
// merged give the same report, and so does a verifier whose grid was built on one thread.
TEST(VerifyMesh, SameReportForAnyThreadCountAndChunking) {
  const TriangleMesh mesh = test::random_height_field(30, 40, 5, 9);
  const MeshVerifier verifier(mesh);
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> X(0, 40), Z(2, 7), U(0, 1);
  Paths first, second;
  for (int k = 0; k < 40; ++k) {
    std::vector<Vec3> path;
    for (int i = 0; i < 60; ++i) path.emplace_back(X(rng), X(rng), Z(rng));
    const PathKind kind = U(rng) < 0.2 ? PathKind::kRapid : PathKind::kCut;
    (k < 25 ? first : second).add(path, kind);
  }
  ClChunk all = first.chunk;
  all.append(second.chunk);
  MeshVerifyParams params;
  params.worst = 20;
  const Cutter c = bull_nose_cutter(6, 1);
  MeshVerifyReport one, two, chunked, built_alone;
  {
    par::ThreadLimit limit(1);
    one = verify_moves(verifier, c, all, params);
    const MeshVerifier alone(mesh);  // its grid built on one thread
    built_alone = verify_moves(alone, c, all, params);
  }
  {
    par::ThreadLimit limit(2);
    two = verify_moves(verifier, c, all, params);
    chunked = verify_moves(verifier, c, first.chunk, params);
    merge(chunked, verify_moves(verifier, c, second.chunk, params, 25 * 59, 25));
  }
  EXPECT_GT(one.gouging_moves, 100u);
  EXPECT_GT(one.rapid_moves, 100u);
  for (const MeshVerifyReport* r : {&two, &chunked, &built_alone}) {
    EXPECT_EQ(r->moves, one.moves);
    EXPECT_EQ(r->gouging_moves, one.gouging_moves);
    EXPECT_EQ(r->rapid_moves, one.rapid_moves);
    EXPECT_EQ(r->unsafe_rapids, one.unsafe_rapids);
    EXPECT_EQ(r->gjk_calls, one.gjk_calls);
    EXPECT_EQ(r->max_gouge, one.max_gouge);
    EXPECT_EQ(r->min_rapid_clearance, one.min_rapid_clearance);
    EXPECT_EQ(r->closest_rapid.move, one.closest_rapid.move);
    ASSERT_EQ(r->worst.size(), one.worst.size());
    for (std::size_t i = 0; i < one.worst.size(); ++i) {
      EXPECT_EQ(r->worst[i].move, one.worst[i].move);
      EXPECT_EQ(r->worst[i].path, one.worst[i].path);
      EXPECT_EQ(r->worst[i].amount, one.worst[i].amount);
      EXPECT_EQ(r->worst[i].facet, one.worst[i].facet);
    }
  }
}

TEST(VerifyMesh, MalformedChunkIsReported) {
  const MeshVerifier verifier(groove());
  Paths p;
  p.add(touching_paths()[0], PathKind::kCut);
  p.chunk.path_sizes[0] += 1;
  EXPECT_FALSE(verify(verifier, p.chunk).error.empty());
}

// Largest depth of the tip below the drop height over 129 positions along the move, by
// brute force over the facets whose box lies within reach of the move's box.
double deepest_drop_along(const TriangleMesh& mesh, const Cutter& c, const Vec3& p0,
                          const Vec3& p1) {
  TriangleMesh near;
  near.vertices = mesh.vertices;
  const Vec3 lo = p0.cwiseMin(p1), hi = p0.cwiseMax(p1);
  for (const auto& f : mesh.facets) {
    Aabb3 box;
    for (std::uint32_t v : f) box.add(mesh.vertices[v]);
    if (box.hi.x() >= lo.x() - c.radius && box.lo.x() <= hi.x() + c.radius &&
        box.hi.y() >= lo.y() - c.radius && box.lo.y() <= hi.y() + c.radius)
      near.facets.push_back(f);
  }
  const FacetTable table = build_facet_table(near);
  double deepest = -INFINITY;
  for (int k = 0; k <= 128; ++k) {
    const Vec3 q = p0 + (p1 - p0) * (k / 128.0);
    const CutterContact cc = drop_brute_force(table, c, q.x(), q.y());
    if (cc.kind != ContactKind::kNone) deepest = std::max(deepest, cc.tip_z - q.z());
  }
  return deepest;
}

// The bunny at 200 mm: raster points (exact drop-cutter heights from the planner) touch,
// 0.01 mm lower they gouge 0.01; then the throughput over the whole raster job.
TEST(VerifyMeshBunny, RasterPointsTouchAndThroughput) {
  const auto file = std::filesystem::path(NCPATH_SOURCE_DIR) / "datasets/cache/meshes/bunny00.off";
  if (!std::filesystem::exists(file)) GTEST_SKIP() << file << " is missing";
  const TriangleMesh mesh = test_meshes::load("bunny00");
  const Cutter ball = ball_cutter(5);
  RasterParams rp;
  rp.interval = 0.4;
  rp.step = 0.4;
  ClChunk job;
  RunControl control;
  run_raster(
      mesh, ball, rp, [&](const ClChunk& c) { job.append(c); }, control);

  const auto t0 = std::chrono::steady_clock::now();
  const MeshVerifier verifier(mesh);
  const double build_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  const SweptTool tool{ball, 50, 0};
  for (std::size_t i = 0; i < job.xyz.size() / 3; i += 97) {
    const Vec3 p(job.xyz[3 * i], job.xyz[3 * i + 1], job.xyz[3 * i + 2]);
    ASSERT_EQ(verifier.check_move(tool, p, p, 1e-6).gouge, 0) << p.transpose();
    const Vec3 q = p - Vec3(0, 0, 0.01);
    const double g = verifier.check_move(tool, q, q, 1e-6).gouge;
    if (job.contact[i] != 0) {  // points on the floor touch nothing
      EXPECT_NEAR(g, 0.01, 2e-6) << p.transpose();
    }
  }

  // Moves of the job against the drop-cutter (brute force over the facets near the move,
  // an independent method): the swept gouge is the deepest drop depth along the move.
  int compared = 0, gouging = 0;
  for (std::size_t i = 0; i + 1 < job.xyz.size() / 3 && compared < 120; i += 1511) {
    const Vec3 p0(job.xyz[3 * i], job.xyz[3 * i + 1], job.xyz[3 * i + 2]);
    const Vec3 p1(job.xyz[3 * i + 3], job.xyz[3 * i + 4], job.xyz[3 * i + 5]);
    if ((p1 - p0).norm() > 1) continue;  // from one line to the next
    const double gouge = verifier.check_move(tool, p0, p1, 1e-6).gouge;
    const double oracle = deepest_drop_along(mesh, ball, p0, p1);
    EXPECT_GE(gouge, oracle - 2e-6) << p0.transpose() << " -> " << p1.transpose();
    EXPECT_LE(gouge, std::max(oracle, 0.0) * 1.05 + 1e-4) << p0.transpose();
    ++compared;
    gouging += gouge > 0;
  }
  EXPECT_GE(compared, 100);
  EXPECT_GT(gouging, 10);

  MeshVerifyParams params;
  for (int threads : {1, 2}) {
    par::ThreadLimit limit(threads);
    const auto t1 = std::chrono::steady_clock::now();
    const MeshVerifyReport r = verify_moves(verifier, ball, job, params);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
    std::printf(
        "bunny00 %llu facets (grid %.3f s), ball 5 raster %.1f/%.1f mm: %llu moves, %d threads: "
        "%.3f s = %.0f moves/s; %.2f candidates, %.3f GJK calls per move; max gouge %.3g mm "
        "(%llu moves above 1e-6)\n",
        (unsigned long long)verifier.facet_count(), build_s, rp.interval, rp.step,
        (unsigned long long)r.moves, threads, s, r.moves / s, double(r.candidates) / r.moves,
        double(r.gjk_calls) / r.moves, r.max_gouge, (unsigned long long)r.gouging_moves);
    EXPECT_GT(r.moves, 100000u);
  }
}

// A fine ball raster (0.1 mm steps) of a bumpy height field, its chords guarded.
struct GuardedRaster {
  TriangleMesh mesh = test::random_height_field(30, 40, 5, 9);
  Cutter ball = ball_cutter(6);
  ClChunk in, out;
  ChordGuardStats stats;
  PrecheckedMoves checks;
  explicit GuardedRaster(const MeshVerifier& verifier) {
    RasterParams rp;
    rp.interval = 2;
    rp.step = 0.1;
    RunControl control;
    run_raster(mesh, ball, rp, [&](const ClChunk& c) { in.append(c); }, control);
    out = guard_chords(verifier, SweptTool{ball, 50, 0}, in, stats, &checks);
  }
};

TEST(ChordGuard, ShallowCutsRaisedDeepOnesLiftedAndEveryMoveClean) {
  const TriangleMesh mesh = test::random_height_field(30, 40, 5, 9);
  const MeshVerifier verifier(mesh);
  const GuardedRaster g(verifier);
  EXPECT_GT(g.stats.raised, 1000u);
  EXPECT_GT(g.stats.lifted, 10u);
  EXPECT_GT(g.stats.max_raise, 0);
  EXPECT_LE(g.stats.max_raise, tol::kChordRaise);
  // Every move out clean (the verifier's kernel); the points of the paths' ends unchanged.
  const MeshVerifyReport r = verify_moves(verifier, g.ball, g.out, MeshVerifyParams{});
  EXPECT_EQ(r.gouging_moves, 0u);
  ASSERT_EQ(g.out.path_sizes.size(), g.in.path_sizes.size());
  std::size_t a = 0, b = 0;
  for (std::size_t k = 0; k < g.in.path_sizes.size(); ++k) {
    EXPECT_EQ(g.out.point(b), g.in.point(a));
    EXPECT_EQ(g.out.point(b + g.out.path_sizes[k] - 1), g.in.point(a + g.in.path_sizes[k] - 1));
    a += g.in.path_sizes[k];
    b += g.out.path_sizes[k];
  }
  // Against the drop-cutter (an independent oracle): no point below the CL surface, points
  // with a contact (drop points, raised or not) at most kChordRaise above it, and sampled
  // moves nowhere below it.
  const DropIndex drop(mesh, g.ball);
  std::size_t raised = 0;
  for (std::size_t i = 0; i < g.out.point_count(); ++i) {
    const Vec3 p = g.out.point(i);
    const double z = drop.query(p.x(), p.y()).tip_z;
    if (!std::isfinite(z)) continue;
    EXPECT_GE(p.z(), z - 1e-9) << p.transpose();
    if (g.out.contact[i] == 0) continue;
    EXPECT_LE(p.z(), z + tol::kChordRaise + 1e-9) << p.transpose();
    raised += p.z() > z + 1e-9;
  }
  EXPECT_GT(raised, 1000u);
  int compared = 0;
  for (std::size_t i = 0; i + 1 < g.out.point_count(); i += 53) {
    const Vec3 p0 = g.out.point(i), p1 = g.out.point(i + 1);
    if ((p1 - p0).head<2>().norm() > 0.5) continue;  // from one line to the next
    EXPECT_LE(deepest_drop_along(mesh, g.ball, p0, p1), 2e-6) << p0.transpose();
    ++compared;
  }
  EXPECT_GT(compared, 100);
}

TEST(ChordGuard, ItsChecksGiveTheVerifiersReportAndStaleOnesAreNotUsed) {
  const TriangleMesh mesh = test::random_height_field(30, 40, 5, 9);
  const MeshVerifier verifier(mesh);
  GuardedRaster g(verifier);
  std::size_t known = 0;
  for (std::uint8_t k : g.checks.known) known += k;
  EXPECT_GT(known, g.checks.known.size() / 2);
  EXPECT_LT(known, g.checks.known.size());  // the lift-overs' moves are the verifier's
  auto same = [](const MeshVerifyReport& x, const MeshVerifyReport& y) {
    EXPECT_EQ(x.moves, y.moves);
    EXPECT_EQ(x.gouging_moves, y.gouging_moves);
    EXPECT_EQ(x.max_gouge, y.max_gouge);
    EXPECT_EQ(x.rapid_moves, y.rapid_moves);
    EXPECT_EQ(x.min_rapid_clearance, y.min_rapid_clearance);
    ASSERT_EQ(x.worst.size(), y.worst.size());
    for (std::size_t i = 0; i < x.worst.size(); ++i) {
      EXPECT_EQ(x.worst[i].move, y.worst[i].move);
      EXPECT_EQ(x.worst[i].amount, y.worst[i].amount);
    }
  };
  const MeshVerifyParams params;
  same(verify_moves(verifier, g.ball, g.out, params, 0, 0, &g.checks),
       verify_moves(verifier, g.ball, g.out, params));
  // A point lowered by 0.05 mm after the guard: its two moves' checks no longer describe
  // them, and the verifier finds the gouge.
  ClChunk planted = g.out;
  const std::size_t i = planted.path_sizes[0] / 2;
  planted.xyz[3 * i + 2] -= 0.05;
  const MeshVerifyReport bad = verify_moves(verifier, g.ball, planted, params, 0, 0, &g.checks);
  EXPECT_GE(bad.gouging_moves, 1u);
  EXPECT_GT(bad.max_gouge, 0.04);
  same(bad, verify_moves(verifier, g.ball, planted, params));
  // Checks of another chunk (another count) are not used at all.
  PrecheckedMoves shorter = g.checks;
  shorter.known.pop_back();
  same(verify_moves(verifier, g.ball, planted, params, 0, 0, &shorter),
       verify_moves(verifier, g.ball, planted, params));
}

}  // namespace
}  // namespace ncpath
