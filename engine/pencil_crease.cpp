#include "engine/pencil_crease.hpp"

#include <algorithm>
#include <cmath>

#include "kernels/geom/tolerance.hpp"
#include "kernels/scan/envelope.hpp"

namespace ncpath {

namespace {

// The junction on plane v of a's family nearest to `near` (within w of it along the plane),
// sharp concave, off the floor, with angle >= min_angle and tangent within kCreaseMinCos of t.
bool nearest_crease(const ScanElements& se, const PencilCandidate& a, double v, const Vec3& near,
                    double w, const Vec3& t, double min_angle, double floor_z,
                    PencilCandidate& out) {
  const double u = a.family == 0 ? near.x() : near.y();
  double best = w;
  bool found = false;
  for (const PlaneJunction& j : plane_junctions(se, a.family, v, u - w, u + w, floor_z)) {
    if (j.kind != std::uint8_t(JunctionKind::kSharpConcave) || j.on_floor) continue;
    if (bicontact_angle(j.b1, j.b2) < min_angle) continue;
    if (std::abs(crease_tangent(j.b1, j.b2).dot(t)) < kCreaseMinCos) continue;
    const double d = (j.position - near).norm();
    if (d < best) {
      best = d;
      out = {j.position, j.b1, j.b2, a.family, a.layer};
      found = true;
    }
  }
  return found;
}

}  // namespace

bool crease_between(const ScanElements& se, const PencilCandidate& a, const PencilCandidate& b,
                    double min_angle, double floor_z, PencilCandidate& out) {
  const Vec3 n = layer_normal(a.family);
  const double v = 0.5 * (a.p.dot(n) + b.p.dot(n));
  const double w = std::max(0.5 * (b.p - a.p).norm(), 0.05);
  return nearest_crease(se, a, v, 0.5 * (a.p + b.p), w, crease_tangent(a.b1, a.b2), min_angle,
                        floor_z, out);
}

bool crease_on_plane(const ScanElements& se, const PencilCandidate& a, double v, double min_angle,
                     double floor_z, PencilCandidate& out) {
  const Vec3 n = layer_normal(a.family), t = crease_tangent(a.b1, a.b2);
  if (!(std::abs(t.dot(n)) > tol::kPencilAlongPlane)) return false;  // along the planes
  const Vec3 q = a.p + t * ((v - a.p.dot(n)) / t.dot(n));
  const double w = std::max((q - a.p).norm(), 0.05);
  return nearest_crease(se, a, v, q, w, t, min_angle, floor_z, out);
}

bool crease_end(const ScanElements& se, const PencilCandidate& end, double dir, double spacing,
                double v_min, double v_max, double min_angle, double floor_z,
                PencilCandidate& out) {
  const double v0 = end.p.dot(layer_normal(end.family));
  double lo = 0, hi = std::min(spacing, dir > 0 ? v_max - v0 : v0 - v_min);
  if (!(hi > 0)) return false;
  bool found = false;
  PencilCandidate from = end;
  for (int it = 0; it < 7; ++it) {
    const double mid = 0.5 * (lo + hi);
    PencilCandidate c;
    if (crease_on_plane(se, from, v0 + dir * mid, min_angle, floor_z, c)) {
      out = c;
      from = c;
      found = true;
      lo = mid;
    } else {
      hi = mid;
    }
  }
  return found;
}

}  // namespace ncpath
