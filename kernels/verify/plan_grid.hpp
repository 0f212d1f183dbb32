#pragma once
// A uniform grid over boxes in the plan (CSR: every item listed in each cell its box meets),
// the verifier's spatial index for wall curves, bottom pieces and moves. Pure, in double.
#include <cstdint>
#include <utility>
#include <vector>

#include "kernels/geom/vec.hpp"

namespace ncpath {

class PlanGrid {
 public:
  PlanGrid() = default;
  // boxes[i] = (lo, hi) of item i (mm); cell: the cells' side (mm), raised so that the grid
  // has at most about 2048 cells a side.
  PlanGrid(const std::vector<std::pair<Vec2, Vec2>>& boxes, double cell);

  // The items whose cells meet the box [lo, hi], sorted, each once.
  void query(const Vec2& lo, const Vec2& hi, std::vector<std::uint32_t>& out) const;

 private:
  int cell_x(double x) const;
  int cell_y(double y) const;
  Vec2 origin_ = Vec2::Zero();
  double cell_ = 1;
  int nx_ = 1, ny_ = 1;
  std::vector<std::uint32_t> start_, items_;
};

}  // namespace ncpath
