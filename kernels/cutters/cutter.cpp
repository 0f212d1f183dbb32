#include "kernels/cutters/cutter.hpp"

#include <cmath>
#include <sstream>

namespace ncpath {

Cutter ball_cutter(double diameter_mm) {
  return {CutterType::kBall, diameter_mm / 2, diameter_mm / 2};
}
Cutter flat_cutter(double diameter_mm) { return {CutterType::kFlat, diameter_mm / 2, 0.0}; }
Cutter bull_nose_cutter(double diameter_mm, double corner_radius_mm) {
  return {CutterType::kBullNose, diameter_mm / 2, corner_radius_mm};
}

std::string validate(const Cutter& c) {
  std::ostringstream os;
  if (!std::isfinite(c.radius) || c.radius <= 0) {
    os << "diameter must be a positive number of mm, got " << 2 * c.radius;
  } else if (c.type == CutterType::kBullNose) {
    if (!std::isfinite(c.corner_radius) || c.corner_radius <= 0)
      os << "corner radius must be positive for a bull-nose cutter, got " << c.corner_radius;
    else if (c.corner_radius > c.radius)
      os << "corner radius " << c.corner_radius << " mm exceeds the cutter radius " << c.radius
         << " mm";
  } else if (c.type == CutterType::kBall && c.corner_radius != c.radius) {
    os << "a ball cutter's corner radius must equal its radius";
  } else if (c.type == CutterType::kFlat && c.corner_radius != 0) {
    os << "a flat end mill has no corner radius";
  }
  return os.str();
}

const char* cutter_type_name(CutterType type) {
  switch (type) {
    case CutterType::kBall:
      return "ball";
    case CutterType::kFlat:
      return "flat";
    case CutterType::kBullNose:
      return "bullnose";
  }
  return "?";
}

}  // namespace ncpath
