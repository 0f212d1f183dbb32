#pragma once
// Shared by the coplanar tests (coplanar_terrain_test.cpp, coplanar_cad_test.cpp): the
// drive-plane scan as engine/scan.cpp runs it, and the checks of its curve against a
// drop-cutter oracle and against the curve of the unsplit mesh (heights, junctions, kinks).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <sstream>
#include <string>
#include <unordered_map>
#include <vector>

#include "kernels/geom/tolerance.hpp"
#include "kernels/mesh/offset_elements.hpp"
#include "kernels/scan/envelope.hpp"
#include "kernels/scan/plane_slice.hpp"

namespace ncpath::coplanar_test {

inline constexpr double kCurveTol = 1e-9;    // mm: curve vs drop-cutter
inline constexpr double kKinkAngle = 1e-6;   // rad: bi-contact vectors this far apart make a kink
inline constexpr double kKinkMatchX = 1e-7;  // mm: a kink of one curve found at this x in the other

inline std::uint64_t key(std::uint32_t u, std::uint32_t v) {
  return (std::uint64_t{std::min(u, v)} << 32) | std::max(u, v);
}

// Edge index of el by vertex pair.
inline std::unordered_map<std::uint64_t, std::uint32_t> edge_index(const OffsetElements& el) {
  std::unordered_map<std::uint64_t, std::uint32_t> out;
  for (std::uint32_t e = 0; e < el.edge_count(); ++e)
    out[key(el.edge_vertices[e][0], el.edge_vertices[e][1])] = e;
  return out;
}

inline double angle_between(const Vec3& a, const Vec3& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

// ---- the drive-plane scan, as engine/scan.cpp does it ----

struct Plane {
  std::vector<SlicePiece> pieces;
  std::vector<EnvelopeSpan> spans;
  PlaneCurve curve;
};

// Elements whose trimmed y reach holds y0 (the engine's plane index), sliced with trimming,
// clipped to [x_lo, x_hi], plus the floor.
inline Plane scan_plane(const OffsetElements& el, double y0, double floor_z, double x_lo,
                        double x_hi) {
  Plane p;
  for (std::uint32_t id = 0; id < el.element_count(); ++id) {
    double lo, hi;
    if (element_y_reach(el, id, lo, hi) && lo <= y0 && y0 <= hi)
      slice_elements(el, y0, id, id + 1, p.pieces);
  }
  std::erase_if(p.pieces, [&](SlicePiece& pc) {
    pc.x0 = std::max(pc.x0, x_lo);
    pc.x1 = std::min(pc.x1, x_hi);
    return !(pc.x0 < pc.x1);
  });
  p.pieces.push_back(floor_piece(floor_z, el.radius, y0, x_lo, x_hi));
  upper_envelope(p.pieces, p.spans);
  plane_curve(p.pieces, p.spans, p.curve);
  return p;
}

// Tip z of the curve at x: the highest non-vertical segment holding x.
inline double curve_z(const Plane& p, double x) {
  double best = -INFINITY;
  for (const CurveSegment& s : p.curve.segments)
    if (!s.vertical && x >= s.x0 && x <= s.x1) best = std::max(best, tip_z(p.pieces[s.piece], x));
  return best;
}

struct Worst {
  double err = 0;
  std::string where;
  int checks = 0;
  void add(double got, double want, const std::string& label, double x) {
    ++checks;
    const double e = std::abs(got - want);
    if (!(e <= err)) {
      err = e;
      std::ostringstream s;
      s.precision(17);
      s << label << " x " << x << " curve " << got << " drop-cutter " << want;
      where = s.str();
    }
  }
};

// The curve against the oracle at segment middles and ends, 1e-6 mm either side of each
// jump (vertical segment), and at `samples` random x. Skipped: x within kSteepGap of a jump
// or of a segment end where the piece's slope exceeds kSteepSlope (an arc ending with a
// vertical tangent). There the height is ill-conditioned: where an arc ends is rounded to
// ~1e-15 mm, and the arc rises by sqrt(2 R dx) over dx, ~1e-7 mm; kSteepGap further out
// the slope is at most sqrt(R / (2 kSteepGap)) ~ 4e4 and the same rounding moves z by
// ~1e-11 mm.
inline constexpr double kSteepGap = 1e-9, kSteepSlope = 1e6;
template <class Oracle>
void compare_with_oracle(const Plane& p, Oracle&& want, double x_lo, double x_hi, int samples,
                         std::mt19937_64& rng, const std::string& label, Worst& worst) {
  const auto& segs = p.curve.segments;
  std::vector<double> steep;
  for (const CurveSegment& s : segs) {
    if (s.vertical) {
      steep.push_back(s.x0);
      continue;
    }
    for (double x : {s.x0, s.x1})
      if (!(std::abs(slope(p.pieces[s.piece], x)) <= kSteepSlope)) steep.push_back(x);
  }
  auto check = [&](double got, double x, const char* what) {
    for (double xs : steep)
      if (std::abs(x - xs) <= kSteepGap) return;
    worst.add(got, want(x), label + what, x);
  };
  for (const CurveSegment& s : segs) {
    if (s.vertical) {
      for (double x : {s.x0 - 1e-6, s.x0 + 1e-6})
        if (x > x_lo && x < x_hi) check(curve_z(p, x), x, " near jump");
      continue;
    }
    const double xm = 0.5 * (s.x0 + s.x1);
    check(tip_z(p.pieces[s.piece], xm), xm, " mid");
    check(s.z0, s.x0, " start");
    check(s.z1, s.x1, " end");
  }
  std::uniform_real_distribution<double> rx(x_lo, x_hi);
  for (int k = 0; k < samples; ++k) {
    const double x = rx(rng);
    check(curve_z(p, x), x, " random");
  }
}

// Two junctions share an x only at the two ends of a vertical segment.
inline void expect_distinct_junctions(const Plane& p, const std::string& label) {
  const auto& js = p.curve.junctions;
  for (std::size_t k = 0; k + 1 < js.size(); ++k) {
    if (js[k + 1].x > js[k].x) continue;
    EXPECT_TRUE(p.curve.segments[js[k].segment].vertical)
        << label << ": two junctions at x " << js[k].x << " (elements " << js[k].element1 << ","
        << js[k].element2 << " and " << js[k + 1].element1 << "," << js[k + 1].element2 << ")";
  }
}

inline double junction_angle(const CurveJunction& j) { return angle_between(j.b1, j.b2); }

// |difference of the two pieces' slopes| at a junction (infinite at a vertical segment).
inline double slope_gap(const Plane& p, const CurveJunction& j) {
  const auto& segs = p.curve.segments;
  if (segs[j.segment].vertical || (j.segment > 0 && segs[j.segment - 1].vertical)) return INFINITY;
  if (j.segment == 0) return INFINITY;
  const double a = slope(p.pieces[segs[j.segment - 1].piece], j.x);
  const double b = slope(p.pieces[segs[j.segment].piece], j.x);
  return std::abs(a - b);
}

// Every kink of `a` (bi-contact vectors more than `min_angle` apart) has a junction of the
// same kind in `b` at the same x, bent more than kKinkAngle / 10 (a margin so that a kink
// right at kKinkAngle cannot flip). x within kKinkMatchX, or within what the envelope's tie
// rule allows at a shallow crossing (tol::kEnvelopeTie over the slope difference; at most
// 1e-4 mm, where the slopes agree).
inline void expect_kinks_in(const Plane& a, const Plane& b, double min_angle,
                            const std::string& label, int& kinks) {
  for (const CurveJunction& j : a.curve.junctions) {
    if (!(junction_angle(j) > min_angle)) continue;
    ++kinks;
    const double tol_x = std::min(kKinkMatchX + 2 * tol::kEnvelopeTie / slope_gap(a, j), 1e-4);
    bool found = false;
    for (const CurveJunction& k : b.curve.junctions)
      found = found || (std::abs(k.x - j.x) <= tol_x && k.kind == j.kind &&
                        junction_angle(k) > 0.1 * kKinkAngle);
    EXPECT_TRUE(found) << label << ": kink at x " << j.x << " z " << j.z << " angle "
                       << junction_angle(j) << " kind " << junction_kind_name(j.kind)
                       << " elements " << j.element1 << "," << j.element2;
  }
}

// The split mesh's curve has no kink the unsplit one lacks (kKinkAngle), and keeps the
// unsplit one's creases. The second direction only counts kinks above kCreaseAngle: the
// envelope's tie rule (tol::kEnvelopeTie) can hand a stretch where two arcs touch to the
// lower element id and switch where they part by 1e-10 mm, a junction bent by about
// sqrt(2 tie / R) ~ 1e-5 rad that depends on element ids; the unsplit mesh is the
// reference here, not the subject.
inline constexpr double kCreaseAngle = 1e-3;
inline void expect_same_kinks(const Plane& split, const Plane& unsplit, const std::string& label,
                              int& kinks) {
  expect_kinks_in(split, unsplit, kKinkAngle, label + " split kink missing in unsplit", kinks);
  expect_kinks_in(unsplit, split, kCreaseAngle, label + " unsplit crease missing in split", kinks);
}

}  // namespace ncpath::coplanar_test
