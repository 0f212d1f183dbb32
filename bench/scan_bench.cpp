// Curve-based scanning kernels (issue 5) on real meshes (datasets/cache/meshes, fit to
// 200 mm, ball D = 5): one drive plane (slice the trimmed offset elements it reaches, upper
// envelope, CL curve) through the middle of bunny00 and fandisk, and one z-level contour at
// mid height (also knowing the region of the level above to lie inside), single-threaded.
// The plane benchmarks compare trimmed elements (the engine's choice) with whole cylinders
// and spheres: same curve, far more pieces.
// Counters: pieces, envelope decisions, segments / contours of the last iteration.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <map>
#include <string>

#include "batch/io/mesh_reader.hpp"
#include "engine/offset_elements_build.hpp"
#include "kernels/mesh/mesh_transform.hpp"
#include "kernels/scan/envelope.hpp"
#include "kernels/scan/zlevel.hpp"

namespace ncpath {
namespace {

struct Prepared {
  TriangleMesh mesh;
  OffsetElements el;
  PlaneIndex index;
  Aabb3 box;
};

const Prepared& prepared(const std::string& name) {
  static std::map<std::string, Prepared> cache;
  auto it = cache.find(name);
  if (it != cache.end()) return it->second;
  Prepared p;
  io::MeshReadResult r = io::read_mesh(std::filesystem::path(NCPATH_SOURCE_DIR) /
                                       "datasets/cache/meshes" / (name + ".off"));
  MeshTransform t;
  t.fit_xy_mm = 200;
  apply_transform(t, r.mesh);
  p.mesh = std::move(r.mesh);
  p.el = build_offset_elements_parallel(p.mesh, 2.5, false);
  p.index = build_plane_index(p.el);
  p.box = bounding_box(p.mesh);
  return cache.emplace(name, std::move(p)).first->second;
}

void BM_ScanPlane(benchmark::State& state, const std::string& name, bool trim) {
  const Prepared& p = prepared(name);
  const double y0 = 0.5 * (p.box.lo.y() + p.box.hi.y()) + 0.123;
  std::vector<std::uint32_t> ids;
  std::vector<SlicePiece> pieces;
  std::vector<EnvelopeSpan> spans;
  PlaneCurve curve;
  EnvelopeCounters cnt;
  for (auto _ : state) {
    ids.clear();
    pieces.clear();
    if (trim) {
      p.index.query(y0, ids);
      for (std::uint32_t id : ids) slice_elements(p.el, y0, id, id + 1, pieces, true);
    } else {
      for (std::uint32_t id = 0; id < p.el.element_count(); ++id)
        if (element_reachable(p.el, id)) slice_elements(p.el, y0, id, id + 1, pieces, false);
    }
    pieces.push_back(floor_piece(p.box.lo.z(), 2.5, y0, p.box.lo.x(), p.box.hi.x()));
    cnt = {};
    upper_envelope(pieces, spans, &cnt);
    plane_curve(pieces, spans, curve);
    benchmark::DoNotOptimize(curve.segments.data());
  }
  state.counters["pieces"] = double(pieces.size());
  state.counters["decisions"] = double(cnt.decisions);
  state.counters["segments"] = double(curve.segments.size());
}

// The facet and edge ids of p (the z-level candidates when all are given).
std::vector<std::uint32_t> facets_and_edges(const Prepared& p) {
  std::vector<std::uint32_t> all(p.el.facet_count() + p.el.edge_count());
  for (std::uint32_t i = 0; i < all.size(); ++i) all[i] = i;
  return all;
}

// Times the z-level kernel at tip z; the contours, regions and open chains as counters.
ZLevelResult time_level(benchmark::State& state, const Prepared& p,
                        const std::vector<std::uint32_t>& ids, double z,
                        const ZLevelParams& params) {
  ZLevelResult r;
  for (auto _ : state) {
    r = zlevel_contours(p.el, ids, z, params);
    benchmark::DoNotOptimize(r.contours.data());
  }
  state.counters["contours"] = double(r.contours.size());
  state.counters["regions"] = double(r.stats.regions);
  state.counters["open_chains"] = double(r.stats.open_chains);
  return r;
}

void BM_ZLevel(benchmark::State& state, const std::string& name) {
  const Prepared& p = prepared(name);
  const double z = 0.5 * (p.box.lo.z() + p.box.hi.z()) + 0.0123;
  const ZLevelResult r = time_level(state, p, facets_and_edges(p), z, {});
  state.counters["candidates"] = double(r.stats.candidates);
}

// The same level knowing the region of the level 1 mm above to lie inside (ZLevelInside, as
// the engine's chunks do): same contours, the regions deep inside it dropped.
void BM_ZLevelInside(benchmark::State& state, const std::string& name) {
  const Prepared& p = prepared(name);
  const std::vector<std::uint32_t> all = facets_and_edges(p);
  const double z = 0.5 * (p.box.lo.z() + p.box.hi.z()) + 0.0123;
  const ZLevelInside inside = zlevel_inside(zlevel_contours(p.el, all, z + 1), 0.5 * p.el.radius);
  ZLevelParams params;
  params.inside = &inside;
  const ZLevelResult r = time_level(state, p, all, z, params);
  state.counters["dropped"] = double(r.stats.inside_regions);
}

// A level in anchor_dense's lower part (tip z -70.341, under the overhang of its upper part)
// with the region of the level 4 mm above, as the engine's chunks have it.
void BM_ZLevelLow(benchmark::State& state) {
  const Prepared& p = prepared("anchor_dense");
  const std::vector<std::uint32_t> all = facets_and_edges(p);
  const double z = -70.341;
  const ZLevelElementBoxes boxes = zlevel_element_boxes(p.el);
  ZLevelParams params;
  params.boxes = &boxes;
  const ZLevelInside inside =
      zlevel_inside(zlevel_contours(p.el, all, z + 4, params), 0.5 * p.el.radius);
  params.inside = &inside;
  const ZLevelResult r = time_level(state, p, all, z, params);
  state.counters["dropped"] = double(r.stats.inside_regions);
}

BENCHMARK_CAPTURE(BM_ScanPlane, bunny00_trimmed, std::string("bunny00"), true)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ScanPlane, bunny00_whole, std::string("bunny00"), false)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ScanPlane, fandisk_trimmed, std::string("fandisk"), true)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ScanPlane, fandisk_whole, std::string("fandisk"), false)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ZLevel, bunny00_mid, std::string("bunny00"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ZLevel, fandisk_mid, std::string("fandisk"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ZLevel, anchor_dense_mid, std::string("anchor_dense"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ZLevelInside, bunny00_mid, std::string("bunny00"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ZLevelInside, anchor_dense_mid, std::string("anchor_dense"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ZLevelLow)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace ncpath
