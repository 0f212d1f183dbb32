#pragma once
// Mesh readers of the batch layer: STL (binary and ASCII) and OFF into a TriangleMesh, in
// the file's own units (the job's MeshTransform is applied afterwards).
//
// Every reader reads the whole file into memory and parses it there (a 1.4M-facet binary
// STL takes well under a second); ASCII STL and the body of an OFF file are parsed in 8 MiB
// pieces in parallel, with the same result and, on any error, the same message as one piece. Malformed input throws ReadError naming the file, the
// place (line, or byte offset and facet) and what is wrong. Degenerate facets (doubled area
// below tol::kDegenerateArea2) are skipped and counted, not fatal; a mesh left with no
// facets is an error.
#include <cstdint>
#include <filesystem>
#include <string>

#include "batch/io/read_error.hpp"
#include "kernels/mesh/triangle_mesh.hpp"

namespace ncpath::io {

struct MeshReadStats {
  std::string format;                       // "stl-binary", "stl-ascii" or "off"
  std::uint64_t facets_in_file = 0;         // STL facets / OFF faces (polygons) in the file
  std::uint64_t facets_read = 0;            // triangles in the mesh (== mesh.facets.size())
  std::uint64_t facets_degenerate = 0;      // skipped: zero-area triangles, or OFF polygons
                                            // with no area (each counts once)
  std::uint64_t polygons_triangulated = 0;  // OFF faces of more than 3 vertices, fanned
};

struct MeshReadResult {
  // STL: a triangle soup, 3 vertices per facet in file order (no welding). OFF: the file's
  // vertices (all of them) and its faces, polygons fan-triangulated.
  TriangleMesh mesh;
  MeshReadStats stats;
};

// Picks the reader: a ".off" extension (any case), or content that starts with the "OFF"
// keyword and is not a size-consistent binary STL, reads as OFF; anything else as STL.
MeshReadResult read_mesh(const std::filesystem::path& path);

// How many facets `path` holds, at a glance (its first 4 KiB and its size, nothing parsed
// beyond a header): exact for a size-consistent binary STL; an OFF header's face count (a
// polygon counts once); otherwise the size divided by the fewest bytes a facet takes in a text
// file, so on the high side. 0 when the file cannot be read. For memory estimates only.
std::uint64_t facet_count_hint(const std::filesystem::path& path);

// Binary or ASCII STL. Binary when 84 + 50 * (facet count at byte 80) == file size, even if
// the 80-byte header starts with "solid"; ASCII when the file starts with "solid" and looks
// like text; otherwise binary, and a count/size mismatch is reported. Binary coordinates
// are little-endian float32 widened to double; ASCII ones are parsed in double. Normals in
// the file are ignored.
MeshReadResult read_stl(const std::filesystem::path& path);

// Plain OFF ("OFF" header; counts on the header line or the next one), one vertex or face
// per line, '#' comments and blank lines anywhere. Convex polygons are fan-triangulated
// (kernels/mesh/polygon); non-convex or self-intersecting ones are rejected. Values after a
// face's indices (a face colour) are ignored; content after the last face is an error.
MeshReadResult read_off(const std::filesystem::path& path);

}  // namespace ncpath::io
