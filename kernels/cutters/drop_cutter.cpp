#include "kernels/cutters/drop_cutter.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "kernels/geom/tolerance.hpp"

namespace ncpath {

const char* contact_kind_name(ContactKind kind) {
  switch (kind) {
    case ContactKind::kNone:
      return "none";
    case ContactKind::kVertex:
      return "vertex";
    case ContactKind::kEdge:
      return "edge";
    case ContactKind::kFacet:
      return "facet";
  }
  return "?";
}

bool prepare_facet(const Vec3& a, const Vec3& b, const Vec3& c, PreparedFacet& f) {
  Vec3 n = (b - a).cross(c - a);
  const double len = n.norm();
  if (!(len >= tol::kDegenerateArea2)) return false;
  n /= len;
  if (n.z() < 0) n = -n;
  f.p[0] = a;
  f.p[1] = b;
  f.p[2] = c;
  f.n = n;
  f.plane_d = n.dot(a);
  f.vertical = std::abs(n.z()) < tol::kVerticalNormalZ;
  f.xy_winding = ((b - a).cross(c - a)).z() > 0 ? 1.0 : -1.0;
  f.min_x = std::min({a.x(), b.x(), c.x()});
  f.max_x = std::max({a.x(), b.x(), c.x()});
  f.min_y = std::min({a.y(), b.y(), c.y()});
  f.max_y = std::max({a.y(), b.y(), c.y()});
  f.min_z = std::min({a.z(), b.z(), c.z()});
  f.max_z = std::max({a.z(), b.z(), c.z()});
  for (int k = 0; k < 3; ++k) {
    const Vec3& p = f.p[k];
    const Vec3& q = f.p[(k + 1) % 3];
    const double dx = q.x() - p.x(), dy = q.y() - p.y();
    const double l = std::hypot(dx, dy);
    f.len_xy[k] = l;
    if (l > 0) {
      f.ex[k] = dx / l;
      f.ey[k] = dy / l;
      f.slope[k] = (q.z() - p.z()) / l;
    } else {
      f.ex[k] = f.ey[k] = f.slope[k] = 0;
    }
    f.slope_norm[k] = std::sqrt(1 + f.slope[k] * f.slope[k]);
  }
  return true;
}

namespace {

inline double cross2(double ax, double ay, double bx, double by) { return ax * by - ay * bx; }

// Which edge lines of the triangle (xy projection) have (x, y) strictly on their outer
// side: bit k for edge p[k] -> p[k+1]. Zero means inside, boundary included.
inline unsigned outside_edges_xy(const PreparedFacet& f, double x, double y) {
  const double d0 =
      cross2(f.p[1].x() - f.p[0].x(), f.p[1].y() - f.p[0].y(), x - f.p[0].x(), y - f.p[0].y());
  const double d1 =
      cross2(f.p[2].x() - f.p[1].x(), f.p[2].y() - f.p[1].y(), x - f.p[1].x(), y - f.p[1].y());
  const double d2 =
      cross2(f.p[0].x() - f.p[2].x(), f.p[0].y() - f.p[2].y(), x - f.p[2].x(), y - f.p[2].y());
  const double s = f.xy_winding;
  return (s * d0 < 0 ? 1u : 0u) | (s * d1 < 0 ? 2u : 0u) | (s * d2 < 0 ? 4u : 0u);
}

// Tangent contact with the facet's plane. Always computes the tip height at which the
// cutter touches the infinite plane (an upper bound for every contact with the facet);
// returns the edges whose lines have the tangent point outside (0: the point is inside).
inline unsigned plane_contact(const Cutter& c, const PreparedFacet& f, double x, double y,
                              double& tip, double& ccx, double& ccy) {
  const double r = c.corner_radius, a = c.radius - c.corner_radius;
  const double nx = f.n.x(), ny = f.n.y(), nz = f.n.z();
  const double nxy = std::sqrt(nx * nx + ny * ny);
  ccx = x;
  ccy = y;
  if (nxy > 0) {
    const double k = a / nxy + r;
    ccx -= k * nx;
    ccy -= k * ny;
  }
  const double ccz = (f.plane_d - nx * ccx - ny * ccy) / nz;
  tip = ccz + r * nz - r;
  return outside_edges_xy(f, ccx, ccy);
}

// The torus angle psi at which a bull-nose (flat radius a, corner radius r) touches a line
// of slope m >= 0 at horizontal distance d from the axis: tan(psi) sqrt(1 - d^2/rho^2) = m,
// rho = a + r sin(psi). Returns s = sin(psi). Squared and multiplied out, the condition is
// the quartic H(s) = (1 + m^2) s^2 rho^2 - s^2 d^2 - m^2 rho^2 = 0, which has exactly one
// root between s_lo (rho = max(a, d)) and 1 (H <= 0 there and H(1) = R^2 - d^2 >= 0, and
// H has the sign of the increasing tan(psi) sqrt(...) - m). Newton with a bisection
// safeguard, no trigonometry.
double bull_edge_sine(double a, double r, double d, double m) {
  const double s_lo = d <= a ? 0.0 : std::min(1.0, (d - a) / r);
  if (m <= 0) return s_lo;
  const double m2 = m * m, k2 = 1 + m2, d2 = d * d;
  auto H = [&](double s, double& dH) {
    const double rho = a + r * s, rho2 = rho * rho;
    dH = 2 * k2 * s * rho2 + 2 * k2 * s * s * rho * r - 2 * s * d2 - 2 * m2 * rho * r;
    return k2 * s * s * rho2 - s * s * d2 - m2 * rho2;
  };
  double lo = std::max(s_lo, m / std::sqrt(k2));  // the root when d = 0; d > 0 moves it up
  double hi = 1.0;
  double s = lo;
  for (int it = 0; it < 100; ++it) {
    double dH;
    const double h = H(s, dH);
    if (h > 0)
      hi = s;
    else
      lo = s;
    double next = dH > 0 ? s - h / dH : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    // Newton converges quadratically, so a step of 1e-13 leaves an error near 1e-26 in s;
    // the tip, at a maximum along the edge, is second-order in it: far below
    // tol::kContactSolve.
    if (std::abs(next - s) <= 1e-13 || hi - lo <= 1e-15) return next;
    s = next;
  }
  return s;
}

// Edge contact in the edge's horizontal frame: p is the start vertex, (ex, ey) the unit
// horizontal direction, len its horizontal length, m the slope dz/du. Only contacts at
// interior points of the edge count (the vertices are tested on their own).
// `k` is sqrt(1 + m^2). Contacts whose tip cannot exceed `above` are dismissed before any
// square root: on the whole line the tip is at most z(u0) plus the cutter's rise on a
// slope m, the tilted-plane height g(m) (ball R(k-1), flat |m|R, bull |m|a + r(k-1)).
inline bool edge_contact(const Cutter& c, const Vec3& p, double ex, double ey, double len, double m,
                         double k, double x, double y, double above, double& tip, Vec3& cc) {
  if (!(len > 0)) return false;
  const double R = c.radius;
  const double dx = x - p.x(), dy = y - p.y();
  const double u0 = dx * ex + dy * ey;
  const double rise = std::abs(m) * (R - c.corner_radius) + c.corner_radius * (k - 1);
  if (p.z() + m * u0 + rise <= above) return false;
  const double d = std::abs(dx * ey - dy * ex);
  if (d > R) return false;
  const double s = std::sqrt(R * R - d * d);
  if (u0 + s <= 0 || u0 - s >= len) return false;
  double u;
  switch (c.type) {
    case CutterType::kBall: {
      u = u0 + s * m / k;
      if (!(u > 0 && u < len)) return false;
      tip = p.z() + m * u0 + s * k - R;
      break;
    }
    case CutterType::kFlat: {
      u = m > 0 ? u0 + s : (m < 0 ? u0 - s : u0);
      if (!(u > 0 && u < len)) return false;
      tip = p.z() + m * u;
      break;
    }
    default: {
      const double r = c.corner_radius, a = R - r;
      const double sn = bull_edge_sine(a, r, d, std::abs(m));
      const double rho = a + r * sn;
      const double du = std::sqrt(std::max(0.0, rho * rho - d * d));
      u = m >= 0 ? u0 + du : u0 - du;
      if (!(u > 0 && u < len)) return false;
      tip = p.z() + m * u - r * (1 - std::sqrt(std::max(0.0, 1 - sn * sn)));
      break;
    }
  }
  cc = Vec3(p.x() + u * ex, p.y() + u * ey, p.z() + u * m);
  return true;
}

inline bool vertex_contact(const Cutter& c, const Vec3& v, double x, double y, double& tip) {
  const double dx = v.x() - x, dy = v.y() - y;
  const double rho2 = dx * dx + dy * dy;
  if (rho2 > c.radius * c.radius) return false;
  tip = v.z() - profile_height(c, std::sqrt(rho2));
  return true;
}

}  // namespace

PlaneTip plane_tip(const Cutter& c, const PreparedFacet& f) {
  if (f.vertical) return {0, 0, std::numeric_limits<double>::infinity()};
  // plane_contact's tangent point is (x, y) - (a / |n_xy| + r) n_xy; substituting it into
  // the plane gives a tip linear in (x, y).
  const double r = c.corner_radius, a = c.radius - c.corner_radius;
  const double nx = f.n.x(), ny = f.n.y(), nz = f.n.z();
  const double nxy = std::sqrt(nx * nx + ny * ny);
  return {-nx / nz, -ny / nz, (f.plane_d + a * nxy + r * nxy * nxy) / nz + r * nz - r};
}

bool drop_on_edge(const Cutter& c, const Vec3& p, const Vec3& q, double x, double y, double& tip_z,
                  Vec3& cc) {
  const double dx = q.x() - p.x(), dy = q.y() - p.y();
  const double l = std::hypot(dx, dy);
  if (!(l > 0)) return false;
  const double m = (q.z() - p.z()) / l;
  return edge_contact(c, p, dx / l, dy / l, l, m, std::sqrt(1 + m * m), x, y,
                      -std::numeric_limits<double>::infinity(), tip_z, cc);
}

bool drop_on_vertex(const Cutter& c, const Vec3& v, double x, double y, double& tip_z) {
  return vertex_contact(c, v, x, y, tip_z);
}

bool drop_facet(const Cutter& c, const PreparedFacet& f, double x, double y,
                std::uint32_t facet_index, CutterContact& best) {
  const double R = c.radius;
  if (x < f.min_x - R || x > f.max_x + R || y < f.min_y - R || y > f.max_y + R) return false;
  if (f.max_z <= best.tip_z) return false;  // every contact's tip is at or below max_z
  // Edges (bit k) and vertices to examine. When the plane's tangent point T is outside the
  // triangle, the facet's highest contact is where the largest superlevel set of the
  // (concave) contact height first meets the triangle; its supporting line there separates
  // T from the triangle, so it lies on an edge whose line has T outside, or at a vertex of
  // such an edge. The other edges cannot hold it.
  unsigned edges = 7u;
  if (!f.vertical) {
    double tip, ccx, ccy;
    edges = plane_contact(c, f, x, y, tip, ccx, ccy);
    // The plane contact bounds every contact with the facet from above.
    if (tip <= best.tip_z) return false;
    if (edges == 0) {
      best.tip_z = tip;
      best.cc = Vec3(ccx, ccy, (f.plane_d - f.n.x() * ccx - f.n.y() * ccy) / f.n.z());
      best.kind = ContactKind::kFacet;
      best.facet = facet_index;
      return true;
    }
  }
  // Edge and vertex contacts are never above the highest point they touch, which settles
  // most of them without the square roots.
  bool raised = false;
  for (int k = 0; k < 3; ++k) {
    if (!(edges & (1u << k))) continue;
    const Vec3& p = f.p[k];
    if (std::max(p.z(), f.p[(k + 1) % 3].z()) <= best.tip_z) continue;
    double tip;
    Vec3 cc;
    if (edge_contact(c, p, f.ex[k], f.ey[k], f.len_xy[k], f.slope[k], f.slope_norm[k], x, y,
                     best.tip_z, tip, cc) &&
        tip > best.tip_z) {
      best = {tip, cc, ContactKind::kEdge, facet_index};
      raised = true;
    }
  }
  for (int k = 0; k < 3; ++k) {
    // Vertex k ends edge k-1 and starts edge k.
    if (!(edges & ((1u << k) | (1u << ((k + 2) % 3))))) continue;
    double tip;
    if (f.p[k].z() > best.tip_z && vertex_contact(c, f.p[k], x, y, tip) && tip > best.tip_z) {
      best = {tip, f.p[k], ContactKind::kVertex, facet_index};
      raised = true;
    }
  }
  return raised;
}

}  // namespace ncpath
