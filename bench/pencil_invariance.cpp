// Representation invariance of the pencil-cut (issue 17, item 1), measured: one part written
// the ways exporters write it must give the same answer. For each mesh (fit to 200 mm in xy,
// ball 5 mm), the same pencil job on variants of its vertices, all in mm after the fit:
//   full      the coordinates as read (double)
//   float32   each coordinate rounded to float (binary STL)
//   digits N  each coordinate rounded to N significant decimal digits (ASCII STL / OFF)
//   noise E   each coordinate moved by a uniform amount in [-E, E] (seeded, mt19937_64 bits)
//   turn A    turned about z by A degrees around the box centre
//   far       translated by (1000, 1000, 0) mm
//   reversed  every facet's winding reversed
// and prints paths, traced length, open z-level chains, the ratios to `full` and the largest
// vertex move of the input conditioning: the bar is 0 open chains, length within 1 %,
// paths within 10 %.
//
//   ncpath_pencil_invariance [--mesh PATH ...] [--interval 0.5] [--step-down 1] [--threads 2]
//
// Without --mesh: fandisk and anchor_dense (datasets/cache/meshes).
#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <numbers>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "batch/io/mesh_reader.hpp"
#include "engine/parallel.hpp"
#include "engine/pencil.hpp"
#include "kernels/mesh/mesh_transform.hpp"

using namespace ncpath;

namespace {

using Variant = std::pair<std::string, std::function<void(TriangleMesh&)>>;

void each_coordinate(TriangleMesh& m, const std::function<double(double)>& f) {
  for (Vec3& v : m.vertices)
    for (int k = 0; k < 3; ++k) v[k] = f(v[k]);
}

double round_digits(double x, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, x);
  return std::strtod(buf, nullptr);
}

std::vector<Variant> variants() {
  std::vector<Variant> out;
  out.push_back({"full", [](TriangleMesh&) {}});
  out.push_back({"float32", [](TriangleMesh& m) {
                   each_coordinate(m, [](double x) { return double(static_cast<float>(x)); });
                 }});
  for (int digits : {6, 9, 12, 15, 17})
    out.push_back({"digits " + std::to_string(digits), [digits](TriangleMesh& m) {
                     each_coordinate(m, [digits](double x) { return round_digits(x, digits); });
                   }});
  for (double e : {1e-13, 1e-11, 1e-9, 1e-7}) {
    char name[32];
    std::snprintf(name, sizeof name, "noise %.0e", e);
    out.push_back({name, [e](TriangleMesh& m) {
                     std::mt19937_64 bits(17);
                     each_coordinate(m, [&](double x) {
                       const double u = static_cast<double>(bits() >> 11) * 0x1.0p-53;  // [0, 1)
                       return x + e * (2 * u - 1);
                     });
                   }});
  }
  out.push_back({"turn 37", [](TriangleMesh& m) {
                   const Aabb3 box = bounding_box(m);
                   const Vec3 c = 0.5 * (box.lo + box.hi);
                   const double a = 37 * std::numbers::pi / 180, ca = std::cos(a), sa = std::sin(a);
                   for (Vec3& v : m.vertices) {
                     const double x = v.x() - c.x(), y = v.y() - c.y();
                     v.x() = c.x() + ca * x - sa * y;
                     v.y() = c.y() + sa * x + ca * y;
                   }
                 }});
  out.push_back({"far", [](TriangleMesh& m) {
                   for (Vec3& v : m.vertices) v += Vec3(1000, 1000, 0);
                 }});
  out.push_back({"reversed", [](TriangleMesh& m) {
                   for (auto& f : m.facets) std::swap(f[1], f[2]);
                 }});
  return out;
}

}  // namespace

int main(int argc, char** argv) {
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
  std::printf("%-18s %-12s %6s %10s %12s %9s %9s %9s %7s\n", "mesh", "variant", "paths",
              "length mm", "open chains", "paths/full", "len/full", "moved mm", "s");
  for (const std::string& path : meshes) {
    io::MeshReadResult in = io::read_mesh(path);
    MeshTransform tr;
    tr.fit_xy_mm = fit_xy;
    apply_transform(tr, in.mesh);
    double full_paths = 0, full_length = 0;
    for (const auto& [name, change] : variants()) {
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
      std::printf("%-18s %-12s %6llu %10.1f %12llu %9.3f %9.4f %9.1e %7.2f\n",
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
