#pragma once
// Internals shared by the nurbs_*.cpp files (not part of the public API): span lookup, in-place
// knot insertion, sub-curves, joins and parameterised polylines. Curves are assumed valid
// (validate(curve) == "").
#include <array>
#include <vector>

#include "kernels/curves/nurbs.hpp"

namespace ncpath::nurbs_detail {

// Fixed-capacity buffer on the stack for the usual small degrees, heap beyond.
template <class T, int N>
class SmallBuf {
 public:
  explicit SmallBuf(int n) {
    if (n > N) {
      heap_.resize(n);
      p_ = heap_.data();
    }
  }
  T& operator[](int i) { return p_[i]; }
  const T& operator[](int i) const { return p_[i]; }

 private:
  std::array<T, N> local_{};
  std::vector<T> heap_;
  T* p_ = local_.data();
};

// Index k of the knot span [knots[k], knots[k+1]) holding t (t clamped to [t0, t1]; t1 maps
// to the last non-empty span), degree <= k < ctrl.size().
int find_span(const Nurbs2& c, double t);

// Distinct knot values t0 < ... < t1 (the span boundaries).
std::vector<double> breakpoints(const Nurbs2& c);

// Diagonal of the control points' bounding box, mm (>= a tiny positive floor).
double curve_size(const Nurbs2& c);

// True when the end points coincide (within tol::kNurbsZeroLength * size).
bool is_closed(const Nurbs2& c);

// Snaps t to an existing knot within tol::kKnotSnap * range; returns the multiplicity of the
// (snapped) t in the knot vector.
int snap_knot(const Nurbs2& c, double& t);

// Boehm insertion of t once, in place (multiplicity of t must be < degree, t0 < t < t1).
void insert_knot_once(Nurbs2& c, double t);

// Unit tangent at t, falling back to a short chord where the derivative vanishes; `side` =
// +1 looks forward from t, -1 backward (used at the ends of an interval).
Vec2 unit_tangent(const Nurbs2& c, double t, int side);

// Curve points with their parameters, chords within chordal_tol (see nurbs_polyline).
struct PolyPoint {
  double t;
  Vec2 p;
};
std::vector<PolyPoint> polyline_with_params(const Nurbs2& c, double chordal_tol);

}  // namespace ncpath::nurbs_detail
