#include "kernels/pocket/uncut.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "kernels/geom/tolerance.hpp"
#include "kernels/pocket/seg_grid.hpp"

namespace ncpath {

std::vector<std::vector<Seg2>> reversed_loops(const std::vector<std::vector<Seg2>>& loops) {
  std::vector<std::vector<Seg2>> out;
  out.reserve(loops.size());
  for (const std::vector<Seg2>& l : loops) {
    std::vector<Seg2> r;
    r.reserve(l.size());
    for (auto it = l.rbegin(); it != l.rend(); ++it) r.push_back(reversed(*it));
    out.push_back(std::move(r));
  }
  return out;
}

Reach tool_reach(const std::vector<std::vector<Seg2>>& region, double tool_radius) {
  Reach out;
  double area = 0;
  for (const std::vector<Seg2>& l : region) area += -loop_area2(l) / 2;
  // Erode by R (where the tool centre can go), then dilate by R.
  const OffsetResult centres = offset_loops(region, tool_radius);
  std::vector<std::vector<Seg2>> c;
  for (const OffsetLoop& l : centres.loops) c.push_back(l.segs);
  out.reachable = dilate(c, tool_radius);
  double reach = 0;
  for (const OffsetLoop& l : out.reachable) reach += -l.area2 / 2;
  out.unreachable_area = std::max(0.0, area - reach);
  return out;
}

std::vector<OffsetLoop> dilate(const std::vector<std::vector<Seg2>>& region, double d) {
  // Offsetting the reversed loops grows the region (its complement is the material now).
  std::vector<OffsetLoop> out;
  for (const OffsetLoop& l : offset_loops(reversed_loops(region), d).loops) {
    OffsetLoop r;
    r.segs = reversed_loops({l.segs}).front();
    r.area2 = -l.area2;
    out.push_back(std::move(r));
  }
  return out;
}

std::vector<OffsetLoop> uncut_between(const std::vector<const OffsetLoop*>& outer,
                                      const std::vector<const OffsetLoop*>& inner,
                                      double tool_radius) {
  std::vector<std::vector<Seg2>> band, holes;
  for (const OffsetLoop* l : outer) band.push_back(l->segs);
  for (const OffsetLoop* l : inner) holes.push_back(l->segs);
  for (std::vector<Seg2>& h : reversed_loops(holes)) band.push_back(std::move(h));
  std::vector<OffsetLoop> out;
  for (OffsetLoop& l : offset_loops(band, tool_radius).loops) split_pinched(std::move(l), out);
  return out;
}

namespace {

// Points of the offset of `loops` by R into their material (corner arcs included) at most
// `h` apart along it, passed to `visit` until it returns false.
template <class Visit>
bool offset_samples(const std::vector<const OffsetLoop*>& loops, double r, double h,
                    Visit&& visit) {
  const auto right = [](const Vec2& t) { return Vec2(t.y(), -t.x()); };
  for (const OffsetLoop* loop : loops) {
    const std::vector<Seg2>& segs = loop->segs;
    for (std::size_t i = 0; i < segs.size(); ++i) {
      const Seg2& sg = segs[i];
      const double len = std::max(length(sg), std::abs(sweep(sg)) * (sg.r + r));
      const int n = std::max(1, static_cast<int>(std::ceil(len / h)));
      for (int k = 0; k < n; ++k) {
        const double t = static_cast<double>(k) / n;
        if (!visit(Vec2(point_at(sg, t) + r * right(tangent_at(sg, t))))) return false;
      }
      // A left turn into the next segment leaves a gap between the offsets: the arc of
      // radius R around the vertex joins them.
      const Seg2& next = segs[(i + 1) % segs.size()];
      const Vec2 t1 = tangent_at(sg, 1), t2 = tangent_at(next, 0);
      const double turn = std::atan2(t1.x() * t2.y() - t1.y() * t2.x(), t1.dot(t2));
      if (turn <= 0) continue;
      const int m = std::max(1, static_cast<int>(std::ceil(turn * r / h)));
      const Vec2 n1 = right(t1);
      for (int k = 1; k <= m; ++k) {
        const double a = turn * k / m;
        const Vec2 d(n1.x() * std::cos(a) - n1.y() * std::sin(a),
                     n1.x() * std::sin(a) + n1.y() * std::cos(a));
        if (!visit(Vec2(sg.b + r * d))) return false;
      }
    }
  }
  return true;
}

// True when every sample of the offset of `from` by R comes closer than R to `other`, by a
// margin that covers the points between samples (the distance is 1-Lipschitz).
bool offset_covered(const std::vector<const OffsetLoop*>& from,
                    const std::vector<const OffsetLoop*>& other, double r) {
  std::vector<Seg2> segs;
  for (const OffsetLoop* l : other) segs.insert(segs.end(), l->segs.begin(), l->segs.end());
  if (segs.empty()) return false;
  pocket_detail::SegGrid grid(segs, r);
  const double h = 0.1 * r;
  const double limit = r - 0.5 * h - tol::kOffsetValid;
  return offset_samples(from, r, h, [&](const Vec2& q) {
    std::uint32_t seg = 0;
    double d = 0;
    return grid.nearest_within(q, limit, seg, d);
  });
}

}  // namespace

bool band_cut(const std::vector<const OffsetLoop*>& outer,
              const std::vector<const OffsetLoop*>& inner, double tool_radius) {
  if (inner.empty()) return false;
  // The inner loops' offsets into the band run outward: offset their reversed copies.
  std::vector<OffsetLoop> reversed_inner;
  for (const OffsetLoop* l : inner) {
    OffsetLoop r;
    r.segs = reversed_loops({l->segs}).front();
    reversed_inner.push_back(std::move(r));
  }
  std::vector<const OffsetLoop*> rev;
  for (const OffsetLoop& l : reversed_inner) rev.push_back(&l);
  return offset_covered(outer, inner, tool_radius) && offset_covered(rev, outer, tool_radius);
}

void split_pinched(OffsetLoop loop, std::vector<OffsetLoop>& out) {
  // Vertices on the stack by position (rounded to 1e-9 mm; a touch that rounds apart is
  // left as it is, which is only wasteful).
  const auto key = [](const Vec2& p) {
    return std::pair(std::llround(p.x() / tol::kOffsetPoint),
                     std::llround(p.y() / tol::kOffsetPoint));
  };
  std::map<std::pair<long long, long long>, std::size_t> at;  // vertex -> stack index
  std::vector<Seg2> stack;
  const auto emit = [&](std::size_t from) {
    OffsetLoop part;
    part.segs.assign(stack.begin() + static_cast<std::ptrdiff_t>(from), stack.end());
    for (std::size_t k = from; k < stack.size(); ++k) at.erase(key(stack[k].a));
    stack.resize(from);
    part.area2 = loop_area2(part.segs);
    // Zero-width pieces (a bridge travelled there and back) enclose nothing.
    if (std::abs(part.area2) <= 2 * tol::kUncutArea) return;
    part.parents = loop.parents;
    out.push_back(std::move(part));
  };
  for (const Seg2& s : loop.segs) {
    at.emplace(key(s.a), stack.size());
    stack.push_back(s);
    const auto hit = at.find(key(s.b));
    if (hit != at.end()) emit(hit->second);
  }
  if (!stack.empty()) emit(0);
}

}  // namespace ncpath
