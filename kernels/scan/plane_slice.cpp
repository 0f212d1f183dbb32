#include "kernels/scan/plane_slice.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>

namespace ncpath {

const char* piece_kind_name(PieceKind kind) {
  switch (kind) {
    case PieceKind::kFacetLine:
      return "facet-line";
    case PieceKind::kSphereArc:
      return "sphere-arc";
    case PieceKind::kCylinderEllipse:
      return "cylinder-ellipse";
    case PieceKind::kCylinderLine:
      return "cylinder-line";
    case PieceKind::kCylinderCircle:
      return "cylinder-circle";
    case PieceKind::kFloor:
      return "floor";
  }
  return "?";
}

namespace {

// Upper root w (centre z - A.z) of "distance from (x, y0, A.z + w) to the axis through A
// along u = R": a w^2 - 2 b w + c = 0 with a = ux^2 + uy^2 (> 0: not vertical),
// b = uz (p ux + q uy), c = p^2 + q^2 - (p ux + q uy)^2 - R^2, p = x - A.x, q = y0 - A.y.
// Its discriminant simplifies to b^2 - a c = a R^2 - (uy p - ux q)^2. `ok` is false when
// the line x = const misses the cylinder.
double cylinder_upper_w(const Vec3& A, const Vec3& u, double R, double x, double y0, bool& ok) {
  const double p = x - A.x(), q = y0 - A.y();
  const double a = u.x() * u.x() + u.y() * u.y();
  const double e = u.y() * p - u.x() * q;
  const double disc = a * R * R - e * e;
  ok = disc >= 0;
  const double s = std::sqrt(std::max(0.0, disc));
  const double g = p * u.x() + q * u.y();
  const double b = u.z() * g;
  if (b >= 0) return (b + s) / a;
  // b < 0: (b + s) cancels when s is near -b; the product of the roots, c / a, gives the
  // upper one as c / (b - s). But c carries a rounding of eps (p^2 + q^2 + g^2 + R^2), which
  // that quotient magnifies when b and s both vanish (a nearly horizontal edge at the ends
  // of its section: 3.3 mm off on a generated part); there the direct form errs by at most
  // eps (|b| + s) / a. The form with the smaller error bound is used.
  const double c = p * p + q * q - g * g - R * R;
  const double size = s - b;  // |b| + s
  if (size * size <= a * (p * p + q * q + g * g + R * R)) return (b + s) / a;
  return c / (b - s);
}

double sphere_centre_z(const SlicePiece& pc, double x) {
  const Vec3& v = pc.point;
  const double d = v.y() - pc.y0, dx = x - v.x();
  const double r2 = (pc.radius - d) * (pc.radius + d);
  return v.z() + std::sqrt(std::max(0.0, r2 - dx * dx));
}

void slice_facet(const OffsetElements& el, std::uint32_t f, double y0,
                 std::vector<SlicePiece>& out) {
  if (el.facet_vertical[f]) return;
  const auto t = el.offset_tri(f);
  double lo = INFINITY, hi = -INFINITY;
  for (int k = 0; k < 3; ++k) {
    const Vec3 &a = t[k], &b = t[(k + 1) % 3];
    if (a.y() == y0) {
      lo = std::min(lo, a.x());
      hi = std::max(hi, a.x());
    }
    if ((a.y() < y0 && b.y() > y0) || (a.y() > y0 && b.y() < y0)) {
      // From the lower end: the two facets of an edge get the same x to the last bit, so
      // coplanar neighbours (one offset normal, tol::kCoplanarSine) leave no sliver.
      const Vec3 &p = a.y() < b.y() ? a : b, &q = a.y() < b.y() ? b : a;
      const double x = p.x() + (y0 - p.y()) / (q.y() - p.y()) * (q.x() - p.x());
      lo = std::min(lo, x);
      hi = std::max(hi, x);
    }
  }
  if (!(lo < hi)) return;
  SlicePiece pc;
  pc.kind = PieceKind::kFacetLine;
  pc.element = f;
  pc.x0 = lo;
  pc.x1 = hi;
  pc.y0 = y0;
  pc.radius = el.radius;
  pc.point = t[0];
  pc.dir = el.facet_normal[f];
  out.push_back(pc);
}

// Emits the runs of consecutive valid intervals between sorted breakpoints bp[0..nb) as
// pieces (copies of `proto` with their x range). state(x) at an interval's midpoint: 0 no
// section there, 1 trimmed away (the ball would cut into a facet), 2 kept. A run is grown by
// tol::kTrimExtend into a neighbouring trimmed interval, so that a trimmed end never leaves
// a sliver next to the piece that takes over there (outside its kept part a piece lies
// below the envelope, so growing it never changes the envelope).
template <class State>
void emit_runs(const double* bp, int nb, const SlicePiece& proto, State&& state,
               std::vector<SlicePiece>& out) {
  SlicePiece pc = proto;
  int prev = 0;  // state of the interval before the open run
  bool open = false;
  for (int i = 0; i + 1 < nb; ++i) {
    const double x0 = bp[i], x1 = bp[i + 1];
    if (!(x0 < x1)) continue;
    const int st = state(0.5 * (x0 + x1));
    if (st == 2) {
      if (!open) {
        pc.x0 = prev == 1 ? std::max(x0 - tol::kTrimExtend, bp[i - 1]) : x0;
        open = true;
      }
      pc.x1 = x1;
    } else {
      if (open) {
        if (st == 1) pc.x1 = std::min(pc.x1 + tol::kTrimExtend, x1);
        out.push_back(pc);
        open = false;
      }
      prev = st;
    }
  }
  if (open) out.push_back(pc);
}

void sort_small(double* bp, int nb) {
  for (int i = 1; i < nb; ++i)
    for (int j = i; j > 0 && bp[j] < bp[j - 1]; --j) std::swap(bp[j], bp[j - 1]);
}

void slice_sphere(const OffsetElements& el, std::uint32_t v, double y0, bool trim,
                  std::vector<SlicePiece>& out) {
  const Vec3& c = el.points[el.vertex_source[v]];
  const double R = el.radius, d = c.y() - y0;
  if (!(std::abs(d) < R)) return;
  const double r = std::sqrt((R - d) * (R + d));
  SlicePiece pc;
  pc.kind = PieceKind::kSphereArc;
  pc.element = el.vertex_id(v);
  pc.x0 = c.x() - r;
  pc.x1 = c.x() + r;
  pc.y0 = y0;
  pc.radius = R;
  pc.point = c;
  if (!(pc.x0 < pc.x1)) return;
  const std::uint32_t r0 = trim && !el.ring_offsets.empty() ? el.ring_offsets[v] : 0;
  const std::uint32_t r1 = trim && !el.ring_offsets.empty() ? el.ring_offsets[v + 1] : 0;
  if (r0 == r1) {
    out.push_back(pc);
    return;
  }
  // Keep the arc where the contact direction p - c satisfies (p - c) . w <= 0 for every ring
  // direction w: in the plane, X wx + Z wz <= k with X = x - c.x, Z = z - c.z, k = d wy.
  // Two breakpoints per ring point: every one is needed (a vertex of a CAD fan has dozens;
  // leaving some out decided whole stretches of the arc at one midpoint, and kept arcs were
  // lost). Small rings use the stack, larger ones the heap.
  constexpr std::size_t kInlineBp = 2 + 2 * 16;
  std::array<double, kInlineBp> inline_bp;
  std::vector<double> heap_bp;
  double* bp = inline_bp.data();
  if (const std::size_t need = 2 + 2 * std::size_t(r1 - r0); need > kInlineBp) {
    heap_bp.resize(need);
    bp = heap_bp.data();
  }
  int nb = 0;
  bp[nb++] = pc.x0;
  bp[nb++] = pc.x1;
  const double slack = (el.vertex_flat[v] ? tol::kFlatTrimSlack : tol::kTrimSlack) * R;
  for (std::uint32_t k = r0; k < r1; ++k) {
    const Vec3 w = el.points[el.ring[k]] - c;
    const double wl = w.norm(), h = std::hypot(w.x(), w.z());
    const double kk = d * w.y() + slack * wl;
    if (!(h > 1e-12 * wl)) {
      if (-kk > 0) return;  // the whole section cuts into this facet side
      continue;
    }
    const double dist = kk / h;
    if (!(std::abs(dist) < r)) continue;
    const double t = std::sqrt((r - dist) * (r + dist));
    const double X0 = dist * w.x() / h;
    bp[nb++] = c.x() + X0 - t * w.z() / h;
    bp[nb++] = c.x() + X0 + t * w.z() / h;
  }
  sort_small(bp, nb);
  auto state = [&](double x) {
    const double X = x - c.x(), Z = std::sqrt(std::max(0.0, r * r - X * X));
    for (std::uint32_t k = r0; k < r1; ++k) {
      const Vec3 w = el.points[el.ring[k]] - c;
      if (X * w.x() - d * w.y() + Z * w.z() > slack * w.norm()) return 1;
    }
    return 2;
  };
  emit_runs(bp, nb, pc, state, out);
}

void slice_cylinder(const OffsetElements& el, std::uint32_t e, double y0, bool trim,
                    std::vector<SlicePiece>& out) {
  const auto& ev = el.edge_vertices[e];
  const Vec3& A = el.points[ev[0]];
  const Vec3 d = el.points[ev[1]] - A;
  const double L = d.norm();
  if (!(L > 0)) return;
  const Vec3 u = d / L;
  const double a = u.x() * u.x() + u.y() * u.y();
  if (std::sqrt(a) < tol::kVerticalEdge) return;
  const double R = el.radius, q = y0 - A.y();

  // Candidate x breakpoints: the ends of the x range of the infinite cylinder's section
  // (|uy p - ux q| <= R sqrt(a)) and the points where the section crosses the end planes
  // t = 0 and t = L (on the circles of radius R around A and B perpendicular to u). The
  // valid set is a union of intervals between consecutive breakpoints.
  std::array<double, 10> bp;
  int nb = 0;
  const std::array<Vec3, 2>* wedge =
      trim && !el.edge_wedge.empty() && !el.edge_wedge[e][0].isZero() ? &el.edge_wedge[e] : nullptr;
  if (u.y() != 0) {
    const double h = R * std::sqrt(a);
    const double p0 = (u.x() * q - h) / u.y(), p1 = (u.x() * q + h) / u.y();
    bp[nb++] = A.x() + p0;
    bp[nb++] = A.x() + p1;
  }
  const double exz = std::sqrt(u.x() * u.x() + u.z() * u.z());  // |u x e_y|
  if (exz > 0) {
    const Vec3 e1 = Vec3(-u.z(), 0, u.x()) / exz;  // horizontal, perpendicular to u and y
    const Vec3 e2 = u.cross(e1);                   // e2.y = +-exz
    // The caps are pushed out by tol::kTrimExtend (points there are within 1e-19 mm of the
    // end sphere), so that collinear cylinders of a straight edge line overlap instead of
    // leaving a rounding sliver where the vertex sphere between them is dropped.
    for (double tau : {-tol::kTrimExtend, L + tol::kTrimExtend}) {
      const double sn = (q - tau * u.y()) / (R * e2.y());
      if (!(std::abs(sn) <= 1)) continue;
      const double cs = std::sqrt((1 - sn) * (1 + sn));
      for (double c : {cs, -cs}) bp[nb++] = A.x() + tau * u.x() + R * (c * e1.x() + sn * e2.x());
    }
  }
  // The wedge's sides (planes through the axis perpendicular to w1, w2) meet the plane in
  // lines through the axis point o; where they cross the section ellipse the kept part may
  // start or end. (An axis parallel to the plane gives a line whose contact direction is
  // constant: nothing to add.)
  if (wedge && u.y() != 0) {
    const Vec3 o = A + u * (q / u.y());
    const double M = R / std::abs(u.y());
    Vec2 ax(u.x(), u.z());
    ax = ax.norm() > 0 ? Vec2(ax / ax.norm()) : Vec2(1, 0);
    const Vec2 bx(-ax.y(), ax.x());
    // Side i in the plane: n . (p - o) = slack with n = (w.x, w.z); on the ellipse
    // p - o = M cos(th) a + R sin(th) b this is P cos(th) + Q sin(th) = slack.
    const double side = (el.edge_flat[e] ? tol::kFlatTrimSlack : tol::kTrimSlack) * R;
    for (const Vec3& w : *wedge) {
      const Vec2 n(w.x(), w.z());
      const double P = M * n.dot(ax), Q = R * n.dot(bx), H = std::hypot(P, Q);
      if (!(H > 1e-12 * R) || !(std::abs(side) <= H)) continue;
      const double phi = std::atan2(Q, P), delta = std::acos(side / H);
      for (double th : {phi - delta, phi + delta})
        bp[nb++] = o.x() + M * std::cos(th) * ax.x() + R * std::sin(th) * bx.x();
    }
  }
  if (nb < 2) return;
  sort_small(bp.data(), nb);

  PieceKind kind = PieceKind::kCylinderEllipse;
  if (u.x() == 0 && u.z() == 0)
    kind = PieceKind::kCylinderCircle;
  else if (u.y() == 0)
    kind = PieceKind::kCylinderLine;
  SlicePiece pc;
  pc.kind = kind;
  pc.element = el.edge_id(e);
  pc.y0 = y0;
  pc.radius = R;
  pc.point = A;
  pc.dir = u;
  pc.length = L;
  const double slack = (el.edge_flat[e] ? tol::kFlatTrimSlack : tol::kTrimSlack) * R;
  auto state = [&](double xm) {
    bool ok;
    const double w = cylinder_upper_w(A, u, R, xm, y0, ok);
    const double t = (xm - A.x()) * u.x() + q * u.y() + w * u.z();
    if (!(ok && t >= -tol::kTrimExtend && t <= L + tol::kTrimExtend)) return 0;
    if (wedge) {
      const Vec3 pa(xm - A.x(), q, w);
      if (pa.dot((*wedge)[0]) > slack || pa.dot((*wedge)[1]) > slack) return 1;
    }
    return 2;
  };
  emit_runs(bp.data(), nb, pc, state, out);
}

}  // namespace

SlicePiece floor_piece(double floor_z, double radius, double y0, double x0, double x1) {
  SlicePiece pc;
  pc.kind = PieceKind::kFloor;
  pc.element = kNoElement;
  pc.x0 = x0;
  pc.x1 = x1;
  pc.y0 = y0;
  pc.radius = radius;
  pc.point = Vec3(0, 0, floor_z + radius);
  pc.dir = Vec3(0, 0, 1);
  return pc;
}

bool is_linear(const SlicePiece& pc) {
  return pc.kind == PieceKind::kFacetLine || pc.kind == PieceKind::kCylinderLine ||
         pc.kind == PieceKind::kFloor;
}

double centre_z(const SlicePiece& pc, double x) {
  x = std::clamp(x, pc.x0, pc.x1);
  switch (pc.kind) {
    case PieceKind::kFloor:
      return pc.point.z();
    case PieceKind::kFacetLine: {
      const Vec3 &p = pc.point, &n = pc.dir;
      return p.z() + (n.x() * (p.x() - x) + n.y() * (p.y() - pc.y0)) / n.z();
    }
    case PieceKind::kSphereArc:
      return sphere_centre_z(pc, x);
    default: {
      bool ok;
      return pc.point.z() + cylinder_upper_w(pc.point, pc.dir, pc.radius, x, pc.y0, ok);
    }
  }
}

double slope(const SlicePiece& pc, double x) {
  x = std::clamp(x, pc.x0, pc.x1);
  switch (pc.kind) {
    case PieceKind::kFloor:
      return 0;
    case PieceKind::kFacetLine:
      return -pc.dir.x() / pc.dir.z();
    case PieceKind::kSphereArc: {
      const Vec3& v = pc.point;
      const double d = v.y() - pc.y0, dx = x - v.x();
      const double s2 = (pc.radius - d) * (pc.radius + d) - dx * dx;
      if (s2 <= 0) return dx > 0 ? -INFINITY : INFINITY;
      return -dx / std::sqrt(s2);
    }
    default: {
      // w = (b + s) / a (see cylinder_upper_w): dw/dx = (uz ux - e uy / s) / a.
      const Vec3 &A = pc.point, &u = pc.dir;
      const double p = x - A.x(), q = pc.y0 - A.y();
      const double a = u.x() * u.x() + u.y() * u.y();
      const double e = u.y() * p - u.x() * q;
      const double disc = a * pc.radius * pc.radius - e * e;
      const double lin = u.z() * u.x();
      if (u.y() == 0) return lin / a;
      if (disc <= 0) return -e * u.y() > 0 ? INFINITY : -INFINITY;
      return (lin - e * u.y() / std::sqrt(disc)) / a;
    }
  }
}

double argmax_tilted(const SlicePiece& pc, double m, double a, double b) {
  a = std::max(a, pc.x0);
  b = std::min(b, pc.x1);
  if (!(a < b)) return a;
  double xs;  // unconstrained maximiser of z - m x
  switch (pc.kind) {
    case PieceKind::kFloor:
    case PieceKind::kFacetLine:
    case PieceKind::kCylinderLine: {
      double s = 0, c = 0;
      line_of(pc, s, c);
      return s - m >= 0 ? b : a;
    }
    case PieceKind::kSphereArc: {
      // Circle of radius r about v.x: z' = -dx / sqrt(r^2 - dx^2) = m at dx = -m r / sqrt(1 + m^2).
      const double d = pc.point.y() - pc.y0;
      const double r = std::sqrt(std::max(0.0, (pc.radius - d) * (pc.radius + d)));
      xs = pc.point.x() - m * r / std::sqrt(1 + m * m);
      break;
    }
    default: {
      SectionEllipse el;
      if (!ellipse_of(pc, el)) return a;
      // Maximise n . p over the ellipse, n = (-m, 1): p = o + (M^2 (n.a) a + m^2 (n.b) b) / k.
      const Vec2 ax = el.major_axis, bx(-ax.y(), ax.x());
      const Vec2 n(-m, 1);
      const double na = n.dot(ax), nb = n.dot(bx);
      const double k = std::sqrt(el.major * el.major * na * na + el.minor * el.minor * nb * nb);
      if (!(k > 0)) return a;
      xs = el.centre.x() + (el.major * el.major * na * ax.x() + el.minor * el.minor * nb * bx.x()) / k;
    }
  }
  return std::clamp(xs, a, b);
}

PieceContact piece_contact(const SlicePiece& pc, double x) {
  x = std::clamp(x, pc.x0, pc.x1);
  PieceContact r;
  r.centre = Vec3(x, pc.y0, centre_z(pc, x));
  switch (pc.kind) {
    case PieceKind::kFloor:
    case PieceKind::kFacetLine:
      r.cc = r.centre - pc.radius * pc.dir;
      break;
    case PieceKind::kSphereArc:
      r.cc = pc.point;
      break;
    default: {
      const double t = std::clamp((r.centre - pc.point).dot(pc.dir), 0.0, pc.length);
      r.cc = pc.point + t * pc.dir;
    }
  }
  const Vec3 d = r.centre - r.cc;
  const double len = d.norm();
  r.normal = len > 0 ? Vec3(d / len) : Vec3(0, 0, 1);
  return r;
}

bool ellipse_of(const SlicePiece& pc, SectionEllipse& out) {
  if (pc.kind != PieceKind::kCylinderEllipse && pc.kind != PieceKind::kCylinderCircle) return false;
  const Vec3& u = pc.dir;
  const Vec3 o = pc.point + u * ((pc.y0 - pc.point.y()) / u.y());
  out.centre = Vec2(o.x(), o.z());
  out.minor = pc.radius;
  out.major = pc.radius / std::abs(u.y());
  const double l = std::hypot(u.x(), u.z());
  out.major_axis = l > 0 ? Vec2(u.x() / l, u.z() / l) : Vec2(1, 0);
  return true;
}

bool line_of(const SlicePiece& pc, double& slope, double& intercept) {
  if (pc.kind == PieceKind::kFloor) {
    slope = 0;
    intercept = pc.point.z();
    return true;
  }
  if (pc.kind == PieceKind::kFacetLine) {
    const Vec3 &p = pc.point, &n = pc.dir;
    slope = -n.x() / n.z();
    intercept = p.z() + (n.x() * p.x() + n.y() * (p.y() - pc.y0)) / n.z();
    return true;
  }
  if (pc.kind == PieceKind::kCylinderLine) {
    // Axis parallel to the plane at distance |q|: the upper section line is the axis' trace
    // shifted by sqrt(R^2 - q^2) along the in-plane normal w = (-uz, ux) turned to +z.
    const Vec3& u = pc.dir;
    const double q = pc.y0 - pc.point.y();
    const double h = std::sqrt(std::max(0.0, (pc.radius - q) * (pc.radius + q)));
    Vec2 w(-u.z(), u.x());
    if (w.y() < 0) w = -w;
    slope = u.z() / u.x();
    intercept = pc.point.z() + h * w.y() - slope * (pc.point.x() + h * w.x());
    return true;
  }
  return false;
}

void slice_elements(const OffsetElements& el, double y0, std::uint32_t begin, std::uint32_t end,
                    std::vector<SlicePiece>& out, bool trim) {
  const auto nf = std::uint32_t(el.facet_count()), ne = std::uint32_t(el.edge_count());
  for (std::uint32_t id = begin; id < end; ++id) {
    if (id < nf)
      slice_facet(el, id, y0, out);
    else if (id < nf + ne)
      slice_cylinder(el, id - nf, y0, trim, out);
    else
      slice_sphere(el, id - nf - ne, y0, trim, out);
  }
}

}  // namespace ncpath
