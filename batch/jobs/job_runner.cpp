#include "batch/jobs/job_runner.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <stdexcept>

#include "batch/io/mesh_reader.hpp"
#include "batch/jobs/batch_schedule.hpp"
#include "batch/jobs/fillet_job.hpp"
#include "batch/jobs/job_verify.hpp"
#include "batch/jobs/offset_job.hpp"
#include "batch/jobs/ordered_output.hpp"
#include "batch/jobs/pencil_job.hpp"
#include "batch/jobs/pocket3d_job.hpp"
#include "batch/jobs/pocket_job.hpp"
#include "batch/jobs/profile_input.hpp"
#include "batch/jobs/points_csv.hpp"
#include "batch/jobs/scan_job.hpp"
#include "batch/jobs/shared_mesh.hpp"
#include "batch/jobs/zlevel_job.hpp"
#include "batch/output/cl_writer.hpp"
#include "engine/chord_guard.hpp"
#include "engine/drop_points.hpp"
#include "engine/parallel.hpp"
#include "engine/raster.hpp"
#include "engine/run_control.hpp"

namespace ncpath::jobs {

namespace {

using out::StatValue;

std::int64_t i64(std::uint64_t v) { return static_cast<std::int64_t>(v); }

// The mesh's swept-tool index for the chord guard; its build time (0 when the job's verifier
// or an earlier job on the same mesh built it) as the statistic swept_index_s.
std::shared_ptr<const MeshVerifier> timed_swept_index(SharedMesh& shared,
                                                      std::vector<StatValue>& stats) {
  Stopwatch clock;
  std::shared_ptr<const MeshVerifier> index = shared.swept_index();
  stats.push_back({"swept_index_s", clock.seconds(), "s"});
  return index;
}

// Runs the raster, scan, zlevel, pencil, fillet or drop operation on the job's (shared,
// transformed) mesh into cl.
void run_mesh_job(const JobSpec& job, const MeshUse& use, out::ClJob& cl,
                  const std::function<out::GcodeWriter*(double part_top)>& open_gcode,
                  RunControl& control, std::vector<StatValue>& stats, JobOutcome& o,
                  std::unique_ptr<JobVerifier>& verifier) {
  SharedMesh& shared = *use.mesh;
  // A job sharing a product of the mesh frees it when it is the last to need it, however it
  // ends.
  struct Release {
    SharedMesh& mesh;
    const std::string& product;
    ~Release() {
      if (!product.empty()) mesh.release(product);
    }
  } release{shared, use.product};
  const io::MeshReadResult& in = shared.in();
  stats.push_back({"input_format", in.stats.format, ""});
  stats.push_back({"facets_in_file", i64(in.stats.facets_in_file), ""});
  stats.push_back({"facets_read", i64(in.stats.facets_read), ""});
  stats.push_back({"facets_skipped_degenerate_in_file", i64(in.stats.facets_degenerate), ""});
  stats.push_back({"transform_scale", shared.transform_scale(), ""});
  stats.push_back({"read_s", use.seconds, "s"});
  stats.push_back({"mesh_shared", std::int64_t{use.shared}, ""});
  // The point operation is a probe: its points are answers, not moves to run.
  // Its index is built at the first check (statistic verify_index_s).
  if (job.verify != VerifyMode::kOff && job.operation != Operation::kDrop) {
    verifier = mesh_verifier(job, [mesh = use.mesh] { return mesh->swept_index(); });
    if (verifier) verifier->attach(cl);
  }

  const TriangleMesh& mesh = shared.mesh();
  out::GcodeWriter* gcode = open_gcode(bounding_box(mesh).hi.z());
  // Z-level, pencil and fillet jobs slice the mesh conditioned: once for them when shared.
  std::shared_ptr<const ConditionedMesh> conditioned;
  if (use.product == "conditioned") {
    Stopwatch clock;
    conditioned = shared.conditioned();
    stats.push_back({"conditioned_wait_s", clock.seconds(), "s"});
  }
  if (product_name(job) == "conditioned")
    stats.push_back({"conditioned_shared", std::int64_t{use.product_shared}, ""});
  if (job.operation == Operation::kScan) {
    const ScanJobSummary r =
        run_scan_job(job, mesh, cl, gcode, control, stats, use.product.empty() ? nullptr : &shared,
                     use.product_shared);
    o.points = r.points;
    o.compute_s = r.compute_s;
    return;
  }
  if (job.operation == Operation::kZLevel) {
    const ZLevelJobSummary r =
        run_zlevel_job(job, mesh, cl, gcode, control, stats, conditioned.get());
    o.points = r.points;
    o.compute_s = r.compute_s;
    return;
  }
  // Pencil and fillet jobs ask for the swept-tool index after their computation.
  const SweptIndexSource swept = [&] { return timed_swept_index(shared, stats); };
  if (job.operation == Operation::kPencil) {
    const PencilJobSummary r = run_pencil_job(job, mesh, swept, cl, gcode, control, stats,
                                              conditioned.get());
    o.points = r.points;
    o.compute_s = r.compute_s;
    return;
  }
  if (job.operation == Operation::kFillet) {
    const FilletJobSummary r = run_fillet_job(job, mesh, swept, cl, gcode, control, stats,
                                              conditioned.get());
    o.points = r.points;
    o.compute_s = r.compute_s;
    return;
  }
  // Raster chords between exact drop points are lifted where they would cut in (the drop
  // operation's points are answers, not moves).
  std::optional<ChordGuard> guard;
  if (job.operation == Operation::kRaster)
    guard.emplace(timed_swept_index(shared, stats), job.tool);
  // The guard checks every move with the verifier's kernel, tool (the job's, no stock) and
  // floor: in full mode the verifier takes those checks instead of making them again.
  const bool share_checks = guard && verifier && job.verify == VerifyMode::kFull;
  auto sink = [&](const ClChunk& raw) {
    PrecheckedMoves checked;
    const ClChunk guarded = guard ? guard->apply(raw, share_checks ? &checked : nullptr) : ClChunk{};
    if (share_checks) verifier->use_prechecked(std::move(checked));
    const ClChunk& c = guard ? guarded : raw;
    cl.append_paths(c.xyz, c.contact, c.path_sizes, c.path_kinds);
    if (gcode) gcode->append(c);
  };
  // Statistics raster and drop both have (scan, zlevel, pencil and fillet write their own,
  // see scan_job.cpp, zlevel_job.cpp, pencil_job.cpp, fillet_job.cpp).
  auto common = [&](std::uint64_t facets, std::uint64_t degenerate, double index_s,
                    double compute_s, double sink_s) {
    o.compute_s = compute_s;
    stats.push_back({"facets_skipped_degenerate", i64(degenerate), ""});
    stats.push_back({"facets_used", i64(facets), ""});
    stats.push_back({"index_build_s", index_s, "s"});
    stats.push_back({"compute_s", compute_s, "s"});
    stats.push_back({"write_s", sink_s, "s"});
    stats.push_back({"points", i64(o.points), ""});
  };
  if (job.operation == Operation::kRaster) {
    const RasterStats st = run_raster(mesh, job.tool, job.raster, sink, control);
    o.points = st.cut_points + st.link_points + guard->stats().points_added;
    push_guard_stats(*guard, stats);
    common(st.facets, st.facets_degenerate, st.index_s, st.compute_s,
           st.sink_s - guard->seconds());  // the guard runs in the sink, before the writer
    stats.push_back({"lines", i64(st.lines), ""});
    stats.push_back({"cut_points", i64(st.cut_points), ""});
    stats.push_back({"link_points", i64(st.link_points), ""});
    stats.push_back({"adaptive_points", i64(st.adaptive_points), ""});
    stats.push_back({"floor_points", i64(st.floor_points), ""});
    stats.push_back({"floor_z", st.floor_z, "mm"});
    stats.push_back({"scan_x_min", st.rect[0], "mm"});
    stats.push_back({"scan_y_min", st.rect[1], "mm"});
    stats.push_back({"scan_x_max", st.rect[2], "mm"});
    stats.push_back({"scan_y_max", st.rect[3], "mm"});
    if (job.raster.bands > 1)  // a band of a split job: how join_bands interleaves the bands
      cl.write_array("band", "strip_paths", st.strip_paths, 0, "",
                     "paths of each strip of this band, in order (split_job.hpp)");
  } else {
    const PointList pts = read_points_csv(job.points);
    const DropPointsStats st =
        run_drop_points(mesh, job.tool, pts.xy, pts.path_sizes, sink, control);
    o.points = st.points;
    common(st.facets, st.facets_degenerate, st.index_s, st.compute_s, st.sink_s);
    stats.push_back({"no_contact_points", i64(st.no_contact), ""});
  }
}

// Runs one job; fills stats and returns the outcome. Never throws for job-level problems.
JobOutcome run_one(const JobSpec& job, std::size_t index, MeshCache& meshes, out::ClJob& cl,
                   const BatchObserver& obs, RunControl& control, std::vector<StatValue>& stats) {
  if (obs.progress)
    control.progress = [&obs, index](std::uint64_t done, std::uint64_t total) {
      obs.progress(index, done, total);
    };
  JobOutcome o;
  o.name = job.name;
  Stopwatch all;
  // A failed job's message also carries what the reading had to guess (units read as mm may
  // be why the tool does not fit).
  auto fail = [&](const char* status, const std::string& message) {
    o.status = status;
    o.message = message;
    if (const std::string input = input_warning(stats); !input.empty())
      o.message += "; " + input;
  };
  if (!job.error.empty()) {
    fail(job.error_status.c_str(), job.error);
  } else
    try {
      // The G-code writer is opened once the part's top is known (mesh jobs read it first).
      std::optional<out::GcodeWriter> gcode;
      auto open_gcode = [&](double part_top) -> out::GcodeWriter* {
        if (job.gcode.empty()) return nullptr;
        out::GcodeParams gp = job.gcode_params;
        gp.job_name = job.name;
        gp.safe_z = job.gcode_safe_z.value_or(part_top + kDefaultSafeAboveTop);
        if (gp.safe_z < part_top)
          throw std::invalid_argument("gcode.safe_z " + std::to_string(gp.safe_z) +
                                      " mm is below the part's top " + std::to_string(part_top) +
                                      " mm: rapids would hit it");
        gcode.emplace(job.gcode, gp);
        return &*gcode;
      };
      std::unique_ptr<JobVerifier> verifier;
      const bool profile_op = job.operation == Operation::kOffset ||
                              job.operation == Operation::kPocket ||
                              job.operation == Operation::kPocket3d;
      if (profile_op && job.verify != VerifyMode::kOff) {
        verifier = profile_verifier(job);
        verifier->attach(cl);
      }
      if (job.operation == Operation::kOffset) {
        const OffsetJobSummary r = run_offset_job(job, cl, open_gcode(0.0), stats);
        o.points = r.points;
        o.compute_s = r.compute_s;
      } else if (job.operation == Operation::kPocket) {
        const PocketJobSummary r = run_pocket_job(job, cl, open_gcode(0.0), stats);
        o.points = r.points;
        o.compute_s = r.compute_s;
      } else if (job.operation == Operation::kPocket3d) {
        const Pocket3dJobSummary r = run_pocket3d_job(job, cl, open_gcode(0.0), stats);
        o.points = r.points;
        o.compute_s = r.compute_s;
      } else {
        run_mesh_job(job, meshes.get(index), cl, open_gcode, control, stats, o, verifier);
      }
      std::string verify_failure, bound_warning;
      if (verifier) {
        verify_failure = verification_failure(verifier->finish(stats));
        bound_warning = verifier->bound_warning();
        verifier->write_worst(cl);
      }
      if (gcode) {
        gcode->finish();
        const out::GcodeStats& gs = gcode->stats();
        stats.push_back({"gcode_arcs", gs.arcs, ""});
        stats.push_back({"gcode_lines", gs.lines, ""});
        stats.push_back({"gcode_retractions", gs.retractions, ""});
      }
      stats.push_back({"points_per_s", o.compute_s > 0 ? o.points / o.compute_s : 0.0, "1/s"});
      o.status = verify_failure.empty() ? "ok" : "failed_verification";
      o.message = verify_failure.empty() ? ok_job_warning(stats) : verify_failure;
      // A band of a split job may lie beside the part: join_bands judges the whole job.
      const bool band = job.operation == Operation::kRaster && job.raster.bands > 1;
      if (verify_failure.empty() && !band) o.message = with_nothing_to_cut(job, o.points, o.message);
      if (verify_failure.empty() && !bound_warning.empty())
        o.message = o.message.empty() ? bound_warning : o.message + "; " + bound_warning;
    } catch (const io::ReadError& e) {
      fail("invalid_input", e.what());
    } catch (const std::invalid_argument& e) {
      fail("invalid_parameter", e.what());
    } catch (const Cancelled&) {
      fail("cancelled", "cancelled by the user");
    } catch (const std::bad_alloc&) {
      fail("out_of_memory", "ran out of memory");
    } catch (const std::exception& e) {
      fail("internal_error", e.what());
    }
  o.seconds = all.seconds();
  o.peak_rss_bytes = peak_rss_bytes();
  stats.push_back({"total_s", o.seconds, "s"});
  stats.push_back({"peak_rss_bytes", i64(o.peak_rss_bytes), "bytes"});
  stats.push_back({"threads", std::int64_t{par::max_threads()}, ""});
  return o;
}

}  // namespace

std::string nothing_to_cut_warning(const JobSpec& job) {
  std::string why;
  char diameter[32];
  std::snprintf(diameter, sizeof diameter, "%g", 2 * job.tool.radius);
  switch (job.operation) {
    case Operation::kOffset:
    case Operation::kPocket:
    case Operation::kPocket3d:
      why = std::string("the tool (diameter ") + diameter +
            " mm, with its stock) fits in none of the profile's regions";
      break;
    case Operation::kPencil:
    case Operation::kFillet:
      why = "the part has no concave crease for this tool";
      break;
    case Operation::kZLevel:
      why = "no level meets the part";
      break;
    default:
      why = "no point of the job lies on the part";
  }
  return "warning: nothing to cut (0 points): " + why;
}

std::string with_nothing_to_cut(const JobSpec& job, std::uint64_t points,
                                const std::string& message) {
  if (points > 0) return message;
  const std::string none = nothing_to_cut_warning(job);
  return message.empty() ? none : none + "; " + message;
}

std::string input_warning(const std::vector<out::StatValue>& stats) {
  for (const out::StatValue& s : stats)
    if (const std::string* v = std::get_if<std::string>(&s.value); v && s.name == kInputWarningStat)
      return "warning: " + *v;
  return "";
}

std::string ok_job_warning(const std::vector<out::StatValue>& stats) {
  std::string out = input_warning(stats);
  const std::string chains = open_chain_warning(stats);
  if (!chains.empty()) out = out.empty() ? chains : out + "; " + chains;
  return out;
}

std::string open_chain_warning(const std::vector<out::StatValue>& stats) {
  for (const out::StatValue& s : stats)
    if ((s.name == "open_chains" || s.name == "zlevel_open_chains") &&
        std::holds_alternative<std::int64_t>(s.value) && std::get<std::int64_t>(s.value) > 0)
      return "warning: " + std::to_string(std::get<std::int64_t>(s.value)) +
             " z-level contour chain(s) could not be closed and are left out (stats/" + s.name +
             "); please report the mesh";
  return "";
}

namespace {

// The SHA-256 of each input file, computed once; jobs on other files do not wait for it.
class ShaCache {
 public:
  std::string get(const std::filesystem::path& input) {
    Entry* e;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      e = &sha_[input.string()];
    }
    const std::lock_guard<std::mutex> lock(e->mutex);
    if (!e->done) try {
        e->sha = out::sha256_file(input);
        e->done = true;
      } catch (const std::exception&) {
        return "";  // unreadable input: the job reports why (a later job tries again)
      }
    return e->sha;
  }

 private:
  struct Entry {
    std::mutex mutex;
    std::string sha;
    bool done = false;
  };
  std::mutex mutex_;                  // the map
  std::map<std::string, Entry> sha_;  // entries stay put
};

// One batch run: the jobs as tasks, started by `admission`, written by `output`.
class BatchRun {
 public:
  BatchRun(const BatchSpec& batch, const BatchObserver& obs, out::ClFile& file)
      : batch_(batch),
        obs_(obs),
        meshes_(batch.jobs),
        output_(file, batch.jobs.size()),
        admission_(estimates(batch),
                   batch.memory_limit ? batch.memory_limit : default_memory_limit(),
                   batch.concurrent_jobs > 0 ? static_cast<std::size_t>(batch.concurrent_jobs)
                                             : static_cast<std::size_t>(par::max_threads())),
        outcomes_(batch.jobs.size()) {}

  // Runs every job; rethrows the first error of the output file (the batch stops starting
  // jobs then, and lets the running ones end).
  std::vector<JobOutcome> run() {
    launch_ready();
    tasks_.wait();
    if (error_) std::rethrow_exception(error_);
    return std::move(outcomes_);
  }

 private:
  static std::vector<std::uint64_t> estimates(const BatchSpec& batch) {
    std::vector<std::uint64_t> e;
    for (const JobSpec& job : batch.jobs) e.push_back(estimate_job_bytes(job));
    return e;
  }

  void launch_ready() {
    std::vector<std::size_t> ready;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      if (!error_) ready = admission_.start_ready();
    }
    for (const std::size_t i : ready)
      tasks_.run([this, i] { run_job(i); },
                 [this, i] {
                   {
                     const std::lock_guard<std::mutex> lock(mutex_);
                     admission_.finished(i);
                   }
                   launch_ready();
                 });
  }

  // Runs job i; never throws. An error of the output file stops the batch: no more jobs
  // start and the running ones are cancelled.
  void run_job(std::size_t i) {
    const JobSpec& job = batch_.jobs[i];
    JobOutcome& o = outcomes_[i];
    RunControl control;
    watch(&control, true);
    bool mesh_done = false;
    try {
      if (obs_.job_started) obs_.job_started(i, batch_.jobs.size(), job);
      out::JobInfo info;
      info.operation = operation_name(job.operation);
      info.input_path = job.input.string();
      info.input_sha256 = shas_.get(job.input);
      info.tool_json = job.error.empty() ? tool_json(job.tool) : "{}";
      info.params_json = params_json(job);
      out::ClJob cl = output_.begin(i, job.name, info);
      std::vector<StatValue> stats;
      o = run_one(job, i, meshes_, cl, obs_, control, stats);
      if (batch_.mpi_rank >= 0) stats.push_back({"mpi_rank", std::int64_t{batch_.mpi_rank}, ""});
      meshes_.done(i);  // before writing: a mesh no later job needs is freed now
      mesh_done = true;
      cl.set_status(o.status, o.message);
      cl.write_stats(stats);
      cl.close();
      output_.finished(i);
    } catch (...) {
      stop(std::current_exception());
      if (o.status.empty()) o = {job.name, "io_error", "the batch stopped: the output failed"};
    }
    if (!mesh_done) meshes_.done(i);
    watch(&control, false);
    if (obs_.job_finished) obs_.job_finished(i, o);
  }

  void watch(RunControl* control, bool on) {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (on && error_) control->cancel = true;
    if (on)
      controls_.insert(control);
    else
      controls_.erase(control);
  }

  void stop(std::exception_ptr error) {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (!error_) error_ = error;
    for (RunControl* c : controls_) c->cancel = true;
  }

  const BatchSpec& batch_;
  const BatchObserver& obs_;
  MeshCache meshes_;  // meshes read once, shared by their jobs
  ShaCache shas_;
  OrderedOutput output_;
  std::mutex mutex_;  // admission_, error_ and controls_
  Admission admission_;
  std::exception_ptr error_;
  std::set<RunControl*> controls_;  // of the running jobs
  std::vector<JobOutcome> outcomes_;
  par::TaskGroup tasks_;
};

}  // namespace

std::vector<JobOutcome> run_batch(const BatchSpec& batch, const BatchObserver& obs) {
  par::ThreadLimit limit(batch.threads);
  // The output's folder is created if needed (a batch file may name out/run.h5).
  if (const auto dir = batch.output.parent_path(); !dir.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec)
      throw std::runtime_error(dir.string() + ": cannot create the output folder: " + ec.message());
  }
  out::ClFile file(batch.output, NCPATH_VERSION);
  const auto jobs = static_cast<std::int64_t>(batch.jobs.size());
  file.mark_batch(jobs, false);
  std::vector<JobOutcome> outcomes = BatchRun(batch, obs, file).run();
  file.mark_batch(jobs, true);
  file.close();
  return outcomes;
}

}  // namespace ncpath::jobs
