// Local self-loops of offset curves. Where the curvature radius on the offset side is below
// |d|, the offset C + d N runs backwards between two cusps (1 + d * kappa < 0) and forms a
// swallowtail whose crossing encloses that stretch. The crossing is found on a polyline of the
// offset (x-sorted sweep over its chords), refined by Newton on O(ta) = O(tb), and the part
// between ta and tb is removed. Crossings whose loop encloses no backward stretch, or turns
// the way the offset side does, are global (two far-apart parts of the offset meet): they are
// left to the pocket machinery.
#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>
#include <vector>

#include "kernels/curves/nurbs.hpp"
#include "kernels/curves/nurbs_detail.hpp"
#include "kernels/geom/tolerance.hpp"

namespace ncpath::nurbs_detail {
namespace {

constexpr int kReverseProbes = 8;  // samples of 1 + d * kappa per offset span
constexpr int kNewtonIters = 30;

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

struct Crossing {
  int i, j;  // polyline chords, i < j
  double ta, tb;
};

// Proper or touching intersections of non-adjacent chords of the polyline.
std::vector<Crossing> polyline_crossings(const std::vector<PolyPoint>& pl, bool closed) {
  const int m = static_cast<int>(pl.size()) - 1;
  std::vector<int> order(m);
  std::iota(order.begin(), order.end(), 0);
  auto lo_x = [&](int i) { return std::min(pl[i].p.x(), pl[i + 1].p.x()); };
  auto hi_x = [&](int i) { return std::max(pl[i].p.x(), pl[i + 1].p.x()); };
  std::sort(order.begin(), order.end(), [&](int a, int b) { return lo_x(a) < lo_x(b); });
  std::vector<Crossing> out;
  for (int oi = 0; oi < m; ++oi) {
    const int i = order[oi];
    const Vec2 &a = pl[i].p, &b = pl[i + 1].p;
    const double ylo = std::min(a.y(), b.y()), yhi = std::max(a.y(), b.y());
    for (int oj = oi + 1; oj < m && lo_x(order[oj]) <= hi_x(i); ++oj) {
      const int j = order[oj];
      if (std::abs(i - j) <= 1 || (closed && std::abs(i - j) == m - 1)) continue;
      const Vec2 &c = pl[j].p, &e = pl[j + 1].p;
      if (std::max(c.y(), e.y()) < ylo || std::min(c.y(), e.y()) > yhi) continue;
      const Vec2 r = b - a, s = e - c;
      const double den = cross(r, s);
      if (den == 0) continue;  // parallel chords: a neighbouring pair reports the crossing
      const double u = cross(c - a, s) / den, v = cross(c - a, r) / den;
      if (u < 0 || u > 1 || v < 0 || v > 1) continue;
      Crossing x{i, j, pl[i].t + u * (pl[i + 1].t - pl[i].t),
                 pl[j].t + v * (pl[j + 1].t - pl[j].t)};
      if (x.i > x.j) {
        std::swap(x.i, x.j);
        std::swap(x.ta, x.tb);
      }
      out.push_back(x);
    }
  }
  return out;
}

// Newton on O(ta) - O(tb) = 0 from the chord estimate; keeps the estimate when Newton leaves
// the chords' parameter ranges (near a cusp the Jacobian is singular).
void refine(const Nurbs2& o, const std::vector<PolyPoint>& pl, Crossing& x) {
  double ta = x.ta, tb = x.tb;
  const double alo = pl[x.i].t, ahi = pl[x.i + 1].t, blo = pl[x.j].t, bhi = pl[x.j + 1].t;
  for (int it = 0; it < kNewtonIters; ++it) {
    Vec2 a0, a1, a2, b0, b1, b2;
    nurbs_derivatives(o, ta, a0, a1, a2);
    nurbs_derivatives(o, tb, b0, b1, b2);
    const Vec2 f = nurbs_point(o, ta) - nurbs_point(o, tb);
    if (f.norm() <= tol::kCurveIntersect) {
      x.ta = ta;
      x.tb = tb;
      return;
    }
    // [a1, -b1] (dta, dtb) = -f
    const double det = -cross(a1, b1);
    if (det == 0) return;
    const double dta = cross(-f, -b1) / det, dtb = cross(a1, -f) / det;
    ta += dta;
    tb += dtb;
    const double wa = ahi - alo, wb = bhi - blo;
    if (!(ta > alo - wa && ta < ahi + wa && tb > blo - wb && tb < bhi + wb)) return;
  }
}

bool any_in(const std::vector<double>& sorted, double a, double b) {
  const auto it = std::upper_bound(sorted.begin(), sorted.end(), a);
  return it != sorted.end() && *it < b;
}

}  // namespace

std::vector<Nurbs2> trim_offset_loops(const Nurbs2& orig, const Nurbs2& off, double d, double tol) {
  const double t0 = nurbs_t0(off), t1 = nurbs_t1(off);
  // Parameters where the offset runs backwards.
  std::vector<double> rev;
  const std::vector<double> bp = breakpoints(off);
  for (std::size_t k = 0; k + 1 < bp.size(); ++k)
    for (int j = 0; j < kReverseProbes; ++j) {
      const double t = bp[k] + (bp[k + 1] - bp[k]) * (j + 0.5) / kReverseProbes;
      if (1 + d * nurbs_curvature(orig, t) < 0) rev.push_back(t);
    }
  if (rev.empty()) return {off};

  const bool closed = (off.ctrl.front() - off.ctrl.back()).norm() <= tol;
  const std::vector<PolyPoint> pl = polyline_with_params(off, tol);
  // Prefix sums of chord lengths and of cross(p_k, p_k+1) (twice the signed area).
  const std::size_t np = pl.size();
  std::vector<double> cum(np, 0.0), area(np, 0.0);
  for (std::size_t k = 1; k < np; ++k) {
    cum[k] = cum[k - 1] + (pl[k].p - pl[k - 1].p).norm();
    area[k] = area[k - 1] + cross(pl[k - 1].p, pl[k].p);
  }
  // A swallowtail turns against the offset side: its loop has the sign of d (clockwise for
  // a left offset, d < 0); a loop turning the other way is a global one (e.g. the whole
  // offset of a closed curve) even when it contains backward stretches.
  auto local = [&](double area2) { return (area2 > 0) == (d > 0) && area2 != 0; };

  std::vector<std::pair<double, double>> cut;  // removed parameter intervals
  for (Crossing x : polyline_crossings(pl, closed)) {
    refine(off, pl, x);
    if (!(x.ta < x.tb)) continue;
    const Vec2 X = nurbs_point(off, x.ta);
    const double in_area =
        cross(X, pl[x.i + 1].p) + area[x.j] - area[x.i + 1] + cross(pl[x.j].p, X);
    const double out_area = cross(X, pl[x.j + 1].p) + area[np - 1] - area[x.j + 1] +
                            cross(pl[np - 1].p, pl[0].p) + area[x.i] + cross(pl[x.i].p, X);
    const bool inner = any_in(rev, x.ta, x.tb) && local(in_area);
    const bool outer =
        closed && local(out_area) && (any_in(rev, -INFINITY, x.ta) || any_in(rev, x.tb, INFINITY));
    if (!inner && !outer) continue;  // a global crossing
    const double inner_len = cum[x.j] - cum[x.i];
    if (inner && (!outer || inner_len <= cum.back() - inner_len)) {
      cut.emplace_back(x.ta, x.tb);
    } else {
      cut.emplace_back(t0, x.ta);
      cut.emplace_back(x.tb, t1);
    }
  }
  std::sort(cut.begin(), cut.end());
  std::vector<std::pair<double, double>> keep;
  double from = t0;
  for (const auto& [a, b] : cut) {
    if (a > from) keep.emplace_back(from, a);
    from = std::max(from, b);
  }
  if (from < t1) keep.emplace_back(from, t1);

  auto backwards = [&](double a, double b) {
    for (int j = 0; j < 16; ++j)
      if (1 + d * nurbs_curvature(orig, a + (b - a) * (j + 0.5) / 16) >= 0) return false;
    return true;
  };
  std::vector<Nurbs2> pieces;
  for (const auto& [a, b] : keep) {
    const double snap = tol::kKnotSnap * (t1 - t0);
    if (b - a <= 4 * snap || backwards(a, b)) continue;
    pieces.push_back(sub_curve(off, a <= t0 + snap ? t0 : a, b >= t1 - snap ? t1 : b));
  }
  // A closed offset whose seam survived: the last piece continues into the first.
  if (closed && pieces.size() >= 2 && keep.front().first == t0 && keep.back().second == t1 &&
      !cut.empty()) {
    pieces.front() = join(pieces.back(), pieces.front());
    pieces.pop_back();
    std::rotate(pieces.begin(), pieces.begin() + 1, pieces.end());
  }
  // Pieces meeting at a crossing share the crossing point exactly.
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    const std::size_t next = k + 1 < pieces.size() ? k + 1 : 0;
    if (next == k || (next == 0 && !closed)) continue;
    Vec2& e = pieces[k].ctrl.back();
    Vec2& s = pieces[next].ctrl.front();
    if ((e - s).norm() <= tol) e = s = 0.5 * (e + s);
  }
  return pieces;
}

}  // namespace ncpath::nurbs_detail
