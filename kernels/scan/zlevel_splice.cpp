// Z-level contours (kernels/scan/zlevel.hpp): which regions can make a level's U differ from
// the known inside region's, and a level whose U differs only within some x-slabs as the
// region's contours outside the slabs joined to a local computation's inside them, along
// vertical cut lines. Declarations: zlevel_detail.hpp.
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>

#include "kernels/geom/tolerance.hpp"
#include "kernels/scan/zlevel_detail.hpp"

namespace ncpath::zlevel_detail {

namespace {

constexpr double kPi = std::numbers::pi;

// The parameters of an arc in (t0, t1) where x is extreme (ascending): x(t) = cx + A cos t +
// B sin t (perp(axis) = (-axis.y, axis.x)).
std::vector<double> arc_x_extremes(const ContourSeg& s) {
  const double A = s.r1 * s.axis.x(), B = -s.r2 * s.axis.y();
  std::vector<double> out;
  if (A == 0 && B == 0) return out;
  const double phi = std::atan2(B, A);  // x' = 0 at phi + k pi
  const double k0 = std::ceil((s.t0 - phi) / kPi);
  for (double k = k0;; ++k) {
    const double t = phi + k * kPi;
    if (!(t < s.t1)) break;
    if (t > s.t0) out.push_back(t);
  }
  return out;
}

// The sub-segment of s between fractions f0 < f1 of its parameter, its ends pa and pb.
ContourSeg sub_seg(const ContourSeg& s, double f0, double f1, const Vec2& pa, const Vec2& pb) {
  ContourSeg r = s;
  r.a = pa;
  r.b = pb;
  if (s.kind != ContourSegKind::kLine) {
    const double dt = s.t1 - s.t0;
    r.t0 = s.t0 + f0 * dt;
    r.t1 = f1 == 1 ? s.t1 : s.t0 + f1 * dt;
  }
  return r;
}

// The fractions in (0, 1) where s crosses x = X (ascending), found by bisection on the parts
// of s where x is monotone.
void crossings(const ContourSeg& s, double X, std::vector<double>& out) {
  std::vector<double> f = {0};
  if (s.kind != ContourSegKind::kLine)
    for (double t : arc_x_extremes(s)) f.push_back((t - s.t0) / (s.t1 - s.t0));
  f.push_back(1);
  auto x_at = [&](double g) { return g == 0 ? s.a.x() : g == 1 ? s.b.x() : seg_point(s, g).x(); };
  for (std::size_t k = 0; k + 1 < f.size(); ++k) {
    double lo = f[k], hi = f[k + 1];
    const double xl = x_at(lo) - X, xh = x_at(hi) - X;
    if (!(xl * xh < 0)) continue;
    const bool rising = xl < 0;
    for (int it = 0; it < 200 && lo < hi; ++it) {
      const double mid = 0.5 * (lo + hi);
      if (mid <= lo || mid >= hi) break;
      if ((x_at(mid) < X) == rising)
        lo = mid;
      else
        hi = mid;
    }
    out.push_back(0.5 * (lo + hi));
  }
}

// One segment with the junction at its start (if any).
struct JSeg {
  ContourSeg seg;
  std::optional<ZJunction> junction;
};

// A run of kept sub-segments from a cut point to a cut point, or a whole loop.
struct Chain {
  std::vector<JSeg> segs;
  bool closed = false;
};

bool same_curve(const ContourSeg& p, const ContourSeg& q) {
  return p.element == q.element && p.kind == q.kind && p.shadow == q.shadow;
}

// Whether no segment of the contours starts, nor has an arc's extreme x, within `clearance`
// of a cut line x = cuts[k].
bool cuts_are_clear(const std::vector<ZContour>& contours, const std::vector<double>& cuts,
                    double clearance) {
  for (const ZContour& c : contours)
    for (const ContourSeg& s : c.segs) {
      for (double X : cuts) {
        if (std::abs(s.a.x() - X) < clearance) return false;
        if (s.kind == ContourSegKind::kLine) continue;
        for (double t : arc_x_extremes(s))
          if (std::abs(seg_point(s, (t - s.t0) / (s.t1 - s.t0)).x() - X) < clearance) return false;
      }
    }
  return true;
}

// The contours made of the parts of `outer` in the intervals between the (ascending) cut lines
// where inside[k] is 0 and the parts of `local` where it is 1 (interval k: below cuts[k],
// above cuts[k - 1]); both must run along the same element's curve across every cut line, and
// meet there (within tol::kZLevelLink). `local_open`: chains of `local`'s computation that did
// not close, whose parts kept must lie between cut lines too. The junctions of `outer` are
// moved to tip_z. False when they do not meet one to one.
bool splice_contours(const std::vector<ZContour>& outer, const std::vector<ZContour>& local,
                     const std::vector<ZContour>& local_open, const std::vector<double>& cuts,
                     const std::vector<std::uint8_t>& inside, double tip_z,
                     std::vector<ZContour>& out) {
  // The side of x: the index of the interval between cuts; inside[k] says whether it is the
  // local computation's.
  auto side = [&](double x) {
    return std::size_t(std::upper_bound(cuts.begin(), cuts.end(), x) - cuts.begin());
  };
  std::vector<Chain> chains[2];  // 0: from `outer`, 1: from `local`
  for (int pass = 0; pass < 3; ++pass) {
    const int src = pass == 0 ? 0 : 1;
    const bool cyclic = pass < 2;
    const std::vector<ZContour>& from = pass == 0 ? outer : pass == 1 ? local : local_open;
    for (const ZContour& c : from) {
      // Split every segment at the cuts; mark the pieces kept.
      std::vector<JSeg> pieces;
      std::vector<std::uint8_t> keep;
      std::size_t next_j = 0;
      for (std::size_t i = 0; i < c.segs.size(); ++i) {
        const ContourSeg& s = c.segs[i];
        std::vector<double> f;
        for (double X : cuts) crossings(s, X, f);
        std::sort(f.begin(), f.end());
        f.push_back(1);
        double f0 = 0;
        Vec2 pa = s.a;
        for (std::size_t k = 0; k < f.size(); ++k) {
          const double f1 = f[k];
          Vec2 pb = s.b;
          if (f1 < 1) {
            pb = seg_point(s, f1);
            // On its cut line exactly: the nearest cut.
            const std::size_t q = side(pb.x());
            double X = q < cuts.size() ? cuts[q] : cuts.back();
            if (q > 0 && std::abs(cuts[q - 1] - pb.x()) < std::abs(X - pb.x())) X = cuts[q - 1];
            pb.x() = X;
          }
          JSeg js{sub_seg(s, f0, f1, pa, pb), std::nullopt};
          if (k == 0 && next_j < c.junctions.size() && c.junctions[next_j].seg == i) {
            js.junction = c.junctions[next_j++];
            js.junction->position.z() = tip_z;
          }
          const Vec2 m = seg_point(js.seg, 0.5);
          keep.push_back(std::uint8_t((inside[side(m.x())] != 0) == (src == 1)));
          pieces.push_back(js);
          f0 = f1;
          pa = pb;
        }
      }
      const std::size_t n = pieces.size();
      std::size_t first = n;  // a piece that starts a run (kept, after one not kept)
      for (std::size_t k = 0; k < n; ++k)
        if (keep[k] && !keep[(k + n - 1) % n]) {
          first = k;
          break;
        }
      if (!cyclic) first = 0;
      if (first == n) {
        if (keep[0]) chains[src].push_back({std::move(pieces), true});
        continue;
      }
      if (!cyclic && n > 0 && keep[0]) return false;      // an open chain's start is kept
      if (!cyclic && n > 0 && keep[n - 1]) return false;  // its end too
      for (std::size_t q = 0; q < n;) {
        const std::size_t k = (first + q) % n;
        if (!keep[k]) {
          ++q;
          continue;
        }
        Chain ch;
        while (q < n && keep[(first + q) % n]) ch.segs.push_back(pieces[(first + q++) % n]);
        chains[src].push_back(std::move(ch));
      }
    }
  }
  // Each open chain's end meets one open chain of the other source's start on a cut line.
  const double link = tol::kZLevelLink;
  std::vector<std::uint32_t> next[2];
  for (int src = 0; src < 2; ++src) {
    next[src].assign(chains[src].size(), kNone);
    for (std::size_t i = 0; i < chains[src].size(); ++i) {
      const Chain& a = chains[src][i];
      if (a.closed) continue;
      const ContourSeg& end = a.segs.back().seg;
      std::uint32_t found = kNone;
      for (std::size_t j = 0; j < chains[1 - src].size(); ++j) {
        const Chain& b = chains[1 - src][j];
        if (b.closed) continue;
        const ContourSeg& start = b.segs.front().seg;
        if ((start.a - end.b).norm() > 10 * link) continue;
        if (found != kNone || (start.a - end.b).norm() > link || !same_curve(start, end) ||
            b.segs.front().junction)
          return false;  // ambiguous, or not the same curve on both sides
        found = std::uint32_t(j);
      }
      if (found == kNone) return false;
      next[src][i] = found;
    }
  }
  // Every start is met once.
  for (int src = 0; src < 2; ++src) {
    std::vector<std::uint8_t> met(chains[1 - src].size(), 0);
    for (std::uint32_t j : next[src])
      if (j != kNone && met[j]++) return false;
  }
  // Loops: the closed chains, and the open ones followed from source to source.
  std::vector<std::vector<JSeg>> loops;
  for (int src = 0; src < 2; ++src)
    for (const Chain& c : chains[src])
      if (c.closed) loops.push_back(c.segs);
  std::vector<std::uint8_t> used[2] = {std::vector<std::uint8_t>(chains[0].size(), 0),
                                       std::vector<std::uint8_t>(chains[1].size(), 0)};
  for (std::size_t i0 = 0; i0 < chains[0].size(); ++i0) {
    if (chains[0][i0].closed || used[0][i0]) continue;
    std::vector<JSeg> loop;
    int src = 0;
    std::size_t i = i0;
    while (!used[src][i]) {
      used[src][i] = 1;
      for (const JSeg& js : chains[src][i].segs) {
        // The two halves of a segment cut at the line join again.
        if (!loop.empty() && &js == &chains[src][i].segs.front()) {
          JSeg& last = loop.back();
          last.seg.b = js.seg.b;
          last.seg.t1 += js.seg.t1 - js.seg.t0;
          continue;
        }
        loop.push_back(js);
      }
      const std::uint32_t j = next[src][i];
      src = 1 - src;
      i = j;
    }
    if (src != 0 || i != i0) return false;  // not back where it started
    // The first segment continues the last (cut at the line where the loop was entered),
    // unless the loop is one segment (a circle), which starts there then.
    if (loop.size() > 1) {
      JSeg& last = loop.back();
      last.seg.b = loop.front().seg.b;
      last.seg.t1 += loop.front().seg.t1 - loop.front().seg.t0;
      loop.front() = last;
      loop.pop_back();
    }
    loops.push_back(std::move(loop));
  }
  for (int src = 0; src < 2; ++src)
    for (std::size_t i = 0; i < chains[src].size(); ++i)
      if (!chains[src][i].closed && !used[src][i]) return false;

  // Canonical loops (as build_loops writes them).
  out.clear();
  for (std::vector<JSeg>& loop : loops) {
    std::size_t start = 0;
    for (std::size_t i = 1; i < loop.size(); ++i) {
      const ContourSeg &a = loop[i].seg, &b = loop[start].seg;
      if (a.a.x() < b.a.x() ||
          (a.a.x() == b.a.x() &&
           (a.a.y() < b.a.y() || (a.a.y() == b.a.y() && a.element < b.element))))
        start = i;
    }
    std::rotate(loop.begin(), loop.begin() + std::ptrdiff_t(start), loop.end());
    ZContour c;
    for (std::size_t i = 0; i < loop.size(); ++i) {
      c.segs.push_back(loop[i].seg);
      if (loop[i].junction) {
        ZJunction j = *loop[i].junction;
        j.seg = std::uint32_t(i);
        c.junctions.push_back(j);
      }
    }
    c.area = contour_area(c.segs);
    c.hole = c.area < 0;
    out.push_back(std::move(c));
  }
  sort_contours(out);
  return true;
}

// The regions of the candidates `cand` (facets, edges and their end vertices, vertices) that
// may make U at level lv differ from the known inside region's U (ZLevelInside): their
// x-ranges (false when these, grown by R, cover more than half of `extent`, the known
// contours' x-range grown by R: too much to splice). The others are empty, lie
// wholly above the region's level (strictly; such a region is the same there, inside U) or
// inside its polygon (by its margin; the polygon is inscribed in the region). U only grows
// going down: with none, U is the region's U.
bool changed_regions(const OffsetElements& el, const std::vector<std::uint32_t>& cand,
                     const ZLevelInside& q, const Level& lv, bool reach, const double* extent,
                     std::vector<std::array<double, 2>>& xs) {
  const double zc_known = q.tip_z + lv.R;
  const auto nf = std::uint32_t(el.facet_count()), ne = std::uint32_t(el.edge_count());
  // The x-ranges grown by R on bins over the extent: more than half of it covered is too much
  // for splicing (splice_changed).
  constexpr int kBins = 512;
  std::array<std::uint8_t, kBins> bin{};
  int covered = 0;
  const double bw = (extent[1] - extent[0]) / kBins;
  // The region of element id, of lowest point `low`; false when they cover too much.
  auto visit = [&](std::uint32_t id, double low) {
    if (low > zc_known) return true;
    Region g;
    if (!build_region(el, id, lv, reach, g) || region_in_known(el, q, g, q.margin)) return true;
    xs.push_back({g.box[0], g.box[2]});
    if (!(bw > 0)) return false;
    const int b0 = std::clamp(int(std::floor((g.box[0] - lv.R - extent[0]) / bw)), 0, kBins - 1);
    const int b1 = std::clamp(int(std::floor((g.box[2] + lv.R - extent[0]) / bw)), 0, kBins - 1);
    for (int b = b0; b <= b1; ++b) covered += bin[b] ? 0 : (bin[b] = 1);
    return 2 * covered <= kBins;
  };
  auto visit_vertex = [&](std::uint32_t point) {
    const auto it = std::lower_bound(el.vertex_source.begin(), el.vertex_source.end(), point);
    if (it == el.vertex_source.end() || *it != point) return true;  // not a vertex element
    return visit(el.vertex_id(std::size_t(it - el.vertex_source.begin())), el.points[point].z());
  };
  for (const std::uint32_t id : cand) {
    if (id < nf) {
      double low = INFINITY;
      for (const Vec3& v : el.facet_tri[id]) low = std::min(low, v.z());
      if (!visit(id, low)) return false;
    } else if (id < nf + ne) {
      const auto& ev = el.edge_vertices[id - nf];
      const double low = std::min(el.points[ev[0]].z(), el.points[ev[1]].z());
      if (!visit(id, low) || !visit_vertex(ev[0]) || !visit_vertex(ev[1])) return false;
    } else if (!visit_vertex(el.vertex_source[id - nf - ne])) {
      return false;
    }
  }
  return true;
}

// Where U differs from the known region's U only within x-slabs covering a small part of the
// contours' width (`extent`): cut lines around the changed regions' x-ranges `xs` (grown by
// R; moved outwards by up to 7 R / 16 until clear of the known contours' segment ends and
// arc extremes), the contours of the local candidates (those of params.unfiltered whose box
// meets a slab; their union is U within the slabs) computed, and the two spliced
// (splice_contours). False when that does not apply or the contours do not meet.
bool splice_changed(const OffsetElements& el, std::vector<std::array<double, 2>> xs,
                    const ZLevelInside& q, const double* extent, double tip_z,
                    const ZLevelParams& params, ZLevelResult& result) {
  if (xs.empty() || params.unfiltered.empty() || !params.boxes) return false;
  const double R = el.radius, lo = extent[0], hi = extent[1];
  // Slabs: the x-ranges grown by R, merged.
  std::sort(xs.begin(), xs.end());
  std::vector<std::array<double, 2>> slabs;
  for (const auto& x : xs) {
    const double a = x[0] - R, b = x[1] + R;
    if (!slabs.empty() && a <= slabs.back()[1])
      slabs.back()[1] = std::max(slabs.back()[1], b);
    else
      slabs.push_back({a, b});
  }
  double width = 0;
  for (const auto& s : slabs) width += std::min(s[1], hi) - std::max(s[0], lo);
  if (!(width < 0.4 * (hi - lo))) return false;
  // Cut lines, each moved outwards until clear (by up to 7 R / 16); inside[k]: interval k
  // (below cuts[k], above cuts[k - 1]) is the local computation's.
  std::vector<double> cuts;
  std::vector<std::uint8_t> inside = {0};
  const double clearance = 1e-6;
  for (const auto& s : slabs) {
    for (int side = 0; side < 2; ++side) {
      double X = s[side];
      if (side == 0 ? X <= lo : X >= hi) {
        if (side == 0) inside.back() = 1;  // the slab starts before the contours
        continue;
      }
      bool clear = false;
      for (int k = 0; k < 8 && !clear; ++k) {
        const double Xk = X + (side == 0 ? -1 : 1) * (R / 16) * k;
        if (cuts_are_clear(q.contours, {Xk}, clearance)) {
          X = Xk;
          clear = true;
        }
      }
      if (!clear) return false;
      if (!cuts.empty() && !(X > cuts.back())) return false;
      cuts.push_back(X);
      inside.push_back(side == 0 ? 1 : 0);
    }
  }
  if (cuts.empty()) return false;
  // The local candidates: those whose box meets a local interval (closed at the cuts): the
  // intervals from the first whose upper cut is not below x0 to the one holding x1.
  std::vector<std::uint32_t> local_cand;
  const auto& box = params.boxes->box;
  for (std::uint32_t id : params.unfiltered) {
    const auto k0 = std::lower_bound(cuts.begin(), cuts.end(), double(box[id][0])) - cuts.begin();
    const auto k1 = std::upper_bound(cuts.begin(), cuts.end(), double(box[id][2])) - cuts.begin();
    for (auto k = k0; k <= k1; ++k)
      if (inside[std::size_t(k)]) {
        local_cand.push_back(id);
        break;
      }
  }
  // Without the known region: it lies inside U, not inside the union of the local candidates
  // outside the slabs (chains may not close there).
  ZLevelParams lp = params;
  lp.inside = nullptr;
  lp.candidates_filtered = false;
  lp.unfiltered = {};
  std::vector<ZContour> local_open;
  ZLevelResult local = contours_open(el, local_cand, tip_z, lp, &local_open);
  if (local.stats.repaired_links > 0) return false;
  std::vector<ZContour> out;
  if (!cuts_are_clear(local.contours, cuts, clearance) ||
      !cuts_are_clear(local_open, cuts, clearance) ||
      !splice_contours(q.contours, local.contours, local_open, cuts, inside, tip_z, out))
    return false;
  result.contours = std::move(out);
  result.stats = local.stats;
  result.stats.open_chains = 0;
  result.stats.spliced = 1;
  return true;
}

}  // namespace

bool contours_from_known(const OffsetElements& el, const std::vector<std::uint32_t>& cand,
                         const ZLevelInside& q, const Level& lv, double tip_z,
                         const ZLevelParams& params, ZLevelResult& result) {
  if (q.contours.empty()) return false;
  // The known contours' x extent, grown by R.
  double extent[2] = {INFINITY, -INFINITY};
  for (const ZContour& c : q.contours)
    for (const ContourSeg& s : c.segs) {
      extent[0] = std::min(extent[0], s.a.x());
      extent[1] = std::max(extent[1], s.a.x());
    }
  extent[0] -= lv.R;
  extent[1] += lv.R;
  std::vector<std::array<double, 2>> xs;
  if (!changed_regions(el, cand, q, lv, params.skip_unreachable, extent, xs)) return false;
  if (xs.empty()) {
    result.contours = q.contours;
    for (ZContour& c : result.contours)
      for (ZJunction& j : c.junctions) j.position.z() = tip_z;
    result.stats.unchanged = 1;
    return true;
  }
  const std::uint64_t candidates = result.stats.candidates;
  if (!splice_changed(el, std::move(xs), q, extent, tip_z, params, result)) return false;
  result.stats.candidates = candidates;
  return true;
}

}  // namespace ncpath::zlevel_detail
