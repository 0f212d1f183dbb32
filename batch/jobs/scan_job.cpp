#include "batch/jobs/scan_job.hpp"

#include <span>

#include "batch/jobs/junction_table.hpp"
#include "batch/jobs/record_sink.hpp"
#include "batch/jobs/shared_mesh.hpp"
#include "engine/scan.hpp"
#include "kernels/scan/envelope.hpp"
#include "kernels/scan/plane_slice.hpp"

namespace ncpath::jobs {

namespace {

std::int64_t i64(std::uint64_t v) { return static_cast<std::int64_t>(v); }

// The codes written to scan/segment_kind and scan/junction_kind are the engine's and the
// kernels' own (PieceKind, kScanSegmentVertical, JunctionKind); the enum texts below list them.
static_assert(static_cast<int>(PieceKind::kFacetLine) == 0 &&
              static_cast<int>(PieceKind::kSphereArc) == 1 &&
              static_cast<int>(PieceKind::kCylinderEllipse) == 2 &&
              static_cast<int>(PieceKind::kCylinderLine) == 3 &&
              static_cast<int>(PieceKind::kCylinderCircle) == 4 &&
              static_cast<int>(PieceKind::kFloor) == 5 && kScanSegmentVertical == 6);
static_assert(static_cast<int>(JunctionKind::kConvex) == 0 &&
              static_cast<int>(JunctionKind::kSharpConcave) == 1 &&
              static_cast<int>(JunctionKind::kTangent) == 2);

constexpr const char* kSegmentKindEnum =
    "0=facet_line,1=sphere_arc,2=cylinder_ellipse,3=cylinder_line,4=cylinder_circle,5=floor,"
    "6=vertical";

// The exact segments and junctions of the job, streamed to the scan/ group chunk by chunk in
// cutting order (rows of 3 or 5 values).
class ScanRecords {
 public:
  explicit ScanRecords(out::ClJob& cl)
      : cl_(cl),
        segments_(
            cl, kGroup,
            {"cut path of segment i: its index among the job's cut paths (path_kind 0)",
             kSegmentKindEnum, "tool tip x, y, z where the segment starts, in cutting order", 5,
             "in the plane's (u, tip z), u = x on x lines, y on y lines (mm, rad): lines "
             "(kinds 0, 3, 5): slope, intercept; sphere arc: centre u, centre z, radius; "
             "ellipse and circle (2, 4): centre u, centre z, semi-major, semi-minor, angle "
             "of the major axis from +u (upper arc); vertical: u; unused columns 0"}),
        junctions_(cl, kGroup,
                   "cut path of junction i: its index among the job's cut paths (path_kind 0)",
                   "tool tip x, y, z at the junction") {}

  void append(const ScanChunk& ch) {
    for (const ScanSegmentRecord& s : ch.segments) segments_.push(s);
    segments_.flush(cl_);
    junctions_.append(ch.junctions);
  }

 private:
  static constexpr const char* kGroup = "scan";
  out::ClJob& cl_;
  SegmentTable segments_;
  JunctionTable junctions_;
};

void push_scan_stats(const ScanStats& st, std::vector<out::StatValue>& stats) {
  const out::StatValue list[] = {
      {"facets_skipped_degenerate", i64(st.facets_degenerate), ""},
      {"offset_facets", i64(st.facets), ""},
      {"offset_edges", i64(st.edges), ""},
      {"offset_vertices", i64(st.vertices), ""},
      {"planes", i64(st.planes), ""},
      {"planes_x", i64(st.planes_x), ""},
      {"planes_y", i64(st.planes_y), ""},
      {"pieces", i64(st.pieces), ""},
      {"pieces_linear", i64(st.linear_pieces), ""},
      {"pieces_hidden", i64(st.hidden), ""},
      {"segments", i64(st.segments), ""},
      {"junctions", i64(st.junctions), ""},
      {"junctions_sharp_concave", i64(st.sharp_concave), ""},
      {"junctions_convex", i64(st.convex), ""},
      {"junctions_tangent", i64(st.tangent), ""},
      {"cut_points", i64(st.cut_points), ""},
      {"link_points", i64(st.link_points), ""},
      {"envelope_decisions", i64(st.decisions), ""},
      {"envelope_crossings", i64(st.crossings), ""},
      {"floor_z", st.floor_z, "mm"},
      {"scan_x_min", st.rect[0], "mm"},
      {"scan_y_min", st.rect[1], "mm"},
      {"scan_x_max", st.rect[2], "mm"},
      {"scan_y_max", st.rect[3], "mm"},
      {"elements_s", st.elements_s, "s"},
  };
  stats.insert(stats.end(), std::begin(list), std::end(list));
}

}  // namespace

ScanJobSummary run_scan_job(const JobSpec& job, const TriangleMesh& mesh, out::ClJob& cl,
                            out::GcodeWriter* gcode, RunControl& control,
                            std::vector<out::StatValue>& stats, SharedMesh* shared,
                            bool elements_shared) {
  ScanJobSummary summary;
  ScanRecords records(cl);
  RecordSink<ScanRecords> sink{cl, gcode, records, summary.points};
  const auto to_sink = [&](const ScanChunk& ch) { sink(ch); };
  ScanStats st;
  if (shared && job.tool.type == CutterType::kBall) {
    Stopwatch clock;  // building them, or waiting for the job that does, or nothing
    const std::shared_ptr<const ScanElements> se = shared->scan_elements(job.tool.radius);
    const double got_s = clock.seconds();
    st = run_scan(*se, job.tool, job.scan, to_sink, control);
    st.elements_s = got_s;
  } else {
    st = run_scan(mesh, job.tool, job.scan, to_sink, control);
  }
  stats.push_back({"elements_shared", std::int64_t{elements_shared}, ""});
  summary.compute_s = st.compute_s;
  const double write_s = st.sink_s;

  push_scan_stats(st, stats);
  stats.push_back({"compute_s", st.compute_s, "s"});
  stats.push_back({"write_s", write_s, "s"});
  stats.push_back({"points", i64(summary.points), ""});
  return summary;
}

}  // namespace ncpath::jobs
