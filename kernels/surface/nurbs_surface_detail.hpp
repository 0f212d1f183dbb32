#pragma once
// Internals shared by kernels/surface/*.cpp (not part of the public API): small stack
// buffers, Bernstein bases, rational Bezier patch evaluation and de Casteljau splitting on
// raw homogeneous control nets ((p + 1) x (q + 1) points (x w, y w, z w, w), row-major by u),
// and the rational quotient rule.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Geometry>  // cross products

#include "kernels/surface/nurbs_surface.hpp"

namespace ncpath::surface_detail {

using H4 = Eigen::Vector4d;

// Fixed-capacity buffer on the stack for the usual small sizes, heap beyond. The local storage
// is not value-initialised: callers write before they read.
template <class T, int N>
class SmallBuf {
 public:
  explicit SmallBuf(int n) {
    if (n > N) {
      heap_ = std::make_unique<T[]>(n);
      p_ = heap_.get();
    }
  }
  SmallBuf(const SmallBuf&) = delete;
  SmallBuf& operator=(const SmallBuf&) = delete;
  T* data() { return p_; }
  T& operator[](int i) { return p_[i]; }
  const T& operator[](int i) const { return p_[i]; }

 private:
  std::array<T, N> local_;
  std::unique_ptr<T[]> heap_;
  T* p_ = local_.data();
};

// Homogeneous partial derivatives in the order d00, d10, d01, d20, d11, d02 (first index: u).
struct HomogDerivs {
  H4 d[6];
};
// Point and derivatives of the rational surface A / w from its homogeneous derivatives.
SurfacePoint rational_point(const HomogDerivs& h);

// Bernstein polynomials of degree p at t and their first and second derivatives:
// b0[i], b1[i], b2[i] for i = 0..p (each array holds p + 1 values).
void bernstein(int p, double t, double* b0, double* b1, double* b2);

// Point and derivatives of a rational Bezier patch at local (s, t) in [0, 1]^2 (derivatives
// with respect to s and t).
SurfacePoint bezier_evaluate(const H4* ctrl, int p, int q, double s, double t);
// The same with degrees known at compile time.
template <int P, int Q>
SurfacePoint bezier_evaluate_fixed(const H4* ctrl, double s, double t) {
  double bu[3][P + 1], bv[3][Q + 1];
  bernstein(P, s, bu[0], bu[1], bu[2]);
  bernstein(Q, t, bv[0], bv[1], bv[2]);
  HomogDerivs h;
  for (H4& d : h.d) d.setZero();
  for (int a = 0; a <= P; ++a) {
    H4 r0 = H4::Zero(), r1 = H4::Zero(), r2 = H4::Zero();
    const H4* row = ctrl + a * (Q + 1);
    for (int b = 0; b <= Q; ++b) {
      r0 += bv[0][b] * row[b];
      r1 += bv[1][b] * row[b];
      r2 += bv[2][b] * row[b];
    }
    h.d[0] += bu[0][a] * r0;
    h.d[1] += bu[1][a] * r0;
    h.d[2] += bu[0][a] * r1;
    h.d[3] += bu[2][a] * r0;
    h.d[4] += bu[1][a] * r1;
    h.d[5] += bu[0][a] * r2;
  }
  return rational_point(h);
}

// Point only.
Vec3 bezier_point(const H4* ctrl, int p, int q, double s, double t);

// de Casteljau split at the middle of s (along_u) or of t: a gets [0, 1/2], b [1/2, 1].
// a and b must not alias ctrl.
void bezier_split(const H4* ctrl, int p, int q, bool along_u, H4* a, H4* b);

// Bounding box of the n dehomogenised control points.
void control_box(const H4* ctrl, int n, Vec3& lo, Vec3& hi);

// Scalar tensor-product Bezier polynomials (coefficients c[i * (b + 1) + j], degrees (a, b)).
// Product: result degrees (a1 + a2, b1 + b2).
std::vector<double> bezier_multiply(const std::vector<double>& c1, int a1, int b1,
                                    const std::vector<double>& c2, int a2, int b2);
// de Casteljau split of a scalar polynomial at the middle of s (along_u) or of t.
void bezier_split_scalar(const std::vector<double>& c, int a, int b, bool along_u,
                         std::vector<double>& lo, std::vector<double>& hi);

// "(0.4, 0.7)" with up to 6 significant digits, for messages.
std::string pair_text(double a, double b);

}  // namespace ncpath::surface_detail
