// Chordal polylines of NURBS curves: every knot span is subdivided at parameter midpoints
// until the chord is within the tolerance of curve samples inside it.
#include <algorithm>
#include <vector>

#include "kernels/curves/nurbs.hpp"
#include "kernels/curves/nurbs_detail.hpp"
#include "kernels/geom/segment2.hpp"
#include "kernels/geom/tolerance.hpp"

namespace ncpath {
namespace nurbs_detail {
namespace {

constexpr int kMaxDepth = 30;        // 2^30 chords per span: far beyond any sane tolerance
constexpr int kInteriorSamples = 5;  // deviation probes per chord, at i / 6

struct Refiner {
  const Nurbs2& c;
  double tol;
  std::vector<PolyPoint>& out;

  // Appends the points after (a, pa) up to and including (b, pb).
  void run(double a, const Vec2& pa, double b, const Vec2& pb, int depth) {
    double worst = 0;
    Vec2 mid_point = Vec2::Zero();
    for (int i = 1; i <= kInteriorSamples; ++i) {
      const double t = a + (b - a) * i / (kInteriorSamples + 1);
      const Vec2 q = nurbs_point(c, t);
      if (2 * i == kInteriorSamples + 1) mid_point = q;
      worst = std::max(worst, point_segment_distance(q, pa, pb));
    }
    if (worst <= tol || depth >= kMaxDepth) {
      out.push_back({b, pb});
      return;
    }
    const double m = 0.5 * (a + b);
    run(a, pa, m, mid_point, depth + 1);
    run(m, mid_point, b, pb, depth + 1);
  }
};

}  // namespace

std::vector<PolyPoint> polyline_with_params(const Nurbs2& c, double chordal_tol) {
  std::vector<PolyPoint> out;
  if (!validate(c).empty()) return out;
  const double tol = std::max(chordal_tol, tol::kNurbsMinTol);
  const std::vector<double> b = breakpoints(c);
  out.push_back({b.front(), nurbs_point(c, b.front())});
  Refiner r{c, tol, out};
  for (std::size_t i = 0; i + 1 < b.size(); ++i) {
    // Two starting chords per span: a single chord of a symmetric S-shaped span could have
    // all its probes near the chord.
    const double m = 0.5 * (b[i] + b[i + 1]);
    const Vec2 pm = nurbs_point(c, m);
    r.run(b[i], out.back().p, m, pm, 1);
    r.run(m, pm, b[i + 1], nurbs_point(c, b[i + 1]), 1);
  }
  return out;
}

}  // namespace nurbs_detail

std::vector<Vec2> nurbs_polyline(const Nurbs2& c, double chordal_tol) {
  const auto pts = nurbs_detail::polyline_with_params(c, chordal_tol);
  std::vector<Vec2> out;
  out.reserve(pts.size());
  for (const auto& q : pts) out.push_back(q.p);
  return out;
}

}  // namespace ncpath
