#include "kernels/pocket/offset.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "kernels/geom/tolerance.hpp"
#include "kernels/pocket/offset_crude.hpp"
#include "kernels/pocket/seg_grid.hpp"

namespace ncpath {

namespace {

inline double cross(const Vec2& u, const Vec2& v) { return u.x() * v.y() - u.y() * v.x(); }

using pocket_detail::crude_loop;
using pocket_detail::RawSeg;
using pocket_detail::SegGrid;

}  // namespace

bool raw_offset(const Seg2& s, double d, Seg2& out, bool* inverted) {
  out = s;
  if (!s.is_arc()) {
    const Vec2 dir = s.b - s.a;
    const double l = dir.norm();
    if (l == 0) return false;
    const Vec2 right(dir.y() / l, -dir.x() / l);
    out.a = s.a + d * right;
    out.b = s.b + d * right;
    return true;
  }
  // Counter-clockwise arcs have their centre on the left: moving right grows the radius.
  // An arc whose radius is smaller than d on the side it is offset to turns inside out: its
  // offset points lie past the centre (radius d - r, same turning direction). Kept, so that
  // the crude loop stays continuous through the swallowtail, where validation removes it;
  // the joins to its neighbours are then the arcs of radius d around its end points.
  const double r = s.r + (s.kind == SegKind::kArcCcw ? d : -d);
  if (std::abs(r) <= tol::kOffsetPoint) return false;
  const Vec2 ua = (s.a - s.c) / (s.a - s.c).norm();
  const Vec2 ub = (s.b - s.c) / (s.b - s.c).norm();
  out.a = s.c + r * ua;
  out.b = s.c + r * ub;
  out.r = std::abs(r);
  if (inverted && r < 0) *inverted = true;
  return true;
}

double loop_area2(const std::vector<Seg2>& loop) {
  double a = 0;
  for (const Seg2& s : loop) a += area2_contribution(s);
  return a;
}

double loop_length(const std::vector<Seg2>& loop) {
  double l = 0;
  for (const Seg2& s : loop) l += length(s);
  return l;
}

int winding_number(const std::vector<Seg2>& loop, const Vec2& q) {
  // A horizontal ray to +x; a tiny fixed nudge keeps it off vertices at exactly q.y.
  const Vec2 p(q.x(), q.y() + 1.2345678e-11);
  int w = 0;
  for (const Seg2& s : loop) {
    if (!s.is_arc()) {
      if (s.a.y() <= p.y() && s.b.y() > p.y()) {
        if (cross(s.b - s.a, p - s.a) > 0) ++w;
      } else if (s.b.y() <= p.y() && s.a.y() > p.y()) {
        if (cross(s.b - s.a, p - s.a) < 0) --w;
      }
      continue;
    }
    const double dy = p.y() - s.c.y();
    if (std::abs(dy) >= s.r) continue;
    const double dx = std::sqrt(s.r * s.r - dy * dy);
    for (double x : {s.c.x() - dx, s.c.x() + dx}) {
      if (x <= p.x()) continue;
      const Vec2 hit(x, p.y());
      if (!arc_contains_angle(s, hit)) continue;
      // Direction of travel in y at the hit: ccw arcs go up on the right of the centre.
      const double up = (x - s.c.x()) * s.turn();
      w += up > 0 ? 1 : -1;
    }
  }
  return w;
}

OffsetResult offset_loops(const std::vector<std::vector<Seg2>>& loops, double d,
                          const std::vector<double>* area2) {
  std::vector<RawSeg> raw;
  std::vector<bool> inverted(loops.size());
  for (std::size_t l = 0; l < loops.size(); ++l) {
    pocket_detail::RawOffsets o = pocket_detail::raw_offsets(loops[l].data(), loops[l].size(), d);
    inverted[l] = o.inverted;
    crude_loop(o, static_cast<std::uint32_t>(l), raw);
  }
  std::vector<pocket_detail::Chain> chains(loops.size());
  pocket_detail::DissectParams params;
  params.several_inputs = loops.size() > 1;
  double largest = 0;
  for (std::size_t l = 0; l < loops.size(); ++l) {
    const double a = area2 ? (*area2)[l] : loop_area2(loops[l]);
    chains[l] = {static_cast<std::uint32_t>(l), true, inverted[l], a};
    if (std::abs(a) > largest) {
      largest = std::abs(a);
      params.pocket = a < 0;
    }
  }
  std::vector<Seg2> input;  // all input curves, gathered only when a distance is needed
  std::optional<SegGrid> grid;
  const auto valid = [&](const Seg2& sg, std::uint32_t, double slack) {
    if (!grid) {
      for (const auto& l : loops) input.insert(input.end(), l.begin(), l.end());
      grid.emplace(input, d);
    }
    return !grid->any_closer(sg, d - slack);
  };
  return pocket_detail::dissect(raw, chains, nullptr, params, valid);
}

}  // namespace ncpath
