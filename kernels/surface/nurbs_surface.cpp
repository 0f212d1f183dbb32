// NURBS surface validation and evaluation: the B-spline basis functions of each direction with
// their first two derivatives (from the Cox-de Boor triangle of lower degrees), tensor sums of
// the homogeneous control points, then the rational quotient rule. Normals and normal
// curvature from the first and second fundamental forms.
#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "kernels/geom/tolerance.hpp"
#include "kernels/surface/nurbs_surface.hpp"
#include "kernels/surface/nurbs_surface_detail.hpp"

namespace ncpath {

using surface_detail::H4;
using surface_detail::HomogDerivs;
using surface_detail::SmallBuf;

namespace {

std::string num(double v) { return std::to_string(v); }

// Checks one knot vector (name "knots_u" / "knots_v") against count n and degree p.
std::string validate_knots(const std::vector<double>& U, int n, int p, const char* name,
                           const char* count_name) {
  const std::string nm = name;
  if (U.size() != static_cast<std::size_t>(n + p + 1))
    return "NURBS surface " + nm + " must hold " + count_name +
           " + degree + 1 = " + std::to_string(n + p + 1) + " knots (got " +
           std::to_string(U.size()) + ")";
  const std::size_t m = U.size();
  for (std::size_t i = 0; i < m; ++i) {
    if (!std::isfinite(U[i]))
      return "NURBS surface " + nm + "[" + std::to_string(i) + "] is not finite";
    if (i > 0 && U[i] < U[i - 1])
      return "NURBS surface " + nm + " decrease at index " + std::to_string(i) + " (" +
             num(U[i - 1]) + " > " + num(U[i]) + ")";
  }
  for (int i = 1; i <= p; ++i)
    if (U[i] != U[0] || U[m - 1 - i] != U[m - 1])
      return "NURBS surface " + nm +
             " is not clamped: the first and the last degree + 1 knots must be equal";
  if (!(U[m - 1] > U[0])) return "NURBS surface " + nm + " range is empty (first knot == last)";
  // An interior knot of multiplicity > degree would make the surface discontinuous.
  for (std::size_t i = p + 1; i + p + 1 < m;) {
    std::size_t j = i;
    while (j + 1 < m && U[j + 1] == U[i]) ++j;
    if (static_cast<int>(j - i + 1) > p)
      return "NURBS surface " + nm + " interior knot " + num(U[i]) + " has multiplicity " +
             std::to_string(j - i + 1) + " > degree (the surface would be discontinuous)";
    i = j + 1;
  }
  return "";
}

// Index k of the knot span [U[k], U[k+1]) holding t, clamped to the domain; the last knot
// belongs to the last non-empty span.
int find_span(const std::vector<double>& U, int n, int p, double t) {
  if (!(t > U[p])) return p;  // also NaN; clamped knots: U[p] < U[p + 1]
  if (t >= U[n]) return n - 1;
  const auto it = std::upper_bound(U.begin() + p, U.begin() + n + 1, t);
  return static_cast<int>(it - U.begin()) - 1;
}

double safe_div(double a, double b) { return b != 0 ? a / b : 0.0; }

// Values, first and second derivatives of the p + 1 basis functions N_{k-p..k, p} at t on
// span k.
void basis_derivs(const std::vector<double>& U, int p, int k, double t, double* d0, double* d1,
                  double* d2) {
  // rows[q][j] = N_{k-q+j, q}(t); only the last three degrees are kept.
  SmallBuf<double, 16> cur(p + 1), prev(p + 1), prev2(p + 1);
  cur[0] = 1;
  for (int q = 1; q <= p; ++q) {
    for (int j = 0; j < q; ++j) prev2[j] = prev[j];
    for (int j = 0; j < q; ++j) prev[j] = cur[j];
    for (int j = 0; j <= q; ++j) {
      const int i = k - q + j;
      double v = 0;
      if (j >= 1) v += safe_div(t - U[i], U[i + q] - U[i]) * prev[j - 1];
      if (j <= q - 1) v += safe_div(U[i + q + 1] - t, U[i + q + 1] - U[i + 1]) * prev[j];
      cur[j] = v;
    }
  }
  // Now prev holds degree p - 1 and prev2 degree p - 2 (when p >= 2).
  for (int j = 0; j <= p; ++j) d0[j] = cur[j];
  SmallBuf<double, 16> e(p + 1);
  for (int j = 0; j <= p; ++j) {
    const int i = k - p + j;
    double v = 0;
    if (j >= 1) v += safe_div(prev[j - 1], U[i + p] - U[i]);
    if (j <= p - 1) v -= safe_div(prev[j], U[i + p + 1] - U[i + 1]);
    d1[j] = p * v;
  }
  if (p < 2) {
    for (int j = 0; j <= p; ++j) d2[j] = 0;
    return;
  }
  // Derivatives of the degree p - 1 functions N_{k-p+1+m, p-1}, m = 0..p-1.
  for (int m = 0; m < p; ++m) {
    const int i = k - p + 1 + m;
    double v = 0;
    if (m >= 1) v += safe_div(prev2[m - 1], U[i + p - 1] - U[i]);
    if (m <= p - 2) v -= safe_div(prev2[m], U[i + p] - U[i + 1]);
    e[m] = (p - 1) * v;
  }
  for (int j = 0; j <= p; ++j) {
    const int i = k - p + j;
    double v = 0;
    if (j >= 1) v += safe_div(e[j - 1], U[i + p] - U[i]);
    if (j <= p - 1) v -= safe_div(e[j], U[i + p + 1] - U[i + 1]);
    d2[j] = p * v;
  }
}

H4 homog(const NurbsSurface& s, int i, int j) {
  const int k = i * s.nv + j;
  const double w = s.weights[k];
  const Vec3& c = s.ctrl[k];
  return H4(w * c.x(), w * c.y(), w * c.z(), w);
}

}  // namespace

namespace surface_detail {

SurfacePoint rational_point(const HomogDerivs& h) {
  const double w = h.d[0].w();
  const double wu = h.d[1].w(), wv = h.d[2].w();
  const double wuu = h.d[3].w(), wuv = h.d[4].w(), wvv = h.d[5].w();
  SurfacePoint sp;
  sp.p = h.d[0].head<3>() / w;
  sp.su = (h.d[1].head<3>() - wu * sp.p) / w;
  sp.sv = (h.d[2].head<3>() - wv * sp.p) / w;
  sp.suu = (h.d[3].head<3>() - 2 * wu * sp.su - wuu * sp.p) / w;
  sp.suv = (h.d[4].head<3>() - wu * sp.sv - wv * sp.su - wuv * sp.p) / w;
  sp.svv = (h.d[5].head<3>() - 2 * wv * sp.sv - wvv * sp.p) / w;
  return sp;
}

std::string pair_text(double a, double b) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.6g, %.6g)", a, b);
  return buf;
}

}  // namespace surface_detail

std::string validate(const NurbsSurface& s) {
  if (s.degree_u < 1)
    return "NURBS surface degree_u must be >= 1 (got " + std::to_string(s.degree_u) + ")";
  if (s.degree_v < 1)
    return "NURBS surface degree_v must be >= 1 (got " + std::to_string(s.degree_v) + ")";
  if (s.nu < s.degree_u + 1)
    return "NURBS surface nu (control points along u) must be >= degree_u + 1 = " +
           std::to_string(s.degree_u + 1) + " (got " + std::to_string(s.nu) + ")";
  if (s.nv < s.degree_v + 1)
    return "NURBS surface nv (control points along v) must be >= degree_v + 1 = " +
           std::to_string(s.degree_v + 1) + " (got " + std::to_string(s.nv) + ")";
  const std::size_t n = static_cast<std::size_t>(s.nu) * s.nv;
  if (s.ctrl.size() != n)
    return "NURBS surface ctrl must hold nu * nv = " + std::to_string(n) + " points (got " +
           std::to_string(s.ctrl.size()) + ")";
  if (s.weights.size() != n)
    return "NURBS surface weights must hold nu * nv = " + std::to_string(n) + " values (got " +
           std::to_string(s.weights.size()) + ")";
  for (std::size_t k = 0; k < n; ++k) {
    const std::string at = "[" + std::to_string(k) + "] (i = " + std::to_string(k / s.nv) +
                           ", j = " + std::to_string(k % s.nv) + ")";
    if (!s.ctrl[k].allFinite()) return "NURBS surface ctrl" + at + " is not finite";
    if (!std::isfinite(s.weights[k])) return "NURBS surface weights" + at + " is not finite";
    if (!(s.weights[k] > 0))
      return "NURBS surface weights" + at + " is not > 0 (got " + num(s.weights[k]) + ")";
  }
  std::string e = validate_knots(s.knots_u, s.nu, s.degree_u, "knots_u", "nu");
  if (!e.empty()) return e;
  return validate_knots(s.knots_v, s.nv, s.degree_v, "knots_v", "nv");
}

NurbsSurface bezier_grid_surface(int patches_u, int patches_v, const std::vector<Vec3>& ctrl) {
  if (patches_u < 1 || patches_v < 1)
    throw std::invalid_argument("bezier_grid_surface: patch counts must be >= 1");
  NurbsSurface s;
  s.degree_u = s.degree_v = 3;
  s.nu = 3 * patches_u + 1;
  s.nv = 3 * patches_v + 1;
  if (ctrl.size() != static_cast<std::size_t>(s.nu) * s.nv)
    throw std::invalid_argument("bezier_grid_surface: " + std::to_string(patches_u) + " x " +
                                std::to_string(patches_v) + " bicubic patches need " +
                                std::to_string(s.nu * s.nv) + " control points (got " +
                                std::to_string(ctrl.size()) + ")");
  s.ctrl = ctrl;
  s.weights.assign(ctrl.size(), 1.0);
  auto knots = [](int patches) {
    std::vector<double> k(4, 0.0);
    for (int i = 1; i < patches; ++i) k.insert(k.end(), 3, static_cast<double>(i));
    k.insert(k.end(), 4, static_cast<double>(patches));
    return k;
  };
  s.knots_u = knots(patches_u);
  s.knots_v = knots(patches_v);
  return s;
}

SurfaceDomain domain(const NurbsSurface& s) {
  return {s.knots_u.front(), s.knots_u.back(), s.knots_v.front(), s.knots_v.back()};
}

SurfacePoint evaluate(const NurbsSurface& s, double u, double v) {
  assert(validate(s).empty());
  const int p = s.degree_u, q = s.degree_v;
  const int ku = find_span(s.knots_u, s.nu, p, u);
  const int kv = find_span(s.knots_v, s.nv, q, v);
  u = std::clamp(u, s.knots_u.front(), s.knots_u.back());
  v = std::clamp(v, s.knots_v.front(), s.knots_v.back());
  SmallBuf<double, 16> bu0(p + 1), bu1(p + 1), bu2(p + 1), bv0(q + 1), bv1(q + 1), bv2(q + 1);
  basis_derivs(s.knots_u, p, ku, u, bu0.data(), bu1.data(), bu2.data());
  basis_derivs(s.knots_v, q, kv, v, bv0.data(), bv1.data(), bv2.data());
  HomogDerivs h;
  for (H4& d : h.d) d.setZero();
  for (int a = 0; a <= p; ++a) {
    H4 r0 = H4::Zero(), r1 = H4::Zero(), r2 = H4::Zero();
    for (int b = 0; b <= q; ++b) {
      const H4 c = homog(s, ku - p + a, kv - q + b);
      r0 += bv0[b] * c;
      r1 += bv1[b] * c;
      r2 += bv2[b] * c;
    }
    h.d[0] += bu0[a] * r0;
    h.d[1] += bu1[a] * r0;
    h.d[2] += bu0[a] * r1;
    h.d[3] += bu2[a] * r0;
    h.d[4] += bu1[a] * r1;
    h.d[5] += bu0[a] * r2;
  }
  return surface_detail::rational_point(h);
}

Vec3 surface_point(const NurbsSurface& s, double u, double v) { return evaluate(s, u, v).p; }

Vec3 upward_normal(const SurfacePoint& sp) {
  // At a degenerate point of the parameterisation (a pole, where su or sv vanishes) the normal
  // is the limit from the neighbouring points: next to a pole at which sv = 0,
  // sv ~ suv * du, so the tangent plane is spanned by su and suv.
  const double a = sp.su.norm(), b = sp.sv.norm();
  Vec3 n;
  if (b <= tol::kSurfaceZeroSpeed * a)
    n = sp.su.cross(sp.suv);
  else if (a <= tol::kSurfaceZeroSpeed * b)
    n = sp.suv.cross(sp.sv);
  else
    n = sp.su.cross(sp.sv);
  const double len = n.norm();
  if (!(len > 0)) return Vec3(0, 0, 1);  // no tangent plane at all: keep callers finite
  n /= len;
  return n.z() < 0 ? Vec3(-n) : n;
}

double normal_curvature(const SurfacePoint& sp, double du, double dv) {
  const Vec3 t = sp.su * du + sp.sv * dv;
  const double first = t.squaredNorm();
  if (!(first > 0)) return 0;  // no tangent direction: undefined, 0 keeps callers finite
  const Vec3 second = sp.suu * (du * du) + sp.suv * (2 * du * dv) + sp.svv * (dv * dv);
  // Positive when the surface bends away from (below) its upward normal.
  return -upward_normal(sp).dot(second) / first;
}

}  // namespace ncpath
