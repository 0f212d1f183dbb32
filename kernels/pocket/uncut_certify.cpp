// Certification of crude offset segments as lying near a level's curves (uncut regions,
// kernels/pocket/uncut.cpp): exact upper bounds on the distance, no sampling.
#include <algorithm>
#include <cmath>
#include <limits>

#include "kernels/pocket/offset_crude.hpp"
#include "kernels/pocket/seg_grid.hpp"

namespace ncpath::pocket_detail {

namespace {

// Bisections of a crude segment before it counts as holding a point far from the level (an
// uncertified segment only widens a window of the uncut-region dissection).
constexpr int kCertifyDepth = 16;

// Certifies segments, one after the other along a crude loop, as lying wholly within
// `limit` of the level's curves (the other level of a band: then no point of theirs can be
// on the boundary of an uncut region). A witness w (a curve of the level) bounds the
// distance from every point of a piece of segment: by the distance from its midpoint m plus
// the piece's largest distance from m (the distance is 1-Lipschitz), or by the shapes of the
// piece and of w (bound()). The witness follows the segments along the level; when it
// fails, the grid gives the curve nearest to m; pieces still not certified are bisected.
class NearLevel {
  static constexpr double kLongArc = 1e300;
  static constexpr int kWalk = 32;  // steps along the level from the last witness

 public:
  NearLevel(SegGrid& grid, double limit) : grid_(grid), limit_(limit) {}
  bool operator()(const Seg2& s) {
    // A segment that starts where the last certified one ended lies within its length (its
    // chord, for a line or a minor arc) of that end, whose distance is bounded already: the
    // joins at corners, short arcs, mostly pass this way.
    if (s.a == end_ && sagitta(s) < kLongArc) {
      const double u = end_bound_ + (s.b - s.a).norm();
      if (u < limit_) {
        end_ = s.b;
        end_bound_ = u;
        return true;
      }
    }
    double u = 0;
    if (!near(s, 0, u)) {
      end_bound_ = kLongArc;
      return false;
    }
    end_ = s.b;
    end_bound_ = u;
    return true;
  }

 private:
  // True when every point of s is certified; u: the bound that did it.
  bool near(const Seg2& s, int depth, double& u) {
    Vec2 m;
    double l;
    midpoint(s, m, l);
    const std::vector<Seg2>& curves = grid_.segments();
    if (has_witness_) {
      double best = distance(curves[witness_], m);
      if ((u = best + l) < limit_) return true;
      // The nearest curve moves along the level as the segments advance: walk from
      // the last witness while the distance to m decreases, the way it went last first.
      for (const int step : {step_, -step_}) {
        const std::uint32_t from = witness_;
        for (int k = 0; k < kWalk; ++k) {
          const std::uint32_t w = witness_ + step;
          if (w >= curves.size()) break;
          const double dw = distance(curves[w], m);
          if (dw >= best) break;
          best = dw;
          witness_ = w;
        }
        if (witness_ != from) {
          step_ = step;
          break;
        }
      }
      if ((u = best + l) < limit_ || (u = bound(s, curves[witness_])) < limit_) return true;
    }
    std::uint32_t w = 0;
    double d = 0;
    if (!grid_.nearest_within(m, limit_, w, d)) return false;  // m itself is that far
    witness_ = w;
    has_witness_ = true;
    if ((u = d + l) < limit_ || (u = bound(s, curves[w])) < limit_) return true;
    if (depth == kCertifyDepth) return false;
    if (depth == 0) {
      // A segment whose end is that far needs no bisecting.
      for (const Vec2& e : {s.a, s.b}) {
        std::uint32_t k = 0;
        if (!grid_.nearest_within(e, limit_, k, d)) return false;
      }
    }
    Seg2 first = s, second = s;
    first.b = second.a = m;
    double u1 = 0, u2 = 0;
    if (!near(first, depth + 1, u1) || !near(second, depth + 1, u2)) return false;
    u = std::max(u1, u2);
    return true;
  }

  // Largest distance from a point of s to w, bounded above. Lines w: the distance to a line
  // segment is convex, so along a chord of s it peaks at an end, and a minor arc strays from
  // its chord by its sagitta. Arcs w under a half turn: where s lies in the wedge of w's
  // sweep, the distance to w is the distance to its circle, ||p - c| - r|, whose extremes
  // over s are known; elsewhere w's chord stands in for w, less its sagitta. Longer arcs:
  // either half of w.
  static double bound(const Seg2& s, const Seg2& w) {
    const double ss = sagitta(s);
    if (!w.is_arc()) return std::max(distance(w, s.a), distance(w, s.b)) + ss;
    const double sw = sagitta(w);
    if (!(sw < kLongArc)) {
      Vec2 m;
      double l;
      midpoint(w, m, l);
      Seg2 first = w, second = w;
      first.b = second.a = m;
      return std::min(bound(s, first), bound(s, second));
    }
    if (in_wedge(s, w)) {
      double lo, hi;
      centre_distances(s, w.c, lo, hi);
      return std::max(hi - w.r, w.r - lo);
    }
    const Seg2 chord = make_line(w.a, w.b);
    return std::max(distance(chord, s.a), distance(chord, s.b)) + ss + sw;
  }

  // s lies in the wedge of the minor arc w's sweep: its ends do, and for an arc (up to a
  // quarter turn: the corner is well placed) the corner of its end tangents too (the convex
  // wedge then holds the triangle around the arc).
  static bool in_wedge(const Seg2& s, const Seg2& w) {
    if (!arc_contains_angle(w, s.a) || !arc_contains_angle(w, s.b)) return false;
    if (!s.is_arc()) return true;
    if (!(sagitta(s) < kLongArc)) return false;
    const Vec2 u = (s.a - s.c).normalized(), v = (s.b - s.c).normalized();
    const double c = 1 + u.dot(v);  // 2 cos^2(sweep / 2): at least 1 up to a quarter turn
    if (c < 1) return false;
    return arc_contains_angle(w, s.c + (s.r / c) * (u + v));
  }

  // Smallest and largest distance from p to a point of s.
  static void centre_distances(const Seg2& s, const Vec2& p, double& lo, double& hi) {
    const double da = (s.a - p).norm(), db = (s.b - p).norm();
    hi = std::max(da, db);
    if (!s.is_arc()) {
      lo = distance(s, p);
      return;
    }
    lo = std::min(da, db);
    const Vec2 d = p - s.c;
    const double l = d.norm();
    if (l == 0) {
      lo = hi = s.r;
      return;
    }
    const Vec2 nearest = s.c + (s.r / l) * d, farthest = s.c - (s.r / l) * d;
    if (arc_contains_angle(s, nearest)) lo = std::abs(l - s.r);
    if (arc_contains_angle(s, farthest)) hi = l + s.r;
  }

  // How far a minor arc strays from its chord (0 for lines, kLongArc from a half turn on).
  static double sagitta(const Seg2& s) {
    if (!s.is_arc()) return 0;
    const Vec2 u = s.a - s.c, w = s.b - s.c;
    const double c = u.x() * w.y() - u.y() * w.x();
    if (s.kind == SegKind::kArcCcw ? c <= 0 : c >= 0) return kLongArc;
    const double h = 0.5 * (s.b - s.a).norm();
    return s.r - std::sqrt(std::max(0.0, s.r * s.r - h * h));
  }

  // The point halfway along s and the largest distance from it to a point of s.
  static void midpoint(const Seg2& s, Vec2& m, double& l) {
    if (!s.is_arc()) {
      m = 0.5 * (s.a + s.b);
      l = 0.5 * (s.b - s.a).norm();
      return;
    }
    const Vec2 u = s.a - s.c, w = s.b - s.c;
    Vec2 dir = u + w;
    if (dir.squaredNorm() >= s.r * s.r) {
      // Sweeps under a third of a turn (or over two thirds): u + w bisects them (the ends
      // are r from the centre; m need not be exactly halfway, see below).
      const double c = u.x() * w.y() - u.y() * w.x();
      const bool minor = s.kind == SegKind::kArcCcw ? c >= 0 : c <= 0;
      dir = (minor ? 1.0 : -1.0) * dir.normalized();
    } else {
      // Near half a turn the chord is long: the middle lies square to it, on the right of
      // a counter-clockwise arc's chord and on the left of a clockwise one's.
      const Vec2 d = (s.b - s.a).normalized();
      dir = s.kind == SegKind::kArcCcw ? Vec2(d.y(), -d.x()) : Vec2(-d.y(), d.x());
    }
    m = s.c + s.r * dir;
    // Along the circle the distance from m grows with the angle from it (up to half a turn),
    // so the ends are the farthest points of the arc.
    l = std::max((s.a - m).norm(), (s.b - m).norm());
  }

  SegGrid& grid_;
  double limit_;
  std::uint32_t witness_ = 0;
  int step_ = 1;  // the way the witness last moved along the level
  bool has_witness_ = false;
  Vec2 end_ = Vec2::Constant(std::numeric_limits<double>::quiet_NaN());  // of the last certified
  double end_bound_ = kLongArc;  // bound on the distance at end_
};

}  // namespace

bool uncertified(const std::vector<RawSeg>& raw, std::size_t begin, std::size_t end, SegGrid& level,
                 double limit, std::vector<std::uint8_t>* bad) {
  NearLevel near(level, limit);
  bool any = false;
  for (std::size_t i = begin; i < end; ++i) {
    if (near(raw[i].s)) continue;
    if (!bad) return true;
    (*bad)[i] = 1;
    any = true;
  }
  return any;
}

}  // namespace ncpath::pocket_detail
