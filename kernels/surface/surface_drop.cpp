// Ball-end drop onto a NURBS surface: branch and bound over the rational Bezier patches, then
// projected Newton on f(s, t) = S_z + sqrt(R^2 - |S_xy - q|^2) (the ball centre height that
// touches the surface point S) from each surviving leaf sub-patch, within its parent patch
// (surface_drop_newton.hpp).
//
// Bounds. F(x, y, z) = z + sqrt(R^2 - |(x, y) - q|^2) is concave on the disc |(x, y) - q| < R,
// so it lies below each of its tangent planes there; a linear function takes its maximum over
// a patch's convex hull at a control point. With the control box this gives two upper bounds
// of F over a (sub-)patch: the box top plus the largest sqrt over the box (tight to O(size)),
// and the largest tangent-plane value over the control points (tight to O(size^2)).
#include "kernels/surface/surface_drop.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "kernels/geom/tolerance.hpp"
#include "kernels/surface/nurbs_surface_detail.hpp"
#include "kernels/surface/surface_drop_newton.hpp"

namespace ncpath {

using surface_detail::DropNewton;
using surface_detail::H4;
using surface_detail::KnownMaximum;
using surface_detail::SearchEnd;
using surface_detail::SearchResult;
using surface_detail::SmallBuf;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Control points of a bicubic patch: sub-patches up to this size live on the stack.
constexpr int kFastCtrl = 16;
// Leaf sub-patches, searched by Newton from their middle, are those over which f has a single
// maximum. Let `bend` bound the upward second derivatives of z over the plan (1/mm) from the
// control net. A sub-patch is a leaf when bend <= kLeafBend / R and its plan diagonal is at
// most kLeafMax R (f is then concave: the ball's F has curvature <= -1/R), or when its plan
// diagonal is at most kLeafMin R and at most kLeafArc / bend (small against the ball and
// against z's own bending). Stress runs against the brute-force oracle (~50,000 drops on
// random wavy, bumpy, steep, rational and higher-degree surfaces, R from 0.2 to 160 mm)
// pass at twice kLeafBend, kLeafArc or kLeafMin and first fail (1 drop in ~50,000) at 4 times
// kLeafBend or kLeafArc.
constexpr double kLeafMin = 0.25;
constexpr double kLeafMax = 4;
constexpr double kLeafBend = 0.5;
constexpr double kLeafArc = 0.125;
// Subdivision depth cap (each split halves one parameter side).
constexpr int kMaxDepth = 60;
// Local maxima remembered per drop. A concave leaf holding one of them (within
// tol::kDropInLeaf of its parameter size) has it as its maximum and is not searched again.
constexpr int kMaxMaxima = 16;
// The tangent plane of the bound is taken at most this fraction of R from the tool axis
// (nearer the rim its slope, and so the bound, grows without limit).
constexpr double kTangentReach = 0.9;

// Push-only vector on the stack, spilling to the heap beyond N.
template <class T, int N>
class StackVec {
 public:
  void push_back(const T& v) {
    if (size_ < N) {
      local_[size_++] = v;
      return;
    }
    if (heap_.empty()) heap_.assign(local_.begin(), local_.end());
    heap_.push_back(v);
    ++size_;
  }
  T* begin() { return size_ <= N ? local_.data() : heap_.data(); }
  T* end() { return begin() + size_; }
  const T* begin() const { return size_ <= N ? local_.data() : heap_.data(); }
  int size() const { return size_; }
  T& operator[](int i) { return begin()[i]; }
  const T& operator[](int i) const { return begin()[i]; }

 private:
  std::array<T, N> local_;
  std::vector<T> heap_;
  int size_ = 0;
};

// A sub-patch of patch `patch` covering local parameters [s0, s1] x [t0, t1].
struct Node {
  const H4* ctrl = nullptr;
  Vec3 lo, hi;
  double s0 = 0, s1 = 1, t0 = 0, t1 = 1;
  double ub = -kInf;
  int depth = 0;
  int patch = 0;
  bool along_s = true;   // split direction: the longer plan side
  bool leaf = false;     // small or flat enough for Newton
  bool concave = false;  // f is concave over it (z bends upwards much less than the ball)
};

// P, Q > 0: every patch has degrees (P, Q), known at compile time (loops unroll); 0: any.
template <int P, int Q>
class Solver {
 public:
  Solver(const std::vector<BezierPatch>& patches, bool rational, const Vec2& q, double r)
      : patches_(patches), rational_(rational), q_(q), r_(r), r2_(r * r), newton_(q, r) {}

  // Fills node's box, upper bound, split direction and leaf flags from its control points
  // and offers the corners selected by `corners` (bit k: corner k = (s0, t0), (s0, t1),
  // (s1, t0), (s1, t1)), which are surface points, as contacts. False when no box point is
  // within R of the axis in plan.
  bool prepare(Node& nd, unsigned corners) {
    const BezierPatch& bp = patches_[nd.patch];
    const int p = P > 0 ? P : bp.degree_u, q = Q > 0 ? Q : bp.degree_v, n = (p + 1) * (q + 1);
    SmallBuf<Vec3, kFastCtrl> pts(n);
    if (rational_) {
      for (int i = 0; i < n; ++i) pts[i] = nd.ctrl[i].head<3>() * (1 / nd.ctrl[i].w());
    } else {
      for (int i = 0; i < n; ++i) pts[i] = nd.ctrl[i].head<3>();  // w == 1 exactly
    }
    Vec3 lo = pts[0], hi = pts[0];
    for (int i = 1; i < n; ++i) {
      lo = lo.cwiseMin(pts[i]);
      hi = hi.cwiseMax(pts[i]);
    }
    nd.lo = lo;
    nd.hi = hi;
    const double dx = std::max({lo.x() - q_.x(), 0.0, q_.x() - hi.x()});
    const double dy = std::max({lo.y() - q_.y(), 0.0, q_.y() - hi.y()});
    const double dmin2 = dx * dx + dy * dy;
    if (dmin2 > r2_) return false;
    const double ub_box = hi.z() + std::sqrt(r2_ - dmin2);
    // Tangent plane of F at the box middle (pulled towards the axis if near the rim).
    Vec2 d0 = 0.5 * (lo + hi).head<2>() - q_;
    const double reach = kTangentReach * r_;
    if (d0.squaredNorm() > reach * reach) d0 *= reach / d0.norm();
    const double h0 = std::sqrt(r2_ - d0.squaredNorm());
    const Vec2 grad = -d0 / h0;
    double top = -kInf;
    for (int i = 0; i < n; ++i) top = std::max(top, pts[i].z() + grad.dot(pts[i].head<2>()));
    const double ub_tan = top - grad.dot(q_) + h0 - grad.dot(d0);
    nd.ub = std::min(ub_box, ub_tan);
    const int c10 = p * (q + 1);
    const int corner[4] = {0, q, c10, n - 1};
    for (int k = 0; k < 4; ++k)
      if (corners & (1u << k))
        offer(pts[corner[k]], nd.patch, k < 2 ? nd.s0 : nd.s1, k % 2 ? nd.t1 : nd.t0);
    // Split across the longer plan side (corner to corner distances).
    const double ls2 =
        (pts[c10] - pts[0]).head<2>().squaredNorm() + (pts[n - 1] - pts[q]).head<2>().squaredNorm();
    const double lt2 =
        (pts[q] - pts[0]).head<2>().squaredNorm() + (pts[n - 1] - pts[c10]).head<2>().squaredNorm();
    nd.along_s = ls2 >= lt2;
    // Leaf: f has a single maximum over it, so that Newton from its middle finds it. Either
    // z bends upwards (like a bowl) much less than the ball (F's Hessian is at most -1/R),
    // which makes f concave; or the leaf is small against R and against z's own radius of
    // bending, on which scale f is nearly quadratic.
    const double diag2 = (hi - lo).head<2>().squaredNorm();
    const double reach2 = std::max(kLeafMax * kLeafMax, kLeafMin * kLeafMin) * r2_;
    nd.leaf = nd.concave = false;
    if (diag2 <= reach2) {
      // Height above the plane of the corners' mean slope, h = z - g . (x, y): its second
      // differences hold the bending of z over the plan (a curved plan parameterisation
      // bends a plane's z in (s, t) too).
      const Vec3 es = 0.5 * (pts[c10] + pts[n - 1] - pts[0] - pts[q]);
      const Vec3 et = 0.5 * (pts[q] + pts[n - 1] - pts[0] - pts[c10]);
      const double det = es.x() * et.y() - es.y() * et.x();
      Vec2 g = Vec2::Zero();
      if (det != 0)
        g = Vec2(et.y() * es.z() - es.y() * et.z(), es.x() * et.z() - et.x() * es.z()) / det;
      // Largest upward second differences of h along s and t and largest twist, over the
      // squared plan lengths of the shortest control legs along s and t (the parametric
      // speed is the degree times a leg): a bound of z's second derivatives in plan units
      // that stays conservative where the parameterisation is uneven.
      SmallBuf<double, kFastCtrl> h(n);
      for (int i = 0; i < n; ++i) h[i] = pts[i].z() - g.x() * pts[i].x() - g.y() * pts[i].y();
      const int w = q + 1;  // row stride
      double dss = 0, dtt = 0, dst = 0;
      double ls_min = std::numeric_limits<double>::max(), lt_min = ls_min;
      for (int i = 0; i <= p; ++i)
        for (int j = 0; j <= q; ++j) {
          const int k = i * w + j;
          if (i < p) ls_min = std::min(ls_min, (pts[k + w] - pts[k]).head<2>().squaredNorm());
          if (j < q) lt_min = std::min(lt_min, (pts[k + 1] - pts[k]).head<2>().squaredNorm());
          if (i > 0 && i < p) dss = std::max(dss, h[k + w] - 2 * h[k] + h[k - w]);
          if (j > 0 && j < q) dtt = std::max(dtt, h[k + 1] - 2 * h[k] + h[k - 1]);
          if (i < p && j < q)
            dst = std::max(dst, std::abs(h[k + w + 1] - h[k + w] - h[k + 1] + h[k]));
        }
      double bend = std::numeric_limits<double>::infinity();
      if (ls_min > 0 && lt_min > 0)
        bend = std::max((p - 1.0) / p * dss / ls_min, (q - 1.0) / q * dtt / lt_min) +
               dst / std::sqrt(ls_min * lt_min);
      nd.concave = bend <= kLeafBend / r_ && diag2 <= kLeafMax * kLeafMax * r2_;
      nd.leaf = nd.concave ||
                (diag2 <= kLeafMin * kLeafMin * r2_ && bend * bend * diag2 <= kLeafArc * kLeafArc);
    }
    return true;
  }

  void visit(const Node& nd) {
    if (!(nd.ub > best_f_ + tol::kBoundTie)) return;
    const BezierPatch& bp = patches_[nd.patch];
    const int p = P > 0 ? P : bp.degree_u, q = Q > 0 ? Q : bp.degree_v, n = (p + 1) * (q + 1);
    if (nd.leaf || nd.depth >= kMaxDepth) {
      if (leaf(nd) || nd.depth >= kMaxDepth) return;
    }
    SmallBuf<H4, 2 * kFastCtrl> buf(2 * n);
    Node a = nd, b = nd;
    a.ctrl = buf.data();
    b.ctrl = buf.data() + n;
    surface_detail::bezier_split(nd.ctrl, p, q, nd.along_s, buf.data(), buf.data() + n);
    a.depth = b.depth = nd.depth + 1;
    if (nd.along_s)
      a.s1 = b.s0 = 0.5 * (nd.s0 + nd.s1);
    else
      a.t1 = b.t0 = 0.5 * (nd.t0 + nd.t1);
    // Only the two corners on the split line are new surface points: a offers them.
    const bool ka = prepare(a, nd.along_s ? 0b1100u : 0b1010u), kb = prepare(b, 0u);
    if (ka && kb && b.ub > a.ub) {
      visit(b);
      visit(a);
    } else {
      if (ka) visit(a);
      if (kb) visit(b);
    }
  }

  double best_f() const { return best_f_; }
  int best_patch() const { return best_patch_; }
  double best_s() const { return best_s_; }
  double best_t() const { return best_t_; }
  const Vec3& best_point() const { return best_p_; }

 private:
  // Offers a surface point as a contact.
  void offer(const Vec3& p, int patch, double s, double t) {
    const double d2 = (p.head<2>() - q_).squaredNorm();
    if (!(d2 < r2_)) return;
    const double f = p.z() + std::sqrt(r2_ - d2);
    if (f > best_f_) {
      best_f_ = f;
      best_patch_ = patch;
      best_s_ = s;
      best_t_ = t;
      best_p_ = p;
    }
  }

  // Searches a leaf: Newton from its middle, or from its best corner when the middle is
  // outside the disc. A concave leaf holding a maximum found before needs no search. Returns
  // false when the leaf has no start point inside the disc (it is split further).
  bool leaf(const Node& nd) {
    const double ds = nd.s1 - nd.s0, dt = nd.t1 - nd.t0;
    for (int i = 0; i < maxima_.size() && nd.concave; ++i) {
      const KnownMaximum& m = maxima_[i];
      if (m.patch == nd.patch && m.s >= nd.s0 - tol::kDropInLeaf * ds &&
          m.s <= nd.s1 + tol::kDropInLeaf * ds && m.t >= nd.t0 - tol::kDropInLeaf * dt &&
          m.t <= nd.t1 + tol::kDropInLeaf * dt)
        return true;
    }
    const BezierPatch& patch = patches_[nd.patch];
    const Vec2 reach(nd.s1 - nd.s0, nd.t1 - nd.t0);
    auto search = [&](double s, double t) {
      return newton_.maximise(patch, nd.patch, s, t, reach, maxima_.begin(), maxima_.size());
    };
    SearchResult r = search(0.5 * (nd.s0 + nd.s1), 0.5 * (nd.t0 + nd.t1));
    if (r.end == SearchEnd::kOutside) {
      // The middle is outside the disc: start from the best corner inside it, if any.
      const int p = P > 0 ? P : patch.degree_u, q = Q > 0 ? Q : patch.degree_v;
      const int corner[4] = {0, q, p * (q + 1), (p + 1) * (q + 1) - 1};
      double best = -kInf, bs = 0, bt = 0;
      for (int k = 0; k < 4; ++k) {
        const H4& c = nd.ctrl[corner[k]];
        const Vec3 pt = c.head<3>() / c.w();
        const double d2 = (pt.head<2>() - q_).squaredNorm();
        if (d2 < r2_ && pt.z() + std::sqrt(r2_ - d2) > best) {
          best = pt.z() + std::sqrt(r2_ - d2);
          bs = k < 2 ? nd.s0 : nd.s1;
          bt = k % 2 ? nd.t1 : nd.t0;
        }
      }
      if (best == -kInf) return false;
      r = search(bs, bt);
    }
    if (r.end == SearchEnd::kConverged || r.end == SearchEnd::kStopped)
      offer(r.e.sp.p, nd.patch, r.s, r.t);
    if (r.end == SearchEnd::kConverged && maxima_.size() < kMaxMaxima)
      maxima_.push_back({nd.patch, r.s, r.t});
    return true;
  }

  const std::vector<BezierPatch>& patches_;
  bool rational_;  // some weight != 1 (else every homogeneous w stays exactly 1)
  Vec2 q_;
  double r_, r2_;
  double best_f_ = -kInf;
  int best_patch_ = -1;
  double best_s_ = 0, best_t_ = 0;
  Vec3 best_p_ = Vec3::Zero();
  DropNewton<P, Q> newton_;
  StackVec<KnownMaximum, kMaxMaxima> maxima_;
};

}  // namespace

SurfaceDrop::SurfaceDrop(const NurbsSurface& s) : surface_(s) {
  if (!validate(s).empty()) return;  // an invalid surface touches nothing
  patches_ = bezier_patches(s);
  rational_ = std::any_of(s.weights.begin(), s.weights.end(), [](double w) { return w != 1; });
  order_.resize(patches_.size());
  for (std::size_t i = 0; i < order_.size(); ++i) order_[i] = static_cast<int>(i);
  build_bvh(0, static_cast<int>(order_.size()));
}

int SurfaceDrop::build_bvh(int first, int count) {
  const int id = static_cast<int>(bvh_.size());
  bvh_.emplace_back();
  Vec3 lo = patches_[order_[first]].lo, hi = patches_[order_[first]].hi;
  for (int i = first; i < first + count; ++i) {
    lo = lo.cwiseMin(patches_[order_[i]].lo);
    hi = hi.cwiseMax(patches_[order_[i]].hi);
  }
  bvh_[id].lo = lo;
  bvh_[id].hi = hi;
  bvh_[id].first = first;
  bvh_[id].count = count;
  constexpr int kLeafPatches = 4;
  if (count <= kLeafPatches) return id;
  // Median split on the box middles along the longer plan side.
  const int axis = (hi.x() - lo.x()) >= (hi.y() - lo.y()) ? 0 : 1;
  auto mid = [&](int k) { return patches_[k].lo[axis] + patches_[k].hi[axis]; };
  const int half = count / 2;
  std::nth_element(order_.begin() + first, order_.begin() + first + half,
                   order_.begin() + first + count, [&](int a, int b) { return mid(a) < mid(b); });
  const int l = build_bvh(first, half);
  const int r = build_bvh(first + half, count - half);
  bvh_[id].left = l;
  bvh_[id].right = r;
  return id;
}

SurfaceContact SurfaceDrop::drop(const Vec2& xy, double radius) const {
  SurfaceContact out;
  if (bvh_.empty() || !(radius > 0) || !xy.allFinite()) return out;
  const double r2 = radius * radius;
  auto solve = [&](auto& solver) {
    // Patches whose control box comes within R of the axis in plan, highest bound first.
    struct Cand {
      double ub;
      Node node;
    };
    StackVec<Cand, 64> cands;
    std::array<int, 64> stack;
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const BvhNode& b = bvh_[stack[--top]];
      const double dx = std::max({b.lo.x() - xy.x(), 0.0, xy.x() - b.hi.x()});
      const double dy = std::max({b.lo.y() - xy.y(), 0.0, xy.y() - b.hi.y()});
      if (dx * dx + dy * dy > r2) continue;
      if (b.left >= 0) {
        stack[top++] = b.left;
        stack[top++] = b.right;
        continue;
      }
      for (int i = b.first; i < b.first + b.count; ++i) {
        Node nd;
        nd.patch = order_[i];
        nd.ctrl = patches_[nd.patch].ctrl.data();
        if (solver.prepare(nd, 0b1111u)) cands.push_back({nd.ub, nd});
      }
    }
    std::sort(cands.begin(), cands.end(), [](const Cand& a, const Cand& b) { return a.ub > b.ub; });
    for (int i = 0; i < cands.size(); ++i) solver.visit(cands[i].node);
    if (solver.best_patch() < 0) return;
    const BezierPatch& bp = patches_[solver.best_patch()];
    out.found = true;
    out.cc = solver.best_point();
    const Vec3 centre(xy.x(), xy.y(), solver.best_f());
    out.tip_z = solver.best_f() - radius;
    out.normal = (centre - out.cc) / radius;
    out.u = bp.u0 + solver.best_s() * (bp.u1 - bp.u0);
    out.v = bp.v0 + solver.best_t() * (bp.v1 - bp.v0);
  };
  // All patches share the surface's degrees; bicubic ones get unrolled loops.
  if (surface_.degree_u == 3 && surface_.degree_v == 3) {
    Solver<3, 3> solver(patches_, rational_, xy, radius);
    solve(solver);
  } else {
    Solver<0, 0> solver(patches_, rational_, xy, radius);
    solve(solver);
  }
  return out;
}

}  // namespace ncpath
