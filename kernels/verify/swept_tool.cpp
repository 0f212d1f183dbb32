#include "kernels/verify/swept_tool.hpp"

#include <Eigen/Geometry>  // cross

#include <algorithm>
#include <cmath>
#include <limits>

namespace ncpath {

namespace {

// K relative to the move's first tip p0: the cylinder of radius a spanning heights [z0, z1]
// above the tip, swept along the segment [0, m].
struct SweptCore {
  Vec3 m;
  double a, z0, z1;
};

// The body that is verified: B(rho) + K.
struct Body {
  SweptCore core;
  double rho;  // corner radius plus stock, mm
};

double stock_of(const SweptTool& tool) { return std::max(0.0, tool.stock); }

bool is_sharp(const SweptTool& tool) {
  return tool.cutter.corner_radius + stock_of(tool) < tol::kVerifySharpCorner;
}

// Round tools: B(r + s) + K. Sharp tools: the cylinder of radius R + s spanning [-s, L + s]
// above the tip (rho = 0).
Body verified_body(const SweptTool& tool, const Vec3& p0, const Vec3& p1) {
  const double s = stock_of(tool), L = std::max(0.0, tool.shank);
  const double R = tool.cutter.radius, r = tool.cutter.corner_radius;
  Body b;
  b.core.m = p1 - p0;
  if (is_sharp(tool)) {
    b.core.a = R + s;
    b.core.z0 = -s;
    b.core.z1 = L + s;
    b.rho = 0;
  } else {
    b.core.a = std::max(0.0, R - r);
    b.core.z0 = r;
    b.core.z1 = r + L;
    b.rho = r + s;
  }
  return b;
}

// Support point of K in direction d: the segment's end plus the cylinder's rim or axis point.
Vec3 support_core(const SweptCore& k, const Vec3& d) {
  Vec3 p(0, 0, d.z() > 0 ? k.z1 : k.z0);
  if (d.dot(k.m) > 0) p += k.m;
  const double h2 = d.x() * d.x() + d.y() * d.y();
  if (k.a > 0 && h2 > 0) {
    const double f = k.a / std::sqrt(h2);
    p.x() += f * d.x();
    p.y() += f * d.y();
  }
  return p;
}

const Vec3& support_triangle(const Vec3 t[3], const Vec3& d) {
  const double d0 = d.dot(t[0]), d1 = d.dot(t[1]), d2 = d.dot(t[2]);
  if (d0 >= d1 && d0 >= d2) return t[0];
  return d1 >= d2 ? t[1] : t[2];
}

// Support point of the Minkowski difference D = triangle - K in direction d.
Vec3 support_difference(const Vec3 t[3], const SweptCore& k, const Vec3& d) {
  return support_triangle(t, d) - support_core(k, -d);
}

// ---- Nearest point of a simplex (1 to 4 points of D) to the origin ----
// Every candidate is built as a convex combination of the simplex's points, so rounding can
// make it a little less than nearest but never a point outside D: GJK's upper bound stays a
// real distance.

struct Nearest {
  Vec3 x;
  unsigned mask;  // bit i set: point i is in the smallest face containing x
};

void keep_nearer(Nearest& best, const Nearest& c) {
  if (c.x.squaredNorm() < best.x.squaredNorm()) best = c;
}

Nearest nearest_on_segment(const Vec3* p, int i, int j) {
  const Vec3 ab = p[j] - p[i];
  const double den = ab.squaredNorm(), t = -p[i].dot(ab);
  if (!(den > 0) || t <= 0) return {p[i], 1u << i};
  if (t >= den) return {p[j], 1u << j};
  return {p[i] + ab * (t / den), (1u << i) | (1u << j)};
}

Nearest nearest_on_triangle(const Vec3* p, int i, int j, int k) {
  // Barycentric coordinates of the origin's projection are the triple products n.(q x r).
  const Vec3 n = (p[j] - p[i]).cross(p[k] - p[i]);
  const double li = n.dot(p[j].cross(p[k])), lj = n.dot(p[k].cross(p[i]));
  const double lk = n.dot(p[i].cross(p[j]));
  if (li > 0 && lj > 0 && lk > 0) {
    const double sum = li + lj + lk;
    return {(li * p[i] + lj * p[j] + lk * p[k]) / sum, (1u << i) | (1u << j) | (1u << k)};
  }
  Nearest best = nearest_on_segment(p, i, j);
  keep_nearer(best, nearest_on_segment(p, j, k));
  keep_nearer(best, nearest_on_segment(p, k, i));
  return best;
}

double volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return (b - a).dot((c - a).cross(d - a));
}

Nearest nearest_on_tetrahedron(const Vec3* p) {
  const Vec3 o = Vec3::Zero();
  const double v = volume(p[0], p[1], p[2], p[3]);
  const double w[4] = {volume(o, p[1], p[2], p[3]), volume(p[0], o, p[2], p[3]),
                       volume(p[0], p[1], o, p[3]), volume(p[0], p[1], p[2], o)};
  if (v != 0 && w[0] * v >= 0 && w[1] * v >= 0 && w[2] * v >= 0 && w[3] * v >= 0)
    return {o, 0xFu};  // the origin is inside: the sets overlap
  // Otherwise the nearest point lies on the boundary: the best of the four faces (all of
  // them, so that a flat tetrahedron needs no special case).
  Nearest best = nearest_on_triangle(p, 0, 1, 2);
  keep_nearer(best, nearest_on_triangle(p, 0, 1, 3));
  keep_nearer(best, nearest_on_triangle(p, 0, 2, 3));
  keep_nearer(best, nearest_on_triangle(p, 1, 2, 3));
  return best;
}

struct Simplex {
  Vec3 p[4];
  int n = 0;

  bool contains(const Vec3& w) const {
    for (int i = 0; i < n; ++i)
      if (p[i] == w) return true;
    return false;
  }
  Nearest nearest() const {
    switch (n) {
      case 1:
        return {p[0], 1u};
      case 2:
        return nearest_on_segment(p, 0, 1);
      case 3:
        return nearest_on_triangle(p, 0, 1, 2);
      default:
        return nearest_on_tetrahedron(p);
    }
  }
  void keep(unsigned mask) {
    int m = 0;
    for (int i = 0; i < n; ++i)
      if (mask & (1u << i)) p[m++] = p[i];
    n = m;
  }
};

struct Distance {
  double upper = 0;       // |v|: distance between a point of the triangle and one of K, mm
  double lower = 0;       // from GJK's support planes: no two points are closer, mm
  Vec3 v = Vec3::Zero();  // that point of D = triangle - K (from K towards the triangle)
};

// GJK distance between the triangle t and K. Stops when the support-plane lower bound is
// within kGjkDistance of |v|, when |v|^2 shrinks by less than the fraction kGjkProgress
// (rounding: at a tiny distance from a large flat face of D the plane's tilt keeps the lower
// bound loose, while |v| is exact to ~1e-15 mm), when the support point repeats, or at the
// iteration cap.
Distance gjk_distance(const Vec3 t[3], const SweptCore& k) {
  Simplex s;
  s.p[0] = t[0] - Vec3(0, 0, k.z0);  // a point of D: a vertex minus the bottom centre
  s.n = 1;
  Distance r;
  r.v = s.p[0];
  double vv = r.v.squaredNorm();
  for (int it = 0; it < tol::kGjkMaxIterations && vv > 0; ++it) {
    const double vn = std::sqrt(vv);
    const Vec3 w = support_difference(t, k, -r.v);
    r.lower = std::max(r.lower, r.v.dot(w) / vn);
    if (vn - r.lower <= tol::kGjkDistance || s.contains(w)) break;
    s.p[s.n++] = w;
    const Nearest c = s.nearest();
    const double cc = c.x.squaredNorm();
    if (!(cc < vv * (1 - tol::kGjkProgress))) {  // no real progress: rounding
      if (cc < vv) {
        r.v = c.x;
        vv = cc;
      }
      break;
    }
    s.keep(c.mask);
    r.v = c.x;
    vv = cc;
  }
  r.upper = std::sqrt(vv);
  r.lower = std::min(r.lower, r.upper);
  return r;
}

// ---- Lift search ----

// f(h) = dist(triangle, K raised by h) - threshold through GJK's distance (f_up >= f, equal
// up to rounding) and its slope -v_z / |v| (f is convex in h).
struct Probe {
  double f_up;
  double nz;  // z of the unit vector from K towards the triangle; 0 when they meet
};

Probe probe(const Vec3 t[3], const SweptCore& k, double threshold, double h) {
  const Vec3 dz(0, 0, h);
  const Vec3 th[3] = {t[0] - dz, t[1] - dz, t[2] - dz};
  const Distance d = gjk_distance(th, k);
  return {d.upper - threshold, d.upper > 0 ? d.v.z() / d.upper : 0.0};
}

// Gap of the round tool raised by h: dist(t, K) - rho, with t relative to p0.
double round_gap(const Body& b, const Vec3 t[3], double h) {
  const Vec3 dz(0, 0, h);
  const Vec3 th[3] = {t[0] - dz, t[1] - dz, t[2] - dz};
  return gjk_distance(th, b.core).upper - b.rho;
}

// The smallest h >= h_cut at which the round tool raised by h does not cut into the triangle
// t (relative to p0), given that it cuts at h_cut, where its gap is gap_cut (< -contact).
SweptGouge lift_round(const SweptTool& tool, const Body& b, const Vec3 t[3], double h_cut,
                      double gap_cut, double resolution) {
  const double threshold = b.rho - tol::kVerifyContact;  // clear: distance >= threshold
  SweptGouge out;
  auto eval = [&](double h) {
    ++out.gjk_calls;
    return probe(t, b.core, threshold, h);
  };
  double lo = h_cut;                                          // the lift is in [lo, hi]
  double lo_h = h_cut, lo_f = gap_cut + tol::kVerifyContact;  // a cutting height, f there < 0

  // Raised so that its lowest point (tip - stock) reaches the triangle's top, the body is
  // rho from it: clear. Grown further only if rounding says otherwise.
  const double top = std::max({t[0].z(), t[1].z(), t[2].z()});
  const double bottom = std::min(0.0, b.core.m.z()) - std::max(0.0, tool.stock);
  double hi = std::max(h_cut, top - bottom) + resolution;
  Probe at_hi = eval(hi);
  for (int k = 0; at_hi.f_up < 0 && k < 16; ++k) {
    hi += std::max(hi - lo, resolution);
    at_hi = eval(hi);
  }

  while (hi - lo > resolution && out.gjk_calls < tol::kLiftMaxSteps) {
    // f is convex: the chord through (lo_h, f) and (hi, f) lies above it, so the chord's
    // zero is at or below the lift.
    if (at_hi.f_up >= 0) lo = std::max(lo, lo_h + (-lo_f) * (hi - lo_h) / (at_hi.f_up - lo_f));
    if (hi - lo <= resolution) break;
    // Newton's step from above lands at or above the lift (convex f) but for rounding: when
    // it reaches the lower bound the lift is there (confirm just above it); else take it if
    // it shrinks the bracket by a quarter at least, bisect otherwise.
    double next = 0.5 * (lo + hi);
    if (at_hi.nz < 0 && at_hi.f_up > 0) {
      const double newton = hi - at_hi.f_up / -at_hi.nz;
      if (newton <= lo + 0.5 * resolution) {
        next = lo + 0.5 * resolution;
      } else if (hi - newton >= 0.25 * (hi - lo)) {
        next = newton;
      }
    }
    const Probe p = eval(next);
    if (p.f_up >= 0) {
      hi = next;
      at_hi = p;
    } else {
      lo = next;
      lo_h = next;
      lo_f = p.f_up;
    }
  }
  out.gouge = hi;
  return out;
}

// ---- Sharp tools: g = (triangle point's height above the tip) over the swept disc ----

// A point of the prism triangle x [0, 1] seen from the tool: y is the triangle point's
// horizontal offset from the axis at time t, g its height above the tip.
struct Image {
  Eigen::Vector2d y;
  double g;
};

// The range [lo, hi] of g over the prism points whose |y| <= radius (empty: lo > hi).
class SharpRange {
 public:
  explicit SharpRange(double radius)
      : r2_(radius * radius), r2_slack_(r2_ * (1 + tol::kSharpRimSlack)), radius_(radius) {}

  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();

  void vertex(const Image& a) {
    if (a.y.squaredNorm() <= r2_) add(a.g);
  }

  // Crossings of |y| = radius along a -> b.
  void edge(const Image& a, const Image& b) {
    const Eigen::Vector2d d = b.y - a.y;
    const double dd = d.squaredNorm(), yd = a.y.dot(d), c = a.y.squaredNorm() - r2_;
    if (!(dd > 0)) return;
    const double disc = yd * yd - dd * c;
    if (disc < 0) return;
    const double q = -(yd + std::copysign(std::sqrt(disc), yd));
    point_on_edge(a, b, q / dd);
    if (q != 0) point_on_edge(a, b, c / q);
  }

  // Tangent points of g's level lines with |y| = radius on the face o + al d1 + be d2
  // (al, be >= 0 and al + be <= 1 for a triangle, al, be in [0, 1] for a parallelogram).
  void face(const Image& o, const Image& d1, const Image& d2, bool triangle) {
    const double det = d1.y.x() * d2.y.y() - d1.y.y() * d2.y.x();
    if (!(std::abs(det) > 0)) return;  // the face maps to a line: its edges hold the extremes
    // On the face g = o.g + w . (y - o.y) with w = M^-T (d1.g, d2.g), M = [d1.y d2.y].
    const Eigen::Vector2d w((d2.y.y() * d1.g - d1.y.y() * d2.g) / det,
                            (-d2.y.x() * d1.g + d1.y.x() * d2.g) / det);
    const double wn = w.norm();
    if (!(wn > 0)) return;
    for (double sign : {1.0, -1.0}) {
      const Eigen::Vector2d e = sign * radius_ / wn * w - o.y;
      double al = (d2.y.y() * e.x() - d2.y.x() * e.y()) / det;
      double be = (-d1.y.y() * e.x() + d1.y.x() * e.y()) / det;
      if (!(al >= 0 && be >= 0 && (triangle ? al + be <= 1 : al <= 1 && be <= 1))) continue;
      feasible(o.y + al * d1.y + be * d2.y, o.g + al * d1.g + be * d2.g);
    }
  }

 private:
  void add(double g) {
    lo = std::min(lo, g);
    hi = std::max(hi, g);
  }
  void feasible(const Eigen::Vector2d& y, double g) {
    if (y.squaredNorm() <= r2_slack_) add(g);
  }
  void point_on_edge(const Image& a, const Image& b, double s) {
    if (!(s >= 0 && s <= 1)) return;
    feasible(a.y + s * (b.y - a.y), a.g + s * (b.g - a.g));
  }

  double r2_, r2_slack_, radius_;
};

Image operator-(const Image& a, const Image& b) { return {a.y - b.y, a.g - b.g}; }

// The range of heights above the tip of the triangle points (t relative to p0) that the disc
// of the given radius passes under along the move m. A linear function over a convex set
// (the prism cut by the quadratic constraint) is extreme at the prism's vertices inside it,
// at its edges' crossings of the constraint, or at a tangent point inside a face: nothing
// else (inside the prism the constraint is a cylinder along the map's kernel, on which a
// linear function has no extreme unless it is constant along it, reaching the faces).
SharpRange sharp_range(const Vec3 t[3], const Vec3& m, double radius) {
  Image v[3][2];
  for (int k = 0; k < 3; ++k)
    for (int s = 0; s < 2; ++s) {
      const Vec3 p = t[k] - s * m;
      v[k][s] = {Eigen::Vector2d(p.x(), p.y()), p.z()};
    }
  SharpRange range(radius);
  for (int k = 0; k < 3; ++k) {
    const int n = (k + 1) % 3;
    for (int s = 0; s < 2; ++s) {
      range.vertex(v[k][s]);
      range.edge(v[k][s], v[n][s]);
    }
    range.edge(v[k][0], v[k][1]);
    range.face(v[k][0], v[n][0] - v[k][0], v[k][1] - v[k][0], false);
  }
  for (int s = 0; s < 2; ++s) range.face(v[0][s], v[1][s] - v[0][s], v[2][s] - v[0][s], true);
  return range;
}

// A sharp tool (shrunk by kVerifyContact) cuts when some triangle point under its disc lies
// strictly between its bottom and its top: the deepest such point's depth below the
// unshrunk bottom, or 0 when it does not cut.
double sharp_depth(const SweptTool& tool, const Vec3 t[3], const Vec3& m) {
  const double s = stock_of(tool), L = std::max(0.0, tool.shank), c = tol::kVerifyContact;
  const SharpRange range = sharp_range(t, m, tool.cutter.radius + s - c);
  if (range.lo > range.hi) return 0;
  const bool cuts = range.hi + s > c && range.lo < L + s - c;
  return cuts ? range.hi + s : 0;
}

}  // namespace

double swept_gap(const SweptTool& tool, const Vec3& p0, const Vec3& p1, const Vec3& t0,
                 const Vec3& t1, const Vec3& t2) {
  const Body b = verified_body(tool, p0, p1);
  const Vec3 t[3] = {t0 - p0, t1 - p0, t2 - p0};
  if (is_sharp(tool)) {
    const double depth = sharp_depth(tool, t, b.core.m);
    if (depth > 0) return -depth;
  }
  return round_gap(b, t, 0);
}

namespace {

// What swept_gouge_above() decides before it measures the lift: `gouges` tells whether the
// gouge exceeds the floor; for round tools `gap_floor` is the gap of the move raised by the
// floor, for sharp ones `sharp` is the gouge itself.
struct GougeDecision {
  bool gouges = false;
  double gap_floor = 0, sharp = 0;
  int gjk_calls = 0;
};

GougeDecision decide_gouge(const SweptTool& tool, const Body& b, const Vec3 t[3], double floor) {
  GougeDecision d;
  if (is_sharp(tool)) {
    d.sharp = sharp_depth(tool, t, b.core.m) - tol::kVerifyContact;
    d.gouges = d.sharp > floor;
    return d;
  }
  const double cut = -tol::kVerifyContact;
  ++d.gjk_calls;
  d.gap_floor = round_gap(b, t, floor);
  if (d.gap_floor >= cut) return d;  // raised by floor it does not cut: gouge <= floor
  if (floor > 0) {
    ++d.gjk_calls;
    if (round_gap(b, t, 0) >= cut) return d;  // it does not cut where it is
  }
  d.gouges = true;  // the cutting heights reach from 0 past the floor: the lift exceeds it
  return d;
}

}  // namespace

SweptGouge swept_gouge_above(const SweptTool& tool, const Vec3& p0, const Vec3& p1, const Vec3& t0,
                             const Vec3& t1, const Vec3& t2, double floor, double resolution) {
  const Body b = verified_body(tool, p0, p1);
  const Vec3 t[3] = {t0 - p0, t1 - p0, t2 - p0};
  const GougeDecision d = decide_gouge(tool, b, t, floor);
  SweptGouge out;
  out.gjk_calls = d.gjk_calls;
  if (!d.gouges) return out;
  if (is_sharp(tool)) {
    out.gouge = d.sharp;
    return out;
  }
  const SweptGouge lift = lift_round(tool, b, t, floor, d.gap_floor, resolution);
  out.gjk_calls += lift.gjk_calls;
  if (lift.gouge > floor) out.gouge = lift.gouge;
  return out;
}

SweptGouge swept_gouges_above(const SweptTool& tool, const Vec3& p0, const Vec3& p1,
                              const Vec3& t0, const Vec3& t1, const Vec3& t2, double floor) {
  const Body b = verified_body(tool, p0, p1);
  const Vec3 t[3] = {t0 - p0, t1 - p0, t2 - p0};
  const GougeDecision d = decide_gouge(tool, b, t, floor);
  return {d.gouges ? 1.0 : 0.0, d.gjk_calls};
}

double swept_gouge(const SweptTool& tool, const Vec3& p0, const Vec3& p1, const Vec3& t0,
                   const Vec3& t1, const Vec3& t2, double resolution) {
  return swept_gouge_above(tool, p0, p1, t0, t1, t2, 0, resolution).gouge;
}

Cutter swept_profile(const SweptTool& tool) {
  const double s = stock_of(tool);
  Cutter c = tool.cutter;
  c.radius += s;
  c.corner_radius = is_sharp(tool) ? 0.0 : c.corner_radius + s;
  if (c.corner_radius == 0) c.type = CutterType::kFlat;
  return c;
}

double swept_plane_gap(const SweptTool& tool, const Vec3& p0, const Vec3& p1, const Vec3& n,
                       double d_lo, double d_hi) {
  const Body b = verified_body(tool, p0, p1);
  // Extent of K along n: the segment's ends, the cylinder's rim and its two heights (a ball's
  // cylinder is its axis: no rim, and no hypot, dear in a check's inner loop).
  const double rim = b.core.a > 0 ? b.core.a * std::hypot(n.x(), n.y()) : 0.0;
  const double z_lo = std::min(n.z() * b.core.z0, n.z() * b.core.z1);
  const double z_hi = std::max(n.z() * b.core.z0, n.z() * b.core.z1);
  const double seg = n.dot(b.core.m), base = n.dot(p0);
  const double lo = base + std::min(0.0, seg) + z_lo - rim;
  const double hi = base + std::max(0.0, seg) + z_hi + rim;
  return std::max(lo - d_hi, d_lo - hi) - b.rho;
}

}  // namespace ncpath
