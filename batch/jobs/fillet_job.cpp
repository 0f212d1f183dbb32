#include "batch/jobs/fillet_job.hpp"

#include <string>

#include "batch/jobs/job_verify.hpp"
#include "engine/chord_guard.hpp"
#include "engine/fillet.hpp"

namespace ncpath::jobs {

namespace {

std::int64_t i64(std::uint64_t v) { return static_cast<std::int64_t>(v); }

void push_fillet_stats(const FilletStats& st, std::vector<out::StatValue>& stats) {
  // `pass_points`, not the engine's `points`: every job's `points` counts all CL points
  // written, links and rapids included.
  const out::StatValue own[] = {
      {"passes", i64(st.passes), ""},
      {"pass_points", i64(st.points), ""},
      {"rays", i64(st.rays), ""},
      {"misses", i64(st.misses), ""},
      {"unreachable", i64(st.unreachable), ""},
      {"lifted_points", i64(st.lifted_points), ""},
      {"neutral_passes", i64(st.neutral_passes), ""},
      {"cut_length", st.cut_length, "mm"},
      {"pencil_s", st.pencil_s, "s"},
      {"rays_s", st.rays_s, "s"},
  };
  stats.insert(stats.end(), std::begin(own), std::end(own));
  // The reference ball's pencil run, named as in a pencil job with the prefix.
  const PencilStats& p = st.pencil;
  const out::StatValue reference[] = {
      {"reference_planes", i64(p.planes), ""},
      {"reference_levels", i64(p.levels), ""},
      {"reference_sliced_facets", i64(p.sliced_facets), ""},
      {"reference_candidates", i64(p.candidates), ""},
      {"reference_pencil_points", i64(p.pencil_points), ""},
      {"reference_kept_points", i64(p.kept_points), ""},
      {"reference_chains", i64(p.chains), ""},
      {"reference_refined_points", i64(p.refined_points), ""},
      {"reference_lifted_points", i64(p.lifted_points), ""},
      {"reference_paths", i64(p.paths), ""},
      {"reference_traced_length", p.traced_length, "mm"},
      {"reference_air_length", p.air_length, "mm"},
      {"reference_elements_s", p.elements_s, "s"},
      {"reference_scan_s", p.scan_s, "s"},
      {"reference_zlevel_s", p.zlevel_s, "s"},
      {"reference_zone_s", p.zone_s, "s"},
      {"reference_link_s", p.link_s, "s"},
      {"reference_refine_s", p.refine_s, "s"},
      {"reference_check_s", p.check_s, "s"},
      {"reference_index_s", p.index_s, "s"},
  };
  stats.insert(stats.end(), std::begin(reference), std::end(reference));
}

}  // namespace

FilletJobSummary run_fillet_job(const JobSpec& job, const TriangleMesh& mesh,
                                const SweptIndexSource& swept, out::ClJob& cl,
                                out::GcodeWriter* gcode, RunControl& control,
                                std::vector<out::StatValue>& stats,
                                const ConditionedMesh* conditioned) {
  FilletJobSummary summary;
  Stopwatch compute_clock;
  const FilletResult r = run_fillet(mesh, job.tool, job.fillet, control, conditioned);
  summary.compute_s = compute_clock.seconds();
  if (control.progress) control.progress(1, 1);  // not streamed: all at once

  ChordGuard guard(swept(), job.tool, job.fillet.stock);
  const ClChunk c = guard.apply(fillet_chunk(r));
  Stopwatch write_clock;
  cl.append_paths(c.xyz, c.contact, c.path_sizes, c.path_kinds);
  if (gcode) gcode->append(c);
  summary.points = c.point_count();
  const double write_s = write_clock.seconds();

  push_fillet_stats(r.stats, stats);
  push_guard_stats(guard, stats);
  stats.push_back({"compute_s", summary.compute_s, "s"});
  stats.push_back({"write_s", write_s, "s"});
  stats.push_back({"points", i64(summary.points), ""});
  return summary;
}

}  // namespace ncpath::jobs
