#include "kernels/verify/wall_distance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "kernels/curves/nurbs.hpp"

namespace ncpath {

namespace {

double cross2(const Vec2& u, const Vec2& v) { return u.x() * v.y() - u.y() * v.x(); }

// True when the closed segments [p0, p1] and [q0, q1] share a point (exact signs of the
// double cross products; collinear overlaps included).
bool segments_meet(const Vec2& p0, const Vec2& p1, const Vec2& q0, const Vec2& q1) {
  const double d1 = cross2(p1 - p0, q0 - p0), d2 = cross2(p1 - p0, q1 - p0);
  const double d3 = cross2(q1 - q0, p0 - q0), d4 = cross2(q1 - q0, p1 - q0);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0)))
    return true;
  return (d1 == 0 && point_segment_distance(q0, p0, p1) == 0) ||
         (d2 == 0 && point_segment_distance(q1, p0, p1) == 0) ||
         (d3 == 0 && point_segment_distance(p0, q0, q1) == 0) ||
         (d4 == 0 && point_segment_distance(p1, q0, q1) == 0);
}

double point_arc_gap(const Vec2& p, const Seg2& s) {
  if (p != s.c && arc_contains_angle(s, p)) return std::abs((p - s.c).norm() - s.r);
  return std::min((p - s.a).norm(), (p - s.b).norm());
}

double segment_arc_gap(const Vec2& p0, const Vec2& p1, const Seg2& s) {
  double best =
      std::min({point_arc_gap(p0, s), point_arc_gap(p1, s), point_segment_distance(s.a, p0, p1),
                point_segment_distance(s.b, p0, p1)});
  const Vec2 d = p1 - p0;
  const double len = d.norm();
  if (len == 0) return best;
  const Vec2 u = d / len, n(-u.y(), u.x());
  // Crossings of the segment with the circle: distance 0 when one lies on the arc.
  const double along = (s.c - p0).dot(u), off = (s.c - p0).dot(n);
  const double h2 = s.r * s.r - off * off;
  if (h2 >= 0) {
    const double h = std::sqrt(h2);
    for (double t : {along - h, along + h})
      if (t >= 0 && t <= len && arc_contains_angle(s, p0 + t * u)) return 0;
  }
  // Interior critical points: the arc points on the circle's diameter normal to the segment.
  if (along >= 0 && along <= len)
    for (double sign : {-1.0, 1.0}) {
      const Vec2 q = s.c + sign * s.r * n;
      if (arc_contains_angle(s, q)) best = std::min(best, std::abs((q - p0).dot(n)));
    }
  return best;
}

// de Casteljau split of a homogeneous Bézier at t = 1/2.
void split_half(const std::vector<Eigen::Vector3d>& c, std::vector<Eigen::Vector3d>& left,
                std::vector<Eigen::Vector3d>& right) {
  std::vector<Eigen::Vector3d> w = c;
  const std::size_t n = c.size();
  left.resize(n);
  right.resize(n);
  for (std::size_t r = 0; r < n; ++r) {
    left[r] = w[0];
    right[n - 1 - r] = w[n - 1 - r];
    for (std::size_t j = 0; j + 1 < n - r; ++j) w[j] = 0.5 * (w[j] + w[j + 1]);
  }
}

Vec2 projected(const Eigen::Vector3d& h) { return Vec2(h.x() / h.z(), h.y() / h.z()); }

BezierPiece make_piece(std::vector<Eigen::Vector3d> ctrl) {
  BezierPiece b;
  b.ctrl = std::move(ctrl);
  b.lo = b.hi = projected(b.ctrl.front());
  for (const Eigen::Vector3d& h : b.ctrl) {
    b.lo = b.lo.cwiseMin(projected(h));
    b.hi = b.hi.cwiseMax(projected(h));
  }
  return b;
}

// Largest distance of the control points from the chord: the curve lies within it (convex
// hull property, positive weights).
double flatness(const BezierPiece& b) {
  const Vec2 a = projected(b.ctrl.front()), e = projected(b.ctrl.back());
  double f = 0;
  for (std::size_t k = 1; k + 1 < b.ctrl.size(); ++k)
    f = std::max(f, point_segment_distance(projected(b.ctrl[k]), a, e));
  return f;
}

double box_gap(const Vec2& p0, const Vec2& p1, const Vec2& lo, const Vec2& hi) {
  // A lower bound: the distance between the segment's box and the piece's box.
  const Vec2 slo = p0.cwiseMin(p1), shi = p0.cwiseMax(p1);
  const double dx = std::max({0.0, lo.x() - shi.x(), slo.x() - hi.x()});
  const double dy = std::max({0.0, lo.y() - shi.y(), slo.y() - hi.y()});
  return std::hypot(dx, dy);
}

}  // namespace

double segment_segment_gap(const Vec2& p0, const Vec2& p1, const Vec2& q0, const Vec2& q1) {
  if (segments_meet(p0, p1, q0, q1)) return 0;
  return std::min({point_segment_distance(p0, q0, q1), point_segment_distance(p1, q0, q1),
                   point_segment_distance(q0, p0, p1), point_segment_distance(q1, p0, p1)});
}

double segment_curve_gap(const Vec2& p0, const Vec2& p1, const Seg2& s) {
  return s.is_arc() ? segment_arc_gap(p0, p1, s) : segment_segment_gap(p0, p1, s.a, s.b);
}

std::vector<BezierPiece> bezier_pieces(const Nurbs2& curve) {
  Nurbs2 c = curve;
  const int p = c.degree;
  // Every interior knot to multiplicity p.
  for (std::size_t i = static_cast<std::size_t>(p) + 1;
       i + static_cast<std::size_t>(p) + 1 < c.knots.size();) {
    std::size_t m = 1;
    while (i + m < c.knots.size() && c.knots[i + m] == c.knots[i]) ++m;
    if (m < static_cast<std::size_t>(p)) {
      c = nurbs_insert_knot(c, c.knots[i], p - static_cast<int>(m));
      m = static_cast<std::size_t>(p);
    }
    i += m;
  }
  std::vector<BezierPiece> out;
  for (std::size_t k = 0; k + static_cast<std::size_t>(p) < c.ctrl.size();
       k += static_cast<std::size_t>(p)) {
    std::vector<Eigen::Vector3d> h;
    for (std::size_t j = k; j <= k + static_cast<std::size_t>(p); ++j)
      h.emplace_back(c.weights[j] * c.ctrl[j].x(), c.weights[j] * c.ctrl[j].y(), c.weights[j]);
    out.push_back(make_piece(std::move(h)));
  }
  return out;
}

double segment_bezier_gap(const Vec2& p0, const Vec2& p1, const BezierPiece& piece, double cap,
                          double resolution) {
  double upper = cap, lower = cap;
  std::vector<BezierPiece> stack{piece};
  std::vector<Eigen::Vector3d> l, r;
  while (!stack.empty()) {
    BezierPiece b = std::move(stack.back());
    stack.pop_back();
    if (box_gap(p0, p1, b.lo, b.hi) >= upper) continue;
    const Vec2 a = projected(b.ctrl.front()), e = projected(b.ctrl.back());
    const double f = flatness(b);
    const double chord = segment_segment_gap(p0, p1, a, e);
    upper = std::min({upper, segment_segment_gap(p0, p1, a, a), segment_segment_gap(p0, p1, e, e)});
    if (chord - f >= upper) continue;
    if (f <= 0.5 * resolution) {
      lower = std::min(lower, std::max(0.0, chord - f));
      continue;
    }
    split_half(b.ctrl, l, r);
    stack.push_back(make_piece(l));
    stack.push_back(make_piece(r));
  }
  return std::min(lower, upper);
}

WallSet::WallSet(const std::vector<Region>& regions, double cap) : cap_(cap) {
  for (const Region& reg : regions) {
    std::vector<const Profile*> profiles{&reg.boundary};
    for (const Profile& island : reg.islands) profiles.push_back(&island);
    for (const Profile* pr : profiles)
      for (const ProfileCurve& c : pr->curves) {
        if (c.nurbs < 0) {
          segs_.push_back(c.seg);
          continue;
        }
        for (BezierPiece& b : bezier_pieces(pr->nurbs[static_cast<std::size_t>(c.nurbs)]))
          pieces_.push_back(std::move(b));
      }
  }
  // The grid: cells about cap wide, every item in the cells its box meets.
  std::vector<std::pair<Vec2, Vec2>> boxes;
  for (const Seg2& sg : segs_) {
    Vec2 lo, hi;
    loose_bounds(sg, lo, hi);
    boxes.emplace_back(lo, hi);
  }
  for (const BezierPiece& b : pieces_) boxes.emplace_back(b.lo, b.hi);
  grid_ = PlanGrid(boxes, cap);
}

double WallSet::distance(const Vec2& p0, const Vec2& p1, double resolution) const {
  thread_local std::vector<std::uint32_t> items;
  const Vec2 grow = Vec2::Constant(cap_);
  grid_.query(p0.cwiseMin(p1) - grow, p0.cwiseMax(p1) + grow, items);
  double best = cap_;
  const std::size_t nseg = segs_.size();
  for (std::uint32_t k : items) {
    if (k < nseg) {
      best = std::min(best, segment_curve_gap(p0, p1, segs_[k]));
    } else {
      const BezierPiece& b = pieces_[k - nseg];
      if (box_gap(p0, p1, b.lo, b.hi) < best)
        best = std::min(best, segment_bezier_gap(p0, p1, b, best, resolution));
    }
  }
  return best;
}

}  // namespace ncpath
