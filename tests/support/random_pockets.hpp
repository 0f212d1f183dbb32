#pragma once
// Random pocket regions for property tests (tests/batch/io/random_pocket_dxf_test.cpp checks
// them; their DXF form is in random_pockets_dxf.hpp).
//
// random_pocket(seed) returns one Region (boundary clockwise, islands counter-clockwise, see
// kernels/pocket/profile.hpp) of a kind chosen by the seed:
//  - kStar: a star-shaped outline, its radius function sampled at 5-24 angles and joined by
//    lines, bulged arcs, clamped cubic NURBS through/near runs of samples and elliptic arcs
//    (rational quadratic NURBS), 20-150 mm across;
//  - kDumbbell: two such lobes joined by a neck whose narrowest width is 1.2-3 tool diameters.
// 0-4 islands (circles as arcs or one rational NURBS, small stars, full or split ellipses) keep
// a gap g in {0.05, 0.5, 3} mm from the boundary and from each other; circles and ellipses are
// often sized to come within g + 0.01 mm of the wall on purpose. Some seeds are rotated and
// moved up to RandomPocketOptions::max_offset from the origin.
// Consecutive curves share bitwise-equal end points. Every candidate is checked on polylines
// within 1 um (no crossings, no touching); a failed candidate is rebuilt from the same random
// stream, so the result depends on the seed only. std::mt19937_64 is fully specified by the
// standard; its raw output feeds our own uniform and shuffle, never a <random> distribution
// (their output differs between standard libraries). libm's last-bit differences remain.
//
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "kernels/curves/nurbs.hpp"
#include "kernels/curves/segment.hpp"
#include "kernels/pocket/profile.hpp"

namespace ncpath::test {

struct RandomPocketOptions {
  double tool_diameter = 6;  // mm; necks are 1.2-3 times as wide
  double min_size = 20;      // mm; bounding-box extent of the boundary, before rotation
  double max_size = 150;     // mm
  int max_islands = 4;       // 0-4 are drawn; fewer when they do not fit
  double max_offset = 1e5;   // mm; far seeds are translated by up to this per axis
  bool allow_far = true;     // false: every region stays within ~max_size of the origin
};

enum class RandomPocketKind : int { kStar = 0, kDumbbell = 1 };

// What a seed produced (for messages and coverage checks in tests).
struct RandomPocketInfo {
  RandomPocketKind kind = RandomPocketKind::kStar;
  int samples = 0;             // angles of the radius function (star) or per lobe (dumbbell)
  double size = 0;             // mm; larger side of the boundary's bounding box (unrotated)
  double gap = 0;              // mm; islands keep at least this from the wall and each other
  double neck_width = 0;       // mm; narrowest neck width (dumbbell), else 0
  double rotation = 0;         // radians, about the origin, applied before the translation
  Vec2 offset = Vec2::Zero();  // mm
  int attempts = 0;            // candidates built (1 when the first was valid)
};

namespace random_pocket_detail {

inline double cross2(const Vec2& u, const Vec2& v) { return u.x() * v.y() - u.y() * v.x(); }
inline Vec2 left_normal(const Vec2& u) { return {-u.y(), u.x()}; }
constexpr double kTwoPi = 2 * std::numbers::pi;
constexpr double kPolylineTol = 1e-3;  // mm; chordal tolerance of the check polylines

class Rng {
 public:
  explicit Rng(std::uint64_t seed) : g_(seed) {}
  double uniform() { return static_cast<double>(g_() >> 11) * 0x1.0p-53; }  // [0, 1)
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  int integer(int lo, int hi) {  // inclusive
    return std::min(hi, lo + static_cast<int>(uniform() * (hi - lo + 1)));
  }
  bool chance(double p) { return uniform() < p; }
  template <class T>
  void shuffle(std::vector<T>& v) {  // Fisher-Yates
    for (std::size_t i = v.size(); i > 1; --i)
      std::swap(v[i - 1], v[static_cast<std::size_t>(integer(0, static_cast<int>(i) - 1))]);
  }

 private:
  std::mt19937_64 g_;
};

inline ProfileCurve nurbs_curve(Profile& p, Nurbs2 n) {
  ProfileCurve pc;
  pc.seg = make_line(n.ctrl.front(), n.ctrl.back());
  pc.nurbs = static_cast<std::int32_t>(p.nurbs.size());
  p.nurbs.push_back(std::move(n));
  return pc;
}

// Applies a similarity without reflection (f maps points) to every curve. Shared end points
// stay bitwise equal because f is a function of the point alone.
template <class F>
void map_profile(Profile& p, F f) {
  for (ProfileCurve& pc : p.curves) {
    pc.seg.a = f(pc.seg.a);
    pc.seg.b = f(pc.seg.b);
    if (pc.nurbs < 0 && pc.seg.is_arc()) {
      pc.seg.c = f(pc.seg.c);
      pc.seg.r = (pc.seg.a - pc.seg.c).norm();
    }
  }
  for (Nurbs2& n : p.nurbs)
    for (Vec2& c : n.ctrl) c = f(c);
}

inline Profile reversed_profile(const Profile& p) {
  Profile r;
  r.nurbs.reserve(p.nurbs.size());
  for (const Nurbs2& n : p.nurbs) r.nurbs.push_back(nurbs_reversed(n));
  for (auto it = p.curves.rbegin(); it != p.curves.rend(); ++it) {
    ProfileCurve pc = *it;
    if (pc.nurbs >= 0)
      std::swap(pc.seg.a, pc.seg.b);
    else
      pc.seg = reversed(pc.seg);
    r.curves.push_back(pc);
  }
  return r;
}

// Closed polyline within kPolylineTol of the profile (first point not repeated).
inline std::vector<Vec2> profile_polyline(const Profile& p) {
  std::vector<Vec2> out;
  for (const ProfileCurve& pc : p.curves) {
    if (pc.nurbs < 0) {
      append_polyline(pc.seg, kPolylineTol, out);
    } else {
      const std::vector<Vec2> q = nurbs_polyline(p.nurbs[pc.nurbs], kPolylineTol);
      out.insert(out.end(), q.begin(), q.end() - 1);
    }
  }
  return out;
}

inline double point_segment_distance(const Vec2& q, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double l2 = ab.squaredNorm();
  const double t = l2 > 0 ? std::clamp((q - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
  return (a + t * ab - q).norm();
}

// Distance from q to the closed polyline, and the nearest vertex-or-projection point.
inline double polyline_distance(const std::vector<Vec2>& loop, const Vec2& q, Vec2* nearest) {
  double best = INFINITY;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const Vec2& a = loop[i];
    const Vec2& b = loop[(i + 1) % loop.size()];
    const double d = point_segment_distance(q, a, b);
    if (d < best) {
      best = d;
      if (nearest) {
        const Vec2 ab = b - a;
        const double l2 = ab.squaredNorm();
        *nearest = a + (l2 > 0 ? std::clamp((q - a).dot(ab) / l2, 0.0, 1.0) : 0.0) * ab;
      }
    }
  }
  return best;
}

inline bool point_in_loop(const std::vector<Vec2>& loop, const Vec2& q) {
  bool in = false;
  for (std::size_t i = 0, j = loop.size() - 1; i < loop.size(); j = i++) {
    const Vec2& a = loop[i];
    const Vec2& b = loop[j];
    if ((a.y() > q.y()) != (b.y() > q.y()) &&
        q.x() < a.x() + (q.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y()))
      in = !in;
  }
  return in;
}

inline bool segments_touch(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const double d1 = cross2(d - c, a - c), d2 = cross2(d - c, b - c);
  const double d3 = cross2(b - a, c - a), d4 = cross2(b - a, d - a);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0)))
    return true;
  auto on = [](const Vec2& p, const Vec2& q, const Vec2& r) {  // r on pq, given collinear
    return std::min(p.x(), q.x()) <= r.x() && r.x() <= std::max(p.x(), q.x()) &&
           std::min(p.y(), q.y()) <= r.y() && r.y() <= std::max(p.y(), q.y());
  };
  return (d1 == 0 && on(c, d, a)) || (d2 == 0 && on(c, d, b)) || (d3 == 0 && on(a, b, c)) ||
         (d4 == 0 && on(a, b, d));
}

// True when two edges of the closed polylines touch or cross (edges adjacent within one loop
// excepted). Sweep over edges sorted by their lowest x.
inline bool loops_cross(const std::vector<std::vector<Vec2>>& loops) {
  struct Edge {
    double lo, hi;
    int loop, k;
  };
  std::vector<Edge> edges;
  for (int l = 0; l < static_cast<int>(loops.size()); ++l) {
    const auto& L = loops[l];
    for (int k = 0; k < static_cast<int>(L.size()); ++k) {
      const Vec2& a = L[k];
      const Vec2& b = L[(k + 1) % L.size()];
      edges.push_back({std::min(a.x(), b.x()), std::max(a.x(), b.x()), l, k});
    }
  }
  std::sort(edges.begin(), edges.end(), [](const Edge& x, const Edge& y) {
    return x.lo != y.lo ? x.lo < y.lo : (x.loop != y.loop ? x.loop < y.loop : x.k < y.k);
  });
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const Edge& e = edges[i];
    const auto& L = loops[e.loop];
    const Vec2& a = L[e.k];
    const Vec2& b = L[(e.k + 1) % L.size()];
    for (std::size_t j = i + 1; j < edges.size() && edges[j].lo <= e.hi; ++j) {
      const Edge& f = edges[j];
      const auto& M = loops[f.loop];
      if (e.loop == f.loop) {
        const int n = static_cast<int>(L.size());
        if ((e.k + 1) % n == f.k || (f.k + 1) % n == e.k) continue;
      }
      const Vec2& c = M[f.k];
      const Vec2& d = M[(f.k + 1) % M.size()];
      if (std::max(a.y(), b.y()) < std::min(c.y(), d.y()) ||
          std::max(c.y(), d.y()) < std::min(a.y(), b.y()))
        continue;
      if (segments_touch(a, b, c, d)) return true;
    }
  }
  return false;
}

// Half or partial ellipse from A to B bulging by `height` to the right of A -> B (height < 0:
// to the left); alpha in [0, pi/2) cuts the arc short of the half ellipse (tangents at A and B
// then lean toward the chord). End control points are exactly A and B.
inline Nurbs2 ellipse_piece(const Vec2& A, const Vec2& B, double height, double alpha) {
  if (height < 0) return nurbs_reversed(ellipse_piece(B, A, -height, alpha));
  const Vec2 u = (B - A).normalized();
  const double a = 0.5 * (B - A).norm() / std::cos(alpha);
  const double ratio = height / (a * (1 - std::sin(alpha)));
  const Vec2 c = 0.5 * (A + B) + ratio * a * std::sin(alpha) * left_normal(u);
  Nurbs2 n = nurbs_ellipse(c, a * u, ratio, std::numbers::pi + alpha, kTwoPi - alpha);
  n.ctrl.front() = A;
  n.ctrl.back() = B;
  return n;
}

// Curves through pts[0], ..., pts[m] (closed: pts[m] == pts[0] bitwise), counter-clockwise
// about `centre` so that "outward" is to the right. mix: 0 mixed, 1 lines and arcs only,
// 2 mostly splines.
inline void add_pieces(Rng& rng, const std::vector<Vec2>& pts, const Vec2& centre, int mix,
                       Profile& out) {
  const int m = static_cast<int>(pts.size()) - 1;
  int k = 0;
  while (k < m) {
    const Vec2& A = pts[k];
    const Vec2& B = pts[k + 1];
    const double L = (B - A).norm();
    const Vec2 right = -left_normal((B - A) / L);
    // Inward excursions stay well short of the centre.
    const double room = std::abs(cross2(B - A, centre - A)) / L;
    const double in_max = std::min(0.25 * L, 0.3 * room);
    const double r = rng.uniform();
    const double p_line = mix == 2 ? 0.1 : 0.3, p_arc = mix == 2 ? 0.2 : (mix == 1 ? 1 : 0.55);
    const double p_spline = mix == 2 ? 0.9 : 0.8;
    if (r < p_line) {
      out.curves.push_back({make_line(A, B), -1});
      ++k;
    } else if (r < p_arc) {
      // bulge = tan(sweep / 4); sagitta = L * |bulge| / 2.
      const double bulge = rng.chance(0.7) ? rng.uniform(0.05, 0.45)
                                           : -std::min(0.4, 2 * in_max / L) * rng.uniform(0.2, 1);
      // Nearly flat arcs (radius > ~12 L) are lines: no huge radii in the files.
      out.curves.push_back(
          {std::abs(bulge) < 0.02 ? make_line(A, B) : make_bulge_segment(A, B, bulge), -1});
      ++k;
    } else if (r < p_spline) {
      const int run = std::min(m - k, rng.integer(1, 4));
      Nurbs2 n;
      n.degree = 3;
      if (run == 1) {
        const double h1 = rng.uniform(-in_max, 0.25 * L), h2 = rng.uniform(-in_max, 0.25 * L);
        n.ctrl = {A, A + (B - A) / 3 + h1 * right, A + 2 * (B - A) / 3 + h2 * right, B};
      } else {
        n.ctrl.assign(pts.begin() + k, pts.begin() + k + run + 1);
        if (n.ctrl.size() < 4) n.ctrl.insert(n.ctrl.begin() + 1, 0.5 * (n.ctrl[0] + n.ctrl[1]));
      }
      n.weights.assign(n.ctrl.size(), 1.0);
      if (rng.chance(0.25))
        for (std::size_t i = 1; i + 1 < n.weights.size(); ++i) n.weights[i] = rng.uniform(0.5, 2);
      n.knots = clamped_uniform_knots(n.ctrl.size(), 3);
      out.curves.push_back(nurbs_curve(out, std::move(n)));
      k += run;
    } else {
      const double h = rng.chance(0.7) ? rng.uniform(0.05, 0.4) * L : -rng.uniform(0.3, 1) * in_max;
      const double alpha = rng.chance(0.5) ? 0.0 : rng.uniform(0.1, 1.0);
      if (std::abs(h) < 0.02 * L)
        out.curves.push_back({make_line(A, B), -1});
      else
        out.curves.push_back(nurbs_curve(out, ellipse_piece(A, B, h, alpha)));
      ++k;
    }
  }
}

// Counter-clockwise star around `centre`: n angles, radii in [rmin_ratio, 1] * R (smooth
// Fourier radius function or independent samples).
inline Profile star_profile(Rng& rng, const Vec2& centre, double R, int n, double rmin_ratio,
                            int mix) {
  const double phase = rng.uniform(0, kTwoPi);
  std::vector<double> th(n), rad(n);
  const bool smooth = rng.chance(0.5);
  double a1 = rng.uniform(0, 0.5), a2 = rng.uniform(0, 0.3), f1 = rng.uniform(0, kTwoPi),
         f2 = rng.uniform(0, kTwoPi);
  const int k1 = rng.integer(2, 4), k2 = rng.integer(3, 6);
  for (int i = 0; i < n; ++i) {
    th[i] = phase + kTwoPi * (i + rng.uniform(-0.3, 0.3)) / n;
    rad[i] = smooth ? 1 + a1 * std::cos(k1 * th[i] + f1) + a2 * std::cos(k2 * th[i] + f2)
                    : rng.uniform(rmin_ratio, 1);
  }
  const double hi = *std::max_element(rad.begin(), rad.end());
  const double lo = *std::min_element(rad.begin(), rad.end());
  std::vector<Vec2> pts;
  for (int i = 0; i < n; ++i) {
    // Map the radii onto [rmin_ratio, 1] * R.
    const double t = hi > lo ? (rad[i] - lo) / (hi - lo) : 1.0;
    const double r = R * (rmin_ratio + (1 - rmin_ratio) * t);
    pts.push_back(centre + r * Vec2(std::cos(th[i]), std::sin(th[i])));
  }
  pts.push_back(pts.front());
  Profile p;
  add_pieces(rng, pts, centre, mix, p);
  return p;
}

// Largest distance from c to the profile's check polyline plus its tolerance.
inline double reach(const Profile& p, const Vec2& c) {
  double m = 0;
  for (const Vec2& q : profile_polyline(p)) m = std::max(m, (q - c).norm());
  return m + 2 * kPolylineTol;
}

inline void scale_about(Profile& p, const Vec2& c, double s) {
  map_profile(p, [&](const Vec2& x) -> Vec2 { return c + s * (x - c); });
}

// Dumbbell along x about the origin, counter-clockwise; returns the narrowest neck width.
inline Profile dumbbell_profile(Rng& rng, double size, double w, int mix, int& samples) {
  const double R1 = size * rng.uniform(0.17, 0.24), R2 = size * rng.uniform(0.17, 0.24);
  const double neck_len = size - 2 * (R1 + R2);
  const Vec2 C1(-(neck_len / 2 + R1), 0), C2(neck_len / 2 + R2, 0);
  // Neck sides: straight at width w, or a cubic whose ends are wider (we) and whose middle is
  // exactly w wide: a symmetric Bezier with y0 = we/2, y1 = y2: y(1/2) = (y0 + 3 y1) / 4.
  const bool waisted = rng.chance(0.5);
  const double we = waisted ? w * rng.uniform(1.15, 1.5) : w;
  const double y1 = (2 * w - we / 2) / 3;
  const double b1 = std::asin(we / 2 / R1), b2 = std::asin(we / 2 / R2);
  const Vec2 Lb = C1 + R1 * Vec2(std::cos(-b1), std::sin(-b1));
  const Vec2 Lt = C1 + R1 * Vec2(std::cos(b1), std::sin(b1));
  const Vec2 Rb = C2 + R2 * Vec2(std::cos(std::numbers::pi + b2), std::sin(std::numbers::pi + b2));
  const Vec2 Rt = C2 + R2 * Vec2(std::cos(std::numbers::pi - b2), std::sin(std::numbers::pi - b2));
  samples = rng.integer(4, 10);
  auto lobe = [&](const Vec2& C, double R, double from, double to, const Vec2& P0, const Vec2& P1) {
    // Interior samples keep 20 degrees from the junctions and stay near the circle, so the
    // lobe does not pinch the neck's ends below its width.
    std::vector<Vec2> pts{P0};
    const double margin = 20 * std::numbers::pi / 180;
    for (int i = 1; i < samples; ++i) {
      const double t = from + margin +
                       (to - from - 2 * margin) * (i - 1 + rng.uniform(0.1, 0.9)) / (samples - 1);
      pts.push_back(C + R * rng.uniform(0.92, 1.05) * Vec2(std::cos(t), std::sin(t)));
    }
    pts.push_back(P1);
    return pts;
  };
  auto neck = [&](Profile& p, const Vec2& A, const Vec2& B, double sign) {
    if (!waisted) {
      p.curves.push_back({make_line(A, B), -1});
      return;
    }
    Nurbs2 n;
    n.degree = 3;
    n.ctrl = {A, Vec2(A.x() + (B.x() - A.x()) / 3, sign * y1),
              Vec2(A.x() + 2 * (B.x() - A.x()) / 3, sign * y1), B};
    n.weights.assign(4, 1.0);
    n.knots = clamped_uniform_knots(4, 3);
    p.curves.push_back(nurbs_curve(p, std::move(n)));
  };
  Profile p;
  neck(p, Lb, Rb, -1);
  add_pieces(rng, lobe(C2, R2, std::numbers::pi + b2, 3 * std::numbers::pi - b2, Rb, Rt), C2, mix,
             p);
  neck(p, Rt, Lt, 1);
  add_pieces(rng, lobe(C1, R1, b1, kTwoPi - b1, Lt, Lb), C1, mix, p);
  return p;
}

// One island (counter-clockwise) whose polyline stays within radius R of q; `toward` is a unit
// direction to put an ellipse's tip in (toward the nearest wall).
inline Profile island_profile(Rng& rng, const Vec2& q, double R, const Vec2& toward, int kind) {
  Profile p;
  if (kind == 0) {  // circle: 2-4 arcs, or one closed rational NURBS
    const int parts = rng.integer(1, 4);
    const double t0 = rng.uniform(0, kTwoPi);
    if (parts == 1) {
      p.curves.push_back(nurbs_curve(
          p, nurbs_ellipse(q, R * Vec2(std::cos(t0), std::sin(t0)), 1, t0, t0 + kTwoPi)));
      return p;
    }
    std::vector<Vec2> pts;
    for (int i = 0; i < std::max(2, parts); ++i) {
      const double t = t0 + kTwoPi * i / std::max(2, parts);
      pts.push_back(q + R * Vec2(std::cos(t), std::sin(t)));
    }
    for (std::size_t i = 0; i < pts.size(); ++i)
      p.curves.push_back({make_arc(pts[i], pts[(i + 1) % pts.size()], q, true), -1});
    return p;
  }
  if (kind == 1) {  // ellipse, tip toward the wall; whole, or two arcs sharing exact ends
    const double ratio = rng.uniform(0.3, 0.8);
    const Vec2 major = R * toward;
    if (rng.chance(0.5)) {
      p.curves.push_back(nurbs_curve(p, nurbs_ellipse(q, major, ratio, 0.3, 0.3 + kTwoPi)));
    } else {
      const double s = rng.uniform(2.0, 4.0);
      Nurbs2 a = nurbs_ellipse(q, major, ratio, 0.3, s);
      Nurbs2 b = nurbs_ellipse(q, major, ratio, s, 0.3 + kTwoPi);
      b.ctrl.front() = a.ctrl.back();
      b.ctrl.back() = a.ctrl.front();
      p.curves.push_back(nurbs_curve(p, std::move(a)));
      p.curves.push_back(nurbs_curve(p, std::move(b)));
    }
    return p;
  }
  // small star, scaled so that its polyline reaches R
  p = star_profile(rng, q, 1, rng.integer(5, 9), rng.uniform(0.55, 0.9), rng.integer(0, 2));
  scale_about(p, q, R / reach(p, q));
  return p;
}

}  // namespace random_pocket_detail

// One region (the vector has one element), a function of seed and options only.
inline std::vector<Region> random_pocket(std::uint64_t seed, const RandomPocketOptions& opt = {},
                                         RandomPocketInfo* info_out = nullptr) {
  namespace d = random_pocket_detail;
  d::Rng rng(seed);
  RandomPocketInfo info;
  Region region;
  for (;;) {
    // A candidate fails rarely (a spline run cutting a corner across another piece): more
    // than a handful of failures in a row means a bug here, not bad luck.
    if (++info.attempts > 100)
      throw std::logic_error("random_pocket: no valid region in 100 candidates, seed " +
                             std::to_string(seed));
    region = Region{};
    info.kind = rng.chance(0.7) ? RandomPocketKind::kStar : RandomPocketKind::kDumbbell;
    const int mix = rng.integer(0, 2);
    const double gaps[] = {0.05, 0.5, 3};
    info.gap = gaps[rng.integer(0, 2)];
    Profile boundary;
    if (info.kind == RandomPocketKind::kStar) {
      info.size = rng.uniform(opt.min_size, opt.max_size);
      info.samples = rng.integer(5, 24);
      info.neck_width = 0;
      boundary = d::star_profile(rng, Vec2::Zero(), 1, info.samples, rng.uniform(0.45, 0.9), mix);
      // Scale so the bounding box's larger side is the size.
      Vec2 lo = Vec2::Constant(INFINITY), hi = -lo;
      for (const Vec2& p : d::profile_polyline(boundary)) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
      d::scale_about(boundary, Vec2::Zero(), info.size / (hi - lo).maxCoeff());
    } else {
      info.neck_width = opt.tool_diameter * rng.uniform(1.2, 3);
      // Lobes of radius >= 0.17 size must be wider than the neck's ends (<= 1.5 w).
      const double smin = std::max(opt.min_size, 1.3 * 0.75 * info.neck_width / 0.17);
      info.size = rng.uniform(std::min(smin, opt.max_size), opt.max_size);
      boundary = d::dumbbell_profile(rng, info.size, info.neck_width, mix, info.samples);
    }
    const std::vector<Vec2> wall = d::profile_polyline(boundary);
    Vec2 lo = Vec2::Constant(INFINITY), hi = -lo;
    for (const Vec2& p : wall) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    if (info.kind == RandomPocketKind::kDumbbell) {
      // Lobe samples and bulges make the extent differ from the requested size a little.
      info.size = (hi - lo).maxCoeff();
      if (info.size < opt.min_size || info.size > opt.max_size) continue;
    }
    std::vector<std::vector<Vec2>> loops{wall};
    if (d::loops_cross(loops)) continue;

    // Islands: a centre inside, at least r_min + gap from the wall (distance to the polyline
    // minus its tolerance) and from the islands' bounding circles.
    const double r_min = std::max(1.0, 0.03 * info.size);
    const int want = rng.integer(0, std::max(0, opt.max_islands));
    std::vector<std::pair<Vec2, double>> placed;
    for (int tries = 0; static_cast<int>(placed.size()) < want && tries < 80; ++tries) {
      const Vec2 q(rng.uniform(lo.x(), hi.x()), rng.uniform(lo.y(), hi.y()));
      if (!d::point_in_loop(wall, q)) continue;
      Vec2 nearest = q;
      double avail = d::polyline_distance(wall, q, &nearest) - 2 * d::kPolylineTol - info.gap;
      for (const auto& [c, r] : placed) avail = std::min(avail, (q - c).norm() - r - info.gap);
      if (avail < r_min) continue;
      const int kind = rng.integer(0, 2);
      const bool touch = kind != 2 && rng.chance(0.5);
      const double R =
          touch ? avail : rng.uniform(r_min, std::min(avail, std::max(r_min, 0.3 * info.size)));
      const Vec2 toward = (nearest - q).norm() > 0 ? Vec2((nearest - q).normalized()) : Vec2(1, 0);
      Profile isl = d::island_profile(rng, q, R, toward, kind);
      placed.push_back({q, R});
      loops.push_back(d::profile_polyline(isl));
      region.islands.push_back(std::move(isl));
    }
    if (region.islands.size() > 0 && d::loops_cross(loops)) continue;

    // Boundary clockwise; then the placement.
    region.boundary = d::reversed_profile(boundary);
    info.rotation = rng.chance(0.5) ? rng.uniform(0, d::kTwoPi) : 0.0;
    info.offset = opt.allow_far && rng.chance(0.35)
                      ? Vec2(rng.uniform(-opt.max_offset, opt.max_offset),
                             rng.uniform(-opt.max_offset, opt.max_offset))
                      : Vec2(rng.uniform(-opt.max_size, opt.max_size),
                             rng.uniform(-opt.max_size, opt.max_size));
    const double cs = std::cos(info.rotation), sn = std::sin(info.rotation);
    const Vec2 t = info.offset;
    auto place = [&](const Vec2& p) -> Vec2 {
      return Vec2(cs * p.x() - sn * p.y(), sn * p.x() + cs * p.y()) + t;
    };
    d::map_profile(region.boundary, place);
    for (Profile& isl : region.islands) d::map_profile(isl, place);
    break;
  }
  if (info_out) *info_out = info;
  return {region};
}

// A random pocket with the tool the randomized pocket tests use for it: diameter 4, 6, 8
// or 10 mm and a stepover of half or 0.8 of it, both from the seed.
struct RandomPocketCase {
  std::vector<Region> regions;
  double tool_diameter = 0;  // mm
  double stepover = 0;       // mm
};

inline RandomPocketCase random_pocket_case(std::uint64_t seed) {
  RandomPocketCase c;
  c.tool_diameter = 4 + static_cast<double>(seed % 4) * 2;
  c.stepover = c.tool_diameter * (seed % 2 ? 0.5 : 0.8);
  RandomPocketOptions opt;
  opt.tool_diameter = c.tool_diameter;
  c.regions = random_pocket(seed, opt);
  return c;
}

}  // namespace ncpath::test
