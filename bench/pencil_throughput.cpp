// Pencil-cut throughput (engine/pencil.hpp), the seed's Table 1 on real meshes: for each
// mesh (fit to 200 mm in xy), cutter ball 5 mm, at each drive-plane interval: facets, time
// per stage (elements, scan, z-levels, linking, refinement, drop-cutter check), pencil
// points, paths, traced length and peak RSS.
//
//   ncpath_pencil_throughput [--mesh PATH ...] [--interval 0.5,0.1] [--step-down 1]
//                            [--threads 2] [--min-angle 20] [--tolerance 0.01]
//                            [--zone-share 0.25]
//
// --zone-share 0,1 runs each case with the z-levels slicing the whole part and the concave
// zone (PencilParams::zone_max_share): a baseline measured in the same run.
//
// Without --mesh: anchor_dense, fandisk, lion-head, refined_elephant (datasets/cache/meshes)
// and anchor_large.stl (486,272 facets, the >= 454k model) and elephant_large.stl when present
// (datasets/make-large-mesh.sh).
#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>

#include "batch/io/mesh_reader.hpp"
#include "batch/cli/huge_pages.hpp"
#include "engine/parallel.hpp"
#include "engine/pencil.hpp"
#include "kernels/mesh/mesh_transform.hpp"

using namespace ncpath;

int main(int argc, char** argv) {
  ncpath::cli::reexec_with_huge_pages(argv);  // as the ncpath command does
  CLI::App app{"ncpath pencil-cut throughput"};
  std::vector<std::string> meshes;
  std::vector<double> intervals = {0.5, 0.1};
  double step_down = 1.0, min_angle = 20, tolerance = 0.01, fit_xy = 200;
  int threads = 2;
  std::vector<double> zone_shares = {PencilParams{}.zone_max_share};
  app.add_option("--mesh", meshes, "Meshes (default: the Table 1 set)");
  app.add_option("--zone-share", zone_shares,
                 "Largest share of facets for which the z-levels slice the concave zone")
      ->delimiter(',');
  app.add_option("--interval", intervals)->delimiter(',');
  app.add_option("--step-down", step_down, "Z-level step for near-vertical creases (0 = none)");
  app.add_option("--min-angle", min_angle, "Bi-contact angle threshold, degrees");
  app.add_option("--tolerance", tolerance);
  app.add_option("--fit-xy", fit_xy);
  app.add_option("--threads", threads);
  CLI11_PARSE(app, argc, argv);
  const std::filesystem::path dir = std::filesystem::path(NCPATH_SOURCE_DIR) / "datasets/cache/meshes";
  if (meshes.empty()) {
    for (const char* m : {"anchor_dense.off", "fandisk.off", "lion-head.off", "refined_elephant.off",
                          "anchor_large.stl", "elephant_large.stl"})
      if (std::filesystem::exists(dir / m)) meshes.push_back((dir / m).string());
  }
  par::ThreadLimit limit(threads);
  std::printf("ball 5 mm, fit %g mm, step-down %g mm, min angle %g deg, tolerance %g mm, %d threads\n",
              fit_xy, step_down, min_angle, tolerance, threads);
  std::printf("%-22s %9s %8s %8s %8s %8s %8s %8s %8s %8s %8s %8s %7s %6s %9s %8s\n", "mesh",
              "facets", "interval", "total s", "elem s", "scan s", "zlev s", "link s", "index s",
              "refine s", "check s", "pencil", "kept", "paths", "length mm", "RSS MB");
  std::printf("%-22s refined / lifted points follow each row\n", "");
  for (const std::string& path : meshes) {
    io::MeshReadResult in = io::read_mesh(path);
    MeshTransform tr;
    tr.fit_xy_mm = fit_xy;
    apply_transform(tr, in.mesh);
    for (double interval : intervals) {
      for (double share : zone_shares) {
        PencilParams p;
        p.zone_max_share = share;
        p.interval = interval;
        p.step_down = step_down;
        p.min_angle_deg = min_angle;
        p.tolerance = tolerance;
        RunControl control;
        Stopwatch clock;
        const PencilResult r = run_pencil(in.mesh, ball_cutter(5), p, control);
        const double total = clock.seconds();
        const PencilStats& s = r.stats;
        std::printf(
            "%-22s %9zu %8g %8.2f %8.2f %8.2f %8.2f %8.2f %8.2f %8.2f %8.2f %8llu %7llu %6llu %9.1f "
            "%8.1f\n",
            std::filesystem::path(path).filename().c_str(), in.mesh.facets.size(), interval, total,
            s.elements_s, s.scan_s, s.zlevel_s, s.link_s, s.index_s, s.refine_s, s.check_s,
            (unsigned long long)s.pencil_points, (unsigned long long)s.kept_points,
            (unsigned long long)s.paths, s.traced_length, peak_rss_bytes() / 1048576.0);
        std::printf("%-22s refined %llu, lifted %llu, candidates %llu, chains %llu; zone share %g: "
                    "z-levels sliced %llu facets, zone %.2f s\n", "",
                    (unsigned long long)s.refined_points, (unsigned long long)s.lifted_points,
                    (unsigned long long)s.candidates, (unsigned long long)s.chains, share,
                    (unsigned long long)s.sliced_facets, s.zone_s);
        std::fflush(stdout);
      }
    }
  }
  return 0;
}
