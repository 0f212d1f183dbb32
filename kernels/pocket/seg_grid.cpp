#include "kernels/pocket/seg_grid.hpp"

#include <algorithm>
#include <cmath>

#include "kernels/curves/intersect.hpp"

namespace ncpath::pocket_detail {

SegGrid::SegGrid(const std::vector<Seg2>& segs, double min_cell) : segs_(&segs) {
  lo_ = Vec2::Constant(1e300);
  Vec2 hi = Vec2::Constant(-1e300);
  boxes_.resize(segs.size());
  for (std::size_t i = 0; i < segs.size(); ++i) {
    loose_bounds(segs[i], boxes_[i].lo, boxes_[i].hi);
    lo_ = lo_.cwiseMin(boxes_[i].lo);
    hi = hi.cwiseMax(boxes_[i].hi);
  }
  const double area = std::max(1e-12, (hi.x() - lo_.x()) * (hi.y() - lo_.y()));
  const double cell =
      std::max(min_cell, std::sqrt(2 * area / std::max<std::size_t>(1, segs.size())));
  nx_ = std::max(1, std::min(2048, static_cast<int>((hi.x() - lo_.x()) / cell) + 1));
  ny_ = std::max(1, std::min(2048, static_cast<int>((hi.y() - lo_.y()) / cell) + 1));
  cell_x_ = (hi.x() - lo_.x()) / nx_ + 1e-12;
  cell_y_ = (hi.y() - lo_.y()) / ny_ + 1e-12;
  start_.assign(static_cast<std::size_t>(nx_) * ny_ + 1, 0);
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<std::uint32_t> cursor;
    if (pass == 1) {
      for (std::size_t c = 0; c + 1 < start_.size(); ++c) start_[c + 1] += start_[c];
      ids_.resize(start_.back());
      cursor.assign(start_.begin(), start_.end() - 1);
    }
    for (std::size_t i = 0; i < segs.size(); ++i) {
      int x0, y0, x1, y1;
      range(boxes_[i].lo, boxes_[i].hi, x0, y0, x1, y1);
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
          const std::size_t c = static_cast<std::size_t>(y) * nx_ + x;
          if (pass == 0)
            ++start_[c + 1];
          else
            ids_[cursor[c]++] = static_cast<std::uint32_t>(i);
        }
    }
  }
  stamp_.assign(segs.size(), 0);
}

template <class Visit>
void SegGrid::visit(const Vec2& lo, const Vec2& hi, Visit&& visit) {
  int x0, y0, x1, y1;
  range(lo, hi, x0, y0, x1, y1);
  ++tick_;
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      const std::size_t c = static_cast<std::size_t>(y) * nx_ + x;
      for (std::uint32_t k = start_[c]; k < start_[c + 1]; ++k) {
        const std::uint32_t id = ids_[k];
        if (stamp_[id] == tick_) continue;
        stamp_[id] = tick_;
        const Box& b = boxes_[id];
        if (b.lo.x() > hi.x() || b.hi.x() < lo.x() || b.lo.y() > hi.y() || b.hi.y() < lo.y())
          continue;
        if (!visit(id)) return;
      }
    }
}

bool SegGrid::any_closer(const Seg2& s, double limit) {
  Vec2 lo, hi;
  loose_bounds(s, lo, hi);
  lo.array() -= limit;
  hi.array() += limit;
  bool found = false;
  visit(lo, hi, [&](std::uint32_t id) {
    found = distance(s, (*segs_)[id]) < limit;
    return !found;
  });
  return found;
}

bool SegGrid::nearest_within(const Vec2& p, double limit, std::uint32_t& seg, double& dist) {
  bool found = false;
  visit(p.array() - limit, p.array() + limit, [&](std::uint32_t id) {
    const double d = distance((*segs_)[id], p);
    if (d < limit && (!found || d < dist || (d == dist && id < seg))) {
      found = true;
      seg = id;
      dist = d;
    }
    return true;
  });
  return found;
}

void SegGrid::range(const Vec2& lo, const Vec2& hi, int& x0, int& y0, int& x1, int& y1) const {
  // Clamped as doubles before the conversion: a query box may be unbounded (an infinite
  // search limit), and converting an out-of-range double to int is undefined.
  const auto cell = [](double v, double origin, double size, int n) {
    const double c = std::floor((v - origin) / size);
    return static_cast<int>(std::clamp(c, 0.0, static_cast<double>(n - 1)));
  };
  x0 = cell(lo.x(), lo_.x(), cell_x_, nx_);
  y0 = cell(lo.y(), lo_.y(), cell_y_, ny_);
  x1 = cell(hi.x(), lo_.x(), cell_x_, nx_);
  y1 = cell(hi.y(), lo_.y(), cell_y_, ny_);
}

}  // namespace ncpath::pocket_detail
