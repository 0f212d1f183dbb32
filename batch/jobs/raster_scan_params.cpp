// The raster and scan operations' parameters: reading a job's `params` table (the values are
// checked by the engine's validate), and the text form of the scan families ("x", "y",
// "both") that the command line shares.
#include "batch/jobs/raster_scan_params.hpp"

#include <array>
#include <string>

#include "batch/jobs/job_spec.hpp"

namespace ncpath::jobs {

std::string parse_families(const std::string& text, ScanFamilies& out) {
  if (text == "x")
    out = ScanFamilies::kX;
  else if (text == "y")
    out = ScanFamilies::kY;
  else if (text == "both")
    out = ScanFamilies::kBoth;
  else
    return "must be \"x\", \"y\" or \"both\", got \"" + text + "\"";
  return "";
}

const char* families_name(ScanFamilies families) {
  switch (families) {
    case ScanFamilies::kX:
      return "x";
    case ScanFamilies::kY:
      return "y";
    case ScanFamilies::kBoth:
      return "both";
  }
  return "?";
}

void parse_raster_params(Keys& k, RasterParams& p) {
  std::string dir;
  if (k.string("direction", dir)) {
    if (dir == "x")
      p.direction = ScanDirection::kX;
    else if (dir == "y")
      p.direction = ScanDirection::kY;
    else
      k.fail("direction", "must be \"x\" or \"y\", got \"" + dir + "\"");
  }
  k.number("interval", p.interval);
  k.number("step", p.step);
  k.number("margin", p.margin);
  double rect[4];
  if (k.numbers("rect", 4, rect))
    p.rect = std::array<double, 4>{rect[0], rect[1], rect[2], rect[3]};
  k.number("adaptive_tolerance", p.adaptive_tolerance);
  k.number("min_step", p.min_step);
  double floor_z;
  if (k.number("floor_z", floor_z)) p.floor_z = floor_z;
  k.whole_number("chunk_lines", p.chunk_lines);
  k.number("strip_height", p.strip_height);
  k.number("bin_width", p.bin_width);
}

void parse_scan_params(Keys& k, ScanParams& p) {
  std::string families;
  if (k.string("families", families))
    if (std::string e = parse_families(families, p.families); !e.empty()) k.fail("families", e);
  k.number("interval", p.interval);
  k.number("tolerance", p.tolerance);
  k.number("margin", p.margin);
  double rect[4];
  if (k.numbers("rect", 4, rect))
    p.rect = std::array<double, 4>{rect[0], rect[1], rect[2], rect[3]};
  double floor_z;
  if (k.number("floor_z", floor_z)) p.floor_z = floor_z;
  k.whole_number("chunk_planes", p.chunk_planes);
}

}  // namespace ncpath::jobs
