// Throughput runner: exact raster drop-cutting on real meshes, CL points per second and
// peak RSS, against the Embree baseline (one exact ray query per point through DropIndex)
// measured in the same run on the same points.
//
//   ncpath_throughput [--mesh PATH --fit-xy MM] [--tool ball:5] [--interval 0.5]
//                     [--step 0.1] [--threads 1,2] [--baseline] [--write out.h5]
//
// Without --mesh it runs the documented cases (docs/performance.md): bunny00 fit to
// 200 mm, ball 5, interval 0.5 and 0.1, step 0.1, on 1 and 2 threads.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>

#include "batch/io/mesh_reader.hpp"
#include "batch/cli/huge_pages.hpp"
#include "batch/jobs/job_spec.hpp"
#include "engine/drop_index.hpp"
#include "engine/parallel.hpp"
#include "engine/raster.hpp"
#include "kernels/mesh/mesh_transform.hpp"

using namespace ncpath;

namespace {

struct Result {
  std::uint64_t points = 0;
  double seconds = 0;
  double checksum = 0;
};

Result run_raster_case(const TriangleMesh& mesh, const Cutter& tool, const RasterParams& p) {
  Result r;
  RunControl control;
  const RasterStats st = run_raster(
      mesh, tool, p,
      [&](const ClChunk& c) {
        for (std::size_t k = 2; k < c.xyz.size(); k += 3) r.checksum += c.xyz[k];
      },
      control);
  r.points = st.cut_points + st.link_points;
  r.seconds = st.compute_s;
  return r;
}

// The same grid of points, each answered by one exact Embree query (user geometry, double
// kernel in the callback): the straightforward accelerated method.
Result run_embree_baseline(const TriangleMesh& mesh, const Cutter& tool, const RasterParams& p,
                           double floor_z, const Aabb3& box) {
  const DropIndex index(mesh, tool, DropIndex::Facets::kPrepared);
  const std::size_t lines = raster_sample_count(box.hi.y() - box.lo.y(), p.interval);
  const std::size_t samples = raster_sample_count(box.hi.x() - box.lo.x(), p.step);
  std::vector<double> line_sum(lines);
  Stopwatch clock;
  par::for_each(lines, 1, [&](std::size_t i) {
    const double y = box.lo.y() + static_cast<double>(i) * p.interval;
    double s = 0;
    for (std::size_t j = 0; j < samples; ++j) {
      const CutterContact c = index.query(box.lo.x() + static_cast<double>(j) * p.step, y);
      s += std::max(c.tip_z, floor_z);
    }
    line_sum[i] = s;
  });
  Result r;
  r.seconds = clock.seconds();
  r.points = lines * samples;
  for (double s : line_sum) r.checksum += s;
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  ncpath::cli::reexec_with_huge_pages(argv);  // as the ncpath command does
  CLI::App app{"ncpath raster throughput"};
  std::string mesh_path, tool_text = "ball:5";
  double fit_xy = 200;
  std::vector<double> intervals = {0.5, 0.1};
  double step = 0.1;
  std::vector<int> threads = {1, 2};
  bool baseline = false;
  double strip_height = 0, bin_width = 0;
  app.add_option("--mesh", mesh_path, "Mesh (default: bunny00 from datasets/cache/meshes)");
  app.add_option("--fit-xy", fit_xy, "Fit the longest xy side to this many mm (0 = no)");
  app.add_option("--tool", tool_text);
  app.add_option("--interval", intervals)->delimiter(',');
  app.add_option("--step", step);
  app.add_option("--threads", threads)->delimiter(',');
  app.add_flag("--baseline", baseline, "Also time the one-Embree-query-per-point baseline");
  app.add_option("--strip-height", strip_height, "Raster tuning (0 = automatic)");
  app.add_option("--bin-width", bin_width, "Raster tuning (0 = automatic)");
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
  std::printf("mesh %s: %zu facets, xy %.1f x %.1f mm, tool %s\n",
              std::filesystem::path(mesh_path).filename().c_str(), in.mesh.facets.size(),
              box.hi.x() - box.lo.x(), box.hi.y() - box.lo.y(), tool_text.c_str());
  std::printf("%-9s %-7s %12s %10s %14s %12s\n", "interval", "threads", "points", "seconds",
              "points/s", "peak RSS MB");
  for (double interval : intervals) {
    RasterParams p;
    p.interval = interval;
    p.step = step;
    p.strip_height = strip_height;
    p.bin_width = bin_width;
    double raster_rate_2 = 0, raster_checksum = 0;
    for (int t : threads) {
      par::ThreadLimit limit(t);
      const Result r = run_raster_case(in.mesh, tool, p);
      raster_checksum = r.checksum;
      const double rate = r.points / r.seconds;
      if (t == threads.back()) raster_rate_2 = rate;
      std::printf("%-9g %-7d %12llu %10.3f %14.0f %12.1f\n", interval, t,
                  static_cast<unsigned long long>(r.points), r.seconds, rate,
                  peak_rss_bytes() / 1048576.0);
    }
    if (baseline) {
      par::ThreadLimit limit(threads.back());
      const Result b = run_embree_baseline(in.mesh, tool, p, box.lo.z(), box);
      const double rate = b.points / b.seconds;
      std::printf(
          "%-9g %-7d %12llu %10.3f %14.0f   embree baseline (cut points only); "
          "raster is %.2fx\n",
          interval, threads.back(), static_cast<unsigned long long>(b.points), b.seconds, rate,
          raster_rate_2 / rate);
      (void)raster_checksum;
    }
  }
  return 0;
}
