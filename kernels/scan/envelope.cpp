#include "kernels/scan/envelope.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace ncpath {

const char* junction_kind_name(JunctionKind kind) {
  switch (kind) {
    case JunctionKind::kConvex:
      return "convex";
    case JunctionKind::kSharpConcave:
      return "sharp-concave";
    case JunctionKind::kTangent:
      return "tangent";
  }
  return "?";
}

namespace {

// Decides which of two pieces is on top over intervals and appends the result as spans.
class Merger {
 public:
  Merger(std::span<const SlicePiece> pieces, double tie, EnvelopeCounters& counters)
      : pc_(pieces), tie_(tie), cnt_(counters) {}

  std::vector<EnvelopeSpan> merge(const std::vector<EnvelopeSpan>& A,
                                  const std::vector<EnvelopeSpan>& B) {
    std::vector<EnvelopeSpan> out;
    out.reserve(A.size() + B.size());
    out_ = &out;
    std::size_t i = 0, j = 0;
    double ax = A.empty() ? 0 : A[0].x0, bx = B.empty() ? 0 : B[0].x0;
    while (i < A.size() && j < B.size()) {
      const EnvelopeSpan &sa = A[i], &sb = B[j];
      if (sa.x1 <= bx) {
        emit(sa.piece, ax, sa.x1);
        if (++i < A.size()) ax = A[i].x0;
        continue;
      }
      if (sb.x1 <= ax) {
        emit(sb.piece, bx, sb.x1);
        if (++j < B.size()) bx = B[j].x0;
        continue;
      }
      const double lo = std::max(ax, bx), hi = std::min(sa.x1, sb.x1);
      if (ax < lo) emit(sa.piece, ax, lo);
      if (bx < lo) emit(sb.piece, bx, lo);
      resolve(sa.piece, sb.piece, lo, hi);
      ax = bx = hi;
      if (sa.x1 <= hi && ++i < A.size()) ax = A[i].x0;
      if (sb.x1 <= hi && ++j < B.size()) bx = B[j].x0;
    }
    while (i < A.size()) {
      emit(A[i].piece, ax, A[i].x1);
      if (++i < A.size()) ax = A[i].x0;
    }
    while (j < B.size()) {
      emit(B[j].piece, bx, B[j].x1);
      if (++j < B.size()) bx = B[j].x0;
    }
    return out;
  }

 private:
  void emit(std::uint32_t piece, double s, double t) {
    if (!(s < t)) return;
    auto& out = *out_;
    if (!out.empty() && out.back().piece == piece && out.back().x1 == s) {
      out.back().x1 = t;
      return;
    }
    out.push_back({piece, s, t});
  }

  // Lower element id first (the floor, kNoElement, last); then lower piece index.
  bool before(std::uint32_t a, std::uint32_t b) const {
    const std::uint32_t ea = pc_[a].element, eb = pc_[b].element;
    return ea != eb ? ea < eb : a < b;
  }

  double diff(std::uint32_t A, std::uint32_t B, double x) const {
    return centre_z(pc_[A], x) - centre_z(pc_[B], x);
  }

  void resolve(std::uint32_t p, std::uint32_t q, double s, double t) {
    if (before(q, p)) std::swap(p, q);
    if (same_curve(pc_[p], pc_[q])) return emit(p, s, t);
    budget_ = kDecisionBudget;
    decide(p, q, s, t, 0);
  }

  // Two pieces on the same circle or ellipse (within the tie): duplicated vertices or edges.
  // Their difference is below the tie everywhere, but the chord bounds only prove it on tiny
  // intervals, so they are settled here.
  bool same_curve(const SlicePiece& a, const SlicePiece& b) const {
    if (is_linear(a) || is_linear(b)) return false;  // lines are settled exactly anyway
    SectionEllipse ea, eb;
    if (a.kind == PieceKind::kSphereArc || b.kind == PieceKind::kSphereArc) {
      if (a.kind != b.kind) return false;
      const double da = a.point.y() - a.y0, db = b.point.y() - b.y0;
      const double ra = std::sqrt(std::max(0.0, (a.radius - da) * (a.radius + da)));
      const double rb = std::sqrt(std::max(0.0, (b.radius - db) * (b.radius + db)));
      return std::abs(a.point.x() - b.point.x()) <= tie_ &&
             std::abs(a.point.z() - b.point.z()) <= tie_ && std::abs(ra - rb) <= tie_;
    }
    if (!ellipse_of(a, ea) || !ellipse_of(b, eb)) return false;
    return (ea.centre - eb.centre).norm() <= tie_ && std::abs(ea.major - eb.major) <= tie_ &&
           std::abs(ea.minor - eb.minor) <= tie_ &&
           std::abs(ea.major_axis.x() * eb.major_axis.y() - ea.major_axis.y() * eb.major_axis.x()) *
                   ea.major <= tie_;
  }

  // A wins ties (A before B). Emits the spans of [s, t] left to right.
  void decide(std::uint32_t A, std::uint32_t B, double s, double t, int depth) {
    ++cnt_.decisions;
    const SlicePiece &a = pc_[A], &b = pc_[B];
    const double as = centre_z(a, s), at = centre_z(a, t);
    const double bs = centre_z(b, s), bt = centre_z(b, t);
    const double ds = as - bs, dt = at - bt;
    const double w = t - s;
    const double ma = (at - as) / w, mb = (bt - bs) / w;
    // A - B >= chord_A - B >= -max(B - chord_A); exact maximum of a concave function.
    const double x1 = argmax_tilted(b, ma, s, t);
    const double low = std::min({as + ma * (x1 - s) - centre_z(b, x1), ds, dt});
    if (low >= -tie_) return emit(A, s, t);
    const double x2 = argmax_tilted(a, mb, s, t);
    const double high = std::max({centre_z(a, x2) - (bs + mb * (x2 - s)), ds, dt});
    if (high <= 0) return emit(B, s, t);
    const double xm = 0.5 * (s + t);
    if (w <= tol::kEnvelopeMinWidth || depth >= 200 || !(s < xm && xm < t) || budget_ <= 0) {
      if (budget_ <= 0) ++cnt_.unsettled;
      return emit(diff(A, B, xm) >= -tie_ ? A : B, s, t);
    }
    --budget_;
    if ((ds < 0 && dt > 0) || (ds > 0 && dt < 0)) {
      const double r = crossing(A, B, s, t, ds, dt);
      if (s < r && r < t) {
        ++cnt_.crossings;
        decide(A, B, s, r, depth + 1);
        decide(A, B, r, t, depth + 1);
        return;
      }
    }
    decide(A, B, s, xm, depth + 1);
    decide(A, B, xm, t, depth + 1);
  }

  // Root of A - B in (s, t), d(s) and d(t) of opposite signs (Illinois regula falsi).
  double crossing(std::uint32_t A, std::uint32_t B, double s, double t, double ds,
                  double dt) const {
    int side = 0;
    double x = 0.5 * (s + t);
    for (int it = 0; it < 200; ++it) {
      x = (s * dt - t * ds) / (dt - ds);
      if (!(x > s && x < t)) x = 0.5 * (s + t);
      if (!(x > s && x < t)) break;
      const double dx = diff(A, B, x);
      if (dx == 0) return x;
      if ((dx < 0) == (dt < 0)) {
        t = x;
        dt = dx;
        if (side == -1) ds *= 0.5;
        side = -1;
      } else {
        s = x;
        ds = dx;
        if (side == 1) dt *= 0.5;
        side = 1;
      }
      if (t - s <= 1e-15 * (1 + std::abs(x))) break;
    }
    return std::abs(ds) <= std::abs(dt) ? s : t;
  }

  // Interval splits allowed per pair of spans; beyond it intervals are decided at their
  // midpoints and counted (EnvelopeCounters::unsettled). Never reached in the tests.
  static constexpr int kDecisionBudget = 4096;

  std::span<const SlicePiece> pc_;
  double tie_;
  int budget_ = kDecisionBudget;
  EnvelopeCounters& cnt_;
  std::vector<EnvelopeSpan>* out_ = nullptr;
};

std::vector<EnvelopeSpan> envelope_of(Merger& m, std::span<const SlicePiece> pieces,
                                      std::span<const std::uint32_t> order) {
  if (order.size() == 1) {
    const SlicePiece& p = pieces[order[0]];
    if (!(p.x0 < p.x1)) return {};
    return {EnvelopeSpan{order[0], p.x0, p.x1}};
  }
  const std::size_t half = order.size() / 2;
  const auto left = envelope_of(m, pieces, order.first(half));
  const auto right = envelope_of(m, pieces, order.subspan(half));
  return m.merge(left, right);
}

// Unit direction of (dx, dz), dz possibly infinite.
Vec2 direction(double dx, double dz) {
  if (std::isinf(dz)) return Vec2(0, dz > 0 ? 1 : -1);
  const Vec2 v(dx, dz);
  const double n = v.norm();
  return n > 0 ? Vec2(v / n) : Vec2(1, 0);
}

}  // namespace

namespace {

// True when curved piece q is certified to lie within `tie` below the envelope `spans`
// everywhere on its range: against a line exactly (q - line is concave: its maximum is at
// argmax_tilted), against a curved span by its chord (the span lies above its chord, so
// q <= chord + tie suffices). False may also mean "not certified".
bool hidden_by(const SlicePiece& q, std::span<const SlicePiece> pieces,
               const std::vector<EnvelopeSpan>& spans, double tie) {
  auto it = std::upper_bound(spans.begin(), spans.end(), q.x0,
                             [](double x, const EnvelopeSpan& s) { return x < s.x1; });
  double covered = q.x0;
  for (; it != spans.end() && it->x0 < q.x1; ++it) {
    if (it->x0 > covered) return false;  // a gap: nothing below to hide q
    const double a = std::max(q.x0, it->x0), b = std::min(q.x1, it->x1);
    const SlicePiece& l = pieces[it->piece];
    const double la = centre_z(l, a);
    const double m = b > a ? (centre_z(l, b) - la) / (b - a) : 0.0;
    const double x = argmax_tilted(q, m, a, b);
    if (centre_z(q, x) - (la + m * (x - a)) > tie) return false;
    covered = it->x1;
  }
  return covered >= q.x1;
}

}  // namespace

void upper_envelope(std::span<const SlicePiece> pieces, std::vector<EnvelopeSpan>& out,
                    EnvelopeCounters* counters, double tie) {
  out.clear();
  if (pieces.empty()) return;
  auto by_x = [&](std::uint32_t a, std::uint32_t b) {
    const SlicePiece &pa = pieces[a], &pb = pieces[b];
    if (pa.x0 != pb.x0) return pa.x0 < pb.x0;
    if (pa.element != pb.element) return pa.element < pb.element;
    return a < b;
  };
  // Linear pieces first (facet lines, the floor: cheap, exact decisions). Then the curved
  // pieces they do not hide: the highest ones (by peak) first, which on a part are the
  // blends of its top surface; what that envelope certifiably hides (the far side of the
  // part, blends under blends) is dropped, and the rest merged in.
  std::vector<std::uint32_t> lines, curved;
  for (std::uint32_t i = 0; i < pieces.size(); ++i)
    (is_linear(pieces[i]) ? lines : curved).push_back(i);
  std::sort(lines.begin(), lines.end(), by_x);
  EnvelopeCounters local;
  EnvelopeCounters& cnt = counters ? *counters : local;
  Merger m(pieces, tie, cnt);
  std::vector<EnvelopeSpan> env;
  if (!lines.empty()) env = envelope_of(m, pieces, lines);
  auto drop_hidden = [&](std::vector<std::uint32_t>& ids) {
    if (!env.empty())
      cnt.hidden += std::erase_if(
          ids, [&](std::uint32_t i) { return hidden_by(pieces[i], pieces, env, tie); });
  };
  auto merge_in = [&](std::vector<std::uint32_t>& ids) {
    if (ids.empty()) return;
    std::sort(ids.begin(), ids.end(), by_x);
    std::vector<EnvelopeSpan> e = envelope_of(m, pieces, ids);
    env = env.empty() ? std::move(e) : m.merge(env, e);
  };
  drop_hidden(curved);
  const std::size_t first = 2 * lines.size() + 64;
  if (curved.size() > first) {
    std::vector<double> peak(pieces.size());
    for (std::uint32_t i : curved) {
      const SlicePiece& q = pieces[i];
      peak[i] = centre_z(q, argmax_tilted(q, 0, q.x0, q.x1));
    }
    std::sort(curved.begin(), curved.end(), [&](std::uint32_t a, std::uint32_t b) {
      return peak[a] != peak[b] ? peak[a] > peak[b] : by_x(a, b);
    });
    std::vector<std::uint32_t> rest(curved.begin() + std::ptrdiff_t(first), curved.end());
    curved.resize(first);
    merge_in(curved);
    drop_hidden(rest);
    curved = std::move(rest);
  }
  merge_in(curved);
  out = std::move(env);
}

JunctionKind junction_kind(double dx1, double dz1, double dx2, double dz2) {
  const Vec2 t1 = direction(dx1, dz1), t2 = direction(dx2, dz2);
  const double angle = std::atan2(t1.x() * t2.y() - t1.y() * t2.x(), t1.dot(t2));
  if (std::abs(angle) <= tol::kJunctionTangentAngle) return JunctionKind::kTangent;
  return angle > 0 ? JunctionKind::kSharpConcave : JunctionKind::kConvex;
}

namespace {

// Highest tip z of a piece over [a, b] (pieces are concave: the tilted maximum at slope 0).
double peak_tip(const SlicePiece& p, double a, double b) {
  return tip_z(p, argmax_tilted(p, 0, a, b));
}

// Where two touching spans meet at x and the lower piece there (say the right one, below the
// left one's end by more than tol::kEnvelopeJump) rises above that end within
// tol::kEnvelopeHole, x is not a wall but a crossing the merge placed too early: an interval too narrow to
// split (tol::kEnvelopeMinWidth) is decided at its midpoint, and a nearly vertical facet line
// (a wall tilted by rounding) is above the floor at the midpoint but below it at the end, by
// its slope times the width (1e-3 mm). The junction moves to where the rising piece reaches
// the other's end height (bisection), so that the curve never drops below it there.
void place_crossings(std::span<const SlicePiece> pieces, std::vector<EnvelopeSpan>& spans) {
  for (std::size_t k = 0; k + 1 < spans.size(); ++k) {
    EnvelopeSpan &l = spans[k], &r = spans[k + 1];
    if (l.x1 != r.x0) continue;
    const SlicePiece &p = pieces[l.piece], &q = pieces[r.piece];
    const double zl = tip_z(p, l.x1), zr = tip_z(q, r.x0);
    const bool right_low = zr < zl - tol::kEnvelopeJump, left_low = zl < zr - tol::kEnvelopeJump;
    if (!right_low && !left_low) continue;
    const SlicePiece& low = right_low ? q : p;
    const EnvelopeSpan& ls = right_low ? r : l;
    const double target = right_low ? zl : zr;
    if (!(peak_tip(low, ls.x0, ls.x1) > target)) continue;  // a wall: it stays lower
    // From the junction to the peak the low piece rises through the target (it is concave);
    // only a crossing within tol::kEnvelopeHole of the junction is one the merge misplaced.
    const double x = right_low ? r.x0 : l.x1;
    double near = x, far = argmax_tilted(low, 0, ls.x0, ls.x1);
    for (int it = 0; it < 100 && near != far; ++it) {
      const double m = 0.5 * (near + far);
      if (m == near || m == far) break;
      (tip_z(low, m) > target ? far : near) = m;
    }
    if (std::abs(far - x) < tol::kEnvelopeHole) l.x1 = r.x0 = far;
  }
}

// The spans the curve keeps (indices into spans, in order). A run of spans [k, m] narrower
// than tol::kEnvelopeHole from the end of span k - 1 to the start of span m + 1, whose
// pieces stay below the higher of the two facing ends (span k - 1's end, span m + 1's
// start), is a hole that rounding opened between two pieces (tol::kEnvelopeHole): it is left
// out, and the curve crosses it at that height (plane_curve). A run that sticks out above
// both is kept (a spike of the part).
std::vector<std::size_t> kept_spans(std::span<const SlicePiece> pieces,
                                    std::span<const EnvelopeSpan> spans) {
  std::vector<std::size_t> kept;
  const std::size_t n = spans.size();
  for (std::size_t k = 0; k < n; ++k) {
    std::size_t last = n;  // the longest hole [k, last] found
    if (!kept.empty() && kept.back() + 1 == k) {
      const EnvelopeSpan& l = spans[k - 1];
      const double zl = tip_z(pieces[l.piece], l.x1);
      double high = -INFINITY;  // the run's highest point so far
      for (std::size_t m = k; m + 1 < n && spans[m + 1].x0 - l.x1 < tol::kEnvelopeHole; ++m) {
        high = std::max(high, peak_tip(pieces[spans[m].piece], spans[m].x0, spans[m].x1));
        const EnvelopeSpan& r = spans[m + 1];
        if (high <= std::max(zl, tip_z(pieces[r.piece], r.x0)) + tol::kEnvelopeJump) last = m;
      }
    }
    if (last == n)
      kept.push_back(k);
    else
      k = last;  // skip [k, last]
  }
  return kept;
}

// A junction between the kept spans `left` and `sp` (touching, or across a hole), with a
// vertical segment before it where the heights differ (the tool passes a wall). Across a hole
// [a, b] the vertical stands on the lower side's end, so the curve crosses at the higher
// height.
void join_spans(std::span<const SlicePiece> pieces, const EnvelopeSpan& left,
                const EnvelopeSpan& sp, PlaneCurve& out) {
  const SlicePiece &p = pieces[left.piece], &q = pieces[sp.piece];
  const double zl = tip_z(p, left.x1), zr = tip_z(q, sp.x0);
  const double x = zr > zl ? left.x1 : sp.x0;
  const double sl = slope(p, left.x1), sr = slope(q, sp.x0);
  const Vec3 bl = piece_contact(p, left.x1).normal, br = piece_contact(q, sp.x0).normal;
  CurveJunction j;
  j.x = x;
  j.element1 = p.element;
  j.element2 = q.element;
  if (std::abs(zl - zr) > tol::kEnvelopeJump) {
    const bool left_high = zl > zr;
    const std::uint32_t high = left_high ? left.piece : sp.piece;
    const Vec3 bh = left_high ? bl : br;
    const double dz = zr - zl;
    j.z = zl;
    j.kind = junction_kind(1, sl, 0, dz);
    j.element2 = pieces[high].element;
    j.b1 = bl;
    j.b2 = bh;
    j.segment = std::uint32_t(out.segments.size());
    out.junctions.push_back(j);
    out.segments.push_back({high, true, x, x, zl, zr});
    j.z = zr;
    j.kind = junction_kind(0, dz, 1, sr);
    j.element1 = pieces[high].element;
    j.element2 = q.element;
    j.b1 = bh;
    j.b2 = br;
  } else {
    j.z = zr;
    j.kind = junction_kind(1, sl, 1, sr);
    j.b1 = bl;
    j.b2 = br;
  }
  j.segment = std::uint32_t(out.segments.size());
  out.junctions.push_back(j);
}

}  // namespace

void plane_curve(std::span<const SlicePiece> pieces, std::span<const EnvelopeSpan> given,
                 PlaneCurve& out) {
  out.segments.clear();
  out.junctions.clear();
  out.run_starts.clear();
  std::vector<EnvelopeSpan> spans(given.begin(), given.end());
  place_crossings(pieces, spans);
  const std::vector<std::size_t> kept = kept_spans(pieces, spans);
  for (std::size_t i = 0; i < kept.size(); ++i) {
    const EnvelopeSpan& sp = spans[kept[i]];
    const SlicePiece& q = pieces[sp.piece];
    if (i == 0 || spans[kept[i - 1]].x1 + tol::kEnvelopeHole <= sp.x0)
      out.run_starts.push_back(std::uint32_t(out.segments.size()));  // nothing covers the gap
    else
      join_spans(pieces, spans[kept[i - 1]], sp, out);
    out.segments.push_back({sp.piece, false, sp.x0, sp.x1, tip_z(q, sp.x0), tip_z(q, sp.x1)});
  }
}

namespace {

void discretise_arc(const SlicePiece& pc, double s, double zs, double t, double zt, double tol,
                    int depth, std::vector<Vec2>& points, std::vector<double>& lift) {
  const double m = (zt - zs) / (t - s);
  const double xm = argmax_tilted(pc, m, s, t);
  const double dev = std::max(0.0, tip_z(pc, xm) - (zs + m * (xm - s)));
  if (dev / std::sqrt(1 + m * m) <= tol || depth >= 60 || !(t - s > 1e-9)) {
    points.emplace_back(s, zs);
    lift.push_back(dev);
    return;
  }
  // Split at the farthest point unless it hugs an end (near-vertical ends): then halve.
  double x = xm;
  if (!(x > s + 0.1 * (t - s) && x < t - 0.1 * (t - s))) x = 0.5 * (s + t);
  const double zx = tip_z(pc, x);
  discretise_arc(pc, s, zs, x, zx, tol, depth + 1, points, lift);
  discretise_arc(pc, x, zx, t, zt, tol, depth + 1, points, lift);
}

}  // namespace

void discretise_segment(const SlicePiece& piece, const CurveSegment& seg, double tolerance,
                        std::vector<Vec2>& points, std::vector<double>& lift) {
  if (seg.vertical || is_linear(piece) || !(seg.x0 < seg.x1)) {
    points.emplace_back(seg.x0, seg.z0);
    lift.push_back(0);
    return;
  }
  discretise_arc(piece, seg.x0, seg.z0, seg.x1, seg.z1, tolerance, 0, points, lift);
}

}  // namespace ncpath
