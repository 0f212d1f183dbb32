#include "batch/jobs/zlevel_job.hpp"

#include <cassert>
#include <span>
#include <string>

#include "batch/jobs/junction_table.hpp"
#include "batch/jobs/record_sink.hpp"
#include "engine/zlevel.hpp"
#include "kernels/scan/envelope.hpp"
#include "kernels/scan/zlevel.hpp"

namespace ncpath::jobs {

namespace {

std::int64_t i64(std::uint64_t v) { return static_cast<std::int64_t>(v); }

// The codes written to zlevel/segment_kind and zlevel/junction_kind are the kernels' own
// (ContourSegKind, JunctionKind); the enum texts below list them.
static_assert(static_cast<int>(ContourSegKind::kLine) == 0 &&
              static_cast<int>(ContourSegKind::kCircleArc) == 1 &&
              static_cast<int>(ContourSegKind::kEllipseArc) == 2);
static_assert(static_cast<int>(JunctionKind::kConvex) == 0 &&
              static_cast<int>(JunctionKind::kSharpConcave) == 1 &&
              static_cast<int>(JunctionKind::kTangent) == 2);

constexpr const char* kSegmentKindEnum = "0=line,1=circular_arc,2=elliptic_arc";

// The exact contours of the job, streamed to the zlevel/ group chunk by chunk in cutting
// order (rows of 3 or 7 values).
class ZLevelRecords {
 public:
  explicit ZLevelRecords(out::ClJob& cl)
      : cl_(cl),
        segments_(cl, kGroup,
                  {"cut path (contour) of segment i: its index among the job's cut paths "
                   "(path_kind 0)",
                   kSegmentKindEnum,
                   "tool tip x, y, z where the segment starts, in cutting order (z: the level)",
                   7,
                   "arcs (kinds 1, 2): centre x, centre y (mm), r1, r2 (mm), angle of the axis "
                   "from +x, t0, t1 (rad): p(t) = centre + r1 cos t axis + r2 sin t perp(axis), "
                   "t from t0 to t1 (t1 > t0, counter-clockwise); lines: zeros"}),
        shadow_(cl, kGroup, "segment_shadow", 0, "",
                "1: the element lies above the level there (the ball passes under it: a wall "
                "or an overhang; the contact is on the vertical below it), else 0"),
        junctions_(cl, kGroup,
                   "cut path (contour) of junction i: its index among the job's cut paths",
                   "tool tip x, y, z at the junction (the start of a segment)"),
        level_(cl, kGroup, "contour_level", 0, "mm", "tool-tip z of contour k (the k-th cut path)"),
        hole_(cl, kGroup, "contour_hole", 0, "",
              "1: contour k is a hole (clockwise, the region outside it), 0: an outer boundary "
              "(counter-clockwise)") {}

  void append(const ZLevelChunk& ch) {
    for (const ZLevelSegmentRecord& s : ch.segments) {
      segments_.push(s);
      shadow_.push(s.shadow);
    }
    segments_.flush(cl_);
    shadow_.flush(cl_);
    junctions_.append(ch.junctions);
    for (const double z : ch.contour_level) level_.push(z);
    for (const std::uint8_t h : ch.contour_hole) hole_.push(h);
    level_.flush(cl_);
    hole_.flush(cl_);
  }

 private:
  static constexpr const char* kGroup = "zlevel";
  out::ClJob& cl_;
  SegmentTable segments_;
  Column<std::uint8_t> shadow_;
  JunctionTable junctions_;
  Column<double> level_;
  Column<std::uint8_t> hole_;
};

void push_zlevel_stats(const ZLevelOpStats& st, std::vector<out::StatValue>& stats) {
  const out::StatValue list[] = {
      {"offset_facets", i64(st.facets), ""},
      {"offset_edges", i64(st.edges), ""},
      {"offset_vertices", i64(st.vertices), ""},
      {"top_z", st.top_z, "mm"},
      {"bottom_z", st.bottom_z, "mm"},
      {"levels", i64(st.levels), ""},
      {"contours", i64(st.contours), ""},
      {"holes", i64(st.holes), ""},
      {"segments", i64(st.segments), ""},
      {"junctions", i64(st.junctions), ""},
      {"junctions_sharp_concave", i64(st.sharp_concave), ""},
      {"junctions_convex", i64(st.convex), ""},
      {"junctions_tangent", i64(st.tangent), ""},
      {"candidates", i64(st.candidates), ""},
      {"open_chains", i64(st.open_chains), ""},
      {"condition_planes", i64(st.condition.planes), ""},
      {"condition_moved_vertices", i64(st.condition.moved_vertices), ""},
      {"condition_max_move", st.condition.max_move, "mm"},
      {"cut_points", i64(st.points), ""},
      {"elements_s", st.elements_s, "s"},
  };
  stats.insert(stats.end(), std::begin(list), std::end(list));
}

}  // namespace

ZLevelJobSummary run_zlevel_job(const JobSpec& job, const TriangleMesh& mesh, out::ClJob& cl,
                                out::GcodeWriter* gcode, RunControl& control,
                                std::vector<out::StatValue>& stats,
                                const ConditionedMesh* conditioned) {
  ZLevelJobSummary summary;
  ZLevelRecords records(cl);
  RecordSink<ZLevelRecords> sink{cl, gcode, records, summary.points};
  auto on_chunk = [&](const ZLevelChunk& ch) {
    // One contour per cut path.
    assert(static_cast<std::size_t>(cut_path_count(ch.cl)) == ch.contour_level.size());
    sink(ch);
  };
  const ZLevelOpStats st = run_zlevel(mesh, job.tool, job.zlevel, on_chunk, control, conditioned);
  summary.compute_s = st.compute_s;
  const double write_s = st.sink_s;

  push_zlevel_stats(st, stats);
  stats.push_back({"compute_s", st.compute_s, "s"});
  stats.push_back({"write_s", write_s, "s"});
  stats.push_back({"points", i64(summary.points), ""});
  return summary;
}

}  // namespace ncpath::jobs
