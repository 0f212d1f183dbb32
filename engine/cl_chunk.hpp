#pragma once
// CL data as the engine hands it to a writer: a run of whole paths in cutting order,
// structure-of-arrays. Operations stream these; nobody holds a whole job's points.
#include <cstdint>
#include <vector>

namespace ncpath {

// What a path is for (stored per path in HDF5 /cl/path_kind).
enum class PathKind : std::uint8_t { kCut = 0, kLinkAtDepth = 1, kRapid = 2 };

struct ClChunk {
  std::vector<double> xyz;                // 3 per point: tool tip, mm
  std::vector<std::uint8_t> contact;      // 1 per point: ContactKind (0 = touched nothing)
  std::vector<std::uint32_t> path_sizes;  // 1 per path: number of points
  std::vector<std::uint8_t> path_kinds;   // 1 per path: PathKind

  std::size_t point_count() const { return contact.size(); }
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

}  // namespace ncpath
