#include "kernels/pocket/loop_polygon.hpp"

#include <algorithm>
#include <limits>

namespace ncpath::detail {
namespace {

double orient(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

// p is known to be collinear with a-b.
bool on_segment(const Vec2& a, const Vec2& b, const Vec2& p) {
  return std::min(a.x(), b.x()) <= p.x() && p.x() <= std::max(a.x(), b.x()) &&
         std::min(a.y(), b.y()) <= p.y() && p.y() <= std::max(a.y(), b.y());
}

bool opposite(double u, double v) { return (u > 0 && v < 0) || (u < 0 && v > 0); }

// Closed segments p1-q1 and p2-q2 share a point; `at` gets one.
bool segments_meet(const Vec2& p1, const Vec2& q1, const Vec2& p2, const Vec2& q2, Vec2& at) {
  const double d1 = orient(p2, q2, p1), d2 = orient(p2, q2, q1);
  const double d3 = orient(p1, q1, p2), d4 = orient(p1, q1, q2);
  if (opposite(d1, d2) && opposite(d3, d4)) {
    at = p1 + (d1 / (d1 - d2)) * (q1 - p1);
    return true;
  }
  if (d1 == 0 && on_segment(p2, q2, p1)) return at = p1, true;
  if (d2 == 0 && on_segment(p2, q2, q1)) return at = q1, true;
  if (d3 == 0 && on_segment(p1, q1, p2)) return at = p2, true;
  if (d4 == 0 && on_segment(p1, q1, q2)) return at = q2, true;
  return false;
}

struct Edge {
  double xmin, xmax, ymin, ymax;
  int loop, k;
};

}  // namespace

void update_bounds(LoopPolygon& poly) {
  poly.lo = Vec2::Constant(std::numeric_limits<double>::infinity());
  poly.hi = -poly.lo;
  for (const Vec2& p : poly.pts) {
    poly.lo = poly.lo.cwiseMin(p);
    poly.hi = poly.hi.cwiseMax(p);
  }
}

bool point_in_polygon(const LoopPolygon& poly, const Vec2& p) {
  bool inside = false;
  const std::size_t m = poly.pts.size();
  for (std::size_t i = 0, j = m - 1; i < m; j = i++) {
    const Vec2& a = poly.pts[i];
    const Vec2& b = poly.pts[j];
    // Half-open rule on y so that a vertex at p.y() counts once.
    if ((a.y() > p.y()) != (b.y() > p.y())) {
      const double x = a.x() + (p.y() - a.y()) / (b.y() - a.y()) * (b.x() - a.x());
      if (p.x() < x) inside = !inside;
    }
  }
  return inside;
}

PolygonCrossing find_crossing(const std::vector<LoopPolygon>& loops) {
  std::vector<Edge> edges;
  for (std::size_t l = 0; l < loops.size(); ++l) {
    const auto& pts = loops[l].pts;
    for (std::size_t k = 0; k < pts.size(); ++k) {
      const Vec2& p = pts[k];
      const Vec2& q = pts[(k + 1) % pts.size()];
      edges.push_back({std::min(p.x(), q.x()), std::max(p.x(), q.x()), std::min(p.y(), q.y()),
                       std::max(p.y(), q.y()), static_cast<int>(l), static_cast<int>(k)});
    }
  }
  std::sort(edges.begin(), edges.end(), [](const Edge& u, const Edge& v) {
    return u.xmin < v.xmin ||
           (u.xmin == v.xmin && (u.loop < v.loop || (u.loop == v.loop && u.k < v.k)));
  });

  PolygonCrossing out;
  auto report = [&](const Edge& e, const Edge& f, const Vec2& at) {
    out.found = true;
    out.loop_a = e.loop;
    out.loop_b = f.loop;
    out.curve_a = loops[e.loop].curve[e.k];
    out.curve_b = loops[f.loop].curve[f.k];
    out.at = at;
  };
  std::vector<Edge> active;
  for (const Edge& e : edges) {
    std::erase_if(active, [&](const Edge& f) { return f.xmax < e.xmin; });
    const auto& pe = loops[e.loop].pts;
    const Vec2& p1 = pe[e.k];
    const Vec2& q1 = pe[(e.k + 1) % pe.size()];
    for (const Edge& f : active) {
      if (f.ymax < e.ymin || e.ymax < f.ymin) continue;
      const auto& pf = loops[f.loop].pts;
      const Vec2& p2 = pf[f.k];
      const Vec2& q2 = pf[(f.k + 1) % pf.size()];
      const int m = static_cast<int>(pe.size());
      if (e.loop == f.loop && ((e.k + 1) % m == f.k || (f.k + 1) % m == e.k)) {
        // Adjacent edges share a vertex; they only overlap when one folds back on the other.
        const bool e_first = (e.k + 1) % m == f.k;
        const Vec2& a = e_first ? p1 : p2;
        const Vec2& v = e_first ? q1 : q2;
        const Vec2& b = e_first ? q2 : q1;
        if (orient(a, v, b) == 0 && (v - a).dot(b - v) < 0) {
          report(e, f, v);
          return out;
        }
        continue;
      }
      Vec2 at;
      if (segments_meet(p1, q1, p2, q2, at)) {
        report(e, f, at);
        return out;
      }
    }
    active.push_back(e);
  }
  return out;
}

}  // namespace ncpath::detail
