#include "kernels/curves/segment.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace ncpath {

namespace {

inline double cross(const Vec2& u, const Vec2& v) { return u.x() * v.y() - u.y() * v.x(); }

// Angle of p - c, radians in (-pi, pi].
inline double angle_of(const Vec2& p, const Vec2& c) {
  return std::atan2(p.y() - c.y(), p.x() - c.x());
}

}  // namespace

Seg2 make_line(const Vec2& a, const Vec2& b, std::uint32_t source) {
  Seg2 s;
  s.a = a;
  s.b = b;
  s.kind = SegKind::kLine;
  s.source = source;
  return s;
}

Seg2 make_arc(const Vec2& a, const Vec2& b, const Vec2& c, bool ccw, std::uint32_t source) {
  Seg2 s;
  s.a = a;
  s.b = b;
  s.c = c;
  s.r = (a - c).norm();
  s.kind = ccw ? SegKind::kArcCcw : SegKind::kArcCw;
  s.source = source;
  return s;
}

Seg2 make_bulge_segment(const Vec2& a, const Vec2& b, double bulge, std::uint32_t source) {
  if (bulge == 0 || a == b) return make_line(a, b, source);
  // Centre on the chord's perpendicular bisector, at signed distance L (1 - b^2) / (4 b)
  // to the left of a -> b (tan(sweep / 2) = 2b / (1 - b^2)).
  const Vec2 ab = b - a;
  const Vec2 left(-ab.y(), ab.x());
  const Vec2 c = 0.5 * (a + b) + left * ((1 - bulge * bulge) / (4 * bulge));
  return make_arc(a, b, c, bulge > 0, source);
}

double sweep(const Seg2& s) {
  if (!s.is_arc()) return 0;
  double phi = std::atan2(cross(s.a - s.c, s.b - s.c), (s.a - s.c).dot(s.b - s.c));
  if (s.kind == SegKind::kArcCcw) {
    if (phi <= 0) phi += 2 * std::numbers::pi;
  } else {
    if (phi >= 0) phi -= 2 * std::numbers::pi;
  }
  return phi;
}

double length(const Seg2& s) { return s.is_arc() ? s.r * std::abs(sweep(s)) : (s.b - s.a).norm(); }

Vec2 point_at(const Seg2& s, double t) {
  if (t <= 0) return s.a;
  if (t >= 1) return s.b;
  if (!s.is_arc()) return s.a + t * (s.b - s.a);
  const double ang = angle_of(s.a, s.c) + t * sweep(s);
  return s.c + s.r * Vec2(std::cos(ang), std::sin(ang));
}

Vec2 tangent_at(const Seg2& s, double t) {
  if (!s.is_arc()) return (s.b - s.a).normalized();
  const Vec2 p = point_at(s, t) - s.c;
  const Vec2 left(-p.y(), p.x());
  return (s.turn() > 0 ? left : Vec2(-left)).normalized();
}

double area2_contribution(const Seg2& s) {
  double v = cross(s.a, s.b);
  if (s.is_arc()) {
    // Twice the circular segment between chord and arc: r^2 (theta - sin theta).
    const double cr = cross(s.a - s.c, s.b - s.c);    // r^2 sin(theta)
    const double x = 0.5 * (s.b - s.a).norm() / s.r;  // sin(|theta| / 2)
    if (x < 0.05 && cr * s.turn() > 0) {
      // Small minor arc (most arcs of real profiles and offsets): series in x, no
      // trigonometry. |theta|/2 = asin x; theta - sin theta = t^3/6 - t^5/120 + t^7/5040
      // - t^9/362880 with t = |theta|; truncation error below 1e-17 relative.
      const double x2 = x * x;
      const double half =
          x * (1 + x2 * (1.0 / 6 + x2 * (3.0 / 40 + x2 * (5.0 / 112 + x2 * 35.0 / 1152))));
      const double t = 2 * half, t2 = t * t;
      const double seg = t * t2 * (1.0 / 6 - t2 * (1.0 / 120 - t2 * (1.0 / 5040 - t2 / 362880)));
      v += s.turn() * s.r * s.r * seg;
    } else {
      v += s.r * s.r * sweep(s) - cr;
    }
  }
  return v;
}

// True when the direction of p from the centre lies within the arc's sweep (inclusive).
// Cross products only (this runs in every offset's inner loops): a counter-clockwise arc
// from direction u to direction w covers v when v lies counter-clockwise from u and
// clockwise from w (minor arcs), or outside the minor arc from w to u (major arcs).
bool arc_contains_angle(const Seg2& s, const Vec2& p) {
  Vec2 u = s.a - s.c, w = s.b - s.c;
  if (s.kind == SegKind::kArcCw) std::swap(u, w);  // a clockwise arc = ccw from b to a
  const Vec2 v = p - s.c;
  const double uw = cross(u, w);
  if (uw > 0) return cross(u, v) >= 0 && cross(v, w) >= 0;
  if (uw < 0) return !(cross(w, v) > 0 && cross(v, u) > 0);
  if (u.dot(w) > 0) return cross(u, v) == 0 && u.dot(v) > 0;  // no sweep: one direction
  return cross(u, v) >= 0;                                    // a half circle
}

double distance(const Seg2& s, const Vec2& p) {
  if (!s.is_arc()) {
    const Vec2 ab = s.b - s.a;
    const double l2 = ab.squaredNorm();
    const double t = l2 > 0 ? std::clamp((p - s.a).dot(ab) / l2, 0.0, 1.0) : 0.0;
    return (p - (s.a + t * ab)).norm();
  }
  if (p != s.c && arc_contains_angle(s, p)) return std::abs((p - s.c).norm() - s.r);
  return std::min((p - s.a).norm(), (p - s.b).norm());
}

void bounds(const Seg2& s, Vec2& lo, Vec2& hi) {
  lo = s.a.cwiseMin(s.b);
  hi = s.a.cwiseMax(s.b);
  if (!s.is_arc()) return;
  const Vec2 extremes[4] = {s.c + Vec2(s.r, 0), s.c + Vec2(0, s.r), s.c + Vec2(-s.r, 0),
                            s.c + Vec2(0, -s.r)};
  for (const Vec2& e : extremes)
    if (arc_contains_angle(s, e)) {
      lo = lo.cwiseMin(e);
      hi = hi.cwiseMax(e);
    }
}

void append_polyline(const Seg2& s, double chordal_tol, std::vector<Vec2>& out) {
  out.push_back(s.a);
  if (!s.is_arc()) return;
  const double th = sweep(s);
  // A chord spanning angle phi deviates r (1 - cos(phi / 2)) from the arc.
  const double ratio = std::clamp(1 - chordal_tol / s.r, -1.0, 1.0);
  const double max_phi = std::max(2 * std::acos(ratio), 1e-6);
  const int n = std::max(1, static_cast<int>(std::ceil(std::abs(th) / max_phi)));
  for (int k = 1; k < n; ++k) out.push_back(point_at(s, static_cast<double>(k) / n));
}

void loose_bounds(const Seg2& s, Vec2& lo, Vec2& hi) {
  lo = s.a.cwiseMin(s.b);
  hi = s.a.cwiseMax(s.b);
  if (!s.is_arc()) return;
  const double half = 0.5 * (s.b - s.a).norm();
  if (cross(s.a - s.c, s.b - s.c) * s.turn() > 0 && half < s.r) {
    // Minor arc: it stays within its sagitta of the chord.
    const double sag = s.r - std::sqrt(s.r * s.r - half * half);
    lo.array() -= sag;
    hi.array() += sag;
  } else {
    lo = lo.cwiseMin(s.c - Vec2::Constant(s.r));
    hi = hi.cwiseMax(s.c + Vec2::Constant(s.r));
  }
}

Seg2 reversed(const Seg2& s) {
  Seg2 r = s;
  std::swap(r.a, r.b);
  if (s.kind == SegKind::kArcCcw) r.kind = SegKind::kArcCw;
  if (s.kind == SegKind::kArcCw) r.kind = SegKind::kArcCcw;
  return r;
}

}  // namespace ncpath
