#include "batch/jobs/split_job.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <set>
#include <stdexcept>
#include <string_view>
#include <variant>

#include "batch/jobs/job_runner.hpp"
#include "batch/jobs/job_verify.hpp"
#include "batch/output/cl_reader.hpp"
#include "engine/run_control.hpp"
#include "engine/verify_report.hpp"

namespace ncpath::jobs {

bool splittable(const JobSpec& job) {
  return job.error.empty() && job.operation == Operation::kRaster && job.gcode.empty() &&
         job.verify != VerifyMode::kSample;
}

JobSpec band_job(const JobSpec& job, std::uint32_t band, std::uint32_t bands) {
  JobSpec b = job;
  b.raster.band = band;
  b.raster.bands = bands;
  return b;
}

StatMerge split_stat_rule(const out::StatValue& stat) {
  static const std::set<std::string_view> sum = {"points",
                                                 "lines",
                                                 "cut_points",
                                                 "link_points",
                                                 "adaptive_points",
                                                 "floor_points",
                                                 "chord_guard_moves",
                                                 "chord_guard_lifted",
                                                 "chord_guard_points_added",
                                                 "chord_guard_raised",
                                                 "verify_moves"};
  static const std::set<std::string_view> max = {"chord_guard_max_lift", "chord_guard_max_raise",
                                                 "verify_max_gouge",
                                                 "peak_rss_bytes"};
  static const std::set<std::string_view> min = {"verify_min_clearance",
                                                 "verify_min_rapid_clearance"};
  if (stat.name == "total_s" || stat.name == "points_per_s") return StatMerge::kJob;
  if (stat.name == "mpi_rank") return StatMerge::kFirst;
  if (sum.count(stat.name) || stat.unit == "s") return StatMerge::kSum;
  if (max.count(stat.name)) return StatMerge::kMax;
  if (min.count(stat.name)) return StatMerge::kMin;
  return StatMerge::kSame;
}

namespace {

bool same_value(const out::StatValue& a, const out::StatValue& b) {
  const auto* x = std::get_if<double>(&a.value);
  const auto* y = std::get_if<double>(&b.value);
  if (x && y && std::isnan(*x) && std::isnan(*y)) return true;
  return a.value == b.value;
}

// Folds band value `b` into `into` by `rule` (both of one type).
void fold(out::StatValue& into, const out::StatValue& b, StatMerge rule) {
  if (into.value.index() != b.value.index() || into.unit != b.unit)
    throw std::logic_error("statistic '" + into.name + "' has another type or unit in a band");
  if (rule == StatMerge::kSame && !same_value(into, b))
    throw std::logic_error("statistic '" + into.name +
                           "' differs between the bands and has no merge rule");
  if (rule != StatMerge::kSum && rule != StatMerge::kMax && rule != StatMerge::kMin) return;
  std::visit(
      [&](auto& v) {
        using T = std::decay_t<decltype(v)>;
        if constexpr (!std::is_same_v<T, std::string>) {
          const T w = std::get<T>(b.value);
          v = rule == StatMerge::kSum   ? v + w
              : rule == StatMerge::kMax ? std::max(v, w)
                                        : std::min(v, w);
        }
      },
      into.value);
}

}  // namespace

std::vector<out::StatValue> merge_band_stats(
    const std::vector<std::vector<out::StatValue>>& bands) {
  std::vector<out::StatValue> merged = bands.at(0);
  for (std::size_t b = 1; b < bands.size(); ++b) {
    if (bands[b].size() != merged.size())
      throw std::logic_error("band " + std::to_string(b) + " wrote other statistics than band 0");
    for (std::size_t i = 0; i < merged.size(); ++i) {
      if (bands[b][i].name != merged[i].name)
        throw std::logic_error("band " + std::to_string(b) + " wrote statistic '" +
                               bands[b][i].name + "' where band 0 wrote '" + merged[i].name + "'");
      fold(merged[i], bands[b][i], split_stat_rule(merged[i]));
    }
  }
  return merged;
}

namespace {

template <class T>
T stat_or(const std::vector<out::StatValue>& stats, std::string_view name, T fallback) {
  for (const out::StatValue& s : stats)
    if (s.name == name)
      if (const T* v = std::get_if<T>(&s.value)) return *v;
  return fallback;
}

template <class T>
void set_stat(std::vector<out::StatValue>& stats, std::string_view name, T value) {
  for (out::StatValue& s : stats)
    if (s.name == name) s.value = value;
}

// Where one strip of a band went in the job: its first path and move in the band and in the
// job.
struct Placement {
  std::uint64_t band_path = 0, band_move = 0, job_path = 0, job_move = 0;
};

// The number of paths of each of the band's strips (band/strip_paths; a job of one band
// that has none: all its `paths` as one strip).
std::vector<double> strip_paths(const Band& band, const std::string& job, std::size_t bands,
                                std::size_t paths) {
  if (auto a = out::read_float64_array(band.file, job, "band/strip_paths")) return a->data;
  if (bands == 1) return {static_cast<double>(paths)};
  throw std::runtime_error(band.file.string() + ": a band without band/strip_paths");
}

// Appends the bands' paths to cl strip by strip, the bands in turn (the job's strip s is strip
// s / n of band s % n: engine/raster.hpp), and returns where each band's strips went.
std::vector<std::vector<Placement>> interleave_paths(const std::vector<Band>& bands,
                                                     const std::string& job, out::ClJob& cl) {
  const std::size_t n = bands.size();
  std::vector<std::unique_ptr<out::PathReader>> readers;
  std::vector<std::vector<double>> strips;
  std::size_t total = 0;
  for (const Band& b : bands) {
    readers.push_back(std::make_unique<out::PathReader>(b.file, job));
    strips.push_back(strip_paths(b, job, n, readers.back()->paths()));
    total += strips.back().size();
  }
  std::vector<std::vector<Placement>> placed(n);
  std::vector<Placement> next(n);  // each band's next path and move (band_path, band_move)
  std::uint64_t job_path = 0, job_move = 0;
  ClChunk c;
  for (std::size_t s = 0; s < total; ++s) {
    const std::size_t b = s % n;
    if (s / n >= strips[b].size())
      throw std::runtime_error("band " + std::to_string(b) + " has too few strips");
    const auto count = static_cast<std::size_t>(strips[b][s / n]);
    readers[b]->read(next[b].band_path, count, c);
    cl.append_paths(c.xyz, c.contact, c.path_sizes, c.path_kinds);
    placed[b].push_back({next[b].band_path, next[b].band_move, job_path, job_move});
    const std::uint64_t moves = move_count(c);
    next[b].band_path += count;
    next[b].band_move += moves;
    job_path += count;
    job_move += moves;
  }
  for (std::size_t b = 0; b < n; ++b)
    if (next[b].band_path != readers[b]->paths())
      throw std::runtime_error("band " + std::to_string(b) + " has paths outside its strips");
  return placed;
}

// A band's verification report from its file, its moves and paths numbered job-wide.
VerifyReport band_report(const std::vector<out::StatValue>& stats, const out::Float64Array& worst,
                         const std::vector<Placement>& placed) {
  VerifyReport r;
  r.moves = static_cast<std::uint64_t>(stat_or<std::int64_t>(stats, "verify_moves", 0));
  r.max_gouge = stat_or(stats, "verify_max_gouge", 0.0);
  r.min_clearance = stat_or(stats, "verify_min_clearance", r.min_clearance);
  r.min_rapid_clearance = stat_or(stats, "verify_min_rapid_clearance", r.min_rapid_clearance);
  r.worst = violations_from_rows(worst.data);
  for (VerifyViolation& v : r.worst) {
    auto it = std::upper_bound(placed.begin(), placed.end(), std::uint64_t{v.path},
                               [](std::uint64_t p, const Placement& q) { return p < q.band_path; });
    if (it == placed.begin()) throw std::runtime_error("a violation outside the band's paths");
    --it;
    v.move = it->job_move + (v.move - it->band_move);
    v.path = static_cast<std::uint32_t>(it->job_path + (v.path - it->band_path));
  }
  return r;
}

// "0 1 2": the rank of each band, in band order.
std::string band_ranks(const std::vector<Band>& bands) {
  std::string s;
  for (const Band& b : bands) {
    if (!s.empty()) s += ' ';
    s += std::to_string(b.rank);
  }
  return s;
}

// "12.301 11.874": each band's wall time, s.
std::string band_seconds(const std::vector<Band>& bands) {
  std::string s;
  for (const Band& b : bands) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%s%.3f", s.empty() ? "" : " ", b.outcome.seconds);
    s += buf;
  }
  return s;
}

// The job with the status and message of its first band that failed other than by its
// verification (or wrote no file), and no paths; false when there is none.
bool write_failed_band(out::ClFile& file, const JobSpec& job, const std::vector<Band>& bands,
                       double seconds, JobOutcome& o) {
  for (std::size_t b = 0; b < bands.size(); ++b) {
    const JobOutcome& bo = bands[b].outcome;
    const bool failed = bo.status != "ok" && bo.status != "failed_verification";
    if (!failed && std::filesystem::exists(bands[b].file)) continue;
    o.status = bo.status;
    o.message = bo.message + " (band " + std::to_string(b) + " of " + std::to_string(bands.size()) +
                ", rank " + std::to_string(bands[b].rank) + ")";
    out::JobInfo info;
    info.operation = operation_name(job.operation);
    info.input_path = job.input.string();
    info.tool_json = tool_json(job.tool);
    info.params_json = params_json(job);
    out::ClJob cl = file.begin_job(job.name, info);
    cl.set_status(o.status, o.message);
    const std::vector<out::StatValue> stats = {
        {"total_s", seconds, "s"},
        {"mpi_bands", static_cast<std::int64_t>(bands.size()), ""},
        {"mpi_band_ranks", band_ranks(bands), ""}};
    cl.write_stats(stats);
    cl.close();
    return true;
  }
  return false;
}

}  // namespace

JobOutcome join_bands(out::ClFile& file, const JobSpec& job, const std::vector<Band>& bands,
                      double waited_s) {
  Stopwatch clock;
  JobOutcome o;
  o.name = job.name;
  o.seconds = waited_s;
  if (write_failed_band(file, job, bands, waited_s, o)) return o;
  const out::StoredJob first = out::read_jobs(bands.at(0).file).at(0);
  out::JobInfo info{first.operation, first.input_path, first.input_sha256, first.tool_json,
                    first.params_json};
  out::ClJob cl = file.begin_job(job.name, info);
  const std::vector<std::vector<Placement>> placed = interleave_paths(bands, job.name, cl);
  VerifyReport report;
  bool verified = false;
  std::vector<std::vector<out::StatValue>> stats;
  for (std::size_t b = 0; b < bands.size(); ++b) {
    stats.push_back(out::read_stats(bands[b].file, job.name));
    if (auto worst = out::read_float64_array(bands[b].file, job.name, "verify/worst")) {
      verified = true;
      report.merge(band_report(stats.back(), *worst, placed[b]));
    }
  }
  if (verified) write_verify_worst(cl, report);
  std::vector<out::StatValue> merged = merge_band_stats(stats);
  o.points = static_cast<std::uint64_t>(stat_or<std::int64_t>(merged, "points", 0));
  o.compute_s = stat_or(merged, "compute_s", 0.0);
  o.peak_rss_bytes = static_cast<std::uint64_t>(stat_or<std::int64_t>(merged, "peak_rss_bytes", 0));
  const double join_s = clock.seconds();
  o.seconds = waited_s + join_s;
  set_stat(merged, "total_s", o.seconds);
  set_stat(merged, "points_per_s", o.compute_s > 0 ? o.points / o.compute_s : 0.0);
  merged.push_back({"mpi_bands", static_cast<std::int64_t>(bands.size()), ""});
  merged.push_back({"mpi_band_ranks", band_ranks(bands), ""});
  merged.push_back({"mpi_band_seconds", band_seconds(bands), "s"});
  merged.push_back({"mpi_join_s", join_s, "s"});
  const std::string failure = verification_failure(report);
  o.status = failure.empty() ? "ok" : "failed_verification";
  for (const Band& b : bands)
    if (o.message.empty()) o.message = b.outcome.message;
  if (failure.empty()) o.message = with_nothing_to_cut(job, o.points, o.message);
  if (!failure.empty()) o.message = failure;
  cl.set_status(o.status, o.message);
  cl.write_stats(merged);
  cl.close();
  return o;
}

}  // namespace ncpath::jobs
