#pragma once
// A uniform grid over line/arc segments for "does anything come closer than L to this
// segment" queries (offset validation). Internal to kernels/pocket.
#include <cstdint>
#include <vector>

#include "kernels/curves/segment.hpp"

namespace ncpath::pocket_detail {

struct Box {
  Vec2 lo, hi;
};

class SegGrid {
 public:
  // segs must outlive the grid (and stay where they are: the grid keeps their address). Cells are
  // at least min_cell wide and hold about two segments' worth of area each: a finer grid costs more
  // to build than it saves.
  SegGrid(const std::vector<Seg2>& segs, double min_cell);
  // True when some segment comes closer to s than limit (exact segment distances).
  bool any_closer(const Seg2& s, double limit);
  // The segment closest to p among those closer than limit: its index and distance; false
  // when none is. Ties go to the lowest index.
  bool nearest_within(const Vec2& p, double limit, std::uint32_t& seg, double& dist);
  const std::vector<Seg2>& segments() const { return *segs_; }

 private:
  void range(const Vec2& lo, const Vec2& hi, int& x0, int& y0, int& x1, int& y1) const;
  // Calls visit(id) once for each segment whose box meets [lo, hi] until it returns false.
  template <class Visit>
  void visit(const Vec2& lo, const Vec2& hi, Visit&& visit);
  const std::vector<Seg2>* segs_;
  std::vector<Box> boxes_;
  Vec2 lo_;
  double cell_x_ = 1, cell_y_ = 1;
  int nx_ = 1, ny_ = 1;
  std::vector<std::uint32_t> start_, ids_, stamp_;
  std::uint32_t tick_ = 0;
};

}  // namespace ncpath::pocket_detail
