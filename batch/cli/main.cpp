// ncpath command line: raster, scan, zlevel, pencil, fillet, drop, offset, pocket, pocket3d and
// run (a TOML batch). Every command builds the same JobSpec a batch file would, so a job behaves
// the same whichever way it was given.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <functional>
#include <iostream>
#include <optional>

#include "batch/cli/cli_options.hpp"
#include "batch/cli/huge_pages.hpp"
#include "batch/cli/mesh_op_cli.hpp"
#include "batch/cli/preview_cli.hpp"
#include "batch/cli/progress_bar.hpp"
#include "batch/cli/verify_cli.hpp"
#include "batch/jobs/batch_schedule.hpp"
#include "batch/jobs/job_runner.hpp"
#ifdef NCPATH_MPI
#include <mpi.h>

#include "batch/jobs/mpi_batch.hpp"
#endif

using namespace ncpath;
using namespace ncpath::cli;

namespace {

// Options of the profile commands (offset, pocket, pocket3d); defaults as in OffsetParams /
// PocketParams.
struct ProfileCli {
  std::string profile, tool = "flat:6", out = "ncpath-out.h5", name, stepover, units;
  int threads = 0;
  bool quiet = false;
  double stock = jobs::PocketParams{}.stock;
  double tolerance = jobs::PocketParams{}.tolerance;
  double join_tolerance = jobs::PocketParams{}.join_tolerance;
  GcodeCli gcode;
};

// Returns the --tolerance option (pocket3d's default depends on --eps).
CLI::Option* add_profile(CLI::App* app, ProfileCli& c) {
  app->add_option("--profile", c.profile, "Pocket profile: .dxf or .toml (docs/profile-format.md)")
      ->required();
  app->add_option("--tool", c.tool, "Cutter: ball:D, flat:D or bull:D:r (mm)")
      ->capture_default_str();
  app->add_option("--units", c.units,
                  "The drawing's units (mm, inch, foot, cm, m, micron, ...), overriding what it "
                  "declares; default: the drawing's ($INSUNITS), else mm with a warning");
  app->add_option("--stock", c.stock, "Material left on walls and islands (mm)")
      ->capture_default_str();
  CLI::Option* tolerance =
      app->add_option("--tolerance", c.tolerance, "NURBS-to-arc and arc-to-polyline tolerance (mm)")
          ->capture_default_str();
  app->add_option("--join-tolerance", c.join_tolerance,
                  "Profile end points closer than this are joined (mm)")
      ->capture_default_str();
  app->add_option("--out", c.out, "HDF5 file to write")->capture_default_str();
  app->add_option("--name", c.name, "Job name inside the HDF5 file (default: the command)");
  app->add_option("--threads", c.threads, "Worker threads, 0 = all cores")->capture_default_str();
  app->add_flag("-q,--quiet", c.quiet, "No progress bar");
  add_gcode(app, c.gcode);
  return tolerance;
}

CLI::Option* add_stepover(CLI::App* app, ProfileCli& c) {
  return app->add_option("--stepover", c.stepover,
                         "Distance between levels: mm, or a percentage of the tool diameter (40%)");
}

// --order and --milling of the linked pocket commands.
void add_order_milling(CLI::App* app, std::string& order, std::string& milling) {
  app->add_option("--order", order,
                  "outward: start at the innermost loop; inward: start at the walls")
      ->check(CLI::IsMember({"outward", "inward"}))
      ->capture_default_str();
  app->add_option("--milling", milling, "Cut direction (spindle clockwise, M3)")
      ->check(CLI::IsMember({"climb", "conventional"}))
      ->capture_default_str();
}

// Parses --order and --milling into the job's values: "" or the first problem.
std::string order_milling(const std::string& order, const std::string& milling, CutOrder& o,
                          Milling& m) {
  if (std::string e = jobs::parse_order(order, o); !e.empty()) return "--order " + e;
  if (std::string e = jobs::parse_milling(milling, m); !e.empty()) return "--milling " + e;
  return "";
}

// The job of a profile command; `check` fills the operation's parameters and returns their
// first problem ("" when none). A bad tool is reported first.
void add_profile_job(const ProfileCli& c, jobs::Operation op,
                     const std::function<std::string(jobs::JobSpec&)>& check,
                     jobs::BatchSpec& batch, bool& quiet) {
  jobs::JobSpec j;
  j.operation = op;
  j.name = c.name.empty() ? jobs::operation_name(op) : c.name;
  j.input = c.profile;
  j.tool_text = c.tool;
  std::string e = jobs::parse_tool(c.tool, j.tool);
  if (!e.empty()) e = "--tool: " + e;
  if (!c.units.empty())
    if (std::string u = jobs::parse_units(c.units, j.units); !u.empty() && e.empty())
      e = "--units " + u;
  if (std::string p = check(j); e.empty()) e = p;
  if (!e.empty()) {
    j.error = e;
    j.error_status = "invalid_parameter";
  }
  apply_gcode(c.gcode, j);
  batch.output = c.out;
  batch.threads = c.threads;
  quiet = c.quiet;
  batch.jobs.push_back(std::move(j));
}

std::string human(double v) {
  char buf[32];
  if (v >= 1e6)
    std::snprintf(buf, sizeof buf, "%.2f M", v / 1e6);
  else if (v >= 1e3)
    std::snprintf(buf, sizeof buf, "%.1f k", v / 1e3);
  else
    std::snprintf(buf, sizeof buf, "%.0f ", v);
  return buf;
}

#ifdef NCPATH_MPI
// MPI from the start of main to its end (ncpath-mpi); only this thread calls MPI.
struct MpiSession {
  MpiSession(int& argc, char**& argv) {
    int provided = 0;
    MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  }
  ~MpiSession() { MPI_Finalize(); }
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
};
#endif

// Runs the batch (over the MPI ranks in ncpath-mpi: only rank 0 prints) and prints a line
// per job.
int run(const jobs::BatchSpec& batch, bool quiet) {
#ifdef NCPATH_MPI
  const bool mpi = true;
#else
  const bool mpi = false;
#endif
  cli::BatchProgress bar(!quiet && !mpi && cli::stderr_is_terminal(), batch.jobs.size());
  jobs::BatchObserver obs;
  obs.job_started = [&](std::size_t i, std::size_t, const jobs::JobSpec& j) {
    bar.started(i, j.name);
  };
  obs.progress = [&](std::size_t i, std::uint64_t done, std::uint64_t total) {
    bar.update(i, done, total);
  };
  obs.job_finished = [&](std::size_t i, const jobs::JobOutcome&) { bar.finished(i); };
  std::vector<jobs::JobOutcome> outcomes;
  std::vector<std::string> where;  // where each job ran (ncpath-mpi)
  try {
#ifdef NCPATH_MPI
    std::size_t done = 0;
    obs.job_finished = [&](std::size_t, const jobs::JobOutcome& o) {
      if (!quiet)
        std::fprintf(stderr, "[%zu/%zu] %s %s\n", ++done, batch.jobs.size(), o.name.c_str(),
                     o.status.c_str());
    };
    jobs::MpiBatchResult r = jobs::run_batch_mpi(batch, obs);
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    if (rank != 0) return 0;
    outcomes = std::move(r.outcomes);
    where = std::move(r.where);
#else
    outcomes = jobs::run_batch(batch, obs);
#endif
  } catch (const std::exception& e) {
    bar.clear();
    std::fprintf(stderr, "ncpath: %s\n", e.what());
    return 2;
  }
  int failed = 0;
  for (std::size_t i = 0; i < outcomes.size(); ++i) {
    const jobs::JobOutcome& o = outcomes[i];
    const std::string on = where.empty() ? "" : " on " + where[i];
    if (o.status == "ok") {
      std::printf("  %-24s ok      %spoints in %.2f s (%spoints/s computing), peak RSS %.0f MB%s\n",
                  o.name.c_str(), human(static_cast<double>(o.points)).c_str(), o.seconds,
                  human(o.compute_s > 0 ? o.points / o.compute_s : 0).c_str(),
                  o.peak_rss_bytes / 1048576.0, on.c_str());
      if (!o.message.empty()) std::printf("  %-24s %s\n", "", o.message.c_str());
    } else {
      ++failed;
      std::printf("  %-24s %s: %s%s\n", o.name.c_str(), o.status.c_str(), o.message.c_str(),
                  on.c_str());
    }
  }
  std::printf("ncpath: %zu job(s), %zu ok, %d failed -> %s\n", outcomes.size(),
              outcomes.size() - failed, failed, batch.output.string().c_str());
  if (!write_batch_pictures(batch)) return 2;
  return failed == 0 ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  reexec_with_huge_pages(argv);
#ifdef NCPATH_MPI
  MpiSession mpi(argc, argv);
#endif
  CLI::App app{
      "ncpath: exact cutter-location (CL) data for NC milling, in bulk.\n"
      "Units are mm; CL points are tool-tip positions, tool axis +Z."};
  app.require_subcommand(1);
  app.set_version_flag("--version", NCPATH_VERSION);

  Common rc;
  RasterParams rp;
  std::string direction = "x";
  std::vector<double> rect;
  std::optional<double> floor_z;
  GcodeCli raster_g, drop_g;
  CLI::App* raster = app.add_subcommand("raster", "Zig-zag drop-cutter finishing over a mesh");
  add_common(raster, rc);
  add_gcode(raster, raster_g);
  raster->add_option("--interval", rp.interval, "Distance between scan lines (mm)")
      ->capture_default_str();
  raster->add_option("--step", rp.step, "Sampling step along a scan line (mm)")
      ->capture_default_str();
  raster->add_option("--direction", direction, "Scan lines run along x or y")
      ->check(CLI::IsMember({"x", "y"}))
      ->capture_default_str();
  raster->add_option("--margin", rp.margin, "Grow the part's xy box by this on every side (mm)")
      ->capture_default_str();
  raster->add_option("--rect", rect, "Scan this rectangle instead: x_min y_min x_max y_max (mm)")
      ->expected(4);
  raster
      ->add_option("--adaptive", rp.adaptive_tolerance,
                   "Chordal tolerance of adaptive sampling (mm), 0 = off")
      ->capture_default_str();
  raster->add_option("--min-step", rp.min_step, "Smallest adaptive spacing (mm), 0 = step/64")
      ->capture_default_str();
  raster->add_option("--floor-z", floor_z,
                     "Height where the tool touches nothing (mm); default: the part's lowest z");

  Common scc;
  ScanParams scp;
  std::string families = "x";
  std::vector<double> scan_rect;
  std::optional<double> scan_floor_z;
  GcodeCli scan_g;
  CLI::App* scan = app.add_subcommand(
      "scan",
      "Curve-based drive-plane scanning with a ball-end mill: exact CL curves, junctions and "
      "bi-contact vectors");
  add_common(scan, scc);
  add_gcode(scan, scan_g);
  scan->get_option("--tool")->description("Ball-end mill ball:D (mm); flat and bull are refused");
  scan->add_option("--families", families, "Drive lines along x, along y, or both (x, then y)")
      ->check(CLI::IsMember({"x", "y", "both"}))
      ->capture_default_str();
  scan->add_option("--interval", scp.interval, "Distance between drive planes (mm)")
      ->capture_default_str();
  scan->add_option("--tolerance", scp.tolerance,
                   "Chordal tolerance of the CL polylines (mm); they never dip below the curve")
      ->capture_default_str();
  scan->add_option("--margin", scp.margin, "Grow the part's xy box by this on every side (mm)")
      ->capture_default_str();
  scan->add_option("--rect", scan_rect, "Scan this rectangle instead: x_min y_min x_max y_max (mm)")
      ->expected(4);
  scan->add_option("--floor-z", scan_floor_z,
                   "Height where the tool touches nothing (mm); default: the part's lowest z");

  ZLevelCommand zlevel(app);
  PencilCommand pencil(app);
  FilletCommand fillet(app);

  Common dc;
  std::string points;
  CLI::App* drop = app.add_subcommand("drop", "Drop the tool at given xy points (CSV x,y lines)");
  add_common(drop, dc);
  add_gcode(drop, drop_g);
  drop->add_option("--points", points, "CSV of x,y lines (mm); a blank line starts a new path")
      ->required();

  ProfileCli oc;
  jobs::OffsetParams op;
  CLI::App* offset =
      app.add_subcommand("offset", "Multi-level pocket offset loops of a DXF or TOML profile");
  add_profile(offset, oc);
  add_stepover(offset, oc)->required();
  offset->add_option("--depth", op.depth, "Depth at which loops are written as paths (mm)")
      ->capture_default_str();

  ProfileCli pc;
  pc.stepover = "50%";
  jobs::PocketParams pp;
  std::string order = "outward", milling = "climb";
  CLI::App* pocket = app.add_subcommand(
      "pocket",
      "Linked pocket tool paths (clean-up, entry, depth passes) of a DXF or TOML profile");
  add_profile(pocket, pc);
  add_stepover(pocket, pc)->capture_default_str();
  pocket->add_option("--depth", pp.depth, "Pocket depth below the top z = 0 (mm)")->required();
  pocket->add_option("--stepdown", pp.stepdown, "Depth per pass (mm), 0 = one pass at full depth")
      ->capture_default_str();
  add_order_milling(pocket, order, milling);
  pocket->add_option("--helix-radius", pp.helix_radius, "Helix entry radius (mm), 0 = R/2")
      ->capture_default_str();
  pocket->add_option("--ramp-angle", pp.ramp_angle, "Helix and ramp descent angle (degrees)")
      ->capture_default_str();
  pocket->add_option("--clearance", pp.clearance, "Feed moves start this far above the top (mm)")
      ->capture_default_str();

  ProfileCli sc;
  sc.tool = "";
  jobs::Pocket3dJobParams sp;
  std::string surface, order3 = "outward", milling3 = "climb";
  CLI::App* pocket3d = app.add_subcommand(
      "pocket3d", "Ball-end pocket paths over a sculptured (NURBS) bottom, scallop-height spaced");
  CLI::Option* tolerance3 = add_profile(pocket3d, sc);
  tolerance3->description("NURBS-to-arc tolerance of the profile (mm)")
      ->default_str("min(0.01, eps/4)");
  pocket3d->get_option("--tool")->description("Ball-end mill ball:D (mm)")->required();
  pocket3d
      ->add_option("--surface", surface,
                   "Bottom surface: .toml (docs/profile-format.md, \"Bottom surfaces\")")
      ->required();
  pocket3d->add_option("--scallop", sp.scallop, "Cusp height left between passes (mm), < D/2")
      ->required();
  pocket3d->add_option("--eps", sp.eps, "Plan tolerance of the straight moves (mm)")
      ->capture_default_str();
  pocket3d->add_option("--delta", sp.delta, "Surface tolerance of the straight moves (mm)")
      ->capture_default_str();
  add_order_milling(pocket3d, order3, milling3);
  pocket3d->add_option("--clearance", sp.clearance, "Feed moves start this far above z = 0 (mm)")
      ->capture_default_str();
  pocket3d
      ->add_option("--min-interval", sp.min_interval,
                   "Smallest plan distance between passes (mm), 0 = D/200")
      ->capture_default_str();

  std::string batch_file, batch_out;
  int batch_threads = -1;
  bool batch_quiet = false;
  CLI::App* runc = app.add_subcommand("run", "Run the jobs of a TOML batch file (docs/cli.md)");
  runc->add_option("jobs", batch_file, "Batch file (TOML)")->required();
  runc->add_option("--out", batch_out, "Override the batch file's output path");
  runc->add_option("--threads", batch_threads, "Override the batch file's thread count");
  int batch_concurrent = -1;
  std::string batch_memory;
  runc->add_option("--concurrent-jobs", batch_concurrent,
                   "Jobs at the same time at most, 0 = as many as threads (overrides the file)");
  runc->add_option("--memory-limit", batch_memory,
                   "Memory budget of the jobs running at the same time, e.g. 8G (overrides the "
                   "file; default 3/4 of the memory available)");
  runc->add_flag("-q,--quiet", batch_quiet, "No progress bar");

  std::string batch_report;
  runc->add_option("--report", batch_report,
                   "Also write an HTML page of the results here (overrides the file's 'report')");

  VerifyCli verify_cli;
  CLI::App* verifyc = add_verify_command(app, verify_cli);
  PictureCli preview_cli, report_cli;
  CLI::App* previewc = add_preview_command(app, preview_cli);
  CLI::App* reportc = add_report_command(app, report_cli);

  CLI11_PARSE(app, argc, argv);
  if (verifyc->parsed()) return run_verify_command(verify_cli);
  if (previewc->parsed()) return run_preview_command(preview_cli);
  if (reportc->parsed()) return run_report_command(report_cli);

  jobs::BatchSpec batch;
  bool quiet = false;
  if (raster->parsed()) {
    jobs::JobSpec j = job_from(rc, jobs::Operation::kRaster);
    rp.direction = direction == "y" ? ScanDirection::kY : ScanDirection::kX;
    if (rect.size() == 4) rp.rect = std::array<double, 4>{rect[0], rect[1], rect[2], rect[3]};
    rp.floor_z = floor_z;
    j.raster = rp;
    add_mesh_job(rc, raster_g, std::move(j), validate(rp), batch, quiet);
  } else if (scan->parsed()) {
    jobs::JobSpec j = job_from(scc, jobs::Operation::kScan);
    std::string e = jobs::parse_families(families, scp.families);
    if (!e.empty()) e = "families " + e;
    if (scan_rect.size() == 4)
      scp.rect = std::array<double, 4>{scan_rect[0], scan_rect[1], scan_rect[2], scan_rect[3]};
    scp.floor_z = scan_floor_z;
    j.scan = scp;
    add_mesh_job(scc, scan_g, std::move(j), e.empty() ? validate(scp) : e, batch, quiet);
  } else if (zlevel.parsed()) {
    zlevel.add_job(batch, quiet);
  } else if (pencil.parsed()) {
    pencil.add_job(batch, quiet);
  } else if (fillet.parsed()) {
    fillet.add_job(batch, quiet);
  } else if (offset->parsed()) {
    add_profile_job(
        oc, jobs::Operation::kOffset,
        [&](jobs::JobSpec& j) {
          j.offset = op;
          j.offset.stock = oc.stock;
          j.offset.tolerance = oc.tolerance;
          j.offset.join_tolerance = oc.join_tolerance;
          std::string e = jobs::parse_stepover(oc.stepover, j.tool, j.offset.stepover);
          return e.empty() ? jobs::validate(j.offset) : e;
        },
        batch, quiet);
  } else if (pocket->parsed()) {
    add_profile_job(
        pc, jobs::Operation::kPocket,
        [&](jobs::JobSpec& j) {
          j.pocket = pp;
          j.pocket.stock = pc.stock;
          j.pocket.tolerance = pc.tolerance;
          j.pocket.join_tolerance = pc.join_tolerance;
          std::string e = jobs::parse_stepover(pc.stepover, j.tool, j.pocket.stepover);
          if (e.empty()) e = order_milling(order, milling, j.pocket.order, j.pocket.milling);
          return e.empty() ? jobs::validate(j.pocket, j.tool) : e;
        },
        batch, quiet);
    // The pocket's rapids run at the safe height even without G-code.
    batch.jobs.back().gcode_safe_z = pc.gcode.safe_z;
  } else if (pocket3d->parsed()) {
    add_profile_job(
        sc, jobs::Operation::kPocket3d,
        [&](jobs::JobSpec& j) {
          j.surface = surface;
          j.pocket3d = sp;
          j.pocket3d.stock = sc.stock;
          j.pocket3d.tolerance =
              tolerance3->count() > 0 ? sc.tolerance : jobs::default_pocket3d_tolerance(sp.eps);
          j.pocket3d.join_tolerance = sc.join_tolerance;
          const std::string e =
              order_milling(order3, milling3, j.pocket3d.order, j.pocket3d.milling);
          return e.empty() ? jobs::validate(j.pocket3d, j.tool) : e;
        },
        batch, quiet);
    batch.jobs.back().gcode_safe_z = sc.gcode.safe_z;
  } else if (drop->parsed()) {
    jobs::JobSpec j = job_from(dc, jobs::Operation::kDrop);
    j.points = points;
    add_mesh_job(dc, drop_g, std::move(j), "", batch, quiet);
  } else {
    try {
      batch = jobs::parse_batch_file(batch_file);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "ncpath: %s\n", e.what());
      return 2;
    }
    if (!batch_out.empty()) batch.output = batch_out;
    if (!batch_report.empty()) batch.report = batch_report;
    if (batch_threads >= 0) batch.threads = batch_threads;
    if (batch_concurrent >= 0) batch.concurrent_jobs = batch_concurrent;
    if (!batch_memory.empty())
      if (const std::string e = jobs::parse_byte_size(batch_memory, batch.memory_limit);
          !e.empty()) {
        std::fprintf(stderr, "ncpath: --memory-limit %s\n", e.c_str());
        return 2;
      }
    if (batch.output.empty()) {
      std::fprintf(stderr, "ncpath: %s: no output file: set 'output' or pass --out\n",
                   batch_file.c_str());
      return 2;
    }
    quiet = batch_quiet;
  }
  return run(batch, quiet);
}
