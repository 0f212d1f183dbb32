// The soak command of the exact curve kernels (issue 34): the checks of
// tests/engine/robustness_test.cpp over many more seeds, or over any meshes.
//
//   ncpath_corpus_soak [--seeds 2000] [--first 0] [--kind cad|relief|both]
//                      [--mesh PATH ...] [--fit-xy 100] [--step-down 3] [--threads 2]
//                      [--verbose]
//
// Generated parts (tests/support/random_parts.hpp): per seed a ball of 1, 3 or 6 mm and one
// representation (tests/support/representation_variants.hpp) picked from the seed; scan,
// z-levels and pencil on the representation and, for z-levels and pencil, on the
// full-precision part. Meshes (--mesh): fit to --fit-xy, balls of 1, 3 and 6 mm, no variant,
// z-levels every --step-down mm (the CI test's 3 mm by default).
// A line per failed check; at the end the counts per kind of check (raster, scan, z-level,
// z-level areas, pencil, pencil invariance). Exit code 1 if anything failed.
#include <CLI/CLI.hpp>

#include <array>
#include <cmath>
#include <map>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "batch/io/mesh_reader.hpp"
#include "engine/parallel.hpp"
#include "kernels/mesh/mesh_transform.hpp"
#include "tests/support/random_parts.hpp"
#include "tests/support/representation_variants.hpp"
#include "tests/support/robustness.hpp"

using namespace ncpath;

namespace {

constexpr double kScanInterval = 2, kStepDown = 1.5, kPencilInterval = 0.5, kPencilStep = 1;

// Checks run and failed per kind of check ("scan", "z-level areas", "pencil invariance", ...).
struct Tally {
  std::map<std::string, std::array<long, 2>> by;
  void check(const std::string& kind, bool ok, const std::string& what) {
    auto& n = by[kind];
    ++n[0];
    if (ok) return;
    ++n[1];
    std::printf("FAIL %s\n", what.c_str());
    std::fflush(stdout);
  }
  long failed() const {
    long f = 0;
    for (const auto& [k, n] : by) f += n[1];
    return f;
  }
};

void clean(Tally& t, const char* kind, const test::KernelRun& r, const std::string& what) {
  char buf[256];
  std::snprintf(buf, sizeof buf, " (error '%s', gouge %g, open %llu, scan dev %g, area dev %g > %g)",
                r.error.c_str(), r.max_gouge, static_cast<unsigned long long>(r.open_chains),
                r.scan_deviation, r.area_deviation, r.area_resolution);
  t.check(kind, r.ok() && r.scan_deviation <= 1e-6 && r.area_deviation <= r.area_resolution,
          what + buf);
}

void same(Tally& t, const test::KernelRun& full, const test::KernelRun& v, const std::string& what) {
  bool ok = full.level_area.size() == v.level_area.size();
  if (ok) {
    auto a = full.level_area.rbegin();
    for (auto b = v.level_area.rbegin(); b != v.level_area.rend(); ++a, ++b)
      ok = ok && std::abs(b->second - a->second) <= 1e-3 * std::max(std::abs(a->second), 1.0);
  }
  t.check("z-level areas", ok, what + " z-level areas differ from the full-precision part's");
}

void same_pencil(Tally& t, const test::KernelRun& full, const test::KernelRun& v,
                 const std::string& what) {
  const double dp = std::abs(double(v.paths) - double(full.paths));
  char buf[160];
  std::snprintf(buf, sizeof buf, " pencil: %llu paths %.4g mm against %llu paths %.4g mm",
                static_cast<unsigned long long>(v.paths), v.length,
                static_cast<unsigned long long>(full.paths), full.length);
  t.check("pencil invariance", std::abs(v.length - full.length) <= 0.01 * full.length + 1e-9 &&
              dp <= std::max(1.0, 0.1 * double(full.paths)),
          what + buf);
}

void soak_seed(Tally& t, bool cad, std::uint64_t seed, bool verbose) {
  static const std::vector<test::Variant> variants = test::more_representation_variants();
  const double radii[] = {0.5, 1.5, 3};
  const TriangleMesh part = cad ? test::random_cad_part(seed) : test::random_relief(seed);
  std::mt19937_64 pick(seed * 7919u + 1);
  const double R = radii[pick() % 3];
  const test::Variant& v = variants[pick() % variants.size()];
  TriangleMesh m = part;
  v.second(m);
  const std::string what = std::string(cad ? "cad" : "relief") + " seed " +
                           std::to_string(seed) + " R " + std::to_string(R) + " " + v.first;
  if (verbose) std::printf("%s\n", what.c_str());
  clean(t, "raster", test::run_raster_checked(m, R, kScanInterval, 0.5), what + " raster");
  clean(t, "scan", test::run_scan_checked(m, R, kScanInterval), what + " scan");
  const test::KernelRun zf = test::run_zlevel_checked(part, R, kStepDown, seed % 4 == 0 ? 0.5 : 0);
  const test::KernelRun zv = test::run_zlevel_checked(m, R, kStepDown);
  clean(t, "z-level", zf, what + " z-level full");
  clean(t, "z-level", zv, what + " z-level");
  same(t, zf, zv, what);
  const test::KernelRun pf = test::run_pencil_checked(part, R, kPencilInterval, kPencilStep);
  const test::KernelRun pv = test::run_pencil_checked(m, R, kPencilInterval, kPencilStep);
  clean(t, "pencil", pf, what + " pencil full");
  clean(t, "pencil", pv, what + " pencil");
  same_pencil(t, pf, pv, what);
}

void soak_mesh(Tally& t, const std::string& path, double fit, double step_down, bool verbose) {
  io::MeshReadResult r = io::read_mesh(path);
  MeshTransform tr;
  tr.fit_xy_mm = fit;
  apply_transform(tr, r.mesh);
  for (double R : {0.5, 1.5, 3.0}) {
    const std::string what = path + " R " + std::to_string(R);
    if (verbose) std::printf("%s\n", what.c_str());
    clean(t, "raster", test::run_raster_checked(r.mesh, R, 2 * kScanInterval, 0.5),
          what + " raster");
    clean(t, "scan", test::run_scan_checked(r.mesh, R, 2 * kScanInterval), what + " scan");
    clean(t, "z-level", test::run_zlevel_checked(r.mesh, R, step_down, 1.0),
          what + " z-level");
    clean(t, "pencil", test::run_pencil_checked(r.mesh, R, 2 * kPencilInterval, 2 * kPencilStep),
          what + " pencil");
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"ncpath exact-curve soak: generated parts in every representation, or meshes"};
  long seeds = 2000, first = 0;
  std::string kind = "both";
  std::vector<std::string> meshes;
  double fit = 100, step_down = 2 * kStepDown;
  int threads = 2;
  bool verbose = false;
  app.add_option("--seeds", seeds, "Generated parts per kind");
  app.add_option("--first", first, "First seed");
  app.add_option("--kind", kind, "cad, relief or both")->check(CLI::IsMember({"cad", "relief", "both"}));
  app.add_option("--mesh", meshes, "Meshes to check instead of generated parts");
  app.add_option("--fit-xy", fit, "Meshes: longest xy side, mm");
  app.add_option("--step-down", step_down, "Meshes: distance between z-levels, mm")
      ->check(CLI::PositiveNumber);
  app.add_option("--threads", threads);
  app.add_flag("--verbose", verbose, "Print each part before its checks");
  CLI11_PARSE(app, argc, argv);
  par::ThreadLimit limit(threads);
  Tally t;
  if (!meshes.empty()) {
    for (const std::string& m : meshes) soak_mesh(t, m, fit, step_down, verbose);
  } else {
    for (long s = first; s < first + seeds; ++s) {
      if (kind != "relief") soak_seed(t, true, std::uint64_t(s), verbose);
      if (kind != "cad") soak_seed(t, false, std::uint64_t(s), verbose);
    }
  }
  for (const auto& [kind, n] : t.by) std::printf("%-18s %6ld checks, %ld failed\n", kind.c_str(), n[0], n[1]);
  return t.failed() ? 1 : 0;
}
