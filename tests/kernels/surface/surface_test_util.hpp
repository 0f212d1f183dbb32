#pragma once
// Test surfaces and independent oracles for kernels/surface. Nothing here calls
// kernels/surface/*.cpp except the NurbsSurface struct and bezier_grid_surface (a data
// constructor): evaluation is the textbook Cox-de Boor recursion or direct Bernstein sums,
// and the drop oracle is dense sampling plus a derivative-free local zoom.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "kernels/surface/nurbs_surface.hpp"
#include "tests/kernels/curves/nurbs_test_util.hpp"  // basis()

namespace ncpath::test {

constexpr double kSqrtHalf = std::numbers::sqrt2 / 2;

inline Vec3 cox_de_boor(const NurbsSurface& s, double u, double v) {
  Vec3 num = Vec3::Zero();
  double den = 0;
  for (int i = 0; i < s.nu; ++i) {
    const double bu = basis(s.knots_u, i, s.degree_u, u);
    if (bu == 0) continue;
    for (int j = 0; j < s.nv; ++j) {
      const double b = bu * basis(s.knots_v, j, s.degree_v, v) * s.weights[i * s.nv + j];
      num += b * s.ctrl[i * s.nv + j];
      den += b;
    }
  }
  return num / den;
}

inline double bernstein3(int i, double t) {
  const double s = 1 - t;
  switch (i) {
    case 0:
      return s * s * s;
    case 1:
      return 3 * t * s * s;
    case 2:
      return 3 * t * t * s;
    default:
      return t * t * t;
  }
}

// Direct Bernstein evaluation of a bicubic grid (as built by bezier_grid_surface): ctrl is
// (3 pu + 1) x (3 pv + 1), row-major by u, patch (a, b) covers [a, a + 1] x [b, b + 1].
struct BicubicGrid {
  int pu = 0, pv = 0;
  std::vector<Vec3> ctrl;

  Vec3 point(double u, double v) const {
    const int a = std::clamp(static_cast<int>(std::floor(u)), 0, pu - 1);
    const int b = std::clamp(static_cast<int>(std::floor(v)), 0, pv - 1);
    const double s = u - a, t = v - b;
    const int nv = 3 * pv + 1;
    Vec3 p = Vec3::Zero();
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j)
        p += bernstein3(i, s) * bernstein3(j, t) * ctrl[(3 * a + i) * nv + 3 * b + j];
    return p;
  }
};

// Knot vector 0,0,0,k,k,...,1,1,1 style helpers.
inline NurbsSurface make_surface(int p, int q, int nu, int nv, std::vector<double> ku,
                                 std::vector<double> kv) {
  NurbsSurface s;
  s.degree_u = p;
  s.degree_v = q;
  s.nu = nu;
  s.nv = nv;
  s.ctrl.assign(nu * nv, Vec3::Zero());
  s.weights.assign(nu * nv, 1.0);
  s.knots_u = std::move(ku);
  s.knots_v = std::move(kv);
  return s;
}

// Upper (sign = +1) or lower (sign = -1) hemisphere of radius r about the origin: u runs from
// the equator (u = 0) to the pole (u = 1), v once around (four quarter arcs). Exact rational
// biquadratic; the pole row is degenerate.
inline NurbsSurface hemisphere(double r, double sign) {
  const double w = kSqrtHalf;
  // Meridian (radius, height, weight) and circle (x, y, weight) control polygons.
  const double mer[3][3] = {{r, 0, 1}, {r, sign * r, w}, {0, sign * r, 1}};
  const double cir[9][3] = {{1, 0, 1},   {1, 1, w},  {0, 1, 1},  {-1, 1, w}, {-1, 0, 1},
                            {-1, -1, w}, {0, -1, 1}, {1, -1, w}, {1, 0, 1}};
  NurbsSurface s = make_surface(2, 2, 3, 9, {0, 0, 0, 1, 1, 1},
                                {0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1});
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 9; ++j) {
      s.ctrl[i * 9 + j] = Vec3(mer[i][0] * cir[j][0], mer[i][0] * cir[j][1], mer[i][1]);
      s.weights[i * 9 + j] = mer[i][2] * cir[j][2];
    }
  return s;
}

// Half cylinder of radius r about the x axis, x in [-len, len]: the upper half (sign = +1,
// a vault) or the lower half (sign = -1, a trough). u along x (degree 1), v around (two
// quarter arcs from y = -r to y = +r).
inline NurbsSurface half_cylinder(double r, double len, double sign) {
  const double w = kSqrtHalf;
  const double arc[5][3] = {
      {-r, 0, 1}, {-r, sign * r, w}, {0, sign * r, 1}, {r, sign * r, w}, {r, 0, 1}};
  NurbsSurface s = make_surface(1, 2, 2, 5, {0, 0, 1, 1}, {0, 0, 0, 0.5, 0.5, 1, 1, 1});
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 5; ++j) {
      s.ctrl[i * 5 + j] = Vec3(i == 0 ? -len : len, arc[j][0], arc[j][1]);
      s.weights[i * 5 + j] = arc[j][2];
    }
  return s;
}

// A wavy bicubic grid over [0, size]^2 with patches x patches patches: waves of amplitude amp
// plus random control-point noise (creases at the patch seams, concave regions of curvature
// radius below a few mm).
inline BicubicGrid wavy_grid(int patches, double size, double amp, double noise, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(-1, 1);
  BicubicGrid g;
  g.pu = g.pv = patches;
  const int n = 3 * patches + 1;
  const double ph1 = U(rng) * 3, ph2 = U(rng) * 3;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double x = size * i / (n - 1), y = size * j / (n - 1);
      const double z = amp * std::sin(2 * std::numbers::pi * x / (0.4 * size) + ph1) *
                           std::cos(2 * std::numbers::pi * y / (0.5 * size) + ph2) +
                       noise * U(rng);
      g.ctrl.emplace_back(x + 0.2 * noise * U(rng), y + 0.2 * noise * U(rng), z);
    }
  return g;
}

// Brute-force ball drop: the largest z + sqrt(R^2 - d^2) over surface samples within R of q in
// plan, from a dense sample grid then a derivative-free zoom around every grid local maximum
// within `margin` of the best sample. `eval(u, v)` gives the surface point on [u0, u1] x
// [v0, v1].
template <class Eval>
class DropOracle {
 public:
  DropOracle(Eval eval, double u0, double u1, double v0, double v1, int n)
      : eval_(eval), u0_(u0), u1_(u1), v0_(v0), v1_(v1), n_(n) {
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j <= n; ++j) samples_.push_back(eval(u(i), v(j)));
  }

  double f(const Vec3& p, const Vec2& q, double r) const {
    const double d2 = (p.head<2>() - q).squaredNorm();
    return d2 <= r * r ? p.z() + std::sqrt(r * r - d2) : -kInf;
  }

  // Smallest distance from c to a sample.
  double min_distance(const Vec3& c) const {
    double best = kInf;
    for (const Vec3& p : samples_) best = std::min(best, (p - c).squaredNorm());
    return std::sqrt(best);
  }

  // Largest f over the samples (no refinement).
  double sample_max(const Vec2& q, double r) const {
    double best = -kInf;
    for (const Vec3& p : samples_) best = std::max(best, f(p, q, r));
    return best;
  }

  double drop(const Vec2& q, double r, double margin) const {
    std::vector<double> fs(samples_.size());
    double best = -kInf;
    for (std::size_t k = 0; k < samples_.size(); ++k) {
      fs[k] = f(samples_[k], q, r);
      best = std::max(best, fs[k]);
    }
    if (best == -kInf) return best;
    double refined = best;
    for (int i = 0; i <= n_; ++i)
      for (int j = 0; j <= n_; ++j) {
        const double fk = fs[i * (n_ + 1) + j];
        if (fk < best - margin) continue;
        bool local_max = true;
        for (int di = -1; di <= 1 && local_max; ++di)
          for (int dj = -1; dj <= 1; ++dj) {
            const int a = i + di, b = j + dj;
            if (a < 0 || a > n_ || b < 0 || b > n_) continue;
            if (fs[a * (n_ + 1) + b] > fk) local_max = false;
          }
        if (local_max) refined = std::max(refined, zoom(q, r, u(i), v(j), fk));
      }
    return refined;
  }

 private:
  static constexpr double kInf = std::numeric_limits<double>::infinity();
  double u(int i) const { return u0_ + (u1_ - u0_) * i / n_; }
  double v(int j) const { return v0_ + (v1_ - v0_) * j / n_; }

  // Pattern search with a shrinking 5 x 5 stencil, clamped to the domain: the stencil moves
  // to its best point, and halves when its middle is best.
  double zoom(const Vec2& q, double r, double cu, double cv, double fc) const {
    double hu = 2 * (u1_ - u0_) / n_, hv = 2 * (v1_ - v0_) / n_;
    for (int it = 0; it < 5000 && hu > 1e-15 * (u1_ - u0_); ++it) {
      double bu = cu, bv = cv, bf = fc;
      for (int a = -2; a <= 2; ++a)
        for (int b = -2; b <= 2; ++b) {
          const double uu = std::clamp(cu + 0.5 * a * hu, u0_, u1_);
          const double vv = std::clamp(cv + 0.5 * b * hv, v0_, v1_);
          const double fv = f(eval_(uu, vv), q, r);
          if (fv > bf) bf = fv, bu = uu, bv = vv;
        }
      if (bu == cu && bv == cv) {
        hu *= 0.5;
        hv *= 0.5;
      }
      cu = bu;
      cv = bv;
      fc = bf;
    }
    return fc;
  }

  Eval eval_;
  double u0_, u1_, v0_, v1_;
  int n_;
  std::vector<Vec3> samples_;
};

// z = a x + b y + c over [x0, x1] x [y0, y1] (bilinear NURBS).
inline NurbsSurface tilted_plane(double a, double b, double c, double x0, double y0, double x1,
                                 double y1) {
  NurbsSurface s;
  s.degree_u = s.degree_v = 1;
  s.nu = s.nv = 2;
  for (double x : {x0, x1})
    for (double y : {y0, y1}) s.ctrl.emplace_back(x, y, a * x + b * y + c);
  s.weights.assign(4, 1.0);
  s.knots_u = s.knots_v = {0, 0, 1, 1};
  return s;
}

}  // namespace ncpath::test
