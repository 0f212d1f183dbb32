// Representation invariance of the pencil-cut (issue 17, item 1), measured: one part written
// the ways exporters write it must give the same answer. For each mesh (fit to 200 mm in xy,
// ball 5 mm), the same pencil job on the full-precision vertices and on the variants the
// tests use (tests/support/representation_variants.hpp), and prints paths, traced length, open z-level chains, the ratios to `full` and the largest
// vertex move of the input conditioning: the bar is 0 open chains, length within 1 %,
// paths within 10 %.
//
//   ncpath_pencil_invariance [--mesh PATH ...] [--interval 0.5] [--step-down 1] [--threads 2]
//
// Without --mesh: fandisk and anchor_dense (datasets/cache/meshes).
#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "batch/io/mesh_reader.hpp"
#include "batch/cli/huge_pages.hpp"
#include "engine/parallel.hpp"
#include "engine/pencil.hpp"
#include "kernels/mesh/mesh_transform.hpp"
#include "tests/support/representation_variants.hpp"

using namespace ncpath;

int main(int argc, char** argv) {
  ncpath::cli::reexec_with_huge_pages(argv);  // as the ncpath command does
  CLI::App app{"ncpath pencil-cut representation invariance"};
  std::vector<std::string> meshes;
  double interval = 0.5, step_down = 1.0, fit_xy = 200;
  int threads = 2;
  app.add_option("--mesh", meshes, "Meshes (default: fandisk, anchor_dense)");
  app.add_option("--interval", interval);
  app.add_option("--step-down", step_down, "Z-level step for near-vertical creases (0 = none)");
  app.add_option("--fit-xy", fit_xy);
  app.add_option("--threads", threads);
  CLI11_PARSE(app, argc, argv);
  const std::filesystem::path dir =
      std::filesystem::path(NCPATH_SOURCE_DIR) / "datasets/cache/meshes";
  if (meshes.empty())
    for (const char* m : {"fandisk.off", "anchor_dense.off"})
      if (std::filesystem::exists(dir / m)) meshes.push_back((dir / m).string());
  par::ThreadLimit limit(threads);
  std::printf("ball 5 mm, fit %g mm, interval %g mm, step-down %g mm, %d threads\n", fit_xy,
              interval, step_down, threads);
  std::printf("%-18s %-19s %6s %10s %12s %9s %9s %9s %7s\n", "mesh", "variant", "paths",
              "length mm", "open chains", "paths/full", "len/full", "moved mm", "s");
  for (const std::string& path : meshes) {
    io::MeshReadResult in = io::read_mesh(path);
    MeshTransform tr;
    tr.fit_xy_mm = fit_xy;
    apply_transform(tr, in.mesh);
    double full_paths = 0, full_length = 0;
    std::vector<test::Variant> all = test::representation_variants();
    all.insert(all.begin(), {"full", [](TriangleMesh&) {}});
    for (const auto& [name, change] : all) {
      TriangleMesh m = in.mesh;
      change(m);
      PencilParams p;
      p.interval = interval;
      p.step_down = step_down;
      RunControl control;
      Stopwatch clock;
      const PencilResult r = run_pencil(m, ball_cutter(5), p, control);
      const PencilStats& s = r.stats;
      if (name == "full") {
        full_paths = static_cast<double>(s.paths);
        full_length = s.traced_length;
      }
      std::printf("%-18s %-19s %6llu %10.1f %12llu %9.3f %9.4f %9.1e %7.2f\n",
                  std::filesystem::path(path).filename().c_str(), name.c_str(),
                  (unsigned long long)s.paths, s.traced_length,
                  (unsigned long long)s.zlevel_open_chains, s.paths / std::max(1.0, full_paths),
                  s.traced_length / std::max(1e-300, full_length), s.condition.max_move,
                  clock.seconds());
      std::fflush(stdout);
    }
  }
  return 0;
}
