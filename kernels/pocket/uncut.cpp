#include "kernels/pocket/uncut.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "kernels/geom/tolerance.hpp"

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
