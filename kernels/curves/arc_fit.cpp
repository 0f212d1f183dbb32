#include "kernels/curves/arc_fit.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "kernels/geom/tolerance.hpp"

namespace ncpath {

namespace {

inline double cross(const Vec2& u, const Vec2& v) { return u.x() * v.y() - u.y() * v.x(); }

// Read-only view of the path's points.
struct Pts {
  std::span<const double> xyz;
  Vec3 p(std::size_t i) const { return Vec3(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]); }
  Vec2 q(std::size_t i) const { return Vec2(xyz[3 * i], xyz[3 * i + 1]); }
  double z(std::size_t i) const { return xyz[3 * i + 2]; }
};

// True when the 3-D segment p_i -> p_j takes the points i..j within tol, advancing along it.
// Distance to a segment is convex, so chords between points within tol stay within tol.
bool line_fits(const Pts& pts, std::size_t i, std::size_t j, double tol) {
  const Vec3 a = pts.p(i);
  const Vec3 ab = pts.p(j) - a;
  const double len2 = ab.squaredNorm();
  const double len = std::sqrt(len2);
  double prev_s = 0;  // arc length of the previous point's projection, mm
  for (std::size_t k = i + 1; k < j; ++k) {
    const Vec3 ap = pts.p(k) - a;
    const double t = len2 > 0 ? std::clamp(ap.dot(ab) / len2, 0.0, 1.0) : 0.0;
    if ((ap - t * ab).squaredNorm() > tol * tol) return false;
    // Back-tracking along the line by more than tol would not be the same path.
    const double s = t * len;
    if (s < prev_s - tol) return false;
    prev_s = std::max(prev_s, s);
  }
  return true;
}

struct Arc {
  Vec2 c = Vec2::Zero();
  double r = 0;
  int turn = 0;  // +1 ccw, -1 cw
};

// Circle through three xy points; false when they are (nearly) collinear or the radius is
// outside (min_r, max_r].
bool circle_through(const Vec2& a, const Vec2& b, const Vec2& c, double min_r, double max_r,
                    Vec2& centre, double& r) {
  const Vec2 u = b - a;
  const Vec2 v = c - a;
  const double d = 2 * cross(u, v);
  if (d == 0) return false;
  const Vec2 off((v.y() * u.squaredNorm() - u.y() * v.squaredNorm()) / d,
                 (u.x() * v.squaredNorm() - v.x() * u.squaredNorm()) / d);
  r = off.norm();
  if (!std::isfinite(r) || r <= min_r || r > max_r) return false;
  centre = a + off;
  return true;
}

// Combined error of a point at xy distance rho from the centre, at unwrapped angle theta
// (from the start), with height z, against the helix through the run.
inline double helix_error(double rho, double r, double theta, double sweep, double z0, double dz,
                          double z) {
  return std::hypot(rho - r, z - (z0 + dz * theta / sweep));
}

// True when the arc (or helix) through points i, (i + j) / 2 and j takes every point i..j and
// every chord between them within tol, with the points advancing monotonically along it.
bool arc_fits(const Pts& pts, std::size_t i, std::size_t j, const ArcFitParams& prm, Arc& arc) {
  const double tol = prm.tol;
  const std::size_t m = i + (j - i) / 2;
  const Vec2 a = pts.q(i);
  const Vec2 b = pts.q(j);
  if (!circle_through(a, pts.q(m), b, tol, prm.max_radius, arc.c, arc.r)) return false;
  arc.turn = cross(pts.q(m) - a, b - pts.q(m)) > 0 ? 1 : -1;
  const Vec2 va = a - arc.c;
  const Vec2 vb = b - arc.c;
  // Sweep from a to b in the turning direction, in (0, 2 pi) times turn.
  double sweep = std::atan2(cross(va, vb), va.dot(vb));
  if (arc.turn > 0 && sweep <= 0) sweep += 2 * std::numbers::pi;
  if (arc.turn < 0 && sweep >= 0) sweep -= 2 * std::numbers::pi;
  if (std::abs(sweep) > prm.max_sweep || std::abs(sweep) < tol::kArcAsLineSweep) return false;

  const double z0 = pts.z(i);
  const double dz = pts.z(j) - z0;
  const double back = tol / arc.r;  // largest backward step allowed, radians
  double theta = 0;                 // unwrapped angle of the previous point
  Vec2 vprev = va;
  for (std::size_t k = i + 1; k <= j; ++k) {
    const Vec2 pk = pts.q(k);
    const Vec2 v = pk - arc.c;
    const double step = std::atan2(cross(vprev, v), vprev.dot(v));
    if (step * arc.turn < -back) return false;
    const double theta_k = theta + step;
    if (helix_error(v.norm(), arc.r, theta_k, sweep, z0, dz, pts.z(k)) > tol) return false;
    // The chord k-1 -> k: its point closest to the centre (deepest inside the circle) and its
    // midpoint. Farthest outside are its end points, checked as points.
    const Vec2 p0 = pts.q(k - 1);
    const Vec2 d = pk - p0;
    const double len2 = d.squaredNorm();
    if (len2 > 0) {
      const double s_foot = std::clamp((arc.c - p0).dot(d) / len2, 0.0, 1.0);
      for (const double s : {s_foot, 0.5}) {
        const Vec2 w = p0 + s * d - arc.c;
        const double th = theta + std::atan2(cross(vprev, w), vprev.dot(w));
        const double zc = pts.z(k - 1) + s * (pts.z(k) - pts.z(k - 1));
        if (helix_error(w.norm(), arc.r, th, sweep, z0, dz, zc) > tol) return false;
      }
    }
    theta = theta_k;
    vprev = v;
  }
  // The points must wind exactly once from a to b: a path that loops around the centre ends
  // with an unwrapped angle a non-zero multiple of 2 pi away from the sweep (pi splits the two).
  return std::abs(theta - sweep) < std::numbers::pi;
}

}  // namespace

void fit_arcs(std::span<const double> xyz, const ArcFitParams& params, std::vector<FitMove>& out) {
  assert(params.tol > 0);
  assert(xyz.size() % 3 == 0);
  const std::size_t n = xyz.size() / 3;
  if (n < 2) return;
  const Pts pts{xyz};
  Arc arc;
  const auto fits = [&](std::size_t i, std::size_t j) {
    return line_fits(pts, i, j, params.tol) ||
           (params.allow_arcs && j >= i + 2 && arc_fits(pts, i, j, params, arc));
  };

  std::size_t i = 0;
  while (i + 1 < n) {
    // Galloping search: double the run while it fits, then bisect between the last run that
    // fitted and the first that did not. Fitting is not strictly monotone in j (the circle
    // changes with j), so the end found is a local maximum; every emitted move is verified.
    std::size_t good = i + 1;  // a two-point run is always its own chord
    std::size_t bad = n;       // first run end known not to fit (n: none)
    for (std::size_t step = 2; good + 1 < n; step *= 2) {
      const std::size_t cand = std::min(i + step, n - 1);
      if (!fits(i, cand)) {
        bad = cand;
        break;
      }
      good = cand;
    }
    while (bad - good > 1) {
      const std::size_t mid = good + (bad - good) / 2;
      (fits(i, mid) ? good : bad) = mid;
    }

    FitMove mv;
    mv.end = pts.p(good);
    mv.end_index = static_cast<std::uint32_t>(good);
    if (!line_fits(pts, i, good, params.tol)) {
      [[maybe_unused]] const bool ok = arc_fits(pts, i, good, params, arc);
      assert(ok);
      mv.kind = arc.turn > 0 ? SegKind::kArcCcw : SegKind::kArcCw;
      mv.centre = arc.c;
    }
    out.push_back(mv);
    i = good;
  }
}

}  // namespace ncpath
