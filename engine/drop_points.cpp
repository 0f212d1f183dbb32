#include "engine/drop_points.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "engine/drop_index.hpp"
#include "engine/parallel.hpp"

namespace ncpath {

DropPointsStats run_drop_points(const TriangleMesh& mesh, const Cutter& cutter,
                                std::span<const double> xy,
                                std::span<const std::uint32_t> path_sizes,
                                const std::function<void(const ClChunk&)>& sink,
                                RunControl& control) {
  if (std::string e = validate(cutter); !e.empty()) throw std::invalid_argument("tool: " + e);
  if (xy.size() % 2 != 0) throw std::invalid_argument("xy must hold 2 numbers per point");
  std::uint64_t total = 0;
  for (std::uint32_t s : path_sizes) total += s;
  if (total * 2 != xy.size())
    throw std::invalid_argument("path sizes do not add up to the number of points");

  DropPointsStats st;
  Stopwatch index_clock;
  const DropIndex index(mesh, cutter, DropIndex::Facets::kPrepared);
  st.facets = index.facet_count();
  st.facets_degenerate = index.degenerate();
  st.index_s = index_clock.seconds();

  constexpr std::size_t kChunkPoints = 1 << 16;
  ClChunk chunk;
  Stopwatch total_clock;
  std::size_t p0 = 0, path = 0;
  while (path < path_sizes.size()) {
    if (control.cancel.load()) throw Cancelled{};
    // Whole paths, up to kChunkPoints points (or one longer path).
    std::size_t n = 0, path_end = path;
    while (path_end < path_sizes.size() && (n == 0 || n + path_sizes[path_end] <= kChunkPoints))
      n += path_sizes[path_end++];
    chunk.clear();
    chunk.xyz.resize(3 * n);
    chunk.contact.resize(n);
    par::for_each(n, 1024, [&](std::size_t k) {
      const double x = xy[2 * (p0 + k)], y = xy[2 * (p0 + k) + 1];
      const CutterContact c = index.query(x, y);
      chunk.xyz[3 * k] = x;
      chunk.xyz[3 * k + 1] = y;
      chunk.xyz[3 * k + 2] =
          c.kind == ContactKind::kNone ? std::numeric_limits<double>::quiet_NaN() : c.tip_z;
      chunk.contact[k] = static_cast<std::uint8_t>(c.kind);
    });
    for (std::size_t k = 0; k < n; ++k) st.no_contact += chunk.contact[k] == 0;
    for (std::size_t q = path; q < path_end; ++q) {
      chunk.path_sizes.push_back(path_sizes[q]);
      chunk.path_kinds.push_back(static_cast<std::uint8_t>(PathKind::kCut));
    }
    Stopwatch sink_clock;
    sink(chunk);
    st.sink_s += sink_clock.seconds();
    p0 += n;
    path = path_end;
    st.points += n;
    if (control.progress) control.progress(st.points, total);
  }
  st.compute_s = total_clock.seconds() - st.sink_s;
  return st;
}

}  // namespace ncpath
