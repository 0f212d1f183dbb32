#include "kernels/curves/intersect.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace ncpath {

namespace {

inline double cross(const Vec2& u, const Vec2& v) { return u.x() * v.y() - u.y() * v.x(); }

// Candidate point p lies on s (within eps)? Writes its parameter when asked. A point of s's
// carrier (on_carrier: computed on the line or circle through s) only needs to lie within
// s's extent: its distance to s is rounding, which grows with the radius and the
// coordinates (a 50 m radius arc's crossing lies 1e-8 mm off it), not a miss.
bool on_segment(const Seg2& s, const Vec2& p, double eps, bool on_carrier, bool want, double& t) {
  bool in;
  if (!on_carrier) {
    in = distance(s, p) <= eps;
  } else if (!s.is_arc()) {
    const Vec2 ab = s.b - s.a;
    const double l = ab.norm(), along = (p - s.a).dot(ab) / l;
    in = along >= -eps && along <= l + eps;
  } else {
    in = arc_contains_angle(s, p) || (p - s.a).norm() <= eps || (p - s.b).norm() <= eps;
  }
  if (!in) return false;
  t = want ? parameter_of(s, p) : 0.0;
  return true;
}

int add_hit(SegHit hits[2], int n, const Vec2& p, double t0, double t1, double eps) {
  for (int k = 0; k < n; ++k)
    if ((hits[k].p - p).norm() <= eps) return n;  // the same point found twice
  if (n < 2) hits[n++] = {p, t0, t1};
  return n;
}

// Points of the infinite line through s (a line) and the circle (c, r).
int line_circle(const Vec2& a, const Vec2& b, const Vec2& c, double r, double eps, Vec2 out[2]) {
  const Vec2 d = b - a;
  const double l = d.norm();
  if (l == 0) return 0;
  const Vec2 u = d / l;
  const double tc = (c - a).dot(u);
  const Vec2 foot = a + tc * u;
  const double h = (c - foot).norm();
  if (h > r + eps) return 0;
  if (h >= r - eps * 1e-3) {
    out[0] = foot;  // tangent
    return 1;
  }
  const double s = std::sqrt(r * r - h * h);
  out[0] = foot - s * u;
  out[1] = foot + s * u;
  return 2;
}

int circle_circle(const Vec2& c0, double r0, const Vec2& c1, double r1, double eps, Vec2 out[2]) {
  const Vec2 d = c1 - c0;
  const double l = d.norm();
  if (l == 0) return 0;  // concentric: no point, or the same circle (handled by the caller)
  if (l > r0 + r1 + eps || l < std::abs(r0 - r1) - eps) return 0;
  const double x = (l * l + r0 * r0 - r1 * r1) / (2 * l);
  const double h2 = r0 * r0 - x * x;
  const Vec2 u = d / l;
  const Vec2 mid = c0 + x * u;
  if (h2 <= 0) {
    out[0] = mid;  // tangent
    return 1;
  }
  const double h = std::sqrt(h2);
  const Vec2 v(-u.y(), u.x());
  out[0] = mid - h * v;
  out[1] = mid + h * v;
  return 2;
}

}  // namespace

int carrier_crossings(const Seg2& s0, const Seg2& s1, Vec2 out[2]) {
  if (!s0.is_arc() && !s1.is_arc()) {
    const Vec2 d0 = s0.b - s0.a, d1 = s1.b - s1.a;
    const double den = cross(d0, d1);
    if (den == 0) return 0;
    out[0] = s0.a + (cross(s1.a - s0.a, d1) / den) * d0;
    return 1;
  }
  if (s0.is_arc() != s1.is_arc()) {
    const Seg2& line = s0.is_arc() ? s1 : s0;
    const Seg2& arc = s0.is_arc() ? s0 : s1;
    return line_circle(line.a, line.b, arc.c, arc.r, 0.0, out);
  }
  return circle_circle(s0.c, s0.r, s1.c, s1.r, 0.0, out);
}

double parameter_of(const Seg2& s, const Vec2& p) {
  if (!s.is_arc()) {
    const Vec2 ab = s.b - s.a;
    const double l2 = ab.squaredNorm();
    return l2 > 0 ? std::clamp((p - s.a).dot(ab) / l2, 0.0, 1.0) : 0.0;
  }
  const double th = sweep(s);
  const double a0 = std::atan2(s.a.y() - s.c.y(), s.a.x() - s.c.x());
  const double ap = std::atan2(p.y() - s.c.y(), p.x() - s.c.x());
  double d = th > 0 ? ap - a0 : a0 - ap;
  while (d < 0) d += 2 * std::numbers::pi;
  while (d >= 2 * std::numbers::pi) d -= 2 * std::numbers::pi;
  const double t = d / std::abs(th);
  if (t > 1) {
    // Outside the sweep: the nearer end.
    return (p - s.a).squaredNorm() < (p - s.b).squaredNorm() ? 0.0 : 1.0;
  }
  return t;
}

Seg2 sub_segment(const Seg2& s, const Vec2& from, const Vec2& to) {
  Seg2 r = s;
  r.a = from;
  r.b = to;
  return r;
}

int intersect(const Seg2& s0, const Seg2& s1, SegHit hits[2], double eps, bool want_params) {
  int n = 0;
  Vec2 cand[4];
  int nc = 0;
  bool on_carriers = true;  // false: end points of collinear or co-circular overlaps
  if (!s0.is_arc() && !s1.is_arc()) {
    const Vec2 d0 = s0.b - s0.a, d1 = s1.b - s1.a;
    const double den = cross(d0, d1);
    const double l0 = d0.norm(), l1 = d1.norm();
    if (std::abs(den) > 1e-14 * l0 * l1) {
      const double t = cross(s1.a - s0.a, d1) / den;
      cand[nc++] = s0.a + t * d0;
    } else {
      // Parallel: overlapping if collinear; the overlap's ends are the end points that lie
      // on the other segment.
      on_carriers = false;
      for (const Vec2& p : {s0.a, s0.b}) cand[nc++] = p;
      for (const Vec2& p : {s1.a, s1.b})
        if (nc < 4) cand[nc++] = p;
    }
  } else if (s0.is_arc() != s1.is_arc()) {
    const Seg2& line = s0.is_arc() ? s1 : s0;
    const Seg2& arc = s0.is_arc() ? s0 : s1;
    nc = line_circle(line.a, line.b, arc.c, arc.r, eps, cand);
  } else if ((s0.c - s1.c).norm() <= eps && std::abs(s0.r - s1.r) <= eps) {
    // Co-circular arcs: the overlap's ends.
    on_carriers = false;
    for (const Vec2& p : {s0.a, s0.b, s1.a, s1.b}) cand[nc++] = p;
  } else {
    nc = circle_circle(s0.c, s0.r, s1.c, s1.r, eps, cand);
  }
  for (int k = 0; k < nc; ++k) {
    double t0, t1;
    if (on_segment(s0, cand[k], eps, on_carriers, want_params, t0) &&
        on_segment(s1, cand[k], eps, on_carriers, want_params, t1))
      n = add_hit(hits, n, cand[k], t0, t1, eps);
  }
  return n;
}

double distance(const Seg2& s0, const Seg2& s1) {
  SegHit hits[2];
  // Crossing points are computed, so they lie on the curves only up to rounding.
  if (intersect(s0, s1, hits, 1e-12 * (1 + s0.a.norm()), false) > 0) return 0.0;
  double d =
      std::min({distance(s0, s1.a), distance(s0, s1.b), distance(s1, s0.a), distance(s1, s0.b)});
  // Interior-interior minima: along the line through the centres (arc-arc) or the
  // perpendicular from the centre (line-arc).
  auto arc_points_towards = [](const Seg2& arc, const Vec2& target, Vec2 out[2]) {
    const Vec2 u = target - arc.c;
    const double l = u.norm();
    if (l == 0) return 0;
    out[0] = arc.c + arc.r * u / l;
    out[1] = arc.c - arc.r * u / l;
    return 2;
  };
  if (s0.is_arc() && s1.is_arc()) {
    // (Concentric arcs have no such line; their overlap, if any, contains an end point of
    // one of them, already measured above.)
    Vec2 p[2], q[2];
    const int np = arc_points_towards(s0, s1.c, p);
    const int nq = arc_points_towards(s1, s0.c, q);
    for (int k = 0; k < np; ++k)
      if (arc_contains_angle(s0, p[k])) d = std::min(d, distance(s1, p[k]));
    for (int k = 0; k < nq; ++k)
      if (arc_contains_angle(s1, q[k])) d = std::min(d, distance(s0, q[k]));
  } else if (s0.is_arc() || s1.is_arc()) {
    const Seg2& line = s0.is_arc() ? s1 : s0;
    const Seg2& arc = s0.is_arc() ? s0 : s1;
    const Vec2 ab = line.b - line.a;
    const double l2 = ab.squaredNorm();
    if (l2 > 0) {
      const double t = (arc.c - line.a).dot(ab) / l2;
      if (t > 0 && t < 1) {
        const Vec2 foot = line.a + t * ab;
        Vec2 p[2];
        if (arc_points_towards(arc, foot, p) > 0 && arc_contains_angle(arc, p[0]))
          d = std::min(d, (p[0] - foot).norm());
      }
    }
  }
  return d;
}

}  // namespace ncpath
