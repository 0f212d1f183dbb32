#pragma once
// STL writers: the mesh as facets with their unit normals (zero for degenerate facets), in
// the mesh's own units. Throw std::runtime_error naming the path when the file cannot be
// written, or when the mesh cannot be written (a facet index out of range, more than 2^32-1
// facets for binary STL).
#include <filesystem>
#include <string_view>

#include "kernels/mesh/triangle_mesh.hpp"

namespace ncpath::io {

// Binary STL: the 80-byte header holds `header` (cut at 80 bytes, zero-padded), then the
// facet count and per facet the normal and three vertices as little-endian float32.
void write_binary_stl(const std::filesystem::path& path, const TriangleMesh& mesh,
                      std::string_view header = "ncpath");

// ASCII STL, "solid <name>" ... "endsolid <name>"; coordinates in shortest round-trip
// decimal form, so reading the file back gives the same doubles.
void write_ascii_stl(const std::filesystem::path& path, const TriangleMesh& mesh,
                     std::string_view solid_name = "ncpath");

}  // namespace ncpath::io
