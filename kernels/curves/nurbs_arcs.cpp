// NURBS to lines and arcs by biarcs. The curve is cut at its knots and inflections, then each
// piece is fitted with the equal-tangent-length biarc matching its end points and tangents;
// pieces turning by more than 90 degrees, or whose biarc deviates from dense curve samples by
// more than the tolerance (measured both ways), are halved. Shared break points are computed
// once, so the segments chain bitwise and G1 wherever the curve is.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "kernels/curves/nurbs.hpp"
#include "kernels/curves/nurbs_detail.hpp"
#include "kernels/geom/segment2.hpp"
#include "kernels/geom/tolerance.hpp"

namespace ncpath {
namespace {

using nurbs_detail::unit_tangent;

constexpr int kInflectionProbes = 16;  // samples of cross(C', C'') per knot span
constexpr int kTurnProbes = 8;         // tangent samples for the turning angle of a piece
constexpr int kCurveSamples = 24;      // interior curve samples checked against the biarc
constexpr int kArcSamples = 6;         // interior arc samples checked against the curve
constexpr int kMaxDepth = 40;
constexpr double kPi = std::numbers::pi;

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

Seg2 line(const Vec2& a, const Vec2& b) {
  Seg2 s;
  s.a = a;
  s.b = b;
  s.kind = SegKind::kLine;
  return s;
}

// Arc from a, leaving along unit tangent ta, to b (a line when nearly straight).
Seg2 tangent_arc(const Vec2& a, const Vec2& ta, const Vec2& b) {
  const Vec2 ch = b - a;
  const double sw = 2 * std::atan2(cross(ta, ch), ta.dot(ch));
  if (std::abs(sw) < tol::kArcAsLineSweep) return line(a, b);
  const Vec2 n(-ta.y(), ta.x());
  const double s = ch.squaredNorm() / (2 * ch.dot(n));  // signed radius, > 0 turning left
  Seg2 g;
  g.a = a;
  g.b = b;
  g.c = a + s * n;
  g.r = 0.5 * ((a - g.c).norm() + (b - g.c).norm());
  g.kind = s > 0 ? SegKind::kArcCcw : SegKind::kArcCw;
  return g;
}

Seg2 flipped(const Seg2& s) {
  Seg2 r = s;
  std::swap(r.a, r.b);
  if (s.kind != SegKind::kLine)
    r.kind = s.kind == SegKind::kArcCcw ? SegKind::kArcCw : SegKind::kArcCcw;
  return r;
}

// Signed sweep of an arc in (-2 pi, 2 pi); 0 for lines.
double arc_sweep(const Seg2& s) {
  if (s.kind == SegKind::kLine) return 0;
  double a = std::atan2(cross(s.a - s.c, s.b - s.c), (s.a - s.c).dot(s.b - s.c));
  if (s.kind == SegKind::kArcCcw && a < 0) a += 2 * kPi;
  if (s.kind == SegKind::kArcCw && a > 0) a -= 2 * kPi;
  return a;
}

Vec2 on_seg(const Seg2& s, double f) {
  if (s.kind == SegKind::kLine) return s.a + f * (s.b - s.a);
  const double a0 = std::atan2(s.a.y() - s.c.y(), s.a.x() - s.c.x()) + f * arc_sweep(s);
  return s.c + s.r * Vec2(std::cos(a0), std::sin(a0));
}

double seg_distance(const Seg2& s, const Vec2& p) {
  if (s.kind == SegKind::kLine) return point_segment_distance(p, s.a, s.b);
  const double sw = arc_sweep(s);
  double a = std::atan2(cross(s.a - s.c, p - s.c), (s.a - s.c).dot(p - s.c));
  if (sw > 0 && a < 0) a += 2 * kPi;
  if (sw < 0 && a > 0) a -= 2 * kPi;
  if (std::abs(a) <= std::abs(sw)) return std::abs((p - s.c).norm() - s.r);
  return std::min((p - s.a).norm(), (p - s.b).norm());
}

struct Fitter {
  const Nurbs2& c;
  double tol;
  std::uint32_t source;
  std::vector<Seg2>& out;

  double turning(double a, double b) const {
    double sum = 0;
    Vec2 prev = unit_tangent(c, a, +1);
    for (int i = 1; i <= kTurnProbes; ++i) {
      const Vec2 t = unit_tangent(c, a + (b - a) * i / kTurnProbes, i == kTurnProbes ? -1 : +1);
      sum += std::atan2(cross(prev, t), prev.dot(t));
      prev = t;
    }
    return std::abs(sum);
  }

  // Equal-tangent-length biarc; returns the junction point.
  static Vec2 biarc(const Vec2& pa, const Vec2& ta, const Vec2& pb, const Vec2& tb, Seg2& s1,
                    Seg2& s2) {
    const Vec2 v = pb - pa, t = ta + tb;
    const double denom = 2 * (1 - ta.dot(tb));
    double dl;
    if (denom < 1e-12) {
      const double vt2 = v.dot(tb);
      dl = std::abs(vt2) > 1e-300 ? v.squaredNorm() / (4 * vt2) : 0.0;
    } else {
      const double vt = v.dot(t);
      dl = (-vt + std::sqrt(vt * vt + denom * v.squaredNorm())) / denom;
    }
    const Vec2 pm = 0.5 * (pa + pb + dl * (ta - tb));
    s1 = tangent_arc(pa, ta, pm);
    s2 = flipped(tangent_arc(pb, -tb, pm));
    return pm;
  }

  double deviation(double a, const Vec2& pa, double b, const Vec2& pb, const Seg2& s1,
                   const Seg2& s2) const {
    std::vector<Vec2> q;
    std::vector<double> qt;
    q.reserve(kCurveSamples + 2);
    q.push_back(pa);
    qt.push_back(a);
    double worst = 0;
    for (int i = 1; i <= kCurveSamples; ++i) {
      const double t = a + (b - a) * i / (kCurveSamples + 1);
      const Vec2 p = nurbs_point(c, t);
      worst = std::max(worst, std::min(seg_distance(s1, p), seg_distance(s2, p)));
      q.push_back(p);
      qt.push_back(t);
    }
    q.push_back(pb);
    qt.push_back(b);
    // The other way: the biarc must not wander away from the curve between samples. Nearest
    // sample, then Newton on (C(t) - p) . C'(t) = 0 within [a, b].
    for (const Seg2* s : {&s1, &s2})
      for (int i = 1; i <= kArcSamples; ++i) {
        const Vec2 p = on_seg(*s, static_cast<double>(i) / (kArcSamples + 1));
        std::size_t k = 0;
        for (std::size_t j = 1; j < q.size(); ++j)
          if ((q[j] - p).squaredNorm() < (q[k] - p).squaredNorm()) k = j;
        double best = (q[k] - p).norm(), t = qt[k];
        for (int it = 0; it < 4; ++it) {
          Vec2 d0, d1, d2;
          nurbs_derivatives(c, t, d0, d1, d2);
          const double den = d1.squaredNorm() + (d0 - p).dot(d2);
          if (!(den > 0)) break;
          t = std::clamp(t - (d0 - p).dot(d1) / den, a, b);
          best = std::min(best, (nurbs_point(c, t) - p).norm());
        }
        worst = std::max(worst, best);
      }
    return worst;
  }

  void emit(Seg2 s) {
    if (s.a == s.b) return;  // zero length: the chain stays exact without it
    s.source = source;
    out.push_back(s);
  }

  void fit(double a, const Vec2& pa, double b, const Vec2& pb, int depth) {
    if (pa == pb && depth > 0) return;
    const double m = 0.5 * (a + b);
    const bool can_split = depth < kMaxDepth && m > a && m < b;
    if (can_split && turning(a, b) > 0.5 * kPi + 1e-6) {  // slack: quarter circles stay whole
      const Vec2 pm = nurbs_point(c, m);
      fit(a, pa, m, pm, depth + 1);
      fit(m, pm, b, pb, depth + 1);
      return;
    }
    Seg2 s1, s2;
    biarc(pa, unit_tangent(c, a, +1), pb, unit_tangent(c, b, -1), s1, s2);
    if (can_split && deviation(a, pa, b, pb, s1, s2) > tol) {
      const Vec2 pm = nurbs_point(c, m);
      fit(a, pa, m, pm, depth + 1);
      fit(m, pm, b, pb, depth + 1);
      return;
    }
    emit(s1);
    emit(s2);
  }
};

double curvature_sign_function(const Nurbs2& c, double t) {
  Vec2 d0, d1, d2;
  nurbs_derivatives(c, t, d0, d1, d2);
  return cross(d1, d2);
}

}  // namespace

std::vector<Seg2> nurbs_to_arcs(const Nurbs2& c, double tol, std::uint32_t source) {
  std::vector<Seg2> out;
  if (!validate(c).empty()) return out;
  tol = std::max(tol, tol::kNurbsMinTol);
  // Break points: knots and inflections (sign changes of cross(C', C'') refined by bisection).
  const std::vector<double> knots = nurbs_detail::breakpoints(c);
  std::vector<double> br;
  for (std::size_t k = 0; k + 1 < knots.size(); ++k) {
    br.push_back(knots[k]);
    const double a = knots[k], b = knots[k + 1];
    double prev_t = a, prev_f = curvature_sign_function(c, a + 1e-9 * (b - a));
    for (int i = 1; i <= kInflectionProbes; ++i) {
      const double t =
          i == kInflectionProbes ? b - 1e-9 * (b - a) : a + (b - a) * i / kInflectionProbes;
      const double f = curvature_sign_function(c, t);
      if (f == 0) continue;
      if (prev_f != 0 && (f > 0) != (prev_f > 0)) {
        double lo = prev_t, hi = t;
        for (int it = 0; it < 60 && hi - lo > 0; ++it) {
          const double mid = 0.5 * (lo + hi);
          if ((curvature_sign_function(c, mid) > 0) == (prev_f > 0))
            lo = mid;
          else
            hi = mid;
        }
        const double root = 0.5 * (lo + hi);
        if (root > br.back() && root < b) br.push_back(root);
      }
      prev_t = t;
      prev_f = f;
    }
  }
  br.push_back(knots.back());
  Fitter f{c, tol, source, out};
  Vec2 pa = nurbs_point(c, br[0]);  // exactly ctrl.front()
  for (std::size_t i = 0; i + 1 < br.size(); ++i) {
    const Vec2 pb = nurbs_point(c, br[i + 1]);  // exactly ctrl.back() at the end
    f.fit(br[i], pa, br[i + 1], pb, 0);
    pa = pb;
  }
  return out;
}

}  // namespace ncpath
