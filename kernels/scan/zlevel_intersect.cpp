// Curve evaluation, sub-curves and curve-curve crossings for the z-level contours
// (zlevel_detail.hpp).
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "kernels/geom/tolerance.hpp"
#include "kernels/scan/zlevel_detail.hpp"

namespace ncpath::zlevel_detail {

namespace {

// sin and cos of s / 2 (one call).
inline void sincos_half(double s, double& sn, double& cs) {
  sn = std::sin(0.5 * s);
  cs = std::cos(0.5 * s);
}

// B&B nodes per curve pair before the pair counts as coincident (identical ellipses).
constexpr int kMaxNodes = 20000;

double param_slack(const Curve& c) {
  return c.kind == CurveKind::kLine ? tol::kZLevelSlack
                                    : tol::kZLevelSlack / (c.e1.norm() + c.e2.norm());
}

bool in_range(const Curve& c, double& s) {
  const double sl = param_slack(c);
  if (s < -sl || s > c.len + sl) return false;
  s = std::clamp(s, 0.0, c.len);
  return true;
}

double hess_norm(const Curve& c) {
  return c.kind == CurveKind::kLine ? 0.0 : c.kind == CurveKind::kCircle ? 2.0 : 4.0;
}

// Stable roots of a t^2 + 2 b t + c = 0 (a > 0); returns their number.
int quadratic(double a, double b, double c, double t[2]) {
  const double disc = b * b - a * c;
  if (!(disc >= 0) || !(a > 0)) return 0;
  const double s = std::sqrt(disc);
  const double q = -(b + (b >= 0 ? s : -s));
  if (q == 0) {
    t[0] = 0;
    return 1;
  }
  t[0] = q / a;
  t[1] = c / q;
  return 2;
}

void add_hit(const Curve& C, const Curve& D, const Vec2& p, double sc, std::vector<Hit>& out) {
  double sd = curve_param(D, p);
  if (!in_range(C, sc) || !in_range(D, sd)) return;
  out.push_back({p, sc, sd});
}

// End points of each curve that lie inside the other's parameter range.
void coincident_hits(const Curve& C, const Curve& D, std::vector<Hit>& out) {
  for (const Vec2* p : {&D.a, &D.b}) {
    double sc = curve_param(C, *p);
    if (in_range(C, sc)) out.push_back({*p, sc, p == &D.a ? 0.0 : D.len});
  }
  for (const Vec2* p : {&C.a, &C.b}) {
    double sd = curve_param(D, *p);
    if (in_range(D, sd)) out.push_back({*p, p == &C.a ? 0.0 : C.len, sd});
  }
}

// Lines C and D lie on one line along the shorter one: both ends of one of them lie within
// tol::kZLevelOnBoundary of the other's line. Distances, not directions: the shadows of a
// wall's stacked edges (horizontal and sloping, of different lengths) lie on one line, but
// their directions, from different end points, differ by rounding (1e-14); such a
// near-crossing's place and orientation are noise, and pieces classified by them dropped each
// other in turn.
bool lines_coincident(const Curve& C, const Curve& D) {
  const double on = tol::kZLevelOnBoundary;
  auto near = [on](const Curve& L, const Vec2& p) {
    return std::abs(cross2(L.dir, p - L.a)) <= on;
  };
  return (near(D, C.a) && near(D, C.b)) || (near(C, D.a) && near(C, D.b));
}

void line_line(const Curve& C, const Curve& D, std::vector<Hit>& out, bool& coincident) {
  if (lines_coincident(C, D)) {
    coincident = true;
    coincident_hits(C, D, out);
    return;
  }
  const double denom = cross2(C.dir, D.dir);
  if (std::abs(denom) > tol::kZLevelParallel) {
    const double t = cross2(D.dir, C.a - D.a) / denom;
    add_hit(C, D, C.a + t * C.dir, t, out);
  }
  // T-junctions: an end of one line within 2 on of the other splits the other there too (a
  // touch: it carries no crossing orientation). A piece found along a line (its midpoint and
  // quarter points within `on` of it, classify_pieces) has its ends within 2 on of that line,
  // the distance being linear along a line. Without the split, the other line's piece runs on
  // past the end and is classified at a midpoint beyond it, away from this piece, and both
  // are kept (or neither). Nearly coincident lines make these: the shadow of a sloping wall
  // edge ending where it turns into its ellipse, beside the next edge's shadow, or a clip line
  // leaving its joint on an edge at a grazing angle of 1e-8 to a shadow line (a CAD wall in
  // float coordinates), whose crossing, uncertain by on / angle, lies just beyond the end.
  const double tj = 2 * tol::kZLevelOnBoundary;
  for (const Vec2* p : {&D.a, &D.b}) {
    double sc = (*p - C.a).dot(C.dir);
    if (std::abs(cross2(C.dir, *p - C.a)) <= tj && in_range(C, sc))
      out.push_back({*p, sc, p == &D.a ? 0.0 : D.len, true});
  }
  for (const Vec2* p : {&C.a, &C.b}) {
    double sd = (*p - D.a).dot(D.dir);
    if (std::abs(cross2(D.dir, *p - D.a)) <= tj && in_range(D, sd))
      out.push_back({*p, p == &C.a ? 0.0 : C.len, sd, true});
  }
}

// C a line, D a conic: the conic's implicit along the line is a quadratic in t.
void line_conic(const Curve& C, const Curve& D, const Level& lv, std::vector<Hit>& out) {
  double a, b, c;
  if (D.kind == CurveKind::kCircle) {
    const Vec2 w = C.a - D.centre;
    a = 1;
    b = w.dot(C.dir);
    c = (w.norm() - D.r1) * (w.norm() + D.r1);
  } else {
    const Vec3 w(C.a.x() - D.ax_p.x(), C.a.y() - D.ax_p.y(), lv.zc - D.ax_p.z());
    const Vec3 f0 = w.cross(D.ax_d), f1 = Vec3(C.dir.x(), C.dir.y(), 0).cross(D.ax_d);
    a = f1.squaredNorm();
    b = f0.dot(f1);
    c = (f0.norm() - D.r2) * (f0.norm() + D.r2);
  }
  double t[2];
  const int n = quadratic(a, b, c, t);
  for (int i = 0; i < n; ++i) add_hit(C, D, C.a + t[i] * C.dir, t[i], out);
}

void circle_circle(const Curve& C, const Curve& D, std::vector<Hit>& out, bool& coincident) {
  const Vec2 dv = D.centre - C.centre;
  const double dist = dv.norm();
  if (dist <= tol::kZLevelOnBoundary && std::abs(C.r1 - D.r1) <= tol::kZLevelOnBoundary) {
    coincident = true;
    coincident_hits(C, D, out);
    return;
  }
  if (!(dist > 0)) return;
  const double a = (C.r1 * C.r1 - D.r1 * D.r1 + dist * dist) / (2 * dist);
  const double h2 = (C.r1 - a) * (C.r1 + a);
  if (!(h2 >= 0)) return;
  const double h = std::sqrt(h2);
  const Vec2 e = dv / dist, base = C.centre + a * e;
  for (double sg : {1.0, -1.0}) {
    if (sg < 0 && h == 0) break;
    const Vec2 p = base + sg * h * perp(e);
    add_hit(C, D, p, curve_param(C, p), out);
  }
}

// Certified root isolation of F(s) = Q_D(P_C(s)) on [0, C.len] (C a conic): an interval is
// dropped when the bound |F(s) - F(m) - F'(m)(s - m)| <= M2 w^2 / 2 rules a zero out, a
// monotone interval (|F'(m)| > M2 w) is solved by Illinois regula falsi on a sign change,
// anything else is halved down to tol::kZLevelRootLength.
struct RootSearch {
  const Curve& C;
  const Curve& D;
  double zc, speed, hess, slack;
  int nodes = 0;
  std::vector<double>& roots;

  double F(double s) const { return curve_implicit(D, curve_point(C, s), zc); }

  void solve(double lo, double hi, double flo, double fhi) {
    for (int it = 0, side = 0; it < 100; ++it) {
      if ((hi - lo) * speed < tol::kZLevelRootPrecision) break;
      double m = (lo * fhi - hi * flo) / (fhi - flo);
      if (!(m > lo && m < hi)) m = 0.5 * (lo + hi);
      const double fm = F(m);
      if (fm == 0) {
        lo = hi = m;
        break;
      }
      if ((fm < 0) == (flo < 0)) {
        lo = m;
        flo = fm;
        if (side == -1) fhi *= 0.5;
        side = -1;
      } else {
        hi = m;
        fhi = fm;
        if (side == 1) flo *= 0.5;
        side = 1;
      }
    }
    roots.push_back(0.5 * (lo + hi));
  }

  void search(double lo, double hi, double flo, double fhi) {
    if (++nodes > kMaxNodes) return;
    const double m = 0.5 * (lo + hi), w = 0.5 * (hi - lo);
    Vec2 grad;
    const double fm = curve_implicit(D, curve_point(C, m), zc, &grad);
    const double fp = grad.dot(curve_tangent(C, m));
    const double m2 = hess * speed * speed + (grad.norm() + hess * speed * w) * speed;
    if (std::abs(fm) > std::abs(fp) * w + 0.5 * m2 * w * w + slack) return;
    const bool change = (flo <= 0) != (fhi < 0) || flo == 0 || fhi == 0;
    if (std::abs(fp) > m2 * w) {
      if (change) solve(lo, hi, flo, fhi);
      return;
    }
    if (speed * w < tol::kZLevelRootLength) {
      if (change) roots.push_back(m);
      return;
    }
    search(lo, m, flo, fm);
    search(m, hi, fm, fhi);
  }
};

// The length whose square scales the rounding of Q's implicit function at the points of P: a
// circle's diameter; for an ellipse (a cylinder around an edge), twice the largest distance
// from the cylinder's axis point to P's box at the level, plus the radius, since the implicit
// is computed from that difference. Not the ellipse's diameter: a nearly horizontal edge's
// ellipse is R / slope long (46 m at slope 6.5e-5), and a slack of its square kept every
// interval of a grazing crossing open until the search gave up and called the curves
// coincident.
double implicit_scale(const Curve& Q, const Curve& P, double zc) {
  if (Q.kind != CurveKind::kEllipse) return 2 * std::max(Q.r1, Q.r2);
  double far = 0;
  for (const double x : {P.box[0], P.box[2]})
    for (const double y : {P.box[1], P.box[3]})
      far = std::max(far, Vec3(x - Q.ax_p.x(), y - Q.ax_p.y(), zc - Q.ax_p.z()).norm());
  return 2 * (far + Q.r2);
}

void conic_conic(const Curve& C, const Curve& D, const Level& lv, std::vector<Hit>& out,
                 bool& coincident) {
  // Parametrise the slower curve (a circle, or the steeper edge's ellipse).
  const bool swap = curve_speed(D) < curve_speed(C);
  const Curve& P = swap ? D : C;
  const Curve& Q = swap ? C : D;
  const double scale = implicit_scale(Q, P, lv.zc);
  const double f0 = curve_implicit(Q, P.a, lv.zc), f1 = curve_implicit(Q, P.b, lv.zc);
  const double fm = curve_implicit(Q, curve_point(P, 0.5 * P.len), lv.zc);
  const double on = tol::kZLevelOnBoundary * scale;
  std::vector<double> roots;
  RootSearch rs{
      P, Q,    lv.zc, curve_speed(P), hess_norm(Q), tol::kZLevelImplicitRounding * scale * scale,
      0, roots};
  if (std::abs(f0) <= on && std::abs(f1) <= on && std::abs(fm) <= on) {
    rs.nodes = kMaxNodes + 1;
  } else {
    rs.search(0, P.len, f0, f1);
  }
  if (rs.nodes > kMaxNodes) {
    coincident = true;
    coincident_hits(C, D, out);
    return;
  }
  for (double s : roots) {
    const Vec2 p = s == 0 ? P.a : s == P.len ? P.b : curve_point(P, s);
    double sp = s, sq = curve_param(Q, p);
    if (!in_range(P, sp) || !in_range(Q, sq)) continue;
    out.push_back(swap ? Hit{p, sq, sp} : Hit{p, sp, sq});
  }
}

}  // namespace

Vec2 curve_point(const Curve& c, double s) {
  if (c.kind == CurveKind::kLine) return c.a + s * c.dir;
  double h, k;
  sincos_half(s, h, k);
  return c.a - (2 * h * h) * c.e1 + (2 * h * k) * c.e2;
}

Vec2 curve_tangent(const Curve& c, double s) {
  if (c.kind == CurveKind::kLine) return c.dir;
  return -std::sin(s) * c.e1 + std::cos(s) * c.e2;
}

double curve_speed(const Curve& c) {
  return c.kind == CurveKind::kLine ? 1.0 : c.e1.norm() + c.e2.norm();
}

double curve_curvature(const Curve& c, double s) {
  if (c.kind == CurveKind::kLine) return 0;
  const double sn = std::sin(s), cs = std::cos(s);
  const Vec2 d1 = -sn * c.e1 + cs * c.e2, d2 = -cs * c.e1 - sn * c.e2;
  const double v = d1.norm();
  return cross2(d1, d2) / (v * v * v);
}

double curve_param(const Curve& c, const Vec2& x) {
  const Vec2 w = x - c.a;
  if (c.kind == CurveKind::kLine) return w.dot(c.dir);
  // [e1 e2] (cos s - 1, sin s) = x - a. The solve is ill-conditioned for flat ellipses (e1, e2
  // nearly parallel); there Newton steps on (p(s) - x) . p'(s) = 0 refine it.
  const double det = cross2(c.e1, c.e2);
  const double cm = cross2(w, c.e2) / det, sn = cross2(c.e1, w) / det;
  double s = std::atan2(sn, 1 + cm);
  if (c.kind == CurveKind::kCircle || std::abs(det) > 0.25 * c.e1.norm() * c.e2.norm()) return s;
  for (int it = 0; it < 3; ++it) {
    double h, k;
    sincos_half(s, h, k);
    const double sn_s = 2 * h * k, cs_s = 1 - 2 * h * h;
    const Vec2 r = c.a - (2 * h * h) * c.e1 + sn_s * c.e2 - x;
    const Vec2 d1 = -sn_s * c.e1 + cs_s * c.e2, d2 = -cs_s * c.e1 - sn_s * c.e2;
    const double den = d1.squaredNorm() + r.dot(d2);
    if (!(den > 0)) break;
    const double step = r.dot(d1) / den;
    s -= step;
    if (std::abs(step) * d1.norm() < tol::kZLevelStep * (1 + w.norm())) break;
  }
  return s;
}

double curve_implicit(const Curve& c, const Vec2& x, double zc, Vec2* grad) {
  switch (c.kind) {
    case CurveKind::kLine:
      if (grad) *grad = perp(c.dir);
      return cross2(c.dir, x - c.a);
    case CurveKind::kCircle: {
      const Vec2 w = x - c.centre;
      if (grad) *grad = 2 * w;
      const double n = w.norm();
      return (n - c.r1) * (n + c.r1);
    }
    case CurveKind::kEllipse: {
      const Vec3 w(x.x() - c.ax_p.x(), x.y() - c.ax_p.y(), zc - c.ax_p.z());
      const Vec3 f = w.cross(c.ax_d);
      const Vec3& d = c.ax_d;
      if (grad) *grad = 2 * Vec2(f.dot(Vec3(0, -d.z(), d.y())), f.dot(Vec3(d.z(), 0, -d.x())));
      const double n = f.norm();
      return (n - c.r2) * (n + c.r2);
    }
  }
  return 0;
}

void finish_box(Curve& c) {
  c.box[0] = std::min(c.a.x(), c.b.x());
  c.box[1] = std::min(c.a.y(), c.b.y());
  c.box[2] = std::max(c.a.x(), c.b.x());
  c.box[3] = std::max(c.a.y(), c.b.y());
  if (c.kind != CurveKind::kLine) {
    // The arc (sweep <= pi / 2) lies in the triangle of its ends and its tangents' crossing.
    const Vec2 t = c.a + std::tan(0.5 * c.len) * c.e2;
    c.box[0] = std::min(c.box[0], t.x());
    c.box[1] = std::min(c.box[1], t.y());
    c.box[2] = std::max(c.box[2], t.x());
    c.box[3] = std::max(c.box[3], t.y());
  }
}

Curve sub_curve(const Curve& c, double s0, double s1) {
  if (s0 == 0 && s1 == c.len) return c;
  Curve r = c;
  r.a = s0 == 0 ? c.a : curve_point(c, s0);
  r.b = s1 == c.len ? c.b : curve_point(c, s1);
  r.len = s1 - s0;
  if (c.kind != CurveKind::kLine) {
    const double sn = std::sin(s0), cs = std::cos(s0);
    r.e1 = cs * c.e1 + sn * c.e2;
    r.e2 = -sn * c.e1 + cs * c.e2;
    r.t0 = c.t0 + s0;
  }
  finish_box(r);
  return r;
}

bool coincident_overlap(const Curve& C, const Curve& D, double& d0, double& d1) {
  if (C.kind != D.kind) return false;
  const double on = tol::kZLevelOnBoundary;
  if (C.kind == CurveKind::kLine) {
    if (!lines_coincident(C, D)) return false;  // the test of line_line
    const double ta = (C.a - D.a).dot(D.dir), tb = (C.b - D.a).dot(D.dir);
    d0 = std::max(0.0, std::min(ta, tb));
    d1 = std::min(D.len, std::max(ta, tb));
  } else if (C.kind == CurveKind::kCircle) {
    // The test of circle_circle. Arcs sweep at most pi / 2 counter-clockwise from angle t0.
    if ((D.centre - C.centre).norm() > on || std::abs(C.r1 - D.r1) > on) return false;
    const double delta = std::remainder(C.t0 - D.t0, 2 * std::numbers::pi);
    d0 = std::max(0.0, delta);
    d1 = std::min(D.len, delta + C.len);
  } else {
    return false;
  }
  return d1 > d0;
}

void intersect_curves(const Curve& C, const Curve& D, const Level& lv, std::vector<Hit>& out,
                      bool& coincident) {
  coincident = false;
  const bool lc = C.kind == CurveKind::kLine, ld = D.kind == CurveKind::kLine;
  if (lc && ld) return line_line(C, D, out, coincident);
  if (lc) return line_conic(C, D, lv, out);
  if (ld) {
    const std::size_t first = out.size();
    line_conic(D, C, lv, out);
    for (std::size_t i = first; i < out.size(); ++i) std::swap(out[i].sc, out[i].sd);
    return;
  }
  if (C.kind == CurveKind::kCircle && D.kind == CurveKind::kCircle)
    return circle_circle(C, D, out, coincident);
  conic_conic(C, D, lv, out, coincident);
}

}  // namespace ncpath::zlevel_detail
