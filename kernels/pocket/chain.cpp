#include "kernels/pocket/chain.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <unordered_map>

#include "kernels/curves/nurbs.hpp"
#include "kernels/curves/segment.hpp"
#include "kernels/pocket/loop_polygon.hpp"

namespace ncpath {
namespace {

using detail::LoopPolygon;

std::string num(double x) {
  char buf[32];
  auto res = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, res.ptr);
}
std::string point_text(const Vec2& p) {
  std::string t = "(";  // appended, not a + chain: GCC 12 -Wrestrict false positive
  t.append(num(p.x())).append(", ").append(num(p.y())).append(")");
  return t;
}

// Union-find over curve end points (end e = 2 * curve + 0 for the start, + 1 for the end).
struct Dsu {
  std::vector<int> parent;
  explicit Dsu(int n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void unite(int x, int y) {
    x = find(x), y = find(y);
    if (x != y) parent[std::max(x, y)] = std::min(x, y);
  }
};

// Groups ends within join_tol of each other (transitively) with a uniform grid of cell size
// >= join_tol, so only the 3 x 3 neighbouring cells are searched: O(n) for spread-out ends.
std::vector<int> cluster_ends(const std::vector<Vec2>& ends, double join_tol) {
  double extent = 0;
  for (const Vec2& p : ends) extent = std::max(extent, p.cwiseAbs().maxCoeff());
  // Keeps cell indices far from int64 overflow when join_tol is tiny or 0.
  const double cell = std::max(join_tol, 1e-12 * (1 + extent));
  auto key = [](std::int64_t i, std::int64_t j) {
    return static_cast<std::uint64_t>(i) * 0x9E3779B97F4A7C15ull ^ static_cast<std::uint64_t>(j);
  };
  std::unordered_map<std::uint64_t, std::vector<int>> grid;
  grid.reserve(ends.size());
  Dsu dsu(static_cast<int>(ends.size()));
  for (int e = 0; e < static_cast<int>(ends.size()); ++e) {
    const auto i = static_cast<std::int64_t>(std::floor(ends[e].x() / cell));
    const auto j = static_cast<std::int64_t>(std::floor(ends[e].y() / cell));
    for (std::int64_t di = -1; di <= 1; ++di)
      for (std::int64_t dj = -1; dj <= 1; ++dj) {
        auto it = grid.find(key(i + di, j + dj));
        if (it == grid.end()) continue;
        for (int f : it->second)
          if ((ends[f] - ends[e]).norm() <= join_tol) dsu.unite(e, f);
      }
    grid[key(i, j)].push_back(e);
  }
  std::vector<int> node(ends.size());
  for (int e = 0; e < static_cast<int>(ends.size()); ++e) node[e] = dsu.find(e);
  return node;
}

// Arc through new end points a, b: the centre moves to the closest point of the new chord's
// perpendicular bisector, so both ends lie on the circle exactly (to rounding).
Seg2 refit_arc(const Seg2& s, const Vec2& a, const Vec2& b) {
  const Vec2 mid = 0.5 * (a + b);
  const Vec2 d = Vec2(-(b - a).y(), (b - a).x()).normalized();
  const Vec2 c = mid + d * d.dot(s.c - mid);
  return make_arc(a, b, c, s.kind == SegKind::kArcCcw, s.source);
}

// Forward polyline of a curve, from seg.a to seg.b exactly.
std::vector<Vec2> curve_polyline(const ProfileCurve& c, const std::vector<Nurbs2>& nurbs) {
  std::vector<Vec2> pts;
  if (c.nurbs >= 0) {
    pts = nurbs_polyline(nurbs[c.nurbs], tol::kProfileTestChord);
    if (pts.size() < 2) pts = {c.seg.a, c.seg.b};
    pts.front() = c.seg.a;
    pts.back() = c.seg.b;
  } else if (!c.seg.is_arc()) {
    pts = {c.seg.a, c.seg.b};
  } else {
    const double sw = std::abs(sweep(c.seg));
    const double r = std::max(c.seg.r, tol::kProfileTestChord);
    const double step = 2 * std::acos(std::max(0.0, 1 - tol::kProfileTestChord / r));
    // At least 4 chords per arc so that a circle of two half arcs is never a 2-gon.
    const int n = std::max(4, static_cast<int>(std::ceil(sw / std::max(step, 1e-6))));
    pts.reserve(n + 1);
    pts.push_back(c.seg.a);
    for (int k = 1; k < n; ++k) pts.push_back(point_at(c.seg, static_cast<double>(k) / n));
    pts.push_back(c.seg.b);
  }
  return pts;
}

double polyline_distance(const std::vector<Vec2>& pts, const Vec2& p) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k + 1 < pts.size(); ++k) {
    const Vec2 d = pts[k + 1] - pts[k];
    const double len2 = d.squaredNorm();
    const double t = len2 > 0 ? std::clamp((p - pts[k]).dot(d) / len2, 0.0, 1.0) : 0.0;
    best = std::min(best, (pts[k] + t * d - p).norm());
  }
  return best;
}

struct Step {
  int curve;
  bool reversed;  // traversed from seg.b to seg.a
};

struct Loop {
  std::vector<Step> steps;
  LoopPolygon poly;
  double area2 = 0;  // twice the signed area in the traversal direction
  int depth = 0;
  std::vector<int> children;
};

}  // namespace

ChainResult chain_and_nest(const std::vector<ProfileCurve>& in_curves,
                           const std::vector<Nurbs2>& in_nurbs,
                           const std::vector<SourceEntity>& sources, double join_tol) {
  ChainResult res;
  const int n = static_cast<int>(in_curves.size());
  auto name = [&](int i) {
    const std::uint32_t s = in_curves[i].seg.source;
    if (s < sources.size())
      return sources[s].handle.empty() ? sources[s].type
                                       : sources[s].type + " " + sources[s].handle;
    return "curve " + std::to_string(i);
  };
  if (n == 0) {
    res.error = "no curves to chain";
    return res;
  }
  for (int i = 0; i < n; ++i) {
    const int k = in_curves[i].nurbs;
    if (k >= static_cast<int>(in_nurbs.size())) {
      res.error = name(i) + ": NURBS index " + std::to_string(k) + " out of range";
      return res;
    }
  }

  // 1. Cluster the ends into vertices and snap each vertex's ends to their midpoint.
  std::vector<Vec2> ends(2 * n);
  for (int i = 0; i < n; ++i)
    ends[2 * i] = in_curves[i].seg.a, ends[2 * i + 1] = in_curves[i].seg.b;
  const std::vector<int> node = cluster_ends(ends, join_tol);
  std::unordered_map<int, std::vector<int>> members;
  for (int e = 0; e < 2 * n; ++e) members[node[e]].push_back(e);

  // 1b. Duplicates: two curves between the same two vertices that cover the same path.
  // Checked before the vertex degrees: a duplicate would otherwise read as a branch.
  {
    std::vector<int> order(n);
    std::iota(order.begin(), order.end(), 0);
    auto vkey = [&](int i) { return std::minmax(node[2 * i], node[2 * i + 1]); };
    std::stable_sort(order.begin(), order.end(), [&](int i, int j) { return vkey(i) < vkey(j); });
    for (int s = 0; s + 1 < n; ++s) {
      for (int t = s + 1; t < n && vkey(order[t]) == vkey(order[s]); ++t) {
        const int i = std::min(order[s], order[t]), j = std::max(order[s], order[t]);
        const auto pi = curve_polyline(in_curves[i], in_nurbs);
        const Vec2 mid = pi[pi.size() / 2] * 0.5 + pi[(pi.size() - 1) / 2] * 0.5;
        if (polyline_distance(curve_polyline(in_curves[j], in_nurbs), mid) <=
            join_tol + tol::kProfileTestChord) {
          res.error = "duplicate curves: " + name(i) + " and " + name(j) + " overlap between " +
                      point_text(in_curves[i].seg.a) + " and " + point_text(in_curves[i].seg.b);
          return res;
        }
      }
    }
  }

  // Report problems in input order: the vertex of the lowest end first.
  for (int e = 0; e < 2 * n; ++e) {
    if (node[e] != e) continue;
    const auto& m = members[e];
    if (m.size() == 1) {
      res.error = "open profile: " + name(e / 2) + " " + (e % 2 ? "ends" : "starts") + " at " +
                  point_text(ends[e]) + " and no other curve ends within " + num(join_tol) +
                  " mm of it";
      return res;
    }
    if (m.size() > 2) {
      res.error = "branching profile: " + std::to_string(m.size()) + " curve ends meet at " +
                  point_text(ends[e]) + ":";
      for (int f : m) res.error += " " + name(f / 2) + (f == m.back() ? "" : ",");
      return res;
    }
  }

  std::vector<ProfileCurve> curves = in_curves;
  std::vector<Nurbs2> nurbs = in_nurbs;
  for (int e = 0; e < 2 * n; ++e) {
    if (node[e] != e) continue;
    const int f = members[e][0] == e ? members[e][1] : members[e][0];
    res.largest_gap_closed = std::max(res.largest_gap_closed, (ends[e] - ends[f]).norm());
    ends[e] = ends[f] = 0.5 * (ends[e] + ends[f]);  // bitwise unchanged when already equal
  }
  for (int i = 0; i < n; ++i) {
    ProfileCurve& c = curves[i];
    const Vec2 &a = ends[2 * i], &b = ends[2 * i + 1];
    if (a == c.seg.a && b == c.seg.b) continue;
    if (c.nurbs >= 0) {
      // Each NURBS gets its own snapped copy (two curves may share one input NURBS).
      Nurbs2 copy = in_nurbs[c.nurbs];
      copy.ctrl.front() = a;
      copy.ctrl.back() = b;
      c.nurbs = static_cast<int>(nurbs.size());
      nurbs.push_back(std::move(copy));
      c.seg.a = a, c.seg.b = b;
    } else if (c.seg.is_arc()) {
      c.seg = refit_arc(c.seg, a, b);
    } else {
      c.seg = make_line(a, b, c.seg.source);
    }
  }

  std::vector<std::vector<Vec2>> polys(n);
  for (int i = 0; i < n; ++i) polys[i] = curve_polyline(curves[i], nurbs);

  // 3. Walk the loops: every vertex joins exactly two ends.
  auto other_end = [&](int e) {
    const auto& m = members[node[e]];
    return m[0] == e ? m[1] : m[0];
  };
  std::vector<char> used(n, 0);
  std::vector<Loop> loops;
  for (int start = 0; start < n; ++start) {
    if (used[start]) continue;
    Loop loop;
    int cur = start;
    bool rev = false;
    while (true) {
      used[cur] = 1;
      loop.steps.push_back({cur, rev});
      const int next = other_end(2 * cur + (rev ? 0 : 1));
      cur = next / 2;
      rev = next % 2 == 1;
      if (cur == start) break;
    }
    for (const Step& st : loop.steps) {
      const ProfileCurve& c = curves[st.curve];
      std::vector<Vec2> pts = polys[st.curve];
      if (st.reversed) std::reverse(pts.begin(), pts.end());
      for (std::size_t k = 0; k + 1 < pts.size(); ++k) {
        loop.poly.pts.push_back(pts[k]);
        loop.poly.curve.push_back(st.curve);
      }
      if (c.nurbs >= 0) {
        for (std::size_t k = 0; k + 1 < pts.size(); ++k)
          loop.area2 += pts[k].x() * pts[k + 1].y() - pts[k].y() * pts[k + 1].x();
      } else {
        loop.area2 += (st.reversed ? -1 : 1) * area2_contribution(c.seg);
      }
    }
    detail::update_bounds(loop.poly);
    loops.push_back(std::move(loop));
  }

  // 4. Loops must not cross or touch themselves or each other.
  // A loop of fewer than 3 polygon points has no area; it is reported just below.
  std::vector<LoopPolygon> polygons;
  std::vector<int> polygon_loop;
  for (std::size_t l = 0; l < loops.size(); ++l)
    if (loops[l].poly.pts.size() >= 3) polygons.push_back(loops[l].poly), polygon_loop.push_back(l);
  const detail::PolygonCrossing x = detail::find_crossing(polygons);
  if (x.found) {
    const int ca = std::min(x.curve_a, x.curve_b), cb = std::max(x.curve_a, x.curve_b);
    res.error = x.loop_a == x.loop_b ? "self-intersecting profile: loop through " +
                                           name(loops[polygon_loop[x.loop_a]].steps[0].curve) +
                                           " intersects itself at " + point_text(x.at) + " (" +
                                           name(ca) + (ca == cb ? "" : " and " + name(cb)) + ")"
                                     : "intersecting profiles: " + name(ca) + " and " + name(cb) +
                                           " meet at " + point_text(x.at);
    return res;
  }

  for (const Loop& l : loops) {
    const double size = (l.poly.hi - l.poly.lo).maxCoeff();
    // Relative test: the area of a real loop is of the order of size^2.
    if (l.poly.pts.size() < 3 || std::abs(l.area2) <= 1e-12 * size * size) {
      res.error = "loop through " + name(l.steps[0].curve) + " encloses no area";
      return res;
    }
  }

  // 5. Nesting tree: larger loops first; descend from the roots into the child that contains
  // the loop (siblings are disjoint, so at most one does). Bounding boxes reject most tests.
  std::vector<int> by_area(loops.size());
  std::iota(by_area.begin(), by_area.end(), 0);
  std::stable_sort(by_area.begin(), by_area.end(), [&](int i, int j) {
    return std::abs(loops[i].area2) > std::abs(loops[j].area2);
  });
  std::vector<int> roots;
  auto contains = [&](int outer, int inner) {
    const LoopPolygon &po = loops[outer].poly, &pi = loops[inner].poly;
    if ((pi.lo.array() < po.lo.array()).any() || (pi.hi.array() > po.hi.array()).any())
      return false;
    return detail::point_in_polygon(po, pi.pts[0]);
  };
  for (int i : by_area) {
    std::vector<int>* level = &roots;
    int depth = 0;
    for (bool descended = true; descended;) {
      descended = false;
      for (int j : *level)
        if (contains(j, i)) {
          level = &loops[j].children;
          ++depth;
          descended = true;
          break;
        }
    }
    loops[i].depth = depth;
    level->push_back(i);
  }

  // 6. Orient (boundaries clockwise, islands counter-clockwise) and emit regions.
  auto emit = [&](const Loop& l) {
    Profile p;
    const bool flip = (l.depth % 2 == 0) == (l.area2 > 0);
    auto add = [&](const Step& st) {
      ProfileCurve c = curves[st.curve];
      const bool rev = st.reversed != flip;
      if (c.nurbs >= 0) {
        p.nurbs.push_back(rev ? nurbs_reversed(nurbs[c.nurbs]) : nurbs[c.nurbs]);
        c.nurbs = static_cast<int>(p.nurbs.size()) - 1;
        if (rev) std::swap(c.seg.a, c.seg.b);
      } else if (rev) {
        c.seg = reversed(c.seg);
      }
      p.curves.push_back(c);
    };
    if (flip)
      for (auto it = l.steps.rbegin(); it != l.steps.rend(); ++it) add(*it);
    else
      for (const Step& st : l.steps) add(st);
    return p;
  };
  for (const Loop& l : loops) {
    if (l.depth % 2 != 0) continue;
    Region r;
    r.boundary = emit(l);
    for (int c : l.children) r.islands.push_back(emit(loops[c]));
    res.regions.push_back(std::move(r));
  }
  return res;
}

}  // namespace ncpath
