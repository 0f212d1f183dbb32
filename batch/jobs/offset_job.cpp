#include "batch/jobs/offset_job.hpp"

#include <algorithm>

#include "batch/jobs/profile_input.hpp"
#include "engine/pocket_offset.hpp"
#include "engine/run_control.hpp"

namespace ncpath::jobs {

namespace {

std::int64_t i64(std::uint64_t v) { return static_cast<std::int64_t>(v); }

}  // namespace

OffsetJobSummary run_offset_job(const JobSpec& job, out::ClJob& cl, out::GcodeWriter* gcode,
                                std::vector<out::StatValue>& stats) {
  OffsetJobSummary summary;
  const ProfileInput in = read_profile_regions(job.input, job.offset.join_tolerance, job.units, stats);

  // Loop paths are polylines within the tolerance; when G-code is written they are finer
  // than its arc tolerance, so that the G-code writer can fit the arcs back. The loops lie
  // that much farther from the walls, so the polylines never come closer than R + stock.
  const double chord = gcode ? std::min(job.offset.tolerance, gcode->params().arc_tolerance / 4)
                             : job.offset.tolerance;
  Stopwatch compute_clock;
  PocketOffsetParams p;
  p.tool_radius = job.tool.radius;
  p.stepover = job.offset.stepover;
  p.stock = job.offset.stock;
  p.tolerance = job.offset.tolerance;
  p.wall_margin = chord;
  const PocketOffsetResult res = offset_pocket(in.regions, p);
  summary.compute_s = compute_clock.seconds();

  Stopwatch write_clock;
  // Exact loops: segments (CSR by loop), level, signed area, region; OGH edges.
  std::vector<std::uint8_t> kind;
  std::vector<double> xy, radius, area;
  std::vector<std::int64_t> seg_offsets{0}, level, region, edges;
  std::vector<double> cl_xyz;
  std::vector<std::uint8_t> contact;
  std::vector<std::uint32_t> path_sizes;
  std::vector<std::uint8_t> path_kinds;
  std::vector<Vec2> poly;
  std::uint64_t segments = 0;
  for (std::size_t l = 0; l < res.loops.size(); ++l) {
    const PocketLoop& pl = res.loops[l];
    poly.clear();
    for (const Seg2& s : pl.loop.segs) {
      kind.push_back(static_cast<std::uint8_t>(s.kind));
      xy.insert(xy.end(), {s.a.x(), s.a.y(), s.b.x(), s.b.y(), s.c.x(), s.c.y()});
      radius.push_back(s.is_arc() ? s.r : 0.0);
      append_polyline(s, chord, poly);
    }
    segments += pl.loop.segs.size();
    seg_offsets.push_back(static_cast<std::int64_t>(segments));
    level.push_back(pl.level);
    region.push_back(pl.region);
    area.push_back(pl.loop.area2 / 2);
    for (std::uint32_t parent : pl.loop.parents) edges.insert(edges.end(), {i64(l), i64(parent)});
    poly.push_back(pl.loop.segs.front().a);  // closed path
    for (const Vec2& q : poly) cl_xyz.insert(cl_xyz.end(), {q.x(), q.y(), -job.offset.depth});
    contact.insert(contact.end(), poly.size(), 0);
    path_sizes.push_back(static_cast<std::uint32_t>(poly.size()));
    path_kinds.push_back(static_cast<std::uint8_t>(PathKind::kCut));
  }
  cl.append_paths(cl_xyz, contact, path_sizes, path_kinds);
  summary.points = cl_xyz.size() / 3;
  if (gcode) {
    ClChunk chunk;
    chunk.xyz = std::move(cl_xyz);
    chunk.contact = std::move(contact);
    chunk.path_sizes = std::move(path_sizes);
    chunk.path_kinds = std::move(path_kinds);
    gcode->append(chunk);
  }
  cl.write_array("offset", "seg_kind", std::span<const std::uint8_t>(kind), 0, "",
                 "0=line,1=arc_ccw,2=arc_cw");
  cl.write_array("offset", "seg_points", std::span<const double>(xy), 6, "mm",
                 "start x, start y, end x, end y, centre x, centre y (centre: arcs only)");
  cl.write_array("offset", "seg_radius", std::span<const double>(radius), 0, "mm",
                 "arc radius, 0 for lines");
  cl.write_array("offset", "loop_offsets", std::span<const std::int64_t>(seg_offsets), 0, "",
                 "loop k is segments [loop_offsets[k], loop_offsets[k+1])");
  cl.write_array("offset", "loop_level", std::span<const std::int64_t>(level), 0, "",
                 "1 = tool radius + stock from the profile, +1 per stepover");
  cl.write_array("offset", "loop_region", std::span<const std::int64_t>(region), 0, "",
                 "input region (pocket) the loop belongs to");
  cl.write_array("offset", "loop_area", std::span<const double>(area), 0, "mm^2",
                 "signed area: < 0 clockwise (material inside), > 0 counter-clockwise (hole)");
  cl.write_array("offset", "ogh_edges", std::span<const std::int64_t>(edges), 2, "",
                 "offset generation history: (child loop, parent loop) pairs");
  const double write_s = write_clock.seconds();

  stats.push_back({"loops", i64(res.loops.size()), ""});
  stats.push_back({"levels", i64(res.levels), ""});
  stats.push_back({"segments", i64(segments), ""});
  stats.push_back({"ogh_edges", i64(edges.size() / 2), ""});
  stats.push_back({"open_fragments", i64(res.open_fragments), ""});
  stats.push_back({"points", i64(summary.points), ""});
  stats.push_back({"compute_s", summary.compute_s, "s"});
  stats.push_back({"write_s", write_s, "s"});
  return summary;
}

}  // namespace ncpath::jobs
