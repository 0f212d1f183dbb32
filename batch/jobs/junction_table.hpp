#pragma once
// The junction table that the scan and zlevel jobs write (groups scan/ and zlevel/,
// docs/hdf5-schema.md): the engine's junction records of a whole job as structure-of-arrays
// in cutting order, and the shared texts of the element and kind columns.
#include <cstdint>
#include <string>
#include <vector>

#include "batch/output/cl_writer.hpp"
#include "engine/scan.hpp"

namespace ncpath::jobs {

inline constexpr const char* kJunctionKindEnum = "0=convex,1=sharp_concave,2=tangent";
inline constexpr const char* kElementText =
    "mesh element: kind (0 facet, 1 edge, 2 vertex), then indices a, b: facet index, -1; "
    "edge's two vertex indices; vertex index, -1";

// Rows of 3 values flattened.
void push_row(std::vector<double>& to, const std::array<double, 3>& v);
void push_row(std::vector<std::int64_t>& to, const ElementRef& e);

struct JunctionTable {
  std::vector<std::int64_t> path, element1, element2;
  std::vector<std::uint8_t> kind;
  std::vector<double> position, b1, b2, angle;

  void add(const ScanJunctionRecord& j);
  // junction_path, _kind, _position, _b1, _b2, _element1, _element2, _angle in `group`;
  // path_text and position_text describe the path and position columns for that group.
  void write(out::ClJob& cl, const std::string& group, const std::string& path_text,
             const std::string& position_text) const;
};

}  // namespace ncpath::jobs
