#pragma once
// Planar test shapes as closed Seg2 loops (material on the right: pass cw = true for a
// pocket boundary, false for an island).
#include <cmath>
#include <vector>

#include "kernels/curves/segment.hpp"

namespace ncpath::test {

inline std::vector<Seg2> maybe_reverse(std::vector<Seg2> loop, bool cw_wanted, bool is_ccw) {
  if (cw_wanted != !is_ccw) {
    std::vector<Seg2> r;
    for (auto it = loop.rbegin(); it != loop.rend(); ++it) r.push_back(reversed(*it));
    return r;
  }
  return loop;
}

inline std::vector<Seg2> rectangle(double x0, double y0, double x1, double y1, bool cw) {
  const Vec2 a(x0, y0), b(x1, y0), c(x1, y1), d(x0, y1);
  return maybe_reverse({make_line(a, b), make_line(b, c), make_line(c, d), make_line(d, a)}, cw,
                       true);
}

inline std::vector<Seg2> circle(const Vec2& c, double r, bool cw) {
  const Vec2 p(c.x() + r, c.y()), q(c.x() - r, c.y());
  return maybe_reverse({make_arc(p, q, c, true), make_arc(q, p, c, true)}, cw, true);
}

// Rectangle with corners rounded by radius rr.
inline std::vector<Seg2> rounded_rectangle(double x0, double y0, double x1, double y1, double rr,
                                           bool cw) {
  std::vector<Seg2> l;
  l.push_back(make_line({x0 + rr, y0}, {x1 - rr, y0}));
  l.push_back(make_arc({x1 - rr, y0}, {x1, y0 + rr}, {x1 - rr, y0 + rr}, true));
  l.push_back(make_line({x1, y0 + rr}, {x1, y1 - rr}));
  l.push_back(make_arc({x1, y1 - rr}, {x1 - rr, y1}, {x1 - rr, y1 - rr}, true));
  l.push_back(make_line({x1 - rr, y1}, {x0 + rr, y1}));
  l.push_back(make_arc({x0 + rr, y1}, {x0, y1 - rr}, {x0 + rr, y1 - rr}, true));
  l.push_back(make_line({x0, y1 - rr}, {x0, y0 + rr}));
  l.push_back(make_arc({x0, y0 + rr}, {x0 + rr, y0}, {x0 + rr, y0 + rr}, true));
  return maybe_reverse(l, cw, true);
}

// Slot (stadium) of length len between centres and radius rr, along x from the origin.
inline std::vector<Seg2> slot(double len, double rr, bool cw) {
  std::vector<Seg2> l;
  l.push_back(make_line({0, -rr}, {len, -rr}));
  l.push_back(make_arc({len, -rr}, {len, rr}, {len, 0}, true));
  l.push_back(make_line({len, rr}, {0, rr}));
  l.push_back(make_arc({0, rr}, {0, -rr}, {0, 0}, true));
  return maybe_reverse(l, cw, true);
}

}  // namespace ncpath::test
