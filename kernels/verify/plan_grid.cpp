#include "kernels/verify/plan_grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ncpath {

PlanGrid::PlanGrid(const std::vector<std::pair<Vec2, Vec2>>& boxes, double cell) {
  if (boxes.empty()) return;
  Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const auto& [a, b] : boxes) {
    lo = lo.cwiseMin(a);
    hi = hi.cwiseMax(b);
  }
  const Vec2 ext = hi - lo;
  cell_ = std::max({cell, ext.x() / 2048, ext.y() / 2048});
  if (!(cell_ > 0)) cell_ = 1;  // all boxes are one point
  origin_ = lo;
  nx_ = static_cast<int>(ext.x() / cell_) + 1;
  ny_ = static_cast<int>(ext.y() / cell_) + 1;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;  // (cell, item)
  for (std::uint32_t k = 0; k < boxes.size(); ++k)
    for (int j = cell_y(boxes[k].first.y()); j <= cell_y(boxes[k].second.y()); ++j)
      for (int i = cell_x(boxes[k].first.x()); i <= cell_x(boxes[k].second.x()); ++i)
        pairs.emplace_back(static_cast<std::uint32_t>(j * nx_ + i), k);
  std::sort(pairs.begin(), pairs.end());
  start_.assign(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_) + 1, 0);
  for (const auto& pr : pairs) ++start_[pr.first + 1];
  for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
  items_.reserve(pairs.size());
  for (const auto& pr : pairs) items_.push_back(pr.second);
}

// Clamped as doubles before the conversion: a query box may reach far outside the grid.
int PlanGrid::cell_x(double x) const {
  return static_cast<int>(std::clamp(std::floor((x - origin_.x()) / cell_), 0.0, nx_ - 1.0));
}
int PlanGrid::cell_y(double y) const {
  return static_cast<int>(std::clamp(std::floor((y - origin_.y()) / cell_), 0.0, ny_ - 1.0));
}

void PlanGrid::query(const Vec2& lo, const Vec2& hi, std::vector<std::uint32_t>& out) const {
  out.clear();
  if (items_.empty()) return;
  for (int j = cell_y(lo.y()); j <= cell_y(hi.y()); ++j)
    for (int i = cell_x(lo.x()); i <= cell_x(hi.x()); ++i) {
      const std::size_t c = static_cast<std::size_t>(j * nx_ + i);
      out.insert(out.end(), items_.begin() + start_[c], items_.begin() + start_[c + 1]);
    }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

}  // namespace ncpath
