#include "batch/jobs/pocket_job.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>

#include "batch/jobs/profile_input.hpp"
#include "engine/pocket_path.hpp"
#include "engine/run_control.hpp"

namespace ncpath::jobs {

namespace {

std::int64_t i64(std::uint64_t v) { return static_cast<std::int64_t>(v); }

PocketPathParams path_params(const JobSpec& job, const out::GcodeWriter* gcode) {
  const PocketParams& q = job.pocket;
  PocketPathParams p;
  p.tool_radius = job.tool.radius;
  p.stepover = q.stepover;
  p.stock = q.stock;
  p.tolerance = q.tolerance;
  // The paths are polylines within the tolerance; when G-code is written they are finer than
  // its arc tolerance, so that the G-code writer can fit the arcs back.
  p.chordal_tolerance =
      gcode ? std::min(q.tolerance, gcode->params().arc_tolerance / 4) : q.tolerance;
  p.top = 0;
  p.depth = q.depth;
  p.stepdown = q.stepdown;
  p.clearance = q.clearance;
  p.safe_z = pocket_safe_z(job, gcode, p.top, p.clearance);
  p.order = q.order;
  p.milling = q.milling;
  p.helix_radius = q.helix_radius;
  p.ramp_angle_deg = q.ramp_angle;
  return p;
}

void push_path_stats(const PocketPathStats& s, std::vector<out::StatValue>& stats) {
  push_plan_stats(s, stats);
  const out::StatValue list[] = {
      {"depth_passes", i64(s.depth_passes), ""},
      {"cleanup_length", s.cleanup_length, "mm"},
      {"slotting_length", s.slotting_length, "mm"},
      {"helix_entries", i64(s.helix_entries), ""},
      {"ramp_entries", i64(s.ramp_entries), ""},
      {"plunge_entries", i64(s.plunge_entries), ""},
      {"path_s", s.path_s, "s"},
  };
  stats.insert(stats.end(), std::begin(list), std::end(list));
}

}  // namespace

void push_plan_stats(const PocketPlanStats& s, std::vector<out::StatValue>& stats) {
  const out::StatValue list[] = {
      {"loops", i64(s.loops), ""},
      {"levels", i64(s.levels), ""},
      {"open_fragments", i64(s.open_fragments), ""},
      {"components", i64(s.components), ""},
      {"links", i64(s.links), ""},
      {"cleanup_curves", i64(s.cleanup_curves), ""},
      {"cut_length", s.cut_length, "mm"},
      {"link_length", s.link_length, "mm"},
      {"rapid_length", s.rapid_length, "mm"},
      {"retractions", i64(s.retractions), ""},
      {"uncut_area_before", s.uncut_area_before, "mm^2"},
      {"uncut_area_after", s.uncut_area_after, "mm^2"},
      {"unreachable_area", s.unreachable_area, "mm^2"},
      {"offset_s", s.offset_s, "s"},
      {"uncut_s", s.uncut_s, "s"},
      {"link_s", s.link_s, "s"},
  };
  stats.insert(stats.end(), std::begin(list), std::end(list));
}

double pocket_safe_z(const JobSpec& job, const out::GcodeWriter* gcode, double top,
                     double clearance) {
  // One rapid height for the HDF5 paths and the G-code program.
  const double safe_z =
      gcode ? gcode->params().safe_z : job.gcode_safe_z.value_or(top + kDefaultSafeAboveTop);
  if (safe_z < top + clearance) {
    std::ostringstream os;
    os << "safe height (gcode.safe_z, --safe-z) " << safe_z << " mm is below the clearance height "
       << top + clearance << " mm (top " << top << " + clearance " << clearance
       << "): rapids must run above the plane where feed moves start";
    throw std::invalid_argument(os.str());
  }
  return safe_z;
}

PocketJobSummary run_pocket_job(const JobSpec& job, out::ClJob& cl, out::GcodeWriter* gcode,
                                std::vector<out::StatValue>& stats) {
  PocketJobSummary summary;
  const ProfileInput in = read_profile_regions(job.input, job.pocket.join_tolerance, job.units, stats);

  const PocketPathParams p = path_params(job, gcode);
  Stopwatch compute_clock;
  std::optional<PocketPath> planned = plan_regions_that_fit(
      in, [&](const std::vector<Region>& regions) { return plan_pocket(regions, p); }, stats);
  summary.compute_s = compute_clock.seconds();
  if (!planned) return summary;  // nothing to cut: the job says so
  PocketPath& path = *planned;

  Stopwatch write_clock;
  ClChunk& c = path.cl;
  cl.append_paths(c.xyz, c.contact, c.path_sizes, c.path_kinds);
  if (gcode) gcode->append(c);
  summary.points = c.point_count();
  const double write_s = write_clock.seconds();

  push_path_stats(path.stats, stats);
  stats.push_back({"points", i64(summary.points), ""});
  stats.push_back({"compute_s", summary.compute_s, "s"});
  stats.push_back({"write_s", write_s, "s"});
  return summary;
}

}  // namespace ncpath::jobs
