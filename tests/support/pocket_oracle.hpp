#pragma once
// Independent answers for pocket tool-path tests: the area a tool disc sweeps along CL
// polylines, the region it may reach and the region it must not leave, all computed by
// Clipper (Debian's libpolyclipping, tests only) on finely discretised copies of the input.
// Nothing here calls kernels/pocket or engine/pocket_* code: lines and arcs are discretised
// by append_polyline, NURBS curves by a de Boor evaluation written out again below.
#include <algorithm>
#include <clipper.hpp>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "engine/cl_chunk.hpp"
#include "kernels/curves/segment.hpp"
#include "kernels/pocket/profile.hpp"

namespace ncpath::test {

namespace clip = ClipperLib;

// Clipper works in integers: 1 unit = 1 nm. Test shapes stay within 1000 mm, i.e. below
// 2^30 units, so Clipper keeps to its fast (64-bit product) range.
inline constexpr double kClipScale = 1e6;
// mm: largest gap between the discretised input and the true curves (chords inside arcs).
inline constexpr double kOracleChord = 1e-4;
// mm: ClipperOffset's round joins and ends are polygons inscribed in the true circles
// within this distance.
inline constexpr double kOracleArcTol = 1e-4;

// --- NURBS, evaluated independently of kernels/curves/nurbs.* -------------------------------

// Rational de Boor in homogeneous coordinates; t is clamped to the knot range.
inline Vec2 nurbs_eval(const Nurbs2& c, double t) {
  const int p = c.degree;
  const int n = static_cast<int>(c.ctrl.size());
  const double t0 = c.knots[p], t1 = c.knots[n];
  t = std::min(std::max(t, t0), t1);
  int k = p;  // knots[k] <= t < knots[k + 1], the last non-empty span for t == t1
  while (k + 1 < n && c.knots[k + 1] <= t) ++k;
  std::vector<Eigen::Vector3d> d(p + 1);
  for (int j = 0; j <= p; ++j) {
    const int i = j + k - p;
    const double w = c.weights[i];
    d[j] = Eigen::Vector3d(w * c.ctrl[i].x(), w * c.ctrl[i].y(), w);
  }
  for (int r = 1; r <= p; ++r)
    for (int j = p; j >= r; --j) {
      const double lo = c.knots[j + k - p], hi = c.knots[j + 1 + k - r];
      const double alpha = hi > lo ? (t - lo) / (hi - lo) : 0.0;
      d[j] = (1 - alpha) * d[j - 1] + alpha * d[j];
    }
  return Vec2(d[p].x() / d[p].z(), d[p].y() / d[p].z());
}

inline double distance_to_chord(const Vec2& a, const Vec2& b, const Vec2& q) {
  const Vec2 ab = b - a;
  const double len2 = ab.squaredNorm();
  if (len2 == 0) return (q - a).norm();
  const double s = std::min(1.0, std::max(0.0, (q - a).dot(ab) / len2));
  return (a + s * ab - q).norm();
}

// Bisects [u0, u1] until the curve's midpoint is within tol of the chord (at least 2^4
// pieces per span so that an S-bend whose midpoint lies on its chord is still split).
inline void nurbs_subdivide(const Nurbs2& c, double u0, const Vec2& p0, double u1, const Vec2& p1,
                            double tol, int depth, std::vector<Vec2>& out) {
  const double um = 0.5 * (u0 + u1);
  const Vec2 pm = nurbs_eval(c, um);
  if (depth < 30 && (depth < 4 || distance_to_chord(p0, p1, pm) > tol)) {
    nurbs_subdivide(c, u0, p0, um, pm, tol, depth + 1, out);
    nurbs_subdivide(c, um, pm, u1, p1, tol, depth + 1, out);
    return;
  }
  out.push_back(p0);
}

// Points from the curve's start (included) to its end (excluded), chords within tol.
inline void append_nurbs_points(const Nurbs2& c, double tol, std::vector<Vec2>& out) {
  const int n = static_cast<int>(c.ctrl.size());
  for (int k = c.degree; k < n; ++k) {
    const double u0 = c.knots[k], u1 = c.knots[k + 1];
    if (u1 > u0) nurbs_subdivide(c, u0, nurbs_eval(c, u0), u1, nurbs_eval(c, u1), tol, 0, out);
  }
}

// --- Regions as Clipper polygons --------------------------------------------------------------

inline std::vector<Vec2> profile_points(const Profile& profile, double chord) {
  std::vector<Vec2> pts;
  for (const ProfileCurve& pc : profile.curves) {
    if (pc.nurbs < 0) {
      append_polyline(pc.seg, chord, pts);
      continue;
    }
    const Nurbs2& c = profile.nurbs[pc.nurbs];
    std::vector<Vec2> np;
    append_nurbs_points(c, chord, np);
    // The curve runs from seg.a to seg.b; a reversed reference is walked backwards.
    if ((nurbs_eval(c, c.knots.back()) - pc.seg.a).norm() <
        (nurbs_eval(c, c.knots.front()) - pc.seg.a).norm()) {
      np.push_back(nurbs_eval(c, c.knots.back()));
      std::reverse(np.begin(), np.end());
      np.pop_back();
    }
    pts.insert(pts.end(), np.begin(), np.end());
  }
  return pts;
}

inline clip::IntPoint to_int(const Vec2& p) {
  return clip::IntPoint(static_cast<clip::cInt>(std::llround(p.x() * kClipScale)),
                        static_cast<clip::cInt>(std::llround(p.y() * kClipScale)));
}

inline clip::Path to_clip(const std::vector<Vec2>& pts) {
  clip::Path path;
  path.reserve(pts.size());
  for (const Vec2& p : pts) path.push_back(to_int(p));
  return path;
}

inline double area(const clip::Paths& paths) {
  double a = 0;  // outer polygons count positive, holes negative
  for (const clip::Path& p : paths) a += clip::Area(p);
  return a / (kClipScale * kClipScale);
}

// Number of separate pieces (outer polygons).
inline std::size_t outer_count(const clip::Paths& paths) {
  std::size_t n = 0;
  for (const clip::Path& p : paths) n += clip::Orientation(p) ? 1 : 0;
  return n;
}

inline clip::Paths boolean(const clip::Paths& a, const clip::Paths& b, clip::ClipType op) {
  clip::Clipper c;
  c.AddPaths(a, clip::ptSubject, true);
  if (!b.empty()) c.AddPaths(b, clip::ptClip, true);
  clip::Paths out;
  c.Execute(op, out, clip::pftNonZero, clip::pftNonZero);
  return out;
}

inline clip::Paths difference(const clip::Paths& a, const clip::Paths& b) {
  return boolean(a, b, clip::ctDifference);
}

// The material of the pockets: every boundary minus its islands (orientation-independent),
// as Clipper polygons with outer loops positive and holes negative.
inline clip::Paths region_paths(const std::vector<Region>& regions, double chord = kOracleChord) {
  clip::Paths all;
  for (const Region& r : regions) {
    clip::Paths islands;
    for (const Profile& i : r.islands) islands.push_back(to_clip(profile_points(i, chord)));
    const clip::Paths one = difference({to_clip(profile_points(r.boundary, chord))}, islands);
    all.insert(all.end(), one.begin(), one.end());
  }
  return boolean(all, {}, clip::ctUnion);
}

// Closed polygons offset by d mm (d < 0: erosion), round joins.
inline clip::Paths offset_closed(const clip::Paths& paths, double d) {
  clip::ClipperOffset off(2.0, kOracleArcTol * kClipScale);
  off.AddPaths(paths, clip::jtRound, clip::etClosedPolygon);
  clip::Paths out;
  off.Execute(out, d * kClipScale);
  return out;
}

// The area a disc of radius r sweeps when its centre runs along the open polylines (a
// single point gives a disc). Long polylines are swept in pieces of `piece` points whose
// outlines are then united: Clipper's offset of one long, finely divided open path is much
// slower (superlinear in its length).
inline clip::Paths sweep(const std::vector<std::vector<Vec2>>& polylines, double r,
                         std::size_t piece = 200) {
  clip::Paths all;
  for (const auto& pl : polylines)
    for (std::size_t b = 0; b < pl.size(); b += piece) {
      const std::size_t e = std::min(pl.size(), b + piece + 1);  // pieces share an end point
      if (b > 0 && e - b < 2) break;
      clip::ClipperOffset off(2.0, kOracleArcTol * kClipScale);
      off.AddPath(to_clip({pl.begin() + b, pl.begin() + e}), clip::jtRound, clip::etOpenRound);
      clip::Paths out;
      off.Execute(out, r * kClipScale);
      all.insert(all.end(), out.begin(), out.end());
    }
  return boolean(all, {}, clip::ctUnion);
}

// How far outside `region` (Clipper polygons, outer loops positive, holes negative) the
// points sampled at most `step` mm apart along the polylines lie, mm; 0 when all are inside
// or on its boundary. Point tests instead of a swept area: helices retrace one circle many
// times, and Clipper unions such self-overlapping outlines very slowly.
inline double max_outside(const clip::Paths& region,
                          const std::vector<std::vector<Vec2>>& polylines, double step) {
  std::vector<int> sign;
  for (const clip::Path& p : region) sign.push_back(clip::Orientation(p) ? 1 : -1);
  auto outside = [&](const Vec2& q) {
    const clip::IntPoint iq = to_int(q);
    int winding = 0;
    for (std::size_t k = 0; k < region.size(); ++k) {
      const int r = clip::PointInPolygon(iq, region[k]);
      if (r == -1) return 0.0;  // on the boundary
      if (r == 1) winding += sign[k];
    }
    if (winding > 0) return 0.0;
    double best = std::numeric_limits<double>::infinity();
    for (const clip::Path& p : region)
      for (std::size_t k = 0; k < p.size(); ++k) {
        const clip::IntPoint& a = p[k];
        const clip::IntPoint& b = p[(k + 1) % p.size()];
        best = std::min(best, distance_to_chord(Vec2(a.X / kClipScale, a.Y / kClipScale),
                                                Vec2(b.X / kClipScale, b.Y / kClipScale), q));
      }
    return best;
  };
  double worst = 0;
  for (const auto& pl : polylines) {
    if (pl.size() == 1) worst = std::max(worst, outside(pl[0]));
    for (std::size_t k = 1; k < pl.size(); ++k) {
      const int n = 1 + static_cast<int>(std::ceil((pl[k] - pl[k - 1]).norm() / step));
      for (int i = 0; i <= n; ++i)
        worst = std::max(worst, outside(pl[k - 1] + (pl[k] - pl[k - 1]) * (double(i) / n)));
    }
  }
  return worst;
}

inline double profile_length(const Profile& profile, double chord = kOracleChord) {
  const std::vector<Vec2> pts = profile_points(profile, chord);
  double len = 0;
  for (std::size_t k = 0; k < pts.size(); ++k) len += (pts[(k + 1) % pts.size()] - pts[k]).norm();
  return len;
}

// --- CL data ----------------------------------------------------------------------------------

struct ClPath {
  PathKind kind;
  std::size_t first;  // index of the first point
  std::size_t size;   // points
};

inline std::vector<ClPath> cl_paths(const ClChunk& cl) {
  std::vector<ClPath> out;
  std::size_t first = 0;
  for (std::size_t k = 0; k < cl.path_sizes.size(); ++k) {
    out.push_back({static_cast<PathKind>(cl.path_kinds[k]), first, cl.path_sizes[k]});
    first += cl.path_sizes[k];
  }
  return out;
}

inline Vec3 cl_point(const ClChunk& cl, std::size_t i) {
  return Vec3(cl.xyz[3 * i], cl.xyz[3 * i + 1], cl.xyz[3 * i + 2]);
}

inline bool is_feed(PathKind k) { return k == PathKind::kCut || k == PathKind::kLinkAtDepth; }

// xy of the maximal runs of consecutive points of cut and link paths that lie at height z
// (within eps): where the tool runs at that height.
inline std::vector<std::vector<Vec2>> runs_at_z(const ClChunk& cl, double z, double eps = 1e-9) {
  std::vector<std::vector<Vec2>> runs;
  for (const ClPath& p : cl_paths(cl)) {
    if (!is_feed(p.kind)) continue;
    bool open = false;
    for (std::size_t i = p.first; i < p.first + p.size; ++i) {
      const Vec3 q = cl_point(cl, i);
      if (std::abs(q.z() - z) <= eps) {
        if (!open) runs.emplace_back();
        runs.back().emplace_back(q.x(), q.y());
        open = true;
      } else {
        open = false;
      }
    }
  }
  return runs;
}

// xy of the runs of consecutive feed segments that are not horizontal at one of `levels`
// (entries, descents, moves in the air): with runs_at_z at every level, all feed moves.
inline std::vector<std::vector<Vec2>> runs_between_levels(const ClChunk& cl,
                                                          const std::vector<double>& levels,
                                                          double eps = 1e-9) {
  auto at_level = [&](double z) {
    for (double l : levels)
      if (std::abs(z - l) <= eps) return true;
    return false;
  };
  std::vector<std::vector<Vec2>> runs;
  for (const ClPath& p : cl_paths(cl)) {
    if (!is_feed(p.kind)) continue;
    bool open = false;
    for (std::size_t i = p.first + 1; i < p.first + p.size; ++i) {
      const Vec3 a = cl_point(cl, i - 1), b = cl_point(cl, i);
      if (std::abs(a.z() - b.z()) <= eps && at_level(a.z())) {
        open = false;
        continue;
      }
      if (!open) runs.push_back({Vec2(a.x(), a.y())});
      runs.back().emplace_back(b.x(), b.y());
      open = true;
    }
  }
  return runs;
}

// xy of every cut and link path, whole.
inline std::vector<std::vector<Vec2>> feed_polylines(const ClChunk& cl) {
  std::vector<std::vector<Vec2>> out;
  for (const ClPath& p : cl_paths(cl)) {
    if (!is_feed(p.kind)) continue;
    out.emplace_back();
    for (std::size_t i = p.first; i < p.first + p.size; ++i) {
      const Vec3 q = cl_point(cl, i);
      out.back().emplace_back(q.x(), q.y());
    }
  }
  return out;
}

inline double path_length(const ClChunk& cl, const ClPath& p) {
  double len = 0;
  for (std::size_t i = p.first + 1; i < p.first + p.size; ++i)
    len += (cl_point(cl, i) - cl_point(cl, i - 1)).norm();
  return len;
}

// Climbs to safe height between cutting: runs of consecutive rapid paths that reach safe_z,
// with feed paths both before and after them.
inline std::size_t count_retractions(const ClChunk& cl, double safe_z, double eps = 1e-9) {
  const std::vector<ClPath> paths = cl_paths(cl);
  std::size_t first_feed = paths.size(), last_feed = 0;
  for (std::size_t k = 0; k < paths.size(); ++k)
    if (is_feed(paths[k].kind)) {
      first_feed = std::min(first_feed, k);
      last_feed = k;
    }
  std::size_t n = 0;
  bool in_run = false, run_reaches = false;
  for (std::size_t k = first_feed; k <= last_feed && k < paths.size(); ++k) {
    if (paths[k].kind == PathKind::kRapid) {
      if (!in_run) run_reaches = false;
      in_run = true;
      for (std::size_t i = paths[k].first; i < paths[k].first + paths[k].size; ++i)
        run_reaches = run_reaches || cl_point(cl, i).z() >= safe_z - eps;
    } else {
      if (in_run && run_reaches) ++n;
      in_run = false;
    }
  }
  return n;
}

}  // namespace ncpath::test
