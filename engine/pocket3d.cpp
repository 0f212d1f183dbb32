#include "engine/pocket3d.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "engine/parallel.hpp"
#include "engine/pocket_stages.hpp"
#include "engine/run_control.hpp"
#include "kernels/curves/intersect.hpp"
#include "kernels/geom/tolerance.hpp"
#include "kernels/pocket/offset.hpp"
#include "kernels/pocket/seg_grid.hpp"
#include "kernels/surface/surface_drop.hpp"
#include "kernels/verify/surface_distance.hpp"

namespace ncpath {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

using pocket_stage::mm;

// The plan interval to the next level from a level region's loops: the smallest scallop
// chord along them, sampled every R / 4 (and at least once per segment).
double level_interval(const SurfaceDrop& drop, const std::vector<const OffsetLoop*>& region,
                      const Pocket3dParams& p, std::atomic<std::uint64_t>& drops) {
  const double r = p.tool_radius;
  const double flat = scallop_chord(r, p.scallop, std::numeric_limits<double>::infinity());
  double best = flat;
  std::uint64_t n_drops = 0;
  for (const OffsetLoop* loop : region)
    for (const Seg2& s : loop->segs) {
      const int n = std::max(1, static_cast<int>(std::ceil(length(s) / (0.25 * r))));
      for (int k = 0; k < n; ++k) {
        const double t = (k + 0.5) / n;
        const Vec2 q = point_at(s, t), tan = tangent_at(s, t);
        const Vec2 across(tan.y(), -tan.x());  // toward the next level (material side)
        const SurfaceContact c = drop.drop(q, r);
        ++n_drops;
        if (!c.found) continue;
        const SurfacePoint sp = evaluate(drop.surface(), c.u, c.v);
        // The surface direction whose plan projection is `across`.
        const double j00 = sp.su.x(), j01 = sp.sv.x(), j10 = sp.su.y(), j11 = sp.sv.y();
        const double det = j00 * j11 - j01 * j10;
        if (std::abs(det) < 1e-12) continue;
        const double du = (across.x() * j11 - j01 * across.y()) / det;
        const double dv = (j00 * across.y() - across.x() * j10) / det;
        const double kappa = normal_curvature(sp, du, dv);
        const double rho = kappa == 0 ? std::numeric_limits<double>::infinity() : 1.0 / kappa;
        const double slope = sp.su.z() * du + sp.sv.z() * dv;
        best = std::min(best, scallop_chord(r, p.scallop, rho) / std::sqrt(1 + slope * slope));
      }
    }
  drops += n_drops;
  const double floor = p.min_interval > 0 ? p.min_interval : 0.01 * r;
  return std::max(best, floor);
}

struct ClPt {
  Vec3 cl = Vec3::Zero(), cc = Vec3::Zero(), n = Vec3::Zero();
};

ClPt drop_point(const SurfaceDrop& drop, const Vec2& q, double r) {
  const SurfaceContact c = drop.drop(q, r);
  ClPt pt;
  if (!c.found) {  // cannot happen over a validated pocket; keep the plan point, no contact
    pt.cl = Vec3(q.x(), q.y(), kNaN);
    pt.cc = pt.n = Vec3::Constant(kNaN);
    return pt;
  }
  pt.cl = Vec3(q.x(), q.y(), c.tip_z);
  pt.cc = c.cc;
  pt.n = c.normal;
  return pt;
}

// A run of consecutive moves of one kind as one plan path, by arc length.
class PlanRun {
 public:
  PlanRun(const std::vector<Move2>& moves, std::size_t b, std::size_t e) {
    cum_.push_back(0);
    for (std::size_t m = b; m < e; ++m) {
      segs_.push_back(moves[m].seg);
      cum_.push_back(cum_.back() + length(moves[m].seg));
    }
  }
  double length_() const { return cum_.back(); }
  std::size_t seg_at(double s) const {
    const auto it = std::upper_bound(cum_.begin(), cum_.end(), s);
    return std::min<std::size_t>(
        segs_.size() - 1,
        static_cast<std::size_t>(std::max<std::ptrdiff_t>(0, (it - cum_.begin()) - 1)));
  }
  Vec2 point(double s) const {
    if (s >= cum_.back()) return segs_.back().b;
    const std::size_t i = seg_at(s);
    const double len = cum_[i + 1] - cum_[i];
    return len > 0 ? point_at(segs_[i], std::clamp((s - cum_[i]) / len, 0.0, 1.0)) : segs_[i].a;
  }
  // Largest distance from the path between s0 and s1 to the chord between its points
  // there: joints exactly, arcs sampled finely enough (sagitta of a sample gap <= tol/8).
  double deviation(double s0, double s1, const Vec2& a, const Vec2& b, double tol) const {
    const Vec2 ab = b - a;
    const double l2 = ab.squaredNorm();
    const auto dist = [&](const Vec2& q) {
      const double t = l2 > 0 ? std::clamp((q - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
      return (a + t * ab - q).norm();
    };
    double worst = 0;
    for (std::size_t i = seg_at(s0); i < segs_.size() && cum_[i] < s1; ++i) {
      const double lo = std::max(s0, cum_[i]), hi = std::min(s1, cum_[i + 1]);
      worst = std::max(worst, dist(point(hi)));
      if (!segs_[i].is_arc() || hi <= lo) continue;
      // On an arc the distance to the chord's line peaks where the arc runs parallel to it.
      const Seg2 piece = sub_segment(segs_[i], point(lo), point(hi));
      if (l2 > 0) {
        const Vec2 nrm = Vec2(-ab.y(), ab.x()) / std::sqrt(l2);
        for (double sgn : {-1.0, 1.0}) {
          const Vec2 q = piece.c + sgn * piece.r * nrm;
          if (arc_contains_angle(piece, q)) worst = std::max(worst, dist(q));
        }
      }
      const double step = 2 * std::sqrt(std::max(1e-12, 2 * segs_[i].r * tol / 8));  // chord
      const int n = std::max(1, static_cast<int>(std::ceil((hi - lo) / step)));
      for (int k = 1; k < n; ++k) worst = std::max(worst, dist(point(lo + (hi - lo) * k / n)));
    }
    return worst;
  }

 private:
  std::vector<Seg2> segs_;
  std::vector<double> cum_;
};

// CL points along one run, its start excluded; deficit[k]: how far chord k (from the
// previous point, the run's start for k = 0) dips below the drop curve at its checks.
struct RunCl {
  std::vector<ClPt> pts;
  std::vector<double> deficit;
  std::uint64_t drops = 0;
};

RunCl run_cl(const SurfaceDrop& drop, const PlanRun& run, const Pocket3dParams& p,
             pocket_detail::SegGrid& walls, double wall_limit) {
  RunCl out;
  const double r = p.tool_radius, total = run.length_();
  const double min_step = 1e-4;  // mm of plan travel: below this a chord is taken as it is
  ClPt p0 = drop_point(drop, run.point(0), r);
  ++out.drops;
  struct Chord {
    ClPt end;
    double below = 0;
  };
  double s0 = 0;
  // Whether the chord from s0 to s1 is acceptable: plan first (no drops: within eps of the
  // path, clear of walls and islands), then the drop curve at its check points.
  const auto accept = [&](double s1, Chord& c) {
    const Vec2 a = p0.cl.head<2>(), b = run.point(s1);
    if (s1 - s0 <= min_step) {  // taken as it is
      c.end = drop_point(drop, b, r);
      c.below = 0;
      ++out.drops;
      return true;
    }
    if (run.deviation(s0, s1, a, b, p.eps) > p.eps || walls.any_closer(make_line(a, b), wall_limit))
      return false;
    c.end = drop_point(drop, b, r);
    const int m = std::max(3, static_cast<int>(std::ceil((b - a).norm() / (0.5 * r))));
    double worst = 0;
    c.below = 0;
    for (int k = 1; k <= m; ++k) {
      const double f = static_cast<double>(k) / (m + 1);
      const ClPt q = drop_point(drop, a + f * (b - a), r);  // where the tool goes
      const double err = q.cl.z() - (p0.cl.z() + f * (c.end.cl.z() - p0.cl.z()));
      worst = std::max(worst, std::abs(err));
      c.below = std::max(c.below, err);
    }
    out.drops += static_cast<std::uint64_t>(m + 1);
    return worst <= 0.5 * p.delta;
  };
  // The longest acceptable chord: from the last one's length, double while acceptable,
  // halve while not; then bisect four times between the longest pass and shortest fail.
  double h = std::min(total, r);
  while (s0 < total) {
    Chord best, c;
    double pass = s0, fail = -1;
    double s1 = std::min(total, s0 + h);
    if (accept(s1, c)) {
      pass = s1;
      best = c;
      while (pass < total) {
        s1 = std::min(total, s0 + 2 * (pass - s0));
        if (!accept(s1, c)) {
          fail = s1;
          break;
        }
        pass = s1;
        best = c;
      }
    } else {
      fail = s1;
      while (pass == s0) {
        s1 = s0 + 0.5 * (fail - s0);
        if (accept(s1, c)) {
          pass = s1;
          best = c;
        } else {
          fail = s1;
        }
      }
    }
    for (int k = 0; k < 4 && fail > 0; ++k) {
      s1 = 0.5 * (pass + fail);
      if (accept(s1, c)) {
        pass = s1;
        best = c;
      } else {
        fail = s1;
      }
    }
    out.pts.push_back(best.end);
    out.deficit.push_back(best.below);
    h = pass - s0;
    s0 = pass;
    p0 = best.end;
  }
  return out;
}

PathKind kind_of(MoveKind k) {
  return k == MoveKind::kCut || k == MoveKind::kCleanup ? PathKind::kCut : PathKind::kLinkAtDepth;
}

bool inside_outline(const std::vector<Seg2>& outline, const Vec2& q) {
  return winding_number(outline, q) != 0;
}

}  // namespace

double scallop_chord(double r, double h, double rho) {
  const double flat = 2 * std::sqrt(std::max(0.0, 2 * r * h - h * h));
  if (!std::isfinite(rho) || std::abs(rho) > 1e9 * r) return flat;
  const double a = rho + r, b = rho + h;
  // A concave bottom tighter than the ball: it cannot follow it (it bridges); the flat
  // chord is then an upper bound of nothing useful, keep it.
  if (a * b <= 0) return flat;
  const double q = std::min(1.0, (2 * r * h - h * h) / (2 * a * b));
  return 2 * std::abs(a) * std::sqrt(q * (2 - q));
}

std::string validate(const Pocket3dParams& p) {
  const double vals[] = {p.tool_radius, p.scallop, p.eps,       p.delta,  p.stock,
                         p.tolerance,   p.top,     p.clearance, p.safe_z, p.min_interval};
  for (double v : vals)
    if (!std::isfinite(v)) return "pocket3d parameters must be finite numbers";
  if (!(p.tool_radius > 0)) return "tool radius must be positive";
  if (!(p.scallop > 0 && p.scallop < p.tool_radius))
    return "scallop height must lie between 0 and the ball radius (got " + mm(p.scallop) + ")";
  if (!(p.eps > 0)) return "eps (plan tolerance) must be positive";
  if (!(p.delta > 0)) return "delta (surface tolerance) must be positive";
  if (p.stock < 0) return "stock must not be negative";
  if (!(p.tolerance > 0)) return "tolerance must be positive";
  if (p.clearance < 0) return "clearance must not be negative";
  if (p.safe_z < p.top + p.clearance) return "safe_z is below the stock top plus clearance";
  if (p.min_interval < 0) return "min_interval must not be negative";
  return "";
}

namespace {

// The smallest lift h (within a tenth of the verifier's gouge tolerance, never below) that
// keeps the ball (centres a + h z, b + h z) within half that tolerance of R from the bottom
// or farther; 0 when the move already does.
double exact_lift(const SurfaceProbe& probe, const Vec3& a, const Vec3& b, double R) {
  const Vec3 up(0, 0, R);
  const double need = R - 0.5 * tol::kVerifyGouge;
  const auto gap = [&](double h) {
    const Vec3 lift(0, 0, h);
    return probe.segment_distance(a + up + lift, b + up + lift, R + 1) - need;
  };
  const double g0 = gap(0);
  if (g0 >= 0) return 0;
  double lo = 0, hi = -g0;
  while (gap(hi) < 0) {
    lo = hi;
    hi *= 2;
  }
  while (hi - lo > 0.1 * tol::kVerifyGouge) {
    const double mid = 0.5 * (lo + hi);
    (gap(mid) >= 0 ? hi : lo) = mid;
  }
  return hi;
}

// The chords between the CL points, checked against the exact bottom (the planner's own check
// samples the drop curve): a chord that comes closer than R is raised at both ends by the
// exact lift, until none does. Adds each point's lift to raised[i].
void lift_exact(const SurfaceProbe& probe, std::vector<ClPt>& pts, double R,
                std::vector<double>& raised) {
  std::vector<std::uint8_t> check(pts.size() > 0 ? pts.size() - 1 : 0, 1);
  for (int round = 0; round < 8; ++round) {
    std::vector<double> lift(check.size(), 0);
    par::for_each(lift.size(), 16, [&](std::size_t i) {
      if (check[i]) lift[i] = exact_lift(probe, pts[i].cl, pts[i + 1].cl, R);
    });
    // Only the chords next to a raised point need another look.
    std::fill(check.begin(), check.end(), 0);
    bool any = false;
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const double up = std::max(i > 0 ? lift[i - 1] : 0.0, i < lift.size() ? lift[i] : 0.0);
      if (up <= 0) continue;
      any = true;
      pts[i].cl.z() += up;
      raised[i] += up;
      if (i > 0) check[i - 1] = 1;
      if (i < check.size()) check[i] = 1;
    }
    if (!any) break;
  }
}

}  // namespace

Pocket3dPath plan_pocket3d(const std::vector<Region>& regions, const NurbsSurface& bottom,
                           const Pocket3dParams& p) {
  if (const std::string m = validate(p); !m.empty()) throw std::invalid_argument(m);
  if (const std::string m = validate(bottom); !m.empty())
    throw std::invalid_argument("bottom surface: " + m);
  if (const std::string m = check_height_field(bottom); !m.empty())
    throw std::invalid_argument("bottom surface is not a height field: " + m);
  // The pocket must lie over the surface.
  {
    const std::vector<Vec2> poly = plan_outline(bottom, 0.01);
    std::vector<Seg2> outline;
    for (std::size_t k = 0; k < poly.size(); ++k)
      outline.push_back(make_line(poly[k], poly[(k + 1) % poly.size()]));
    for (std::size_t r = 0; r < regions.size(); ++r) {
      std::vector<Vec2> pts;
      for (const Seg2& s : profile_segments(regions[r].boundary, p.tolerance))
        append_polyline(s, 0.1, pts);
      for (const Vec2& q : pts)
        if (!inside_outline(outline, q)) {
          std::ostringstream os;
          os << "boundary point (" << q.x() << ", " << q.y() << ") of region " << r
             << " is outside the bottom surface's plan outline: the surface must cover the pocket";
          throw std::invalid_argument(os.str());
        }
    }
  }

  Pocket3dPath out;
  Pocket3dStats& st = out.stats;
  const SurfaceDrop drop(bottom);
  std::atomic<std::uint64_t> drops{0};
  const StepFn step = [&](std::uint32_t, const std::vector<const OffsetLoop*>& region) {
    return level_interval(drop, region, p, drops);
  };
  pocket_stage::Settings settings;
  settings.tool_radius = p.tool_radius;
  settings.stepover =
      scallop_chord(p.tool_radius, p.scallop, std::numeric_limits<double>::infinity());
  // The first level keeps eps/2 more from walls and islands: chords, which may sag toward
  // them by up to eps/2 there, then still keep R + stock (plan tolerance taken on the
  // material side; without it, chords along arcs bending toward a wall would be a few
  // micrometres long).
  settings.stock = p.stock + 0.5 * p.eps;
  settings.tolerance = p.tolerance;
  settings.step = &step;
  settings.order = p.order;
  settings.milling = p.milling;
  settings.helix = false;
  settings.half_step_last = p.half_step_last;
  const pocket_stage::Plan plan = pocket_stage::plan_pocket_parts(regions, settings);
  static_cast<PocketPlanStats&>(st) = plan.stats;
  st.min_interval = std::numeric_limits<double>::infinity();
  for (const PocketLoop& l : plan.off.loops) {
    out.loop_interval.push_back(l.step);
    out.loop_level.push_back(l.level);
    if (l.level > 1) {
      st.min_interval = std::min(st.min_interval, l.step);
      st.max_interval = std::max(st.max_interval, l.step);
    }
  }
  if (!std::isfinite(st.min_interval)) st.min_interval = 0;

  Stopwatch clock;
  // Walls and islands as lines and arcs (NURBS within half the tolerance, sampled): no chord
  // may come closer than R + stock to them, plus the tolerance where they approximate NURBS
  // curves, so that chords keep R + stock from the true walls (one-sided: the margin is on
  // the free side; the first level lies as far, and eps/2 farther, see above and
  // engine/pocket_offset.hpp).
  std::vector<Seg2> wall_segs;
  bool nurbs = false;
  for (const Region& g : regions) {
    std::vector<const Profile*> profiles{&g.boundary};
    for (const Profile& i : g.islands) profiles.push_back(&i);
    for (const Profile* pr : profiles) {
      nurbs = nurbs || !pr->nurbs.empty();
      for (const Seg2& sg : profile_segments(*pr, 0.5 * p.tolerance)) wall_segs.push_back(sg);
    }
  }
  const pocket_detail::SegGrid walls(wall_segs, p.tool_radius);
  const double wall_limit = p.tool_radius + p.stock + (nurbs ? p.tolerance : 0);
  const SurfaceProbe probe(bottom, tol::kVerifyPiece * p.tool_radius);
  pocket_stage::ChunkBuilder b(out.cl, st.cut_length, st.link_length, st.rapid_length);
  std::vector<double> payload;
  b.set_payload(&payload, 6);
  const double feed_z = p.top + p.clearance;
  for (std::size_t k = 0; k < plan.parts.size(); ++k) {
    const PlannedPath& path = plan.paths[k];
    // Runs of moves of one kind, CL points per run in parallel (each range of runs with
    // its own copy of the wall grid: its queries keep scratch state); then chords raised
    // where they dip.
    std::vector<std::pair<std::size_t, std::size_t>> runs;
    for (std::size_t m = 0; m < path.moves.size();) {
      std::size_t e = m + 1;
      while (e < path.moves.size() && kind_of(path.moves[e].kind) == kind_of(path.moves[m].kind))
        ++e;
      runs.emplace_back(m, e);
      m = e;
    }
    std::vector<RunCl> cls(runs.size());
    par::for_ranges(runs.size(), std::max<std::size_t>(1, runs.size() / 16),
                    [&](std::size_t b0, std::size_t e0) {
                      pocket_detail::SegGrid local = walls;
                      for (std::size_t k2 = b0; k2 < e0; ++k2)
                        cls[k2] = run_cl(drop, PlanRun(path.moves, runs[k2].first, runs[k2].second),
                                         p, local, wall_limit);
                    });
    const ClPt start = drop_point(drop, path.start, p.tool_radius);
    std::vector<ClPt> pts{start};
    std::vector<PathKind> kinds{PathKind::kCut};
    std::vector<double> deficit;  // chord i joins pts[i] and pts[i + 1]
    for (std::size_t k2 = 0; k2 < runs.size(); ++k2) {
      const PathKind kind = kind_of(path.moves[runs[k2].first].kind);
      st.drops += cls[k2].drops;
      for (std::size_t i = 0; i < cls[k2].pts.size(); ++i) {
        pts.push_back(cls[k2].pts[i]);
        kinds.push_back(kind);
        deficit.push_back(cls[k2].deficit[i]);
      }
    }
    std::vector<double> raised(pts.size(), 0);
    for (std::size_t i = 0; i < pts.size(); ++i) {
      double lift = 0;
      if (i > 0) lift = std::max(lift, deficit[i - 1]);
      if (i < deficit.size()) lift = std::max(lift, deficit[i]);
      if (lift > tol::kExactZ) {  // rounding-level dips are no gouge
        pts[i].cl.z() += lift;
        raised[i] = lift;
      }
    }
    lift_exact(probe, pts, p.tool_radius, raised);
    for (double r : raised) {
      st.lifted_points += r > 0;
      st.max_lift = std::max(st.max_lift, r);
    }
    st.cl_points += pts.size();
    // Rapid over, plunge to the first CL point, then the path.
    if (k > 0) {
      b.move(Vec3(b.pos().x(), b.pos().y(), p.safe_z), PathKind::kRapid);
      ++st.retractions;
    }
    b.move(Vec3(start.cl.x(), start.cl.y(), p.safe_z), PathKind::kRapid);
    b.move(Vec3(start.cl.x(), start.cl.y(), feed_z), PathKind::kRapid);
    double pay[6];
    for (std::size_t i = 0; i < pts.size(); ++i) {
      for (int c = 0; c < 3; ++c) {
        pay[c] = pts[i].cc[c];
        pay[3 + c] = pts[i].n[c];
      }
      b.move(pts[i].cl, kinds[i], pay);
    }
  }
  if (b.started()) b.move(Vec3(b.pos().x(), b.pos().y(), p.safe_z), PathKind::kRapid);
  st.drops += drops.load();
  out.cc.reserve(payload.size() / 2);
  out.normal.reserve(payload.size() / 2);
  for (std::size_t i = 0; i + 5 < payload.size(); i += 6) {
    out.cc.insert(out.cc.end(), payload.begin() + static_cast<std::ptrdiff_t>(i),
                  payload.begin() + static_cast<std::ptrdiff_t>(i + 3));
    out.normal.insert(out.normal.end(), payload.begin() + static_cast<std::ptrdiff_t>(i + 3),
                      payload.begin() + static_cast<std::ptrdiff_t>(i + 6));
  }
  st.cl_s = clock.seconds();
  return out;
}

}  // namespace ncpath
