#include "kernels/pocket/uncut.hpp"

namespace ncpath {

std::vector<OffsetLoop> uncut_between(const std::vector<const OffsetLoop*>& outer,
                                      const std::vector<const OffsetLoop*>& inner,
                                      double tool_radius) {
  std::vector<std::vector<Seg2>> band;
  for (const OffsetLoop* l : outer) band.push_back(l->segs);
  for (const OffsetLoop* l : inner) {
    std::vector<Seg2> r;
    r.reserve(l->segs.size());
    for (auto it = l->segs.rbegin(); it != l->segs.rend(); ++it) r.push_back(reversed(*it));
    band.push_back(std::move(r));
  }
  return offset_loops(band, tool_radius).loops;
}

}  // namespace ncpath
