// Throughput runner for curve-based drive-plane scanning (engine/scan.hpp) on real meshes:
// time, planes/s, exact segments/s and peak RSS, against the raster drop-cutter measured in
// the same run at the equivalent accuracy: the sample step the raster needs so that its
// straight moves stay within the scan's tolerance of the CL curve (adaptive sampling to the
// same tolerance, with the scan's point count as a reference). Then z-level contouring at a
// step-down (engine/zlevel.hpp): levels, contours, time.
//
//   ncpath_scan_throughput [--mesh PATH --fit-xy MM] [--tool ball:5] [--interval 0.5,0.1]
//                          [--families x|y|both] [--tolerance 0.001] [--threads 2]
//                          [--no-raster] [--step-down 0.5]
//
// Without --mesh: bunny00 from datasets/cache/meshes, fit to 200 mm.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>

#include "batch/io/mesh_reader.hpp"
#include "batch/cli/huge_pages.hpp"
#include "batch/jobs/job_spec.hpp"
#include "engine/parallel.hpp"
#include "engine/raster.hpp"
#include "engine/scan.hpp"
#include "engine/zlevel.hpp"
#include "kernels/mesh/mesh_transform.hpp"

using namespace ncpath;

int main(int argc, char** argv) {
  ncpath::cli::reexec_with_huge_pages(argv);  // as the ncpath command does
  CLI::App app{"ncpath scan throughput"};
  std::string mesh_path, tool_text = "ball:5", families = "both";
  double fit_xy = 200, tolerance = 0.001;
  std::vector<double> intervals = {0.5, 0.1};
  int threads = 2;
  bool no_raster = false;
  double step_down = 0.5;
  app.add_option("--mesh", mesh_path, "Mesh (default: bunny00 from datasets/cache/meshes)");
  app.add_option("--fit-xy", fit_xy, "Fit the longest xy side to this many mm (0 = no)");
  app.add_option("--tool", tool_text);
  app.add_option("--interval", intervals)->delimiter(',');
  app.add_option("--families", families)->check(CLI::IsMember({"x", "y", "both"}));
  app.add_option("--tolerance", tolerance);
  app.add_option("--threads", threads);
  app.add_flag("--no-raster", no_raster, "Skip the raster comparison");
  app.add_option("--step-down", step_down, "Z-level step-down, mm (0 = no z-level run)");
  CLI11_PARSE(app, argc, argv);
  if (mesh_path.empty())
    mesh_path = std::string(NCPATH_SOURCE_DIR) + "/datasets/cache/meshes/bunny00.off";
  Cutter tool;
  if (std::string e = jobs::parse_tool(tool_text, tool); !e.empty()) {
    std::fprintf(stderr, "%s\n", e.c_str());
    return 2;
  }
  io::MeshReadResult in = io::read_mesh(mesh_path);
  MeshTransform tr;
  if (fit_xy > 0) tr.fit_xy_mm = fit_xy;
  apply_transform(tr, in.mesh);
  const Aabb3 box = bounding_box(in.mesh);
  par::ThreadLimit limit(threads);
  std::printf("mesh %s: %zu facets, xy %.1f x %.1f mm, tool %s, families %s, tolerance %g mm, "
              "%d threads\n",
              std::filesystem::path(mesh_path).filename().c_str(), in.mesh.facets.size(),
              box.hi.x() - box.lo.x(), box.hi.y() - box.lo.y(), tool_text.c_str(),
              families.c_str(), tolerance, threads);
  std::printf("%-9s %-8s %8s %10s %10s %12s %12s %10s %10s %9s\n", "interval", "method", "planes",
              "segments", "points", "elements s", "compute s", "planes/s", "segments/s",
              "RSS MB");
  for (double interval : intervals) {
    ScanParams p;
    p.interval = interval;
    p.tolerance = tolerance;
    p.families = families == "x" ? ScanFamilies::kX
                 : families == "y" ? ScanFamilies::kY
                                   : ScanFamilies::kBoth;
    RunControl control;
    const ScanStats st = run_scan(in.mesh, tool, p, [](const ScanChunk&) {}, control);
    std::printf("%-9g %-8s %8llu %10llu %10llu %12.3f %12.3f %10.1f %10.0f %9.1f\n", interval,
                "scan", (unsigned long long)st.planes, (unsigned long long)st.segments,
                (unsigned long long)(st.cut_points + st.link_points), st.elements_s, st.compute_s,
                st.planes / st.compute_s, st.segments / st.compute_s,
                peak_rss_bytes() / 1048576.0);
    std::printf("          junctions %llu (sharp concave %llu, tangent %llu, convex %llu), "
                "pieces/plane %.0f (linear %.0f, hidden curved %.0f), decisions/plane %.0f\n",
                (unsigned long long)st.junctions, (unsigned long long)st.sharp_concave,
                (unsigned long long)st.tangent, (unsigned long long)st.convex,
                double(st.pieces) / st.planes, double(st.linear_pieces) / st.planes,
                double(st.hidden) / st.planes, double(st.decisions) / st.planes);
    if (no_raster) continue;
    // Raster at the same accuracy: adaptive sampling to the same tolerance, both families.
    double seconds = 0;
    std::uint64_t points = 0, planes = 0;
    for (ScanDirection d : {ScanDirection::kX, ScanDirection::kY}) {
      if ((d == ScanDirection::kX && p.families == ScanFamilies::kY) ||
          (d == ScanDirection::kY && p.families == ScanFamilies::kX))
        continue;
      RasterParams rp;
      rp.direction = d;
      rp.interval = interval;
      rp.step = 0.1;
      rp.adaptive_tolerance = tolerance;
      const RasterStats rs = run_raster(in.mesh, tool, rp, [](const ClChunk&) {}, control);
      seconds += rs.compute_s + rs.index_s;
      points += rs.cut_points + rs.link_points;
      planes += rs.lines;
    }
    std::printf("%-9g %-8s %8llu %10s %10llu %12s %12.3f %10.1f %10s %9.1f   scan/raster time "
                "%.2f\n",
                interval, "raster", (unsigned long long)planes, "-", (unsigned long long)points,
                "-", seconds, planes / seconds, "-", peak_rss_bytes() / 1048576.0,
                (st.compute_s + st.elements_s) / seconds);
  }
  if (step_down > 0) {
    ZLevelOpParams zp;
    zp.step_down = step_down;
    zp.tolerance = tolerance;
    RunControl control;
    const ZLevelOpStats zs = run_zlevel(in.mesh, tool, zp, [](const ZLevelChunk&) {}, control);
    std::printf("z-level step-down %g: %llu levels, %llu contours (%llu holes), %llu segments, "
                "%llu junctions (sharp concave %llu), %llu points, open chains %llu\n"
                "          elements %.3f s, compute %.3f s, %.1f levels/s, %.0f candidates/level, "
                "RSS %.1f MB\n",
                step_down, (unsigned long long)zs.levels, (unsigned long long)zs.contours,
                (unsigned long long)zs.holes, (unsigned long long)zs.segments,
                (unsigned long long)zs.junctions, (unsigned long long)zs.sharp_concave,
                (unsigned long long)zs.points, (unsigned long long)zs.open_chains, zs.elements_s,
                zs.compute_s, zs.levels / zs.compute_s, double(zs.candidates) / zs.levels,
                peak_rss_bytes() / 1048576.0);
  }
  return 0;
}
