// Validation of the pencil-cut's parameters (engine/pencil.hpp): messages naming the key.
#include <cmath>
#include <sstream>
#include <string>

#include "engine/pencil.hpp"

namespace ncpath {

std::string validate(const PencilParams& p) {
  std::ostringstream os;
  auto positive = [&](const char* key, double v) {
    if (os.tellp() == 0 && !(std::isfinite(v) && v > 0))
      os << key << " must be a positive number of mm, got " << v;
  };
  positive("interval", p.interval);
  positive("tolerance", p.tolerance);
  if (os.tellp() == 0 && !(std::isfinite(p.step_down) && p.step_down >= 0))
    os << "step_down must be >= 0 mm (0 = no z-levels), got " << p.step_down;
  if (os.tellp() == 0 && !(std::isfinite(p.min_angle_deg) && p.min_angle_deg > 0 &&
                           p.min_angle_deg < 180))
    os << "min_angle must be between 0 and 180 degrees, got " << p.min_angle_deg;
  if (os.tellp() == 0 && !(std::isfinite(p.merge_distance) && p.merge_distance >= 0))
    os << "merge_distance must be >= 0 mm (0 = twice the interval), got " << p.merge_distance;
  if (os.tellp() == 0 && !(std::isfinite(p.min_length) && p.min_length >= 0))
    os << "min_length must be >= 0 mm, got " << p.min_length;
  if (os.tellp() == 0 && !(std::isfinite(p.margin) && p.margin >= 0))
    os << "margin must be >= 0 mm, got " << p.margin;
  if (os.tellp() == 0 && p.floor_z && !std::isfinite(*p.floor_z))
    os << "floor_z must be a finite number of mm";
  if (os.tellp() == 0 && !std::isfinite(p.stock))
    os << "stock must be a finite number of mm, got " << p.stock;
  return os.str();
}

std::string validate_stock(double stock, double radius) {
  std::ostringstream os;
  if (!std::isfinite(stock))
    os << "stock must be a finite number of mm, got " << stock;
  else if (!(stock > -radius))
    os << "stock must be greater than minus the ball radius (-" << radius
       << " mm): the ball's centre runs R + stock from the part, got " << stock;
  return os.str();
}

}  // namespace ncpath
