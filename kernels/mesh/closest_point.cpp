#include "kernels/mesh/closest_point.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

namespace ncpath {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// x lies over the triangle (its projection along n is inside or on the boundary); n is the
// unnormalised normal (b - a) x (c - a). Writes the signs of the three edge tests.
bool over_triangle(const Vec3& x, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& n,
                   double s[3]) {
  s[0] = (b - a).cross(x - a).dot(n);
  s[1] = (c - b).cross(x - b).dot(n);
  s[2] = (a - c).cross(x - c).dot(n);
  return s[0] >= 0 && s[1] >= 0 && s[2] >= 0;
}

// First t >= 0 at which the point x + t d (d unit) comes within r of the centre v; 0 when
// already within; +inf when never. Root of |w + t d|^2 = r^2 in its cancellation-free form.
double sweep_point(const Vec3& x, const Vec3& d, double r, const Vec3& v) {
  const Vec3 w = x - v;
  const double c = w.squaredNorm() - r * r;
  if (c <= 0) return 0;
  const double hb = w.dot(d);
  if (hb >= 0) return kInf;  // moving away
  // hb^2 - c, written without cancelling squares: r^2 minus the squared miss distance.
  const double disc = r * r - w.cross(d).squaredNorm();
  if (disc < 0) return kInf;
  return c / (-hb + std::sqrt(disc));
}

// The same for the finite cylinder of radius r around segment pq (caps excluded: they lie
// inside the end spheres, which the caller tests).
double sweep_segment(const Vec3& x, const Vec3& d, double r, const Vec3& p, const Vec3& q) {
  const Vec3 e = q - p;
  const double l2 = e.squaredNorm();
  const Vec3 w = x - p;
  const Vec3 w_perp = w - (w.dot(e) / l2) * e;
  const double c = w_perp.squaredNorm() - r * r;
  if (c <= 0) {
    // Inside the infinite cylinder: touching now when beside the segment; otherwise the
    // ball can only reach the segment through an end sphere.
    const double u = w.dot(e);
    return (u >= 0 && u <= l2) ? 0 : kInf;
  }
  const Vec3 d_perp = d - (d.dot(e) / l2) * e;
  const double a2 = d_perp.squaredNorm();
  const double hb = w_perp.dot(d_perp);
  if (!(a2 > 0) || hb >= 0) return kInf;
  const double disc = a2 * r * r - w_perp.cross(d_perp).squaredNorm();  // as in sweep_point
  if (disc < 0) return kInf;
  const double t = c / (-hb + std::sqrt(disc));
  const double u = (w + t * d).dot(e);
  return (u >= 0 && u <= l2) ? t : kInf;
}

}  // namespace

double point_segment_closest(const Vec3& x, const Vec3& p, const Vec3& q, Vec3& out) {
  const Vec3 e = q - p;
  const double l2 = e.squaredNorm();
  const double t = l2 > 0 ? (x - p).dot(e) / l2 : 0.0;
  if (!(t > 0))
    out = p;
  else if (t >= 1)
    out = q;
  else
    out = p + t * e;
  return (x - out).norm();
}

double point_triangle_closest(const Vec3& x, const Vec3& a, const Vec3& b, const Vec3& c, Vec3& q) {
  const Vec3 n = (b - a).cross(c - a);
  double s[3];
  if (over_triangle(x, a, b, c, n, s)) {
    // Face region: the projection onto the plane (distance from the plane equation, which
    // is more accurate than |x - q|).
    const double h = (x - a).dot(n), n2 = n.squaredNorm();
    q = x - (h / n2) * n;
    return std::abs(h) / std::sqrt(n2);
  }
  // Outside: the closest point is on an edge whose line x is beyond (for a convex polygon
  // at least one such edge holds it, even when it is a vertex).
  const Vec3* v[3] = {&a, &b, &c};
  double best = kInf;
  for (int k = 0; k < 3; ++k) {
    if (s[k] >= 0) continue;
    Vec3 cand;
    const double d = point_segment_closest(x, *v[k], *v[(k + 1) % 3], cand);
    if (d < best) {
      best = d;
      q = cand;
    }
  }
  return best;
}

double sweep_ball_triangle(const Vec3& x, const Vec3& d, double r, double t_max, const Vec3& a,
                           const Vec3& b, const Vec3& c) {
  // The ball touches the triangle when its centre enters the triangle grown by r: the union
  // of the slab prism (triangle x [-r, r] along the normal), three edge cylinders and three
  // vertex spheres, each convex. The first entry into the union is the first entry into one
  // of them, and an entry through a prism side lies inside that edge's cylinder, so only
  // the two offset faces of the prism are tested.
  const Vec3 n = (b - a).cross(c - a);
  const Vec3 nu = n / n.norm();
  double s[3];
  double t = kInf;
  const double h = (x - a).dot(nu), hd = d.dot(nu);
  if (std::abs(h) <= r) {
    if (over_triangle(x, a, b, c, n, s)) return 0;
  } else if (h * hd < 0) {
    const double tf = (std::abs(h) - r) / std::abs(hd);
    if (tf <= t_max && over_triangle(x + tf * d, a, b, c, n, s)) t = tf;
  }
  const Vec3* v[3] = {&a, &b, &c};
  for (int k = 0; k < 3; ++k) {
    t = std::min(t, sweep_segment(x, d, r, *v[k], *v[(k + 1) % 3]));
    t = std::min(t, sweep_point(x, d, r, *v[k]));
  }
  return t <= t_max ? t : kInf;
}

}  // namespace ncpath
