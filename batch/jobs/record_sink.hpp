#pragma once
// The chunk sink of the jobs that write exact records next to their CL paths (scan, zlevel):
// each chunk's CL paths go to the job's cl/ group and G-code, and its records to the job's
// record tables (batch/jobs/junction_table.hpp), as they stream in.
#include <cassert>
#include <cstdint>

#include "batch/output/cl_writer.hpp"
#include "batch/output/gcode_writer.hpp"
#include "engine/cl_chunk.hpp"

namespace ncpath::jobs {

// Number of cut paths (PathKind::kCut) in a chunk.
inline std::int64_t cut_path_count(const ClChunk& c) {
  std::int64_t cuts = 0;
  for (std::uint8_t k : c.path_kinds) cuts += k == static_cast<std::uint8_t>(PathKind::kCut);
  return cuts;
}

// The state of one job's sink, called with each chunk in order. A Chunk has `cl` (a ClChunk)
// and `segments` whose `path` is the index of the segment's cut path among the job's cut
// paths; Records has append(const Chunk&). Call it from a lambda that captures it by
// reference: the engine takes a std::function, which would copy it.
template <class Records>
struct RecordSink {
  out::ClJob& cl;
  out::GcodeWriter* gcode;  // null: no G-code
  Records& records;
  std::uint64_t& points;       // CL points written so far
  std::int64_t cut_paths = 0;  // cut paths before the chunk (checked in debug builds only)

  template <class Chunk>
  void operator()(const Chunk& ch) {
    const ClChunk& c = ch.cl;
    cl.append_paths(c.xyz, c.contact, c.path_sizes, c.path_kinds);
    if (gcode) gcode->append(c);
    points += c.point_count();
#ifndef NDEBUG
    // The engine numbers the segments' paths among the cut paths.
    const std::int64_t cuts = cut_path_count(c);
    for (const auto& s : ch.segments) assert(s.path >= cut_paths && s.path < cut_paths + cuts);
    cut_paths += cuts;
#endif
    records.append(ch);
  }
};

}  // namespace ncpath::jobs
