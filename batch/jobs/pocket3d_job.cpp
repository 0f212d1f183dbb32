#include "batch/jobs/pocket3d_job.hpp"

#include <cmath>
#include <sstream>

#include "batch/io/surface_toml.hpp"
#include "batch/jobs/pocket_job.hpp"  // pocket_safe_z
#include "batch/jobs/profile_input.hpp"
#include "engine/pocket3d.hpp"
#include "engine/run_control.hpp"
#include "kernels/geom/tolerance.hpp"

namespace ncpath::jobs {

namespace {

std::int64_t i64(std::uint64_t v) { return static_cast<std::int64_t>(v); }

Pocket3dParams plan_params(const JobSpec& job, const out::GcodeWriter* gcode) {
  const Pocket3dJobParams& q = job.pocket3d;
  Pocket3dParams p;
  p.tool_radius = job.tool.radius;
  p.scallop = q.scallop;
  p.eps = q.eps;
  p.delta = q.delta;
  p.stock = q.stock;
  p.tolerance = q.tolerance;
  p.top = 0;
  p.clearance = q.clearance;
  p.safe_z = pocket_safe_z(job, gcode, p.top, p.clearance);
  p.min_interval = q.min_interval;
  p.order = q.order;
  p.milling = q.milling;
  return p;
}

// The stock top is z = 0: a bottom above it inside the pocket is a surface placed wrongly
// (feed moves would start below the cut). Only points touching the bottom are the bottom's
// (the approach and the rapids have no contact point).
void check_below_top(const JobSpec& job, const Pocket3dPath& path, double top) {
  const std::vector<double>& xyz = path.cl.xyz;
  for (std::size_t i = 0; i < path.cl.point_count(); ++i) {
    const double z = xyz[3 * i + 2];
    // A tip on the top itself cuts nothing and harms nothing: allowed.
    if (std::isfinite(path.cc[3 * i]) && z > top + tol::kExactZ) {
      std::ostringstream os;
      os << "the bottom surface rises above the stock top z = " << top
         << " inside the pocket: the ball's tip reaches z = " << z << " at (" << xyz[3 * i] << ", "
         << xyz[3 * i + 1]
         << "); the pocket is cut down from z = 0, so the bottom must lie below it (move the "
            "surface down)";
      throw io::ReadError(job.surface, "", os.str());
    }
  }
}

void push_pocket3d_stats(const Pocket3dStats& st, std::vector<out::StatValue>& stats) {
  push_plan_stats(st, stats);
  const out::StatValue list[] = {
      {"cl_points", i64(st.cl_points), ""},
      {"drops", i64(st.drops), ""},
      {"lifted_points", i64(st.lifted_points), ""},
      {"max_lift", st.max_lift, "mm"},
      {"min_interval", st.min_interval, "mm"},
      {"max_interval", st.max_interval, "mm"},
      {"cl_s", st.cl_s, "s"},
  };
  stats.insert(stats.end(), std::begin(list), std::end(list));
}

}  // namespace

Pocket3dJobSummary run_pocket3d_job(const JobSpec& job, out::ClJob& cl, out::GcodeWriter* gcode,
                                    std::vector<out::StatValue>& stats) {
  Pocket3dJobSummary summary;
  const ProfileInput in = read_profile_regions(job.input, job.pocket3d.join_tolerance, job.units, stats);
  Stopwatch surface_clock;
  const NurbsSurface bottom = io::read_surface_toml(job.surface);
  stats.push_back({"surface_sha256", out::sha256_file(job.surface), ""});
  stats.push_back({"surface_degree_u", std::int64_t{bottom.degree_u}, ""});
  stats.push_back({"surface_degree_v", std::int64_t{bottom.degree_v}, ""});
  stats.push_back({"surface_control_points", i64(bottom.ctrl.size()), ""});
  stats.push_back({"surface_read_s", surface_clock.seconds(), "s"});

  const Pocket3dParams p = plan_params(job, gcode);
  Stopwatch compute_clock;
  std::optional<Pocket3dPath> planned = plan_regions_that_fit(
      in, [&](const std::vector<Region>& regions) { return plan_pocket3d(regions, bottom, p); },
      stats);
  summary.compute_s = compute_clock.seconds();
  if (!planned) return summary;  // nothing to cut: the job says so
  Pocket3dPath& path = *planned;
  const ClChunk& c = path.cl;
  check_below_top(job, path, p.top);

  Stopwatch write_clock;
  cl.append_paths(c.xyz, c.contact, c.path_sizes, c.path_kinds);
  if (gcode) gcode->append(c);
  summary.points = c.point_count();
  std::vector<std::int64_t> level(path.loop_level.begin(), path.loop_level.end());
  cl.write_array("pocket3d", "cc_points", std::span<const double>(path.cc), 3, "mm",
                 "contact point on the bottom of CL point i (row i of cl/points); NaN where the "
                 "tool is off the bottom (rapids and the approach to the first cut)");
  cl.write_array("pocket3d", "normals", std::span<const double>(path.normal), 3, "",
                 "upward unit normal of the bottom at cc_points row i; NaN where that is NaN");
  cl.write_array("pocket3d", "loop_level", std::span<const std::int64_t>(level), 0, "",
                 "offset level of loop k (1 = ball radius + stock from the profile)");
  cl.write_array(
      "pocket3d", "loop_interval", std::span<const double>(path.loop_interval), 0, "mm",
      "plan distance of loop k from its parent loops: the path interval W, the "
      "smallest scallop chord along the parent level (0 on level 1; half of it on a last "
      "level where the full interval leaves nothing)");
  const double write_s = write_clock.seconds();

  push_pocket3d_stats(path.stats, stats);
  stats.push_back({"points", i64(summary.points), ""});
  stats.push_back({"compute_s", summary.compute_s, "s"});
  stats.push_back({"write_s", write_s, "s"});
  return summary;
}

}  // namespace ncpath::jobs
