#include "engine/raster.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "engine/facet_table.hpp"
#include "engine/chunk_stream.hpp"
#include "engine/parallel.hpp"
#include "engine/strip_index.hpp"
#include "kernels/geom/tolerance.hpp"

namespace ncpath {

std::string validate(const RasterParams& p) {
  std::ostringstream os;
  auto positive = [&](const char* key, double v) {
    if (os.tellp() == 0 && !(std::isfinite(v) && v > 0))
      os << key << " must be a positive number of mm, got " << v;
  };
  positive("interval", p.interval);
  positive("step", p.step);
  if (os.tellp() == 0 && !(std::isfinite(p.margin) && p.margin >= 0))
    os << "margin must be >= 0 mm, got " << p.margin;
  if (os.tellp() == 0 && !(std::isfinite(p.adaptive_tolerance) && p.adaptive_tolerance >= 0))
    os << "adaptive_tolerance must be >= 0 mm (0 = off), got " << p.adaptive_tolerance;
  if (os.tellp() == 0 && !(std::isfinite(p.min_step) && p.min_step >= 0))
    os << "min_step must be >= 0 mm (0 = step/64), got " << p.min_step;
  if (os.tellp() == 0 && p.floor_z && !std::isfinite(*p.floor_z))
    os << "floor_z must be a finite number of mm";
  if (os.tellp() == 0 && p.rect) {
    const auto& r = *p.rect;
    if (!(std::isfinite(r[0]) && std::isfinite(r[1]) && std::isfinite(r[2]) &&
          std::isfinite(r[3]) && r[2] >= r[0] && r[3] >= r[1]))
      os << "rect must be [x_min, y_min, x_max, y_max] with x_max >= x_min and y_max >= y_min";
  }
  if (os.tellp() == 0 && p.chunk_lines == 0) os << "chunk_lines must be >= 1";
  if (os.tellp() == 0 && !(p.strip_height >= 0 && p.bin_width >= 0))
    os << "strip_height and bin_width must be >= 0 (0 = automatic)";
  if (os.tellp() == 0 && !(p.bands >= 1 && p.band < p.bands))
    os << "band must be < bands, and bands >= 1 (got band " << p.band << " of " << p.bands << ")";
  return os.str();
}

std::size_t raster_sample_count(double extent, double spacing) {
  return static_cast<std::size_t>(std::floor(extent / spacing + tol::kCountSlack)) + 1;
}

namespace {

// One scan line's work in the scan frame: u along the line, v across it.
struct LineSampler {
  const FacetTable& table;
  const Cutter& cutter;
  const StripBins& bins;
  double floor_z;
  double tolerance, min_step;

  CutterContact at(double u, double v, const CutterContact& hint) const {
    CutterContact seed;
    seed.tip_z = floor_z;
    // Coherence: the previous point's facet usually still gives the answer or close to it,
    // which lets the sorted walk stop almost at once. It only raises the lower bound.
    if (hint.kind != ContactKind::kNone)
      drop_facet(cutter, table.facets[hint.facet], u, v, hint.facet, seed);
    return bins.drop(u, v, seed);
  }
};

struct Sample {
  double u;
  CutterContact c;
};

struct StripOutput {
  ClChunk chunk;
  std::uint64_t cut = 0, link = 0, adaptive = 0, floor = 0;
};

void refine(const LineSampler& s, double v, const Sample& a, const Sample& b,
            std::vector<Sample>& out, std::uint64_t& inserted) {
  const double half = 0.5 * (b.u - a.u);
  if (std::abs(half) < s.min_step) return;
  const double um = a.u + half;
  Sample m{um, s.at(um, v, a.c)};
  if (std::abs(m.c.tip_z - 0.5 * (a.c.tip_z + b.c.tip_z)) <= s.tolerance) return;
  refine(s, v, a, m, out, inserted);
  out.push_back(m);
  ++inserted;
  refine(s, v, m, b, out, inserted);
}

}  // namespace

RasterStats run_raster(const TriangleMesh& mesh, const Cutter& cutter, const RasterParams& p,
                       const std::function<void(const ClChunk&)>& sink, RunControl& control) {
  if (std::string e = validate(cutter); !e.empty()) throw std::invalid_argument("tool: " + e);
  if (std::string e = validate(p); !e.empty()) throw std::invalid_argument(e);
  RasterStats st;
  Stopwatch index_clock;
  const bool swap = p.direction == ScanDirection::kY;
  const FacetTable table = build_facet_table(mesh, swap);
  st.facets = table.facets.size();
  st.facets_degenerate = table.degenerate;
  if (table.facets.empty()) throw std::invalid_argument("the mesh has no usable facet");

  // Rectangle in the scan frame.
  double u0, v0, u1, v1;
  if (p.rect) {
    const auto& r = *p.rect;
    u0 = swap ? r[1] : r[0];
    v0 = swap ? r[0] : r[1];
    u1 = swap ? r[3] : r[2];
    v1 = swap ? r[2] : r[3];
  } else {
    u0 = table.box.lo.x() - p.margin;
    v0 = table.box.lo.y() - p.margin;
    u1 = table.box.hi.x() + p.margin;
    v1 = table.box.hi.y() + p.margin;
  }
  st.rect = swap ? std::array<double, 4>{v0, u0, v1, u1} : std::array<double, 4>{u0, v0, u1, v1};
  st.floor_z = p.floor_z.value_or(table.box.lo.z());
  const std::size_t n_lines = raster_sample_count(v1 - v0, p.interval);
  const std::size_t n_samples = raster_sample_count(u1 - u0, p.step);
  const double u_last = u0 + static_cast<double>(n_samples - 1) * p.step;

  const double R = cutter.radius;
  const double strip_h = p.strip_height > 0 ? p.strip_height : std::max(p.interval, 0.5 * R);
  const std::size_t lines_per_strip = std::max<std::size_t>(
      1, static_cast<std::size_t>(std::floor(strip_h / p.interval + tol::kCountSlack)));
  const double bin_w = p.bin_width > 0 ? p.bin_width : std::max(p.step, 0.5 * R);
  const std::size_t strips = (n_lines + lines_per_strip - 1) / lines_per_strip;
  const ClusteredFacets clustered = cluster_facets(table, cutter);
  const StripBuckets buckets = bucket_clusters_by_strip(
      clustered, R, v0, static_cast<double>(lines_per_strip) * p.interval, strips);
  st.index_s = index_clock.seconds();

  const double min_step = p.min_step > 0 ? p.min_step : p.step / 64;
  const std::size_t link_segments = std::max<std::size_t>(
      1, static_cast<std::size_t>(std::ceil(p.interval / p.step - tol::kCountSlack)));

  auto run_strip = [&](std::size_t s, StripOutput& out) {
    StripBins bins;
    const std::uint32_t* ids = buckets.ids.data() + buckets.offsets[s];
    bins.rebuild(table, clustered, cutter, ids, buckets.offsets[s + 1] - buckets.offsets[s], u0,
                 u_last, bin_w);
    const LineSampler sampler{table, cutter, bins, st.floor_z, p.adaptive_tolerance, min_step};
    ClChunk& ch = out.chunk;
    std::vector<Sample> line;
    auto emit = [&](double u, double v, const CutterContact& c) {
      const double x = swap ? v : u, y = swap ? u : v;
      ch.xyz.insert(ch.xyz.end(), {x, y, c.tip_z});
      ch.contact.push_back(static_cast<std::uint8_t>(c.kind));
      if (c.kind == ContactKind::kNone) ++out.floor;
    };
    const std::size_t first = s * lines_per_strip;
    const std::size_t last = std::min(n_lines, first + lines_per_strip);
    for (std::size_t i = first; i < last; ++i) {
      const double v = v0 + static_cast<double>(i) * p.interval;
      line.clear();
      CutterContact hint;
      Sample prev{};
      for (std::size_t j = 0; j < n_samples; ++j) {
        const double u = u0 + static_cast<double>(j) * p.step;
        Sample cur{u, sampler.at(u, v, hint)};
        if (j > 0 && p.adaptive_tolerance > 0) refine(sampler, v, prev, cur, line, out.adaptive);
        line.push_back(cur);
        hint = cur.c;
        prev = cur;
      }
      const bool forward = i % 2 == 0;
      if (!forward) std::reverse(line.begin(), line.end());
      for (const Sample& smp : line) emit(smp.u, v, smp.c);
      ch.path_sizes.push_back(static_cast<std::uint32_t>(line.size()));
      ch.path_kinds.push_back(static_cast<std::uint8_t>(PathKind::kCut));
      out.cut += line.size();
      if (i + 1 == n_lines) continue;
      // Link at depth along the rectangle's side to the start of the next line.
      const double u = forward ? u_last : u0;
      CutterContact lh;
      for (std::size_t k = 0; k <= link_segments; ++k) {
        const double vk =
            v + p.interval * static_cast<double>(k) / static_cast<double>(link_segments);
        lh = sampler.at(u, vk, lh);
        emit(u, vk, lh);
      }
      ch.path_sizes.push_back(static_cast<std::uint32_t>(link_segments + 1));
      ch.path_kinds.push_back(static_cast<std::uint8_t>(PathKind::kLinkAtDepth));
      out.link += link_segments + 1;
    }
  };

  // A band: strips band, band + bands, ... (k-th: band + k * bands); lines of the band.
  const std::size_t band_strips = strips > p.band ? (strips - p.band - 1) / p.bands + 1 : 0;
  const auto strip_of = [&](std::size_t k) { return p.band + k * p.bands; };
  for (std::size_t k = 0; k < band_strips; ++k)
    st.lines +=
        std::min(n_lines, (strip_of(k) + 1) * lines_per_strip) - strip_of(k) * lines_per_strip;

  // Chunks of whole strips. While the calling thread hands chunk k to the sink (the HDF5
  // writer, which must stay on one thread), the workers compute chunk k+1; the sink still
  // sees the chunks in order, so the output does not depend on the thread count.
  const std::size_t strips_per_chunk = std::max<std::size_t>(1, p.chunk_lines / lines_per_strip);
  std::vector<StripOutput> outs;
  auto compute_chunk = [&](std::size_t c0, ClChunk& merged) {
    const std::size_t c1 = std::min(band_strips, c0 + strips_per_chunk);
    outs.assign(c1 - c0, StripOutput{});
    par::for_each(c1 - c0, 1, [&](std::size_t k) { run_strip(strip_of(c0 + k), outs[k]); });
    merged.clear();
    for (StripOutput& o : outs) {
      merged.append(o.chunk);
      st.strip_paths.push_back(static_cast<std::int64_t>(o.chunk.path_sizes.size()));
      st.cut_points += o.cut;
      st.link_points += o.link;
      st.adaptive_points += o.adaptive;
      st.floor_points += o.floor;
    }
  };
  stream_chunks<ClChunk>(
      band_strips, strips_per_chunk, compute_chunk, sink,
      [&](std::size_t done) {
        if (control.progress)
          control.progress(std::min<std::uint64_t>(st.lines, done * lines_per_strip), st.lines);
      },
      control, st.compute_s, st.sink_s);
  return st;
}

}  // namespace ncpath
