// Height-field check and plan outline of a NURBS surface.
//
// The plan Jacobian J = x_u y_v - x_v y_u of a rational patch satisfies
// det(P, P_u, P_v) = w^3 J for its homogeneous map P = (x w, y w, w), a polynomial of degree
// (3p - 1, 3q - 1) whose Bernstein coefficients bound it (convex hull property). A patch is
// certified when all its coefficients have the reference sign; otherwise it is subdivided
// (de Casteljau on the coefficients) and its corner values, which are exact samples, are
// checked, down to a depth cap. One sign of J everywhere makes the plan map a local
// homeomorphism; with a simple border image it is then one-to-one (a local homeomorphism of a
// disc that is injective on the boundary circle is injective), so the border is checked too.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "kernels/geom/tolerance.hpp"
#include "kernels/surface/nurbs_surface.hpp"
#include "kernels/surface/nurbs_surface_detail.hpp"

namespace ncpath {

using surface_detail::H4;
using surface_detail::pair_text;

namespace {

// 4-way subdivision depth of the Jacobian polynomial of one patch: a sub-patch still
// undecided at 1/1024 of its knot span lies where J is zero or within ~1e-6 (relative) of
// it, which is reported as a vertical tangent plane.
constexpr int kJacobianDepth = 10;
// Bisection steps to locate a sign change of J along a parameter segment.
constexpr int kBisectSteps = 60;

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

struct OutlinePoint {
  double u, v;
  Vec2 xy;
};

// Plan z-component of the unit normal su x sv (not turned upward), NaN where su x sv = 0.
double plan_nz(const SurfacePoint& sp) {
  const Vec3 n = sp.su.cross(sp.sv);
  const double len = n.norm();
  return len > 0 ? n.z() / len : std::nan("");
}

// Border sampling: the iso-curve from (u0, v0) to (u1, v1) (one parameter fixed) with chords
// within tol of the curve, excluding its first point.
class BorderSampler {
 public:
  BorderSampler(const NurbsSurface& s, double tol, std::vector<OutlinePoint>& out)
      : s_(s), tol_(tol), out_(out) {}

  void side(double u0, double v0, double u1, double v1, const std::vector<double>& breaks) {
    // breaks: parameter values (along the varying direction) at which the curve may kink.
    const bool along_u = u0 != u1;
    auto at = [&](double t) {
      return along_u ? OutlinePoint{t, v0, xy(t, v0)} : OutlinePoint{u0, t, xy(u0, t)};
    };
    const double a = along_u ? u0 : v0, b = along_u ? u1 : v1;
    std::vector<double> ts;
    for (double t : breaks)
      if ((t - a) * (t - b) < 0) ts.push_back(t);
    if (a > b) std::reverse(ts.begin(), ts.end());
    ts.insert(ts.begin(), a);
    ts.push_back(b);
    OutlinePoint prev = at(a);
    for (std::size_t i = 0; i + 1 < ts.size(); ++i) {
      // Two starting chords per span: one chord of a symmetric S-shaped span could have all
      // its probes near the chord.
      const OutlinePoint mid = at(0.5 * (ts[i] + ts[i + 1])), end = at(ts[i + 1]);
      refine(prev, mid, along_u, 1);
      refine(mid, end, along_u, 1);
      prev = end;
    }
  }

 private:
  static constexpr int kProbes = 5;
  static constexpr int kMaxDepth = 30;

  Vec2 xy(double u, double v) const { return surface_point(s_, u, v).head<2>(); }

  void refine(const OutlinePoint& a, const OutlinePoint& b, bool along_u, int depth) {
    double worst = 0;
    OutlinePoint mid{};
    for (int i = 1; i <= kProbes; ++i) {
      const double f = static_cast<double>(i) / (kProbes + 1);
      const OutlinePoint q{a.u + f * (b.u - a.u), a.v + f * (b.v - a.v),
                           xy(a.u + f * (b.u - a.u), a.v + f * (b.v - a.v))};
      if (2 * i == kProbes + 1) mid = q;
      const Vec2 ab = b.xy - a.xy;
      const double l2 = ab.squaredNorm();
      const double s = l2 > 0 ? std::clamp((q.xy - a.xy).dot(ab) / l2, 0.0, 1.0) : 0.0;
      worst = std::max(worst, (q.xy - (a.xy + s * ab)).norm());
    }
    if (worst <= tol_ || depth >= kMaxDepth) {
      out_.push_back(b);
      return;
    }
    refine(a, mid, along_u, depth + 1);
    refine(mid, b, along_u, depth + 1);
  }

  const NurbsSurface& s_;
  double tol_;
  std::vector<OutlinePoint>& out_;
};

std::vector<double> breakpoints(const std::vector<double>& U) {
  std::vector<double> b;
  for (double u : U)
    if (b.empty() || u > b.back()) b.push_back(u);
  return b;
}

// Border of the domain in plan, counter-clockwise, consecutive duplicates removed, the first
// point not repeated at the end.
std::vector<OutlinePoint> outline_points(const NurbsSurface& s, double tol) {
  const SurfaceDomain d = domain(s);
  const std::vector<double> bu = breakpoints(s.knots_u), bv = breakpoints(s.knots_v);
  std::vector<OutlinePoint> pts;
  pts.push_back({d.u0, d.v0, surface_point(s, d.u0, d.v0).head<2>()});
  BorderSampler sampler(s, std::max(tol, tol::kNurbsMinTol), pts);
  sampler.side(d.u0, d.v0, d.u1, d.v0, bu);
  sampler.side(d.u1, d.v0, d.u1, d.v1, bv);
  sampler.side(d.u1, d.v1, d.u0, d.v1, bu);
  sampler.side(d.u0, d.v1, d.u0, d.v0, bv);
  pts.pop_back();  // back to the start
  std::vector<OutlinePoint> out;
  for (const OutlinePoint& p : pts)
    if (out.empty() || p.xy != out.back().xy) out.push_back(p);
  while (out.size() > 1 && out.back().xy == out.front().xy) out.pop_back();
  double area2 = 0;
  for (std::size_t i = 0; i < out.size(); ++i)
    area2 += cross2(out[i].xy, out[(i + 1) % out.size()].xy);
  if (area2 < 0) std::reverse(out.begin(), out.end());
  return out;
}

// Orientation of c relative to the line a -> b: +1, -1 or 0.
int orient(const Vec2& a, const Vec2& b, const Vec2& c) {
  const double v = cross2(b - a, c - a);
  return (v > 0) - (v < 0);
}

bool on_segment(const Vec2& a, const Vec2& b, const Vec2& c) {  // c collinear with a, b
  return std::min(a.x(), b.x()) <= c.x() && c.x() <= std::max(a.x(), b.x()) &&
         std::min(a.y(), b.y()) <= c.y() && c.y() <= std::max(a.y(), b.y());
}

// Closed segments [a, b] and [c, d] share a point; t: where along [a, b] (approximate for
// collinear overlaps).
bool segments_meet(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d, double& t) {
  const int o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a), o4 = orient(c, d, b);
  if (o1 != o2 && o3 != o4 && o1 != 0 && o2 != 0 && o3 != 0 && o4 != 0) {
    const double den = cross2(b - a, d - c);
    t = den != 0 ? std::clamp(cross2(c - a, d - c) / den, 0.0, 1.0) : 0.0;
    return true;
  }
  const double l2 = (b - a).squaredNorm();
  auto param = [&](const Vec2& p) { return l2 > 0 ? (p - a).dot(b - a) / l2 : 0.0; };
  if (o1 == 0 && on_segment(a, b, c)) return t = param(c), true;
  if (o2 == 0 && on_segment(a, b, d)) return t = param(d), true;
  if (o3 == 0 && on_segment(c, d, a)) return t = 0, true;
  if (o4 == 0 && on_segment(c, d, b)) return t = 1, true;
  return false;
}

// "" when the closed polygon is simple, else where it touches or crosses itself.
std::string check_simple(const std::vector<OutlinePoint>& pts) {
  const std::size_t n = pts.size();
  if (n < 3) return "the surface's plan outline is degenerate (fewer than 3 distinct points)";
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = i;
  auto seg_a = [&](std::size_t i) -> const Vec2& { return pts[i].xy; };
  auto seg_b = [&](std::size_t i) -> const Vec2& { return pts[(i + 1) % n].xy; };
  auto min_x = [&](std::size_t i) { return std::min(seg_a(i).x(), seg_b(i).x()); };
  auto max_x = [&](std::size_t i) { return std::max(seg_a(i).x(), seg_b(i).x()); };
  std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) {
    return min_x(i) < min_x(j) || (min_x(i) == min_x(j) && i < j);
  });
  // Sweep in x: compare each segment with the ones started before it that still reach it.
  std::vector<std::size_t> active;
  for (std::size_t i : order) {
    const double x = min_x(i);
    active.erase(
        std::remove_if(active.begin(), active.end(), [&](std::size_t j) { return max_x(j) < x; }),
        active.end());
    for (std::size_t j : active) {
      if ((i + 1) % n == j || (j + 1) % n == i) continue;  // neighbours share a vertex
      double t = 0;
      if (!segments_meet(seg_a(i), seg_b(i), seg_a(j), seg_b(j), t)) continue;
      const OutlinePoint &a = pts[i], &b = pts[(i + 1) % n];
      const Vec2 xy = a.xy + t * (b.xy - a.xy);
      // The other segment's parameters at its point nearest xy.
      const OutlinePoint &c = pts[j], &d = pts[(j + 1) % n];
      const double l2 = (d.xy - c.xy).squaredNorm();
      const double r = l2 > 0 ? std::clamp((xy - c.xy).dot(d.xy - c.xy) / l2, 0.0, 1.0) : 0.0;
      return "the surface overlaps itself in plan: its border at (u, v) = " +
             pair_text(a.u + t * (b.u - a.u), a.v + t * (b.v - a.v)) +
             " and at (u, v) = " + pair_text(c.u + r * (d.u - c.u), c.v + r * (d.v - c.v)) +
             " both lie over plan (x, y) = " + pair_text(xy.x(), xy.y());
    }
    active.push_back(i);
  }
  return "";
}

// Homogeneous Jacobian polynomial det(P, P_s, P_t) of a patch in its local parameters,
// degrees (3p - 1, 3q - 1), with xy taken relative to `origin` (rounding).
std::vector<double> jacobian_poly(const BezierPatch& bp, const Vec2& origin) {
  const int p = bp.degree_u, q = bp.degree_v;
  using surface_detail::bezier_multiply;
  std::vector<double> X, Y, W;
  for (const H4& c : bp.ctrl) {
    X.push_back(c.x() - origin.x() * c.w());
    Y.push_back(c.y() - origin.y() * c.w());
    W.push_back(c.w());
  }
  auto ds = [&](const std::vector<double>& f) {  // degrees (p - 1, q)
    std::vector<double> r;
    for (int i = 0; i < p; ++i)
      for (int j = 0; j <= q; ++j) r.push_back(p * (f[(i + 1) * (q + 1) + j] - f[i * (q + 1) + j]));
    return r;
  };
  auto dt = [&](const std::vector<double>& f) {  // degrees (p, q - 1)
    std::vector<double> r;
    for (int i = 0; i <= p; ++i)
      for (int j = 0; j < q; ++j) r.push_back(q * (f[i * (q + 1) + j + 1] - f[i * (q + 1) + j]));
    return r;
  };
  const auto Xs = ds(X), Ys = ds(Y), Ws = ds(W), Xt = dt(X), Yt = dt(Y), Wt = dt(W);
  auto minor = [&](const std::vector<double>& as, const std::vector<double>& bt,
                   const std::vector<double>& at, const std::vector<double>& bs) {
    // as * bt - at * bs, degrees (2p - 1, 2q - 1)
    std::vector<double> m = bezier_multiply(as, p - 1, q, bt, p, q - 1);
    const std::vector<double> m2 = bezier_multiply(at, p, q - 1, bs, p - 1, q);
    for (std::size_t k = 0; k < m.size(); ++k) m[k] -= m2[k];
    return m;
  };
  const auto mx = minor(Ys, Wt, Yt, Ws), my = minor(Xs, Wt, Xt, Ws), mw = minor(Xs, Yt, Xt, Ys);
  std::vector<double> d = bezier_multiply(X, p, q, mx, 2 * p - 1, 2 * q - 1);
  const auto dy = bezier_multiply(Y, p, q, my, 2 * p - 1, 2 * q - 1);
  const auto dw = bezier_multiply(W, p, q, mw, 2 * p - 1, 2 * q - 1);
  for (std::size_t k = 0; k < d.size(); ++k) d[k] += -dy[k] + dw[k];
  return d;
}

std::string where(const BezierPatch& bp, double s, double t) {
  const double u = bp.u0 + s * (bp.u1 - bp.u0), v = bp.v0 + t * (bp.v1 - bp.v0);
  const Vec3 p = patch_point(bp, s, t);
  return "near (u, v) = " + pair_text(u, v) + ", plan (x, y) = " + pair_text(p.x(), p.y());
}

// Where J changes sign on the parameter segment from (gu, gv) (good) to (bu, bv) (bad),
// by bisection on the surface.
void bisect_fold(const NurbsSurface& s, double sign, double gu, double gv, double& bu, double& bv) {
  double lo = 0, hi = 1;
  for (int it = 0; it < kBisectSteps; ++it) {
    const double m = 0.5 * (lo + hi);
    (sign * plan_nz(evaluate(s, gu + m * (bu - gu), gv + m * (bv - gv))) > 0 ? lo : hi) = m;
  }
  bu = gu + hi * (bu - gu);
  bv = gv + hi * (bv - gv);
}

std::string where_uv(const NurbsSurface& s, double u, double v) {
  const Vec3 p = surface_point(s, u, v);
  return "near (u, v) = " + pair_text(u, v) + ", plan (x, y) = " + pair_text(p.x(), p.y());
}

// Checks one patch against the reference sign of J (taken at (ref_u, ref_v)); "" or the
// failure.
std::string check_patch(const NurbsSurface& s, const BezierPatch& bp, double sign, double ref_u,
                        double ref_v) {
  const int p = bp.degree_u, q = bp.degree_v;
  const int a = 3 * p - 1, b = 3 * q - 1;
  const Vec2 origin = 0.5 * (bp.lo + bp.hi).head<2>();
  auto nz = [&](double s, double t) {  // signed: > 0 means the reference orientation
    return sign * plan_nz(surface_detail::bezier_evaluate(bp.ctrl.data(), p, q, s, t));
  };
  struct Job {
    std::vector<double> d;
    double s0, s1, t0, t1;
    int depth;
  };
  std::vector<Job> stack;
  stack.push_back({jacobian_poly(bp, origin), 0, 1, 0, 1, 0});
  while (!stack.empty()) {
    Job job = std::move(stack.back());
    stack.pop_back();
    if (std::all_of(job.d.begin(), job.d.end(), [&](double c) { return sign * c > 0; })) continue;
    const double cs[2] = {job.s0, job.s1}, ct[2] = {job.t0, job.t1};
    double cn[2][2];
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) cn[i][j] = nz(cs[i], ct[j]);
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) {
        const double n = cn[i][j];
        if (n > tol::kHeightFieldNz) continue;
        if (!(n == n) || n >= -tol::kHeightFieldNz)
          return "the surface has a vertical tangent plane (plan Jacobian zero) " +
                 where(bp, cs[i], ct[j]);
        // J has the wrong sign here: locate the fold between this corner and a good one of
        // the same sub-patch, else the reference point.
        double gs = -1, gt = -1;
        for (int k = 0; k < 2 && gs < 0; ++k)
          for (int l = 0; l < 2 && gs < 0; ++l)
            if (cn[k][l] > tol::kHeightFieldNz) gs = cs[k], gt = ct[l];
        const double du = bp.u1 - bp.u0, dv = bp.v1 - bp.v0;
        double fu = bp.u0 + cs[i] * du, fv = bp.v0 + ct[j] * dv;
        if (gs >= 0)
          bisect_fold(s, sign, bp.u0 + gs * du, bp.v0 + gt * dv, fu, fv);
        else
          bisect_fold(s, sign, ref_u, ref_v, fu, fv);
        return "the surface folds over itself in plan (the plan Jacobian changes sign) " +
               where_uv(s, fu, fv);
      }
    if (job.depth >= kJacobianDepth) {
      // Undecided this deep: J comes within rounding of zero inside. Report the position of
      // the most negative coefficient.
      std::size_t worst = 0;
      for (std::size_t k = 1; k < job.d.size(); ++k)
        if (sign * job.d[k] < sign * job.d[worst]) worst = k;
      const double fs = static_cast<double>(worst / (b + 1)) / a;
      const double ft = static_cast<double>(worst % (b + 1)) / b;
      return "the surface has a vertical tangent plane (plan Jacobian zero or nearly zero) " +
             where(bp, job.s0 + fs * (job.s1 - job.s0), job.t0 + ft * (job.t1 - job.t0));
    }
    std::vector<double> lo, hi, ll, lh, hl, hh;
    surface_detail::bezier_split_scalar(job.d, a, b, true, lo, hi);
    surface_detail::bezier_split_scalar(lo, a, b, false, ll, lh);
    surface_detail::bezier_split_scalar(hi, a, b, false, hl, hh);
    const double sm = 0.5 * (job.s0 + job.s1), tm = 0.5 * (job.t0 + job.t1);
    const int dp = job.depth + 1;
    stack.push_back({std::move(hh), sm, job.s1, tm, job.t1, dp});
    stack.push_back({std::move(hl), sm, job.s1, job.t0, tm, dp});
    stack.push_back({std::move(lh), job.s0, sm, tm, job.t1, dp});
    stack.push_back({std::move(ll), job.s0, sm, job.t0, tm, dp});
  }
  return "";
}

}  // namespace

std::vector<Vec2> plan_outline(const NurbsSurface& s, double tol) {
  std::vector<Vec2> out;
  if (!validate(s).empty()) return out;
  for (const OutlinePoint& p : outline_points(s, tol)) out.push_back(p.xy);
  return out;
}

std::string check_height_field(const NurbsSurface& s) {
  const std::string err = validate(s);
  if (!err.empty()) return "invalid surface: " + err;
  // Reference orientation: the sign of J at the middle of the domain.
  const SurfaceDomain d = domain(s);
  const double um = 0.5 * (d.u0 + d.u1), vm = 0.5 * (d.v0 + d.v1);
  const SurfacePoint mid = evaluate(s, um, vm);
  const double n_mid = plan_nz(mid);
  if (!(std::abs(n_mid) > tol::kHeightFieldNz))
    return "the surface has a vertical tangent plane (plan Jacobian zero) near (u, v) = " +
           pair_text(um, vm) + ", plan (x, y) = " + pair_text(mid.p.x(), mid.p.y());
  const double sign = n_mid > 0 ? 1.0 : -1.0;
  const std::vector<BezierPatch> patches = bezier_patches(s);
  Vec3 lo = patches.front().lo, hi = patches.front().hi;
  for (const BezierPatch& bp : patches) {
    const std::string e = check_patch(s, bp, sign, um, vm);
    if (!e.empty()) return e;
    lo = lo.cwiseMin(bp.lo);
    hi = hi.cwiseMax(bp.hi);
  }
  const double size = (hi - lo).head<2>().norm();
  return check_simple(outline_points(s, tol::kHeightFieldOutline * size));
}

}  // namespace ncpath
