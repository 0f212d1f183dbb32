// Swept-tool checks of a raster's moves on real meshes (datasets/cache/meshes: bunny00, 75 k
// facets, and bunny00_loop.stl, Loop x2, 1.2 M, from datasets/make-large-mesh.sh --scans;
// fit to 200 mm, ball D = 5, lines 0.5 mm apart sampled every 0.1 mm over a 20 mm band
// through the middle), one thread:
// - VerifyMoves: the job verifier (engine/verify_mesh.hpp), consecutive moves grouped;
// - MovesOneByOne: the same moves checked one at a time (check_move: one grid walk each),
//   the baseline the grouping is measured against in the same run;
// - ChordGuard: the chord guard on the raw raster (decides each move, lifts the gouging).
// Counter: moves per second.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <map>
#include <string>

#include "batch/io/mesh_reader.hpp"
#include "engine/chord_guard.hpp"
#include "engine/parallel.hpp"
#include "engine/raster.hpp"
#include "engine/verify_mesh.hpp"
#include "kernels/mesh/mesh_transform.hpp"

namespace ncpath {
namespace {

struct Prepared {
  std::unique_ptr<MeshVerifier> verifier;
  ClChunk raster;
  std::size_t moves = 0;
};

const Cutter kBall = ball_cutter(5);

// The mesh's raster band and verifier; nullptr when the mesh file is missing.
const Prepared* prepared(const std::string& name) {
  static std::map<std::string, Prepared> cache;
  if (auto it = cache.find(name); it != cache.end()) return &it->second;
  const auto path = std::filesystem::path(NCPATH_SOURCE_DIR) / "datasets/cache/meshes" / name;
  if (!std::filesystem::exists(path)) return nullptr;
  Prepared q;
  io::MeshReadResult r = io::read_mesh(path);
  MeshTransform t;
  t.fit_xy_mm = 200;
  apply_transform(t, r.mesh);
  const Aabb3 box = bounding_box(r.mesh);
  const double ym = 0.5 * (box.lo.y() + box.hi.y());
  RasterParams rp;
  rp.rect = std::array<double, 4>{box.lo.x(), ym - 10, box.hi.x(), ym + 10};
  RunControl control;
  run_raster(r.mesh, kBall, rp, [&](const ClChunk& c) { q.raster.append(c); }, control);
  for (std::uint32_t n : q.raster.path_sizes) q.moves += n > 0 ? n - 1 : 0;
  q.verifier = std::make_unique<MeshVerifier>(r.mesh);
  return &cache.emplace(name, std::move(q)).first->second;
}

// The prepared mesh, or nullptr after marking the benchmark skipped.
const Prepared* need(benchmark::State& state, const std::string& name) {
  const Prepared* p = prepared(name);
  if (!p) state.SkipWithError((name + " is missing: datasets/make-large-mesh.sh --scans").c_str());
  return p;
}

void rate(benchmark::State& state, const Prepared& p) {
  state.counters["moves/s"] = benchmark::Counter(
      static_cast<double>(p.moves * state.iterations()), benchmark::Counter::kIsRate);
}

void BM_VerifyMoves(benchmark::State& state, const std::string& name) {
  const Prepared* pp = need(state, name);
  if (!pp) return;
  const Prepared& p = *pp;
  par::ThreadLimit one(1);
  for (auto _ : state) {
    const MeshVerifyReport r = verify_moves(*p.verifier, kBall, p.raster, MeshVerifyParams{});
    benchmark::DoNotOptimize(r.moves);
  }
  rate(state, p);
}

void BM_MovesOneByOne(benchmark::State& state, const std::string& name) {
  const Prepared* pp = need(state, name);
  if (!pp) return;
  const Prepared& p = *pp;
  const SweptTool tool{kBall, MeshVerifyParams{}.shank, 0};
  for (auto _ : state) {
    std::size_t first = 0;
    double worst = 0;
    for (std::uint32_t n : p.raster.path_sizes) {
      for (std::size_t i = first + 1; i < first + n; ++i)
        worst = std::max(worst, p.verifier->check_move(tool, p.raster.point(i - 1),
                                                       p.raster.point(i), tol::kVerifyGouge)
                                    .gouge);
      first += n;
    }
    benchmark::DoNotOptimize(worst);
  }
  rate(state, p);
}

void BM_ChordGuard(benchmark::State& state, const std::string& name) {
  const Prepared* pp = need(state, name);
  if (!pp) return;
  const Prepared& p = *pp;
  par::ThreadLimit one(1);
  const SweptTool tool{kBall, MeshVerifyParams{}.shank, 0};
  for (auto _ : state) {
    ChordGuardStats stats;
    const ClChunk out = guard_chords(*p.verifier, tool, p.raster, stats);
    benchmark::DoNotOptimize(out.xyz.data());
  }
  rate(state, p);
}

BENCHMARK_CAPTURE(BM_VerifyMoves, bunny00, std::string("bunny00.off"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_MovesOneByOne, bunny00, std::string("bunny00.off"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ChordGuard, bunny00, std::string("bunny00.off"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_VerifyMoves, loop2, std::string("bunny00_loop.stl"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_MovesOneByOne, loop2, std::string("bunny00_loop.stl"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ChordGuard, loop2, std::string("bunny00_loop.stl"))->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace ncpath
