#pragma once
// CL data as the engine hands it to a writer: a run of whole paths in cutting order,
// structure-of-arrays. Operations stream these; nobody holds a whole job's points.
#include <cstdint>
#include <vector>

#include "kernels/geom/vec.hpp"

namespace ncpath {

// What a path is for (stored per path in HDF5 /cl/path_kind).
enum class PathKind : std::uint8_t { kCut = 0, kLinkAtDepth = 1, kRapid = 2 };

struct ClChunk {
  std::vector<double> xyz;                // 3 per point: tool tip, mm
  std::vector<std::uint8_t> contact;      // 1 per point: ContactKind (0 = touched nothing)
  std::vector<std::uint32_t> path_sizes;  // 1 per path: number of points
  std::vector<std::uint8_t> path_kinds;   // 1 per path: PathKind

  std::size_t point_count() const { return contact.size(); }
  Vec3 point(std::size_t i) const { return Vec3(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]); }
  void append(const ClChunk& other) {
    xyz.insert(xyz.end(), other.xyz.begin(), other.xyz.end());
    contact.insert(contact.end(), other.contact.begin(), other.contact.end());
    path_sizes.insert(path_sizes.end(), other.path_sizes.begin(), other.path_sizes.end());
    path_kinds.insert(path_kinds.end(), other.path_kinds.begin(), other.path_kinds.end());
  }
  void clear() {
    xyz.clear();
    contact.clear();
    path_sizes.clear();
    path_kinds.clear();
  }
};

// The moves of a chunk (a path of n points has n - 1: its consecutive pairs), in order:
// first[m] is the index of move m's first point, path[m] the index of its path.
struct ChunkMoves {
  std::vector<std::uint32_t> first, path;
  std::size_t size() const { return first.size(); }
};
inline ChunkMoves chunk_moves(const ClChunk& cl) {
  ChunkMoves m;
  std::size_t start = 0;
  for (std::size_t k = 0; k < cl.path_sizes.size(); ++k) {
    for (std::size_t i = 1; i < cl.path_sizes[k]; ++i) {
      m.first.push_back(static_cast<std::uint32_t>(start + i - 1));
      m.path.push_back(static_cast<std::uint32_t>(k));
    }
    start += cl.path_sizes[k];
  }
  return m;
}
inline std::uint64_t move_count(const ClChunk& cl) {
  std::uint64_t n = 0;
  for (std::uint32_t s : cl.path_sizes) n += s > 0 ? s - 1 : 0;
  return n;
}

}  // namespace ncpath
