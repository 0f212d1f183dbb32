#pragma once
// Milling cutters with a vertical axis (+Z). All three are described by two radii:
// R (half the diameter) and the corner radius r; the cutter's lower surface is the flat
// disc of radius a = R - r at the tip plus a quarter torus of tube radius r.
//   ball:      r = R (a = 0)
//   flat:      r = 0 (a = R)
//   bull-nose: 0 < r <= R
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

namespace ncpath {

enum class CutterType : std::uint8_t { kBall = 0, kFlat = 1, kBullNose = 2 };

struct Cutter {
  CutterType type = CutterType::kBall;
  double radius = 0;         // R, mm
  double corner_radius = 0;  // r, mm (ball: R, flat: 0)

  double flat_radius() const { return radius - corner_radius; }  // a = R - r, mm
};

// Builders from the machinist's numbers (diameters). They do not validate; see validate().
Cutter ball_cutter(double diameter_mm);
Cutter flat_cutter(double diameter_mm);
Cutter bull_nose_cutter(double diameter_mm, double corner_radius_mm);

// Empty when the cutter is usable; otherwise a sentence naming the bad value, e.g.
// "corner radius 3 mm exceeds the cutter radius 2.5 mm".
std::string validate(const Cutter& cutter);

// Height of the cutter's lower surface above its tip at horizontal distance rho from the
// axis, for 0 <= rho <= R (mm). Convex and non-decreasing in rho.
inline double profile_height(const Cutter& c, double rho) {
  const double a = c.radius - c.corner_radius;
  if (rho <= a) return 0.0;
  const double t = rho - a, r = c.corner_radius;
  return r - std::sqrt(std::max(0.0, r * r - t * t));
}

// profile_height(rho) >= delta, from rho^2, without a square root for ball and flat
// cutters. Used to dismiss geometry whose top, lowered by the cutter's rise at its nearest
// horizontal distance, cannot beat the best tip so far.
inline bool profile_height_at_least(const Cutter& c, double rho2, double delta) {
  const double r = c.corner_radius, a = c.radius - c.corner_radius;
  if (delta <= 0) return true;
  if (delta > r) return false;                // the profile never rises more than r
  const double k2 = delta * (2 * r - delta);  // (rho - a)^2 at which h reaches delta
  if (a == 0) return rho2 >= k2;
  const double k = a + std::sqrt(k2);
  return rho2 >= k * k;
}

const char* cutter_type_name(CutterType type);  // "ball", "flat", "bullnose"

}  // namespace ncpath
