#include "kernels/pocket/uncut.hpp"

#include <algorithm>

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
  // Erode by R (where the tool centre can go), then dilate by R: offsetting the reversed
  // loops grows the region (its complement is the material now).
  const OffsetResult centres = offset_loops(region, tool_radius);
  std::vector<std::vector<Seg2>> c;
  for (const OffsetLoop& l : centres.loops) c.push_back(l.segs);
  const OffsetResult grown = offset_loops(reversed_loops(c), tool_radius);
  double reach = 0;
  for (const OffsetLoop& l : grown.loops) {
    OffsetLoop r;
    r.segs = reversed_loops({l.segs}).front();
    r.area2 = -l.area2;
    reach += -r.area2 / 2;
    out.reachable.push_back(std::move(r));
  }
  out.unreachable_area = std::max(0.0, area - reach);
  return out;
}

std::vector<OffsetLoop> uncut_between(const std::vector<const OffsetLoop*>& outer,
                                      const std::vector<const OffsetLoop*>& inner,
                                      double tool_radius) {
  std::vector<std::vector<Seg2>> band, holes;
  for (const OffsetLoop* l : outer) band.push_back(l->segs);
  for (const OffsetLoop* l : inner) holes.push_back(l->segs);
  for (std::vector<Seg2>& h : reversed_loops(holes)) band.push_back(std::move(h));
  return offset_loops(band, tool_radius).loops;
}

}  // namespace ncpath
