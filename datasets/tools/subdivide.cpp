// ncpath_subdivide IN OUT.stl --min-facets N [--scheme midpoint|loop]
//
// Makes a large benchmark mesh out of a real one: reads IN (OFF or STL, via ncpath_io),
// subdivides it (every triangle -> 4) until the mesh has at least N facets, and writes a
// binary STL. midpoint (the default): shared edge midpoints, the surface does not move
// (CAD-like: coplanar facets stay coplanar). loop: Loop's scheme, every vertex moves (a
// dense scan-like mesh, no coplanar facets; kernels/mesh/subdivide.hpp). Used by
// datasets/make-large-mesh.sh. Prints one line per step on stdout; errors on stderr with
// exit code 1 (2 for bad usage).
//
// Note: an STL input is a triangle soup (the reader does not weld), so its facets share no
// vertices and each one gets its own midpoints; Loop's scheme then sees every edge as a
// border. Give it an OFF (welded) mesh.
#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>
#include <utility>

#include "batch/io/mesh_reader.hpp"
#include "batch/io/stl_writer.hpp"
#include "kernels/mesh/subdivide.hpp"
#include "kernels/mesh/triangle_mesh.hpp"

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void print_box(const char* what, const ncpath::TriangleMesh& mesh) {
  const ncpath::Aabb3 box = ncpath::bounding_box(mesh);
  if (box.empty()) {
    std::printf("%s: empty\n", what);
    return;
  }
  std::printf("%s: [%.6g, %.6g] x [%.6g, %.6g] x [%.6g, %.6g]\n", what, box.lo.x(), box.hi.x(),
              box.lo.y(), box.hi.y(), box.lo.z(), box.hi.z());
}

int run(const std::filesystem::path& in, const std::filesystem::path& out,
        std::uint64_t min_facets, const std::string& scheme) {
  auto t0 = std::chrono::steady_clock::now();
  ncpath::io::MeshReadResult read = ncpath::io::read_mesh(in);
  ncpath::TriangleMesh mesh = std::move(read.mesh);
  std::printf(
      "read %s (%s): %zu vertices, %zu facets (%llu in file, %llu degenerate "
      "skipped) in %.3f s\n",
      in.string().c_str(), read.stats.format.c_str(), mesh.vertices.size(), mesh.facets.size(),
      static_cast<unsigned long long>(read.stats.facets_in_file),
      static_cast<unsigned long long>(read.stats.facets_degenerate), seconds_since(t0));
  print_box("bounding box", mesh);
  if (mesh.facets.empty()) {
    std::fprintf(stderr, "ncpath_subdivide: %s has no facets to subdivide\n", in.string().c_str());
    return 1;
  }

  int rounds = 0;
  while (mesh.facets.size() < min_facets) {
    if (!ncpath::subdivide_midpoint_fits(mesh.vertices.size(), mesh.facets.size())) {
      std::fprintf(stderr,
                   "ncpath_subdivide: another round on %zu facets would overflow 32-bit "
                   "indices (--min-facets %llu is too large)\n",
                   mesh.facets.size(), static_cast<unsigned long long>(min_facets));
      return 1;
    }
    t0 = std::chrono::steady_clock::now();
    mesh = scheme == "loop" ? ncpath::subdivide_loop(mesh) : ncpath::subdivide_midpoint(mesh);
    ++rounds;
    std::printf("round %d: %zu vertices, %zu facets in %.3f s\n", rounds, mesh.vertices.size(),
                mesh.facets.size(), seconds_since(t0));
  }

  // 80-byte STL header: say where the mesh came from and how it was made.
  const std::string header = "ncpath_subdivide " + in.filename().string() + " x" +
                             std::to_string(1ull << (2 * rounds)) + " " + scheme;
  t0 = std::chrono::steady_clock::now();
  ncpath::io::write_binary_stl(out, mesh, header.substr(0, 80));
  std::printf("wrote %s: %zu facets, %ju bytes in %.3f s\n", out.string().c_str(),
              mesh.facets.size(), static_cast<std::uintmax_t>(std::filesystem::file_size(out)),
              seconds_since(t0));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Subdivide a mesh until it has at least N facets; write binary STL."};
  std::filesystem::path in, out;
  std::uint64_t min_facets = 0;
  std::string scheme = "midpoint";
  app.add_option("input", in, "Input mesh (.off or .stl)")->required()->check(CLI::ExistingFile);
  app.add_option("output", out, "Output binary STL")->required();
  app.add_option("--min-facets", min_facets, "Subdivide until at least this many facets")
      ->required();
  app.add_option("--scheme", scheme,
                 "midpoint: the surface stays put (CAD-like); loop: Loop's smoothing, every "
                 "vertex moves (scan-like, no coplanar facets)")
      ->check(CLI::IsMember({"midpoint", "loop"}));
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  try {
    return run(in, out, min_facets, scheme);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ncpath_subdivide: %s\n", e.what());
    return 1;
  }
}
