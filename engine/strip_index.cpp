#include "engine/strip_index.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "engine/parallel.hpp"

namespace ncpath {

namespace {

// Index range [lo, hi] of the cells of size `size` starting at `origin` that the closed
// interval [a, b] touches, clamped to [0, n). The slack makes the test conservative:
// rounding may add a cell, never drop one.
inline bool cell_range(double a, double b, double origin, double size, std::size_t n,
                       std::uint32_t& lo, std::uint32_t& hi) {
  const double slack = 1e-9 * (1.0 + std::abs(origin) + std::abs(b));
  const double fa = std::floor((a - slack - origin) / size);
  const double fb = std::floor((b + slack - origin) / size);
  if (fb < 0 || fa >= static_cast<double>(n)) return false;
  lo = static_cast<std::uint32_t>(std::max(0.0, fa));
  hi = static_cast<std::uint32_t>(std::min(static_cast<double>(n - 1), fb));
  return true;
}

}  // namespace

StripBuckets bucket_facets_by_strip(const FacetTable& table, double radius, double y0,
                                    double height, std::size_t strips) {
  StripBuckets b;
  b.y0 = y0;
  b.height = height;
  b.offsets.assign(strips + 1, 0);
  const std::size_t n = table.facets.size();
  // Facets highest-top first (ties by id): filling strips, and then bins, in this order
  // leaves every list sorted for the walk in StripBins::drop without any further sort.
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  par::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    const double za = table.facets[a].max_z, zb = table.facets[b].max_z;
    return za > zb || (za == zb && a < b);
  });
  std::vector<std::uint32_t> lo(n), hi(n);
  std::vector<std::uint8_t> hit(n);
  // Count.
  for (std::size_t i = 0; i < n; ++i) {
    const PreparedFacet& f = table.facets[i];
    hit[i] = cell_range(f.min_y - radius, f.max_y + radius, y0, height, strips, lo[i], hi[i]);
    if (hit[i])
      for (std::uint32_t s = lo[i]; s <= hi[i]; ++s) ++b.offsets[s + 1];
  }
  // Scan.
  for (std::size_t s = 0; s < strips; ++s) b.offsets[s + 1] += b.offsets[s];
  // Fill, highest top first.
  b.ids.resize(b.offsets[strips]);
  std::vector<std::uint32_t> cursor(b.offsets.begin(), b.offsets.end() - 1);
  for (const std::uint32_t i : order)
    if (hit[i])
      for (std::uint32_t s = lo[i]; s <= hi[i]; ++s) b.ids[cursor[s]++] = i;
  return b;
}

void StripBins::rebuild(const FacetTable& table, const Cutter& cutter, const std::uint32_t* ids,
                        std::size_t count, double x0, double x1, double bin_width) {
  table_ = &table;
  cutter_ = cutter;
  x0_ = x0;
  inv_width_ = 1.0 / bin_width;
  const std::size_t bins =
      static_cast<std::size_t>(std::max(0.0, std::floor((x1 - x0) * inv_width_))) + 1;
  const double R = cutter.radius;
  offsets_.assign(bins + 1, 0);
  lo_.resize(count);
  hi_.resize(count);
  for (std::size_t k = 0; k < count; ++k) {
    const PreparedFacet& f = table.facets[ids[k]];
    if (!cell_range(f.min_x - R, f.max_x + R, x0, bin_width, bins, lo_[k], hi_[k])) {
      lo_[k] = 1;
      hi_[k] = 0;  // empty range
      continue;
    }
    for (std::uint32_t c = lo_[k]; c <= hi_[k]; ++c) ++offsets_[c + 1];
  }
  for (std::size_t c = 0; c < bins; ++c) offsets_[c + 1] += offsets_[c];
  entries_.resize(offsets_[bins]);
  cursor_.assign(offsets_.begin(), offsets_.end() - 1);
  for (std::size_t k = 0; k < count; ++k) {
    const std::uint32_t l = lo_[k], h = hi_[k];
    if (l > h) continue;
    const Entry e = make_entry(table.facets[ids[k]], cutter, ids[k]);
    for (std::uint32_t c = l; c <= h; ++c) entries_[cursor_[c]++] = e;
  }
}

StripBins::Entry StripBins::make_entry(const PreparedFacet& f, const Cutter& c,
                                       std::uint32_t id) {
  const double R = c.radius, r = c.corner_radius, a = R - r;
  Entry e{f.max_z, f.min_x - R, f.max_x + R, f.min_y - R, f.max_y + R, 0, 0, 0, id};
  if (f.vertical) {
    e.plane_c = std::numeric_limits<double>::infinity();  // no plane bound
  } else {
    // Same tangent point as the kernel: (x, y) - (a / |n_xy| + r) n_xy.
    const double nx = f.n.x(), ny = f.n.y(), nz = f.n.z();
    const double nxy = std::sqrt(nx * nx + ny * ny);
    e.plane_a = -nx / nz;
    e.plane_b = -ny / nz;
    e.plane_c = (f.plane_d + a * nxy + r * nxy * nxy) / nz + r * nz - r;
  }
  return e;
}

CutterContact StripBins::drop(double x, double y, CutterContact best) const {
  const double fc = std::floor((x - x0_) * inv_width_);
  const std::size_t bins = offsets_.size() - 1;
  const std::size_t c =
      static_cast<std::size_t>(std::clamp(fc, 0.0, static_cast<double>(bins - 1)));
  const Entry* e = entries_.data() + offsets_[c];
  const Entry* end = entries_.data() + offsets_[c + 1];
  // Rounding slack of the linear plane bound (it is evaluated differently from the
  // kernel's): far below the 1e-9 mm exactness contract.
  constexpr double kBoundSlack = 1e-10;
  for (; e != end && e->top_z > best.tip_z; ++e) {
    if (x < e->x_lo || x > e->x_hi || y < e->y_lo || y > e->y_hi) continue;
    if (e->plane_a * x + e->plane_b * y + e->plane_c + kBoundSlack <= best.tip_z) continue;
    drop_facet(cutter_, table_->facets[e->facet], x, y, e->facet, best);
  }
  return best;
}

}  // namespace ncpath
