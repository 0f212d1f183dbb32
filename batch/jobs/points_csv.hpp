#pragma once
// Points for the drop operation: a text file of "x,y" lines (mm; extra columns ignored,
// '#' comments allowed). A blank line ends a path, so a file can hold several polylines.
// Malformed lines throw io::ReadError naming the file and line.
#include <cstdint>
#include <filesystem>
#include <vector>

namespace ncpath::jobs {

struct PointList {
  std::vector<double> xy;                 // 2 per point, mm
  std::vector<std::uint32_t> path_sizes;  // points per path, in file order
};

PointList read_points_csv(const std::filesystem::path& path);

}  // namespace ncpath::jobs
