#include "kernels/pocket/uncut.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>

#include "kernels/geom/tolerance.hpp"
#include "kernels/pocket/offset_crude.hpp"
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

std::vector<OffsetLoop> uncut_between_full(const std::vector<const OffsetLoop*>& outer,
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

using pocket_detail::RawSeg;
using pocket_detail::SegGrid;

// The band's boundary (outer loops as they are, inner loops reversed: material on the
// right) and its crude offset loops by R, built exactly as offset_loops builds them, loop
// after loop on demand (band_cut stops at the first segment it cannot certify); a grid over
// each level's curves.
class BandCrude {
 public:
  BandCrude(const std::vector<const OffsetLoop*>& outer,
            const std::vector<const OffsetLoop*>& inner, double r)
      : r_(r), outer_count_(outer.size()) {
    std::size_t no = 0, ni = 0;
    for (const OffsetLoop* l : outer) no += l->segs.size();
    for (const OffsetLoop* l : inner) ni += l->segs.size();
    outer_segs_.reserve(no);
    inner_segs_.reserve(ni);
    for (const OffsetLoop* l : outer) {
      loops_.push_back({outer_segs_.size(), l->segs.size()});
      outer_segs_.insert(outer_segs_.end(), l->segs.begin(), l->segs.end());
    }
    for (const OffsetLoop* l : inner) {
      loops_.push_back({inner_segs_.size(), l->segs.size()});
      for (auto it = l->segs.rbegin(); it != l->segs.rend(); ++it)
        inner_segs_.push_back(reversed(*it));
    }
    inverted_.resize(loops_.size());
    raw.reserve(2 * (no + ni) + 8);
  }

  BandCrude(const BandCrude&) = delete;  // the grids point into it
  BandCrude& operator=(const BandCrude&) = delete;

  std::size_t loops() const { return loops_.size(); }
  bool outer(std::size_t l) const { return l < outer_count_; }
  const Seg2* curves(std::size_t l) const {
    return (outer(l) ? outer_segs_.data() : inner_segs_.data()) + loops_[l].first;
  }
  std::size_t curve_count(std::size_t l) const { return loops_[l].second; }
  bool inverted(std::size_t l) const { return inverted_[l]; }
  double area2(std::size_t l) const {
    double a = 0;
    for (std::size_t k = 0; k < curve_count(l); ++k) a += area2_contribution(curves(l)[k]);
    return a;
  }

  // Appends the crude loop of the next band loop to raw (RawSeg::loop = band loop); crude
  // loop l is raw[loop_end[l - 1], loop_end[l]).
  void add_crude() {
    const std::size_t l = loop_end.size();
    pocket_detail::RawOffsets o = pocket_detail::raw_offsets(curves(l), curve_count(l), r_);
    inverted_[l] = o.inverted;
    pocket_detail::crude_loop(o, static_cast<std::uint32_t>(l), raw);
    loop_end.push_back(static_cast<std::uint32_t>(raw.size()));
  }
  void add_all() {
    while (loop_end.size() < loops()) add_crude();
  }

  // The grid over the outer (or the inner) level's curves.
  SegGrid& grid(bool outer_level) {
    std::optional<SegGrid>& g = outer_level ? outer_grid_ : inner_grid_;
    if (!g) g.emplace(outer_level ? outer_segs_ : inner_segs_, r_);
    return *g;
  }
  bool has_level(bool outer_level) const {
    return !(outer_level ? outer_segs_ : inner_segs_).empty();
  }

  std::vector<RawSeg> raw;
  std::vector<std::uint32_t> loop_end;

 private:
  double r_;
  std::size_t outer_count_;
  std::vector<Seg2> outer_segs_, inner_segs_;               // each level's curves, loop after loop
  std::vector<std::pair<std::size_t, std::size_t>> loops_;  // first curve, count
  std::vector<std::uint8_t> inverted_;  // per band loop: its offset has an inside-out arc
  std::optional<SegGrid> outer_grid_, inner_grid_;
};

// Crude segments kept on either side of an uncertified one in a window (at least one, so
// that the ends of a window hold no point of the result).
constexpr std::size_t kWindowMargin = 2;

// Builds the band's crude loops and marks their segments not certified near the other
// level; with bad null, stops at the first. True when there is one.
bool uncertified(BandCrude& band, double r, std::vector<std::uint8_t>* bad) {
  // A point of an uncut region's boundary is at least R - kOffsetValid (the dissection's
  // validity limit) from every curve.
  const double limit = r - tol::kOffsetValid - tol::kUncutCertify;
  bool any = false;
  for (std::size_t l = 0; l < band.loops(); ++l) {
    band.add_crude();
    if (bad) bad->resize(band.raw.size(), 0);
    any = pocket_detail::uncertified(band.raw, l == 0 ? 0 : band.loop_end[l - 1], band.loop_end[l],
                                     band.grid(!band.outer(l)), limit, bad) ||
          any;
    if (any && !bad) return true;
  }
  return any;
}

}  // namespace

bool band_cut(const std::vector<const OffsetLoop*>& outer,
              const std::vector<const OffsetLoop*>& inner, double tool_radius) {
  if (inner.empty() || outer.empty()) return false;
  BandCrude band(outer, inner, tool_radius);
  return !uncertified(band, tool_radius, nullptr);
}

std::vector<OffsetLoop> uncut_between(const std::vector<const OffsetLoop*>& outer,
                                      const std::vector<const OffsetLoop*>& inner,
                                      double tool_radius) {
  BandCrude band(outer, inner, tool_radius);
  const std::size_t nl = band.loops();
  // Crude segments that may hold a point of the result (all for the centre, which has no
  // inner level) and the windows around them along their crude loops.
  std::vector<std::uint8_t> bad;
  if (inner.empty() || outer.empty()) {
    band.add_all();
    bad.assign(band.raw.size(), 1);
  } else if (!uncertified(band, tool_radius, &bad)) {
    return {};
  }
  std::vector<std::uint8_t> in(band.raw.size(), 0), whole(nl, 0);
  bool all = true;
  for (std::size_t l = 0, b = 0; l < nl; b = band.loop_end[l++]) {
    const std::size_t m = band.loop_end[l] - b;
    std::size_t count = 0;
    for (std::size_t i = 0; i < m; ++i) {
      if (!bad[b + i]) continue;
      for (std::size_t k = 0; k <= 2 * kWindowMargin && k < m; ++k) {
        std::uint8_t& f = in[b + (i + m * kWindowMargin + k - kWindowMargin) % m];
        count += !f;
        f = 1;
      }
    }
    whole[l] = count == m;
    all = all && whole[l];
  }

  // The complete dissection's view of the band: its loops' areas and orientation rule.
  pocket_detail::DissectParams params;
  params.several_inputs = nl > 1;
  std::vector<pocket_detail::Chain> loop_chain(nl);
  double largest = 0;
  for (std::size_t l = 0; l < nl; ++l) {
    const double a = band.area2(l);
    loop_chain[l] = {static_cast<std::uint32_t>(l), true, band.inverted(l), a};
    if (std::abs(a) > largest) {
      largest = std::abs(a);
      params.pocket = a < 0;
    }
  }
  const std::vector<std::uint32_t>* ranks = nullptr;
  const auto valid = [&](const Seg2& s, std::uint32_t raw_index, double slack) {
    // A piece of a certified segment comes closer than R - kOffsetValid to the other level.
    if (ranks && !bad[(*ranks)[raw_index]]) return false;
    for (const bool level : {true, false})
      if (band.has_level(level) && band.grid(level).any_closer(s, tool_radius - slack))
        return false;
    return true;
  };

  OffsetResult res;
  if (all) {
    res = pocket_detail::dissect(band.raw, loop_chain, nullptr, params, valid);
  } else {
    // Open chains of the windows (a loop wholly covered stays closed), each segment ranked
    // by its place in the complete crude loops.
    std::vector<RawSeg> raw;
    std::vector<std::uint32_t> rank;
    std::vector<pocket_detail::Chain> chains;
    for (std::size_t l = 0, b = 0; l < nl; b = band.loop_end[l++]) {
      const std::size_t m = band.loop_end[l] - b;
      for (std::size_t i = 0; i < m; ++i) {
        if (!in[b + i] || (!whole[l] && in[b + (i + m - 1) % m])) continue;
        const auto base = static_cast<std::uint32_t>(raw.size());
        const auto id = static_cast<std::uint32_t>(chains.size());
        chains.push_back(loop_chain[l]);
        chains.back().closed = whole[l];
        for (std::size_t k = 0; k < m && in[b + (i + k) % m]; ++k) {
          const std::size_t g = b + (i + k) % m;
          RawSeg rs = band.raw[g];
          rs.loop = id;
          rs.prev = base + static_cast<std::uint32_t>(k) - 1;
          rs.next = base + static_cast<std::uint32_t>(k) + 1;
          raw.push_back(rs);
          rank.push_back(static_cast<std::uint32_t>(g));
        }
        const auto last = static_cast<std::uint32_t>(raw.size()) - 1;
        raw[base].prev = whole[l] ? last : pocket_detail::kNoRaw;
        raw[last].next = whole[l] ? base : pocket_detail::kNoRaw;
        if (whole[l]) break;
      }
    }
    ranks = &rank;
    res = pocket_detail::dissect(raw, chains, &rank, params, valid);
  }
  std::vector<OffsetLoop> out;
  for (OffsetLoop& l : res.loops) split_pinched(std::move(l), out);
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
