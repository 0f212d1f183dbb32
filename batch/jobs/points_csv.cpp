#include "batch/jobs/points_csv.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <string>

#include "batch/io/read_error.hpp"

namespace ncpath::jobs {

PointList read_points_csv(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw io::ReadError(path, "", "cannot open the points file");
  PointList out;
  std::uint32_t current = 0;
  auto end_path = [&] {
    if (current > 0) out.path_sizes.push_back(current);
    current = 0;
  };
  std::string line;
  for (std::size_t number = 1; std::getline(in, line); ++number) {
    if (const auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos) {
      end_path();
      continue;
    }
    double v[2];
    const char* p = line.data() + first;
    const char* end = line.data() + line.size();
    for (int k = 0; k < 2; ++k) {
      while (p < end && (*p == ' ' || *p == '\t')) ++p;
      auto [next, ec] = std::from_chars(p, end, v[k]);
      if (ec != std::errc() || !std::isfinite(v[k]))
        throw io::ReadError(path, "line " + std::to_string(number),
                            std::string("expected a finite number for ") + (k ? "y" : "x") +
                                " in \"" + line + "\"");
      p = next;
      while (p < end && (*p == ' ' || *p == '\t')) ++p;
      if (k == 0) {
        if (p == end || *p != ',')
          throw io::ReadError(path, "line " + std::to_string(number),
                              "expected \"x,y\", got \"" + line + "\"");
        ++p;
      }
    }
    out.xy.push_back(v[0]);
    out.xy.push_back(v[1]);
    ++current;
  }
  end_path();
  if (out.xy.empty()) throw io::ReadError(path, "", "no points in the file");
  return out;
}

}  // namespace ncpath::jobs
