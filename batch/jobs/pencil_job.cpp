#include "batch/jobs/pencil_job.hpp"

#include <span>
#include <string>

#include "batch/jobs/job_verify.hpp"
#include "engine/chord_guard.hpp"
#include "engine/pencil.hpp"

namespace ncpath::jobs {

namespace {

std::int64_t i64(std::uint64_t v) { return static_cast<std::int64_t>(v); }

constexpr const char* kFamilyEnum = "0=x_lines,1=y_lines,2=z_levels";

template <class T>
std::span<const T> all(const std::vector<T>& v) {
  return std::span<const T>(v);
}

// The pencil points as structure-of-arrays (rows of 3 flattened), in the engine's order.
void write_points(const std::vector<PencilPoint>& points, out::ClJob& cl) {
  std::vector<double> position, b1, b2, angle;
  std::vector<std::uint8_t> family, kept;
  for (const PencilPoint& p : points) {
    position.insert(position.end(), {p.position.x(), p.position.y(), p.position.z()});
    b1.insert(b1.end(), {p.b1.x(), p.b1.y(), p.b1.z()});
    b2.insert(b2.end(), {p.b2.x(), p.b2.y(), p.b2.z()});
    angle.push_back(p.angle);
    family.push_back(p.family);
    kept.push_back(p.kept);
  }
  const std::string g = "pencil";
  cl.write_array(g, "point_position", all(position), 3, "mm",
                 "tool tip x, y, z of pencil point i: a sharp-concave junction of an exact CL "
                 "curve (drive plane or z-level) whose bi-contact angle is at least min_angle");
  cl.write_array(g, "point_b1", all(b1), 3, "",
                 "unit vector from the ball's contact on the first of the two touched elements "
                 "to the ball centre");
  cl.write_array(g, "point_b2", all(b2), 3, "",
                 "unit vector from the contact on the second element to the ball centre");
  cl.write_array(g, "point_angle", all(angle), 0, "rad",
                 "bi-contact angle: between point_b1 and point_b2");
  cl.write_array(g, "point_family", all(family), 0, "", kFamilyEnum);
  cl.write_array(g, "point_kept", all(kept), 0, "",
                 "1: traced in its family (the family whose layers cross the crease most "
                 "steeply), 0: left to another family");
}

void push_pencil_stats(const PencilStats& st, std::vector<out::StatValue>& stats) {
  const out::StatValue list[] = {
      {"planes", i64(st.planes), ""},
      {"levels", i64(st.levels), ""},
      {"zlevel_open_chains", i64(st.zlevel_open_chains), ""},
      {"sliced_facets", i64(st.sliced_facets), ""},
      {"condition_planes", i64(st.condition.planes), ""},
      {"condition_moved_vertices", i64(st.condition.moved_vertices), ""},
      {"condition_max_move", st.condition.max_move, "mm"},
      {"candidates", i64(st.candidates), ""},
      {"pencil_points", i64(st.pencil_points), ""},
      {"contactless_points", i64(st.contactless_points), ""},
      {"hanging_points", i64(st.hanging_points), ""},
      {"kept_points", i64(st.kept_points), ""},
      {"chains", i64(st.chains), ""},
      {"refined_points", i64(st.refined_points), ""},
      {"lifted_points", i64(st.lifted_points), ""},
      {"paths", i64(st.paths), ""},
      {"neutral_paths", i64(st.neutral_paths), ""},
      {"traced_length", st.traced_length, "mm"},
      {"air_length", st.air_length, "mm"},
      {"elements_s", st.elements_s, "s"},
      {"scan_s", st.scan_s, "s"},
      {"zlevel_s", st.zlevel_s, "s"},
      {"zone_s", st.zone_s, "s"},
      {"link_s", st.link_s, "s"},
      {"refine_s", st.refine_s, "s"},
      {"check_s", st.check_s, "s"},
      {"index_s", st.index_s, "s"},
  };
  stats.insert(stats.end(), std::begin(list), std::end(list));
}

}  // namespace

PencilJobSummary run_pencil_job(const JobSpec& job, const TriangleMesh& mesh,
                                const SweptIndexSource& swept, out::ClJob& cl,
                                out::GcodeWriter* gcode, RunControl& control,
                                std::vector<out::StatValue>& stats,
                                const ConditionedMesh* conditioned) {
  PencilJobSummary summary;
  Stopwatch compute_clock;
  const PencilResult r = run_pencil(mesh, job.tool, job.pencil, control, conditioned);
  summary.compute_s = compute_clock.seconds();
  if (control.progress) control.progress(1, 1);  // not streamed: all at once

  ChordGuard guard(swept(), job.tool, job.pencil.stock);
  const ClChunk c = guard.apply(pencil_chunk(r));
  Stopwatch write_clock;
  cl.append_paths(c.xyz, c.contact, c.path_sizes, c.path_kinds);
  if (gcode) gcode->append(c);
  summary.points = c.point_count();
  write_points(r.points, cl);
  const double write_s = write_clock.seconds();

  push_pencil_stats(r.stats, stats);
  push_guard_stats(guard, stats);
  stats.push_back({"compute_s", summary.compute_s, "s"});
  stats.push_back({"write_s", write_s, "s"});
  stats.push_back({"points", i64(summary.points), ""});
  return summary;
}

}  // namespace ncpath::jobs
