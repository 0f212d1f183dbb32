#include "batch/io/stl_writer.hpp"

#include <algorithm>
#include <bit>
#include <cerrno>
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

#include "kernels/mesh/mesh_transform.hpp"

namespace ncpath::io {
namespace {

static_assert(std::endian::native == std::endian::little,
              "the binary STL writer assumes a little-endian host");

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& problem) {
  throw std::runtime_error(path.string() + ": " + problem);
}

void check_indices(const std::filesystem::path& path, const TriangleMesh& mesh) {
  const std::size_t n = mesh.vertices.size();
  for (std::size_t f = 0; f < mesh.facets.size(); ++f)
    for (std::uint32_t v : mesh.facets[f])
      if (v >= n)
        fail(path, "cannot write facet " + std::to_string(f + 1) + ": vertex index " +
                       std::to_string(v) + " is out of range (" + std::to_string(n) + " vertices)");
}

// Writes the whole buffer and closes the file, reporting errno on failure.
void write_file(const std::filesystem::path& path, const std::string& bytes) {
  errno = 0;
  std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "wb"));
  if (!file) fail(path, std::string("cannot open for writing: ") + std::strerror(errno));
  if (std::fwrite(bytes.data(), 1, bytes.size(), file.get()) != bytes.size())
    fail(path, std::string("write failed: ") + std::strerror(errno));
  if (std::fclose(file.release()) != 0)
    fail(path, std::string("write failed on close: ") + std::strerror(errno));
}

void append_floats(std::string& out, const Vec3& v) {
  const float f[3] = {static_cast<float>(v.x()), static_cast<float>(v.y()),
                      static_cast<float>(v.z())};
  out.append(reinterpret_cast<const char*>(f), sizeof f);
}

void append_number(std::string& out, double x) {
  char buf[32];
  const auto res = std::to_chars(buf, buf + sizeof buf, x);
  out.append(buf, res.ptr);
}

void append_vec(std::string& out, const Vec3& v) {
  for (int a = 0; a < 3; ++a) {
    out += ' ';
    append_number(out, v[a]);
  }
  out += '\n';
}

}  // namespace

void write_binary_stl(const std::filesystem::path& path, const TriangleMesh& mesh,
                      std::string_view header) {
  check_indices(path, mesh);
  if (mesh.facets.size() > std::numeric_limits<std::uint32_t>::max())
    fail(path, "cannot write " + std::to_string(mesh.facets.size()) +
                   " facets: binary STL holds at most 4294967295");
  std::string out(80, '\0');
  out.replace(0, std::min<std::size_t>(header.size(), 80), header.substr(0, 80));
  const auto count = static_cast<std::uint32_t>(mesh.facets.size());
  out.append(reinterpret_cast<const char*>(&count), 4);
  out.reserve(84 + 50 * std::size_t{count});
  for (const auto& f : mesh.facets) {
    const Vec3& a = mesh.vertices[f[0]];
    const Vec3& b = mesh.vertices[f[1]];
    const Vec3& c = mesh.vertices[f[2]];
    append_floats(out, facet_unit_normal(a, b, c));
    append_floats(out, a);
    append_floats(out, b);
    append_floats(out, c);
    out.append(2, '\0');  // attribute byte count
  }
  write_file(path, out);
}

void write_ascii_stl(const std::filesystem::path& path, const TriangleMesh& mesh,
                     std::string_view solid_name) {
  check_indices(path, mesh);
  std::string out;
  out.reserve(64 + 200 * mesh.facets.size());
  out.append("solid ").append(solid_name).append("\n");
  for (const auto& f : mesh.facets) {
    const Vec3& a = mesh.vertices[f[0]];
    const Vec3& b = mesh.vertices[f[1]];
    const Vec3& c = mesh.vertices[f[2]];
    out += "  facet normal";
    append_vec(out, facet_unit_normal(a, b, c));
    out += "    outer loop\n";
    for (const Vec3* v : {&a, &b, &c}) {
      out += "      vertex";
      append_vec(out, *v);
    }
    out += "    endloop\n  endfacet\n";
  }
  out.append("endsolid ").append(solid_name).append("\n");
  write_file(path, out);
}

}  // namespace ncpath::io
