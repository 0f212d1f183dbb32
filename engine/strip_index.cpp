#include "engine/strip_index.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "engine/parallel.hpp"
#include "kernels/geom/tolerance.hpp"

namespace ncpath {

namespace {

// Index range [lo, hi] of the cells of size `size` starting at `origin` that the closed
// interval [a, b] touches, clamped to [0, n). The slack makes the test conservative:
// rounding may add a cell, never drop one.
inline bool cell_range(double a, double b, double origin, double size, std::size_t n,
                       std::uint32_t& lo, std::uint32_t& hi) {
  const double slack = tol::kCellSlack * (1.0 + std::abs(origin) + std::abs(b));
  const double fa = std::floor((a - slack - origin) / size);
  const double fb = std::floor((b + slack - origin) / size);
  if (fb < 0 || fa >= static_cast<double>(n)) return false;
  lo = static_cast<std::uint32_t>(std::max(0.0, fa));
  hi = static_cast<std::uint32_t>(std::min(static_cast<double>(n - 1), fb));
  return true;
}

// True when nothing in the xy box [x_lo, x_hi] x [y_lo, y_hi] with top `top` can put the
// tool tip above `best`: it is out of reach, or its top lowered by the cutter's rise at
// the box's nearest horizontal distance is not above best.
inline bool box_cannot_beat(const Cutter& c, double x, double y, double x_lo, double x_hi,
                            double y_lo, double y_hi, double top, double best) {
  const double dx = std::max({0.0, x_lo - x, x - x_hi});
  const double dy = std::max({0.0, y_lo - y, y - y_hi});
  const double rho2 = dx * dx + dy * dy;
  return rho2 > c.radius * c.radius ||
         profile_height_at_least(c, rho2, top - best - tol::kBoundTie);
}

}  // namespace

StripBuckets bucket_clusters_by_strip(const ClusteredFacets& clustered, double radius, double y0,
                                      double height, std::size_t strips) {
  StripBuckets b;
  b.y0 = y0;
  b.height = height;
  b.offsets.assign(strips + 1, 0);
  const std::vector<ClusterBound>& cl = clustered.clusters;
  const std::size_t n = cl.size();
  // Highest top first (ties by id): filling strips, and then bins, in this order leaves
  // every list sorted for the walk in StripBins::drop without any further sort.
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  par::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t c) {
    return cl[a].top_z > cl[c].top_z || (cl[a].top_z == cl[c].top_z && a < c);
  });
  std::vector<std::uint32_t> lo(n), hi(n);
  std::vector<std::uint8_t> hit(n);
  for (std::size_t i = 0; i < n; ++i) {  // count
    hit[i] = cell_range(cl[i].y_lo - radius, cl[i].y_hi + radius, y0, height, strips, lo[i], hi[i]);
    if (hit[i])
      for (std::uint32_t s = lo[i]; s <= hi[i]; ++s) ++b.offsets[s + 1];
  }
  for (std::size_t s = 0; s < strips; ++s) b.offsets[s + 1] += b.offsets[s];  // scan
  b.ids.resize(b.offsets[strips]);
  std::vector<std::uint32_t> cursor(b.offsets.begin(), b.offsets.end() - 1);
  for (const std::uint32_t i : order)  // fill
    if (hit[i])
      for (std::uint32_t s = lo[i]; s <= hi[i]; ++s) b.ids[cursor[s]++] = i;
  return b;
}

void StripBins::rebuild(const FacetTable& table, const ClusteredFacets& clustered,
                        const Cutter& cutter, const std::uint32_t* ids, std::size_t count,
                        double x0, double x1, double bin_width) {
  table_ = &table;
  clustered_ = &clustered;
  cutter_ = cutter;
  x0_ = x0;
  inv_width_ = 1.0 / bin_width;
  const std::size_t bins =
      static_cast<std::size_t>(std::max(0.0, std::floor((x1 - x0) * inv_width_))) + 1;
  const double R = cutter.radius;
  offsets_.assign(bins + 1, 0);
  lo_.resize(count);
  hi_.resize(count);
  for (std::size_t k = 0; k < count; ++k) {  // count
    const ClusterBound& c = clustered.clusters[ids[k]];
    if (!cell_range(c.x_lo - R, c.x_hi + R, x0, bin_width, bins, lo_[k], hi_[k])) {
      lo_[k] = 1;
      hi_[k] = 0;  // empty range
      continue;
    }
    for (std::uint32_t b = lo_[k]; b <= hi_[k]; ++b) ++offsets_[b + 1];
  }
  for (std::size_t b = 0; b < bins; ++b) offsets_[b + 1] += offsets_[b];  // scan
  entries_.resize(offsets_[bins]);
  cursor_.assign(offsets_.begin(), offsets_.end() - 1);
  for (std::size_t k = 0; k < count; ++k)  // fill, keeping the highest-top-first order
    for (std::uint32_t b = lo_[k]; b <= hi_[k] && lo_[k] <= hi_[k]; ++b)
      entries_[cursor_[b]++] = clustered.clusters[ids[k]];
}

CutterContact StripBins::drop(double x, double y, CutterContact best) const {
  const double fc = std::floor((x - x0_) * inv_width_);
  const std::size_t bins = offsets_.size() - 1;
  const std::size_t bin =
      static_cast<std::size_t>(std::clamp(fc, 0.0, static_cast<double>(bins - 1)));
  const ClusterBound* e = entries_.data() + offsets_[bin];
  const ClusterBound* end = entries_.data() + offsets_[bin + 1];
  const FacetBound* facets = clustered_->facets.data();
  for (; e != end && e->top_z > best.tip_z; ++e) {
    if (box_cannot_beat(cutter_, x, y, e->x_lo, e->x_hi, e->y_lo, e->y_hi, e->top_z, best.tip_z))
      continue;
    const FacetBound* f = facets + e->first;
    const FacetBound* f_end = f + e->count;
    for (; f != f_end && f->top_z > best.tip_z; ++f) {  // highest top first
      if (box_cannot_beat(cutter_, x, y, f->x_lo, f->x_hi, f->y_lo, f->y_hi, f->top_z, best.tip_z))
        continue;
      if (f->plane_a * x + f->plane_b * y + f->plane_c <= best.tip_z + tol::kBoundTie) continue;
      drop_facet(cutter_, table_->facets[f->facet], x, y, f->facet, best);
    }
  }
  return best;
}

}  // namespace ncpath
