// Rational Bezier patches of a NURBS surface: Boehm knot insertion (in homogeneous
// coordinates) up to multiplicity degree in both directions, then each knot-span rectangle
// is one patch. de Casteljau splitting, Bernstein evaluation and scalar Bezier products for
// the bounds used by the height-field check and the drop.
#include <algorithm>
#include <cassert>
#include <cmath>

#include "kernels/surface/nurbs_surface.hpp"
#include "kernels/surface/nurbs_surface_detail.hpp"

namespace ncpath {

using surface_detail::H4;
using surface_detail::SmallBuf;

namespace surface_detail {

void bernstein(int p, double t, double* b0, double* b1, double* b2) {
  const double s = 1 - t;
  if (p == 3) {  // the common bicubic case, written out
    b0[0] = s * s * s;
    b0[1] = 3 * t * s * s;
    b0[2] = 3 * t * t * s;
    b0[3] = t * t * t;
    b1[0] = -3 * s * s;
    b1[1] = 3 * s * (s - 2 * t);
    b1[2] = 3 * t * (2 * s - t);
    b1[3] = 3 * t * t;
    b2[0] = 6 * s;
    b2[1] = 6 * (3 * t - 2);
    b2[2] = 6 * (1 - 3 * t);
    b2[3] = 6 * t;
    return;
  }
  // In-place triangle B^k_i = (1 - t) B^{k-1}_i + t B^{k-1}_{i-1}, keeping degrees p - 1 and
  // p - 2 for the derivatives p (B^{p-1}_{i-1} - B^{p-1}_i) and its second-order analogue.
  SmallBuf<double, 16> cur(p + 1), d1(p + 1), d2(p + 1);
  cur[0] = 1;
  for (int k = 1; k <= p; ++k) {
    if (k == p - 1)
      for (int i = 0; i < k; ++i) d2[i] = cur[i];  // degree p - 2
    if (k == p)
      for (int i = 0; i < k; ++i) d1[i] = cur[i];  // degree p - 1
    cur[k] = t * cur[k - 1];
    for (int i = k - 1; i >= 1; --i) cur[i] = s * cur[i] + t * cur[i - 1];
    cur[0] = s * cur[0];
  }
  for (int i = 0; i <= p; ++i) b0[i] = cur[i];
  for (int i = 0; i <= p; ++i) {
    const double lo = i >= 1 ? d1[i - 1] : 0.0, hi = i <= p - 1 ? d1[i] : 0.0;
    b1[i] = p * (lo - hi);
  }
  for (int i = 0; i <= p; ++i) {
    if (p < 2) {
      b2[i] = 0;
      continue;
    }
    const double a = i >= 2 ? d2[i - 2] : 0.0;
    const double b = (i >= 1 && i - 1 <= p - 2) ? d2[i - 1] : 0.0;
    const double c = i <= p - 2 ? d2[i] : 0.0;
    b2[i] = p * (p - 1) * (a - 2 * b + c);
  }
}

SurfacePoint bezier_evaluate(const H4* ctrl, int p, int q, double s, double t) {
  SmallBuf<double, 16> bu0(p + 1), bu1(p + 1), bu2(p + 1), bv0(q + 1), bv1(q + 1), bv2(q + 1);
  bernstein(p, s, bu0.data(), bu1.data(), bu2.data());
  bernstein(q, t, bv0.data(), bv1.data(), bv2.data());
  HomogDerivs h;
  for (H4& d : h.d) d.setZero();
  for (int a = 0; a <= p; ++a) {
    H4 r0 = H4::Zero(), r1 = H4::Zero(), r2 = H4::Zero();
    const H4* row = ctrl + a * (q + 1);
    for (int b = 0; b <= q; ++b) {
      r0 += bv0[b] * row[b];
      r1 += bv1[b] * row[b];
      r2 += bv2[b] * row[b];
    }
    h.d[0] += bu0[a] * r0;
    h.d[1] += bu1[a] * r0;
    h.d[2] += bu0[a] * r1;
    h.d[3] += bu2[a] * r0;
    h.d[4] += bu1[a] * r1;
    h.d[5] += bu0[a] * r2;
  }
  return rational_point(h);
}

Vec3 bezier_point(const H4* ctrl, int p, int q, double s, double t) {
  // de Casteljau in both directions (stable, no binomials).
  SmallBuf<H4, 16> col(p + 1), row(q + 1);
  for (int a = 0; a <= p; ++a) {
    for (int b = 0; b <= q; ++b) row[b] = ctrl[a * (q + 1) + b];
    for (int r = 1; r <= q; ++r)
      for (int b = 0; b + r <= q; ++b) row[b] = (1 - t) * row[b] + t * row[b + 1];
    col[a] = row[0];
  }
  for (int r = 1; r <= p; ++r)
    for (int a = 0; a + r <= p; ++a) col[a] = (1 - s) * col[a] + s * col[a + 1];
  return col[0].head<3>() / col[0].w();
}

void bezier_split(const H4* ctrl, int p, int q, bool along_u, H4* a, H4* b) {
  const int n = along_u ? p : q;  // degree in the split direction
  const int lines = along_u ? q + 1 : p + 1;
  const int step = along_u ? q + 1 : 1;  // stride between points of one line
  const int line_step = along_u ? 1 : q + 1;
  if (n == 3) {  // the common cubic case, written out
    for (int l = 0; l < lines; ++l) {
      const H4* c = ctrl + l * line_step;
      H4* x = a + l * line_step;
      H4* y = b + l * line_step;
      const H4 m01 = 0.5 * (c[0] + c[step]), m12 = 0.5 * (c[step] + c[2 * step]);
      const H4 m23 = 0.5 * (c[2 * step] + c[3 * step]);
      const H4 m012 = 0.5 * (m01 + m12), m123 = 0.5 * (m12 + m23);
      const H4 mid = 0.5 * (m012 + m123);
      x[0] = c[0];
      x[step] = m01;
      x[2 * step] = m012;
      x[3 * step] = mid;
      y[0] = mid;
      y[step] = m123;
      y[2 * step] = m23;
      y[3 * step] = c[3 * step];
    }
    return;
  }
  SmallBuf<H4, 16> tmp(n + 1);
  for (int l = 0; l < lines; ++l) {
    const int base = l * line_step;
    for (int i = 0; i <= n; ++i) tmp[i] = ctrl[base + i * step];
    a[base] = tmp[0];
    b[base + n * step] = tmp[n];
    for (int r = 1; r <= n; ++r) {
      for (int i = 0; i + r <= n; ++i) tmp[i] = 0.5 * (tmp[i] + tmp[i + 1]);
      a[base + r * step] = tmp[0];
      b[base + (n - r) * step] = tmp[n - r];
    }
  }
}

void control_box(const H4* ctrl, int n, Vec3& lo, Vec3& hi) {
  lo = hi = ctrl[0].head<3>() / ctrl[0].w();
  for (int i = 1; i < n; ++i) {
    const Vec3 c = ctrl[i].head<3>() / ctrl[i].w();
    lo = lo.cwiseMin(c);
    hi = hi.cwiseMax(c);
  }
}

namespace {

std::vector<double> binomial_row(int n) {
  std::vector<double> c(n + 1, 1.0);
  for (int k = 1; k < n; ++k) c[k] = c[k - 1] * (n - k + 1) / k;
  return c;
}

}  // namespace

std::vector<double> bezier_multiply(const std::vector<double>& c1, int a1, int b1,
                                    const std::vector<double>& c2, int a2, int b2) {
  // B^m_i B^n_j = C(m, i) C(n, j) / C(m + n, i + j) B^{m+n}_{i+j}, in each direction.
  const int a = a1 + a2, b = b1 + b2;
  const auto ca1 = binomial_row(a1), ca2 = binomial_row(a2), ca = binomial_row(a);
  const auto cb1 = binomial_row(b1), cb2 = binomial_row(b2), cb = binomial_row(b);
  std::vector<double> out((a + 1) * (b + 1), 0.0);
  for (int i1 = 0; i1 <= a1; ++i1)
    for (int j1 = 0; j1 <= b1; ++j1) {
      const double x1 = c1[i1 * (b1 + 1) + j1] * ca1[i1] * cb1[j1];
      for (int i2 = 0; i2 <= a2; ++i2)
        for (int j2 = 0; j2 <= b2; ++j2)
          out[(i1 + i2) * (b + 1) + j1 + j2] += x1 * c2[i2 * (b2 + 1) + j2] * ca2[i2] * cb2[j2];
    }
  for (int i = 0; i <= a; ++i)
    for (int j = 0; j <= b; ++j) out[i * (b + 1) + j] /= ca[i] * cb[j];
  return out;
}

void bezier_split_scalar(const std::vector<double>& c, int a, int b, bool along_u,
                         std::vector<double>& lo, std::vector<double>& hi) {
  lo.assign(c.size(), 0.0);
  hi.assign(c.size(), 0.0);
  const int n = along_u ? a : b;
  const int lines = along_u ? b + 1 : a + 1;
  const int step = along_u ? b + 1 : 1;
  const int line_step = along_u ? 1 : b + 1;
  std::vector<double> tmp(n + 1);
  for (int l = 0; l < lines; ++l) {
    const int base = l * line_step;
    for (int i = 0; i <= n; ++i) tmp[i] = c[base + i * step];
    lo[base] = tmp[0];
    hi[base + n * step] = tmp[n];
    for (int r = 1; r <= n; ++r) {
      for (int i = 0; i + r <= n; ++i) tmp[i] = 0.5 * (tmp[i] + tmp[i + 1]);
      lo[base + r * step] = tmp[0];
      hi[base + (n - r) * step] = tmp[n - r];
    }
  }
}

}  // namespace surface_detail

namespace {

// Boehm insertion of t once into the curve (P, U) of degree p (t interior, multiplicity < p).
void insert_knot(std::vector<H4>& P, std::vector<double>& U, int p, double t) {
  const int k = static_cast<int>(std::upper_bound(U.begin(), U.end(), t) - U.begin()) - 1;
  int s = 0;
  while (s <= k && U[k - s] == t) ++s;
  assert(s < p);
  std::vector<H4> Q(P.size() + 1);
  for (int i = 0; i <= k - p; ++i) Q[i] = P[i];
  for (int i = k - p + 1; i <= k - s; ++i) {
    const double a = (t - U[i]) / (U[i + p] - U[i]);
    Q[i] = a * P[i] + (1 - a) * P[i - 1];
  }
  for (int i = k - s + 1; i < static_cast<int>(Q.size()); ++i) Q[i] = P[i - 1];
  P = std::move(Q);
  U.insert(U.begin() + k + 1, t);
}

// Raises every interior knot of (P, U) to multiplicity p.
void refine_to_bezier(std::vector<H4>& P, std::vector<double> U, int p) {
  std::vector<double> interior;
  for (std::size_t i = p + 1; i + p + 1 < U.size(); ++i)
    if (interior.empty() || U[i] != interior.back()) interior.push_back(U[i]);
  for (double t : interior) {
    const auto [lo, hi] = std::equal_range(U.begin(), U.end(), t);
    for (int m = static_cast<int>(hi - lo); m < p; ++m) insert_knot(P, U, p, t);
  }
}

std::vector<double> breakpoints(const std::vector<double>& U) {
  std::vector<double> b;
  for (double u : U)
    if (b.empty() || u > b.back()) b.push_back(u);
  return b;
}

}  // namespace

std::vector<BezierPatch> bezier_patches(const NurbsSurface& s) {
  assert(validate(s).empty());
  const int p = s.degree_u, q = s.degree_v;
  const std::vector<double> bu = breakpoints(s.knots_u), bv = breakpoints(s.knots_v);
  const int su = static_cast<int>(bu.size()) - 1, sv = static_cast<int>(bv.size()) - 1;
  const int mu = p * su + 1, mv = q * sv + 1;  // refined control net size
  // Refine along v (each row i of the net is a curve in v), then along u (each column).
  std::vector<std::vector<H4>> rows(s.nu);
  for (int i = 0; i < s.nu; ++i) {
    std::vector<H4>& r = rows[i];
    for (int j = 0; j < s.nv; ++j) {
      const double w = s.weights[i * s.nv + j];
      const Vec3& c = s.ctrl[i * s.nv + j];
      r.emplace_back(w * c.x(), w * c.y(), w * c.z(), w);
    }
    refine_to_bezier(r, s.knots_v, q);
    assert(static_cast<int>(r.size()) == mv);
  }
  std::vector<H4> net(static_cast<std::size_t>(mu) * mv);
  for (int j = 0; j < mv; ++j) {
    std::vector<H4> col(s.nu);
    for (int i = 0; i < s.nu; ++i) col[i] = rows[i][j];
    refine_to_bezier(col, s.knots_u, p);
    assert(static_cast<int>(col.size()) == mu);
    for (int i = 0; i < mu; ++i) net[static_cast<std::size_t>(i) * mv + j] = col[i];
  }
  std::vector<BezierPatch> out;
  out.reserve(static_cast<std::size_t>(su) * sv);
  for (int a = 0; a < su; ++a)
    for (int b = 0; b < sv; ++b) {
      BezierPatch bp;
      bp.degree_u = p;
      bp.degree_v = q;
      bp.u0 = bu[a];
      bp.u1 = bu[a + 1];
      bp.v0 = bv[b];
      bp.v1 = bv[b + 1];
      bp.ctrl.resize((p + 1) * (q + 1));
      for (int i = 0; i <= p; ++i)
        for (int j = 0; j <= q; ++j)
          bp.ctrl[i * (q + 1) + j] = net[static_cast<std::size_t>(a * p + i) * mv + b * q + j];
      surface_detail::control_box(bp.ctrl.data(), static_cast<int>(bp.ctrl.size()), bp.lo, bp.hi);
      out.push_back(std::move(bp));
    }
  return out;
}

void split_patch(const BezierPatch& p, bool along_u, BezierPatch& a, BezierPatch& b) {
  // Copy the source first: a or b may alias p.
  const BezierPatch src = p;
  a = src;
  b = src;
  surface_detail::bezier_split(src.ctrl.data(), src.degree_u, src.degree_v, along_u, a.ctrl.data(),
                               b.ctrl.data());
  if (along_u) {
    a.u1 = b.u0 = 0.5 * (src.u0 + src.u1);
  } else {
    a.v1 = b.v0 = 0.5 * (src.v0 + src.v1);
  }
  const int n = static_cast<int>(src.ctrl.size());
  surface_detail::control_box(a.ctrl.data(), n, a.lo, a.hi);
  surface_detail::control_box(b.ctrl.data(), n, b.lo, b.hi);
}

void split_patch(const BezierPatch& p, BezierPatch& a, BezierPatch& b) {
  split_patch(p, p.u1 - p.u0 >= p.v1 - p.v0, a, b);
}

Vec3 patch_point(const BezierPatch& p, double s, double t) {
  return surface_detail::bezier_point(p.ctrl.data(), p.degree_u, p.degree_v, s, t);
}

}  // namespace ncpath
