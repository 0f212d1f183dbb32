#pragma once
// Internal to kernels/surface/surface_drop.cpp: the local search of the ball drop on one
// rational Bezier patch. It maximises
//   f(s, t) = S_z + sqrt(R^2 - |S_xy - q|^2)
// (the height of the ball centre touching the surface point S(s, t)) over the patch's local
// parameters [0, 1]^2 by projected Newton, and solves the offset condition
// (S + R n)_xy = q (the same stationarity without the square root) for steep contacts.
// P, Q > 0: the patch degrees, known at compile time (loops unroll); 0: taken from the patch.
#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>

#include "kernels/geom/tolerance.hpp"
#include "kernels/surface/nurbs_surface_detail.hpp"

namespace ncpath::surface_detail {

// Newton on f hands over to Newton on the offset condition after this many iterations; the
// latter gives up after kMaxOffsetNewton.
inline constexpr int kMaxNewton = 40;
inline constexpr int kMaxHalvings = 50;
inline constexpr int kOffsetSwitch = 8;
inline constexpr int kMaxOffsetNewton = 30;

// Value, gradient and Hessian of f at local parameters (s, t) of one patch.
struct FEval {
  bool inside = false;  // S strictly within R of the axis in plan (f defined)
  double f = -std::numeric_limits<double>::infinity();
  Vec2 g = Vec2::Zero();
  Eigen::Matrix2d h = Eigen::Matrix2d::Zero();
  SurfacePoint sp;
};

// A converged local maximum of f found earlier in the same drop.
struct KnownMaximum {
  int patch;
  double s, t;
};

enum class SearchEnd {
  kOutside,    // the start point is not within R of the axis in plan
  kConverged,  // at a maximum of f over the patch (possibly on its border)
  kStopped,    // iteration cap: the best point reached is returned
  kJoined,     // heading for a known maximum: nothing new (the point is not a candidate)
};

struct SearchResult {
  SearchEnd end = SearchEnd::kOutside;
  double s = 0, t = 0;
  FEval e;  // at (s, t)
};

template <int P, int Q>
class DropNewton {
 public:
  DropNewton(const Vec2& q, double r) : q_(q), r_(r), r2_(r * r) {}

  SurfacePoint evaluate(const BezierPatch& bp, double s, double t) const {
    if constexpr (P > 0 && Q > 0)
      return bezier_evaluate_fixed<P, Q>(bp.ctrl.data(), s, t);
    else
      return bezier_evaluate(bp.ctrl.data(), bp.degree_u, bp.degree_v, s, t);
  }

  FEval eval(const BezierPatch& bp, double s, double t) const {
    FEval e;
    e.sp = evaluate(bp, s, t);
    const SurfacePoint& sp = e.sp;
    const Vec2 g = sp.p.head<2>() - q_;
    const double d2 = g.squaredNorm();
    if (!(d2 < r2_)) return e;
    e.inside = true;
    const double h = std::sqrt(r2_ - d2), ih = 1 / h, ih3 = ih * ih * ih;
    const Vec2 su = sp.su.head<2>(), sv = sp.sv.head<2>();
    const double au = g.dot(su), av = g.dot(sv);
    e.f = sp.p.z() + h;
    e.g = Vec2(sp.su.z() - au * ih, sp.sv.z() - av * ih);
    const double huu = sp.suu.z() - (su.dot(su) + g.dot(sp.suu.head<2>())) * ih - au * au * ih3;
    const double huv = sp.suv.z() - (su.dot(sv) + g.dot(sp.suv.head<2>())) * ih - au * av * ih3;
    const double hvv = sp.svv.z() - (sv.dot(sv) + g.dot(sp.svv.head<2>())) * ih - av * av * ih3;
    e.h << huu, huv, huv, hvv;
    return e;
  }

  // Projected Newton ascent of f over the patch's [0, 1]^2 from (s, t), with steps of at most
  // `reach` in each parameter (the search stays local to the leaf it starts from). Bertsekas'
  // two-metric projection: a variable within tol::kDropBoundSnap of a side with the gradient
  // pointing out of the square is fixed there, Newton runs on the others. `known` lists the
  // maxima found before (patch `patch` is this one).
  SearchResult maximise(const BezierPatch& bp, int patch, double s, double t, const Vec2& reach,
                        const KnownMaximum* known, int known_count) const {
    SearchResult out;
    FEval e = eval(bp, s, t);
    if (!e.inside) return out;
    bool converged = false;
    for (int it = 0; it < kMaxNewton && !converged; ++it) {
      bool fixed[2] = {false, false};
      double x[2] = {s, t};
      for (int k = 0; k < 2; ++k) {
        if (x[k] <= tol::kDropBoundSnap && e.g[k] < 0) fixed[k] = true, x[k] = 0;
        if (x[k] >= 1 - tol::kDropBoundSnap && e.g[k] > 0) fixed[k] = true, x[k] = 1;
      }
      if (x[0] != s || x[1] != t) {  // snapped onto a side
        const FEval es = eval(bp, x[0], x[1]);
        if (es.inside) {
          s = x[0];
          t = x[1];
          e = es;
        }
      }
      if (fixed[0] && fixed[1]) {
        converged = true;  // at a corner with the gradient pointing out: a KKT point
        break;
      }
      // Ascent direction: (-H + mu I) d = g on the free variables, mu making -H + mu I
      // positive definite (Levenberg); mu = 0 near a regular maximum, so that Newton converges
      // quadratically.
      Vec2 d = Vec2::Zero();
      bool damped = false;
      const double scale = std::max(e.h.cwiseAbs().maxCoeff(), 1e-300);
      const double floor = 1e-9 * scale;
      if (!fixed[0] && !fixed[1]) {
        const double a = -e.h(0, 0), b = -e.h(0, 1), c = -e.h(1, 1);
        const double lmin = 0.5 * (a + c) - std::sqrt(0.25 * (a - c) * (a - c) + b * b);
        const double mu = lmin < floor ? floor - lmin : 0.0;
        damped = mu > 0;
        const double aa = a + mu, cc = c + mu, det = aa * cc - b * b;
        d = Vec2(cc * e.g.x() - b * e.g.y(), aa * e.g.y() - b * e.g.x()) / det;
      } else {
        const int k = fixed[0] ? 1 : 0;
        damped = -e.h(k, k) < floor;
        d[k] = e.g[k] / std::max(-e.h(k, k), floor);
      }
      if (!(d.cwiseAbs().maxCoeff() > 0)) {
        converged = true;
        break;
      }
      // Backtracking along the projected Newton step; if that finds no ascent, along the
      // projected gradient.
      bool accepted = false;
      for (int pass = 0; pass < 2 && !accepted; ++pass) {
        if (pass == 1) {
          d = e.g / scale;
          if (fixed[0]) d.x() = 0;
          if (fixed[1]) d.y() = 0;
          damped = true;
        }
        const double over = std::max(std::abs(d.x()) / reach.x(), std::abs(d.y()) / reach.y());
        if (over > 1) {
          d /= over;
          damped = true;
        }
        for (int k = 0; k < kMaxHalvings; ++k, d *= 0.5) {
          const double ns = std::clamp(s + d.x(), 0.0, 1.0);
          const double nt = std::clamp(t + d.y(), 0.0, 1.0);
          if (ns == s && nt == t) break;
          const FEval en = eval(bp, ns, nt);
          if (!en.inside) continue;
          // A full Newton step (undamped, neither shortened nor projected) of length e is
          // followed by an error of order e^2 / (curvature radius). Near the maximum f
          // changes by less than its rounding, so such a step is taken if it loses no more
          // than that: the position (cc, normal) then converges as Newton does, not only f.
          const bool full = !damped && k == 0 && ns == s + d.x() && nt == t + d.y();
          const double slack = full ? tol::kDropFlatSlack * (1 + std::abs(e.f)) : 0.0;
          if (!(en.f > e.f - slack)) continue;
          const double moved = (e.sp.su * (ns - s) + e.sp.sv * (nt - t)).norm();
          s = ns;
          t = nt;
          e = en;
          accepted = true;
          converged = moved <= tol::kContactSolve || (full && moved <= tol::kDropNewtonQuadratic);
          break;
        }
      }
      if (!accepted) {
        converged = true;  // no ascent left at rounding level: stationary
        break;
      }
      // Heading for a maximum found before (from another leaf): nothing new to find. The
      // iterate is no candidate: it is no higher than that maximum but for rounding, and
      // would only move the contact off it.
      if (!converged && joins_known(patch, e.sp, s, t, known, known_count)) {
        out.end = SearchEnd::kJoined;
        return out;
      }
      // Slow progress: typically a steep contact near the ball's equator, where f's square
      // root makes Newton on f crawl along the rim of the disc. The contact conditions
      // without the square root are smooth there: the offset condition inside the square,
      // the ball touching the side's curve on a side that f rises towards.
      if (!converged && (it + 1 == kOffsetSwitch || it + 1 == kMaxNewton)) {
        double best_s = s, best_t = t;
        FEval best = e;
        auto consider = [&](double cs, double ct) {
          const FEval ec = eval(bp, cs, ct);
          if (ec.inside && ec.f >= best.f) best_s = cs, best_t = ct, best = ec;
        };
        double os = s, ot = t;
        if (offset_newton(bp, reach, os, ot)) consider(os, ot);
        for (int k = 0; k < 2; ++k)
          for (double side : {0.0, 1.0}) {
            const double x = k == 0 ? s : t;
            if (std::abs(x - side) > reach[k] || (side == 0 ? e.g[k] >= 0 : e.g[k] <= 0)) continue;
            double bs = k == 0 ? side : s, bt = k == 0 ? t : side;
            if (side_newton(bp, 1 - k, e.f, reach, bs, bt)) consider(bs, bt);
          }
        if (best_s != s || best_t != t) {
          s = best_s;
          t = best_t;
          e = best;
          converged = true;
        }
      }
    }
    out.end = converged ? SearchEnd::kConverged : SearchEnd::kStopped;
    out.s = s;
    out.t = t;
    out.e = e;
    return out;
  }

  // The ball touching the curve C(x) = S along a side of the square, x the free parameter
  // (free = 0: s, with t fixed at its current value; free = 1: t): Newton in (x, c) on
  //   (C - P) . C' = 0,  |C - P|^2 = R^2,  P = (q, c) the ball centre,
  // from centre height c. True when it converges with x inside [0, 1] (the contact conditions
  // within tol::kContactSolve) and the contact below the centre.
  bool side_newton(const BezierPatch& bp, int free, double c, const Vec2& reach, double& s,
                   double& t) const {
    double& x = free == 0 ? s : t;
    for (int it = 0; it < kMaxOffsetNewton; ++it) {
      const SurfacePoint sp = evaluate(bp, s, t);
      const Vec3& d1 = free == 0 ? sp.su : sp.sv;
      const Vec3& d2 = free == 0 ? sp.suu : sp.svv;
      const Vec3 w(sp.p.x() - q_.x(), sp.p.y() - q_.y(), sp.p.z() - c);  // C - P
      const double e1 = w.dot(d1), e2 = w.squaredNorm() - r2_;
      const double speed = d1.norm();
      if (std::abs(e1) <= tol::kContactSolve * speed && std::abs(e2) <= tol::kContactSolve * r_)
        return w.z() < 0;
      // Jacobian in (x, c): [[|C'|^2 + w . C'', -C'_z], [2 w . C', -2 w_z]].
      const double a = d1.squaredNorm() + w.dot(d2), b = -d1.z();
      const double cc = 2 * e1, dd = -2 * w.z();
      const double det = a * dd - b * cc;
      if (!(std::abs(det) > 0)) return false;
      double dx = -(dd * e1 - b * e2) / det;
      const double dc = -(a * e2 - cc * e1) / det;
      if (std::abs(dx) > reach[free]) dx *= reach[free] / std::abs(dx);
      x += dx;
      c += dc;
      if (!(x >= 0 && x <= 1)) return false;
    }
    return false;
  }

  // Newton on the offset condition G(s, t) = S_xy + R n_xy - q = 0 (n: upward unit normal;
  // the ball centre S + R n on the tool axis) from (s, t) with steps of at most `reach`. True
  // when it converges inside the patch's square (to |G| <= tol::kContactSolve).
  bool offset_newton(const BezierPatch& bp, const Vec2& reach, double& s, double& t) const {
    for (int it = 0; it < kMaxOffsetNewton; ++it) {
      const SurfacePoint sp = evaluate(bp, s, t);
      Vec3 nn = sp.su.cross(sp.sv);
      Vec3 ns = sp.suu.cross(sp.sv) + sp.su.cross(sp.suv);
      Vec3 nt = sp.suv.cross(sp.sv) + sp.su.cross(sp.svv);
      const double len = nn.norm();
      if (!(len > 0)) return false;
      if (nn.z() < 0) {
        nn = -nn;
        ns = -ns;
        nt = -nt;
      }
      const Vec3 n = nn / len;
      // Derivatives of the unit normal: the part of N's derivative across n, over |N|.
      const Vec3 dns = (ns - n * n.dot(ns)) / len, dnt = (nt - n * n.dot(nt)) / len;
      const Vec2 g = sp.p.head<2>() + r_ * n.head<2>() - q_;
      if (g.norm() <= tol::kContactSolve) return true;
      Eigen::Matrix2d j;
      j << sp.su.x() + r_ * dns.x(), sp.sv.x() + r_ * dnt.x(), sp.su.y() + r_ * dns.y(),
          sp.sv.y() + r_ * dnt.y();
      if (!(std::abs(j.determinant()) > 0)) return false;
      Vec2 d = -j.inverse() * g;
      const double over = std::max(std::abs(d.x()) / reach.x(), std::abs(d.y()) / reach.y());
      if (over > 1) d /= over;
      s += d.x();
      t += d.y();
      if (!(s >= 0 && s <= 1 && t >= 0 && t <= 1)) return false;
    }
    return false;
  }

 private:
  static bool joins_known(int patch, const SurfacePoint& sp, double s, double t,
                          const KnownMaximum* known, int known_count) {
    for (int i = 0; i < known_count; ++i) {
      const KnownMaximum& m = known[i];
      if (m.patch == patch && (sp.su * (m.s - s) + sp.sv * (m.t - t)).squaredNorm() <=
                                  tol::kDropSameMaximum * tol::kDropSameMaximum)
        return true;
    }
    return false;
  }

  Vec2 q_;
  double r_, r2_;
};

}  // namespace ncpath::surface_detail
