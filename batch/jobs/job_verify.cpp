#include "batch/jobs/job_verify.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <variant>

#include <nlohmann/json.hpp>

#include "batch/io/surface_toml.hpp"
#include "batch/jobs/profile_input.hpp"
#include "engine/run_control.hpp"
#include "engine/verify_mesh.hpp"
#include "engine/verify_profile.hpp"
#include "engine/verify_surface.hpp"
#include "kernels/mesh/mesh_transform.hpp"

namespace ncpath::jobs {

namespace {

// The moves of `cl` whose job-wide index is a multiple of `every`, as two-point paths, with
// where each came from.
struct Sampled {
  ClChunk cl;
  std::vector<std::uint64_t> move;
  std::vector<std::uint32_t> path;
};
Sampled sample_moves(const ClChunk& cl, std::uint64_t first_move, std::uint32_t first_path,
                     std::uint64_t every) {
  Sampled s;
  std::uint64_t m = first_move;
  std::size_t start = 0;
  for (std::size_t k = 0; k < cl.path_sizes.size(); ++k) {
    for (std::size_t i = start; i + 1 < start + cl.path_sizes[k]; ++i, ++m) {
      if (m % every != 0) continue;
      s.cl.xyz.insert(s.cl.xyz.end(), cl.xyz.begin() + 3 * i, cl.xyz.begin() + 3 * i + 6);
      s.cl.contact.insert(s.cl.contact.end(), {cl.contact[i], cl.contact[i + 1]});
      s.cl.path_sizes.push_back(2);
      s.cl.path_kinds.push_back(cl.path_kinds[k]);
      s.move.push_back(m);
      s.path.push_back(first_path + static_cast<std::uint32_t>(k));
    }
    start += cl.path_sizes[k];
  }
  return s;
}

class ProfileJobVerifier : public JobVerifier {
 public:
  ProfileJobVerifier(const JobSpec& job, const ProfileVerifyParams& p, const ProfileInput& in)
      : JobVerifier(job.verify), params_(p), walls_(profile_walls(in.regions, p)) {}

 protected:
  VerifyReport check(const ClChunk& cl, std::uint64_t first_move,
                     std::uint32_t first_path) override {
    return verify_profile_moves(walls_, cl, params_, first_move, first_path);
  }

  const WallSet& walls() const { return walls_; }
  double tool_radius() const { return params_.cutter.radius; }
  double top() const { return params_.top; }

 private:
  ProfileVerifyParams params_;
  WallSet walls_;
};

// Walls (as ProfileJobVerifier), the exact bottom, and the scallop grid.
class Pocket3dJobVerifier : public ProfileJobVerifier {
 public:
  Pocket3dJobVerifier(const JobSpec& job, const ProfileVerifyParams& p, const ProfileInput& in,
                      double reach)
      : ProfileJobVerifier(job, p, in),
        bottom_surface_(io::read_surface_toml(job.surface)),
        bottom_(bottom_surface_, tol::kVerifyPiece * job.tool.radius),
        scallop_(in.regions, walls(), bottom_, job.tool.radius, reach, tol::kVerifyScallopGrid),
        bound_(job.pocket3d.scallop + job.pocket3d.delta) {}

 protected:
  VerifyReport check(const ClChunk& cl, std::uint64_t first_move,
                     std::uint32_t first_path) override {
    VerifyReport r = ProfileJobVerifier::check(cl, first_move, first_path);
    const VerifyReport b =
        verify_bottom_moves(bottom_, cl, tool_radius(), top(), first_move, first_path);
    r.min_clearance = std::min(r.min_clearance, b.min_clearance);
    for (const VerifyViolation& v : b.worst) r.add(v);
    scallop_.add(cl, top());
    return r;
  }
  std::string bound_warning() const override {
    if (!(max_scallop_ > bound_ + tol::kVerifyGouge)) return "";
    std::ostringstream os;
    os.precision(4);
    os << "warning: the path leaves up to " << max_scallop_ << " mm of material at ("
       << scallop_at_.x() << ", " << scallop_at_.y() << ") where scallop + delta is " << bound_
       << " mm (stats/verify_max_scallop)";
    return os.str();
  }
  void bound_stats(std::vector<out::StatValue>& stats) override {
    Vec2 at = Vec2::Zero();
    const double s = scallop_.max_scallop(&at);
    max_scallop_ = s;
    scallop_at_ = at;
    stats.push_back({"verify_max_scallop", s, "mm"});
    stats.push_back({"verify_scallop_bound", bound_, "mm"});
    stats.push_back({"verify_scallop_x", at.x(), "mm"});
    stats.push_back({"verify_scallop_y", at.y(), "mm"});
    stats.push_back({"verify_scallop_points", static_cast<std::int64_t>(scallop_.points()), ""});
  }

 private:
  NurbsSurface bottom_surface_;
  SurfaceProbe bottom_;
  ScallopGrid scallop_;
  double bound_;
  double max_scallop_ = 0;
  Vec2 scallop_at_ = Vec2::Zero();
};

class MeshJobVerifier : public JobVerifier {
 public:
  MeshJobVerifier(const JobSpec& job, SweptIndexSource source, const MeshVerifyParams& p)
      : JobVerifier(job.verify), tool_(job.tool), params_(p), source_(std::move(source)) {}

 protected:
  VerifyReport check(const ClChunk& cl, std::uint64_t first_move,
                     std::uint32_t first_path) override {
    if (!index_) {
      Stopwatch clock;
      index_ = source_();
      index_s_ = clock.seconds();
    }
    const MeshVerifyReport m =
        verify_moves(*index_, tool_, cl, params_, first_move, first_path, prechecked());
    if (!m.error.empty()) throw std::runtime_error("verifier: " + m.error);
    VerifyReport r;
    r.moves = m.moves;
    r.min_rapid_clearance = m.min_rapid_clearance;
    for (const MoveViolation& v : m.worst)
      r.add({v.move, v.path, v.from, v.to, v.amount, ViolationKind::kMesh});
    if (m.unsafe_rapids > 0) {
      const MoveViolation& v = m.closest_rapid;
      r.add(
          {v.move, v.path, v.from, v.to, params_.safe_clearance - v.amount, ViolationKind::kRapid});
    }
    return r;
  }
  void bound_stats(std::vector<out::StatValue>& stats) override {
    stats.push_back({"verify_index_s", index_s_, "s"});
  }
  double index_seconds() const override { return index_s_; }

 private:
  Cutter tool_;
  MeshVerifyParams params_;
  SweptIndexSource source_;
  std::shared_ptr<const MeshVerifier> index_;
  double index_s_ = 0;
};

}  // namespace

JobVerifier::~JobVerifier() {
  if (attached_) attached_->set_observer(nullptr);
}

void JobVerifier::attach(out::ClJob& cl) {
  if (mode_ == VerifyMode::kOff) return;
  cl.set_observer([this](const ClChunk& c) { feed(c); });
  attached_ = &cl;
}

void JobVerifier::feed(const ClChunk& cl) {
  Stopwatch clock;
  VerifyReport r;
  if (mode_ == VerifyMode::kSample) {
    const Sampled s = sample_moves(cl, moves_seen_, paths_seen_, kSampleEvery);
    r = check(s.cl, 0, 0);
    for (VerifyViolation& v : r.worst) {
      v.path = s.path[v.move];
      v.move = s.move[v.move];
    }
  } else {
    r = check(cl, moves_seen_, paths_seen_);
  }
  report_.merge(r);
  prechecked_ = {};
  moves_seen_ += move_count(cl);
  paths_seen_ += static_cast<std::uint32_t>(cl.path_sizes.size());
  seconds_ += clock.seconds();
}

const VerifyReport& JobVerifier::finish(std::vector<out::StatValue>& stats) {
  const char* mode = mode_ == VerifyMode::kFull ? "full" : "sample";
  stats.push_back({"verify_mode", std::string(mode), ""});
  stats.push_back({"verify_moves", static_cast<std::int64_t>(report_.moves), ""});
  stats.push_back({"verify_max_gouge", report_.max_gouge, "mm"});
  stats.push_back({"verify_min_clearance", report_.min_clearance, "mm"});
  stats.push_back({"verify_min_rapid_clearance", report_.min_rapid_clearance, "mm"});
  stats.push_back({"verify_s", seconds_ - index_seconds(), "s"});
  // The checks ran inside the job's appends, which its write_s timed: take them out of it.
  for (out::StatValue& s : stats)
    if (double* w = std::get_if<double>(&s.value); w && s.name == "write_s")
      *w = std::max(0.0, *w - seconds_);
  bound_stats(stats);
  return report_;
}

void JobVerifier::write_worst(out::ClJob& cl) {
  cl.set_observer(nullptr);
  attached_ = nullptr;
  write_verify_worst(cl, report_);
}

void write_verify_worst(out::ClJob& cl, const VerifyReport& report) {
  std::vector<double> rows;
  for (const VerifyViolation& v : report.worst)
    rows.insert(rows.end(),
                {static_cast<double>(v.move), static_cast<double>(v.path), v.from.x(), v.from.y(),
                 v.from.z(), v.to.x(), v.to.y(), v.to.z(), v.amount, static_cast<double>(v.kind)});
  cl.write_array("verify", "worst", rows, kWorstColumns, "mm",
                 "worst violations, largest first: move, path, x0, y0, z0, x1, y1, z1, amount, "
                 "kind (0 wall, 1 floor, 2 mesh, 3 rapid, 4 bottom)");
}

std::vector<VerifyViolation> violations_from_rows(std::span<const double> rows) {
  std::vector<VerifyViolation> out;
  for (std::size_t r = 0; r + kWorstColumns <= rows.size(); r += kWorstColumns) {
    const double* v = rows.data() + r;
    VerifyViolation w;
    w.move = static_cast<std::uint64_t>(v[0]);
    w.path = static_cast<std::uint32_t>(v[1]);
    w.from = Vec3(v[2], v[3], v[4]);
    w.to = Vec3(v[5], v[6], v[7]);
    w.amount = v[8];
    w.kind = static_cast<ViolationKind>(static_cast<std::uint8_t>(v[9]));
    out.push_back(w);
  }
  return out;
}

std::unique_ptr<JobVerifier> profile_verifier(const JobSpec& job) {
  std::vector<out::StatValue> ignored;
  ProfileVerifyParams p;
  p.cutter = job.tool;
  p.top = 0;
  double join = 0;
  if (job.operation == Operation::kOffset) {
    p.stock = job.offset.stock;
    p.floor = -job.offset.depth;
    join = job.offset.join_tolerance;
  } else if (job.operation == Operation::kPocket) {
    p.stock = job.pocket.stock;
    p.floor = p.top - job.pocket.depth;
    join = job.pocket.join_tolerance;
  } else {
    return pocket3d_verifier(job);
  }
  p.rapid_limit = p.top;
  const ProfileInput in = read_profile_regions(job.input, join, job.units, ignored);
  return std::make_unique<ProfileJobVerifier>(job, p, in);
}

std::unique_ptr<JobVerifier> pocket3d_verifier(const JobSpec& job) {
  std::vector<out::StatValue> ignored;
  const Pocket3dJobParams& q = job.pocket3d;
  ProfileVerifyParams p;
  p.cutter = job.tool;
  p.stock = q.stock;
  p.top = 0;
  p.rapid_limit = p.top;
  const ProfileInput in = read_profile_regions(job.input, q.join_tolerance, job.units, ignored);
  bool nurbs = false;
  for (const Region& r : in.regions) {
    nurbs = nurbs || !r.boundary.nurbs.empty();
    for (const Profile& i : r.islands) nurbs = nurbs || !i.nurbs.empty();
  }
  // The scallop is promised between passes: inside the outermost pass as it runs. The first
  // level lies R + stock + eps/2 from the walls (engine/pocket3d.hpp), one tolerance more on
  // NURBS walls (engine/pocket_offset.hpp), and its chords may run up to eps (the plan
  // tolerance) inside it, away from the walls round convex corners. Between there and the
  // walls lies the wall band, which no pass is spaced for.
  const double reach =
      job.tool.radius + q.stock + 0.5 * q.eps + q.eps + (nurbs ? q.tolerance : 0);
  return std::make_unique<Pocket3dJobVerifier>(job, p, in, reach);
}

std::unique_ptr<JobVerifier> mesh_verifier(const JobSpec& job, SweptIndexSource index) {
  MeshVerifyParams p;
  if (job.operation == Operation::kPencil) p.stock = job.pencil.stock;
  if (job.operation == Operation::kFillet) p.stock = job.fillet.stock;
  return std::make_unique<MeshJobVerifier>(job, std::move(index), p);
}

JobSpec stored_job_spec(const std::string& operation, const std::string& input_path,
                        const std::string& tool_json, const std::string& params_json) {
  JobSpec job;
  job.input = input_path;
  if (!operation_by_name(operation, job.operation))
    throw std::invalid_argument("unknown operation '" + operation + "'");
  try {
    const nlohmann::json tool = nlohmann::json::parse(tool_json);
    const std::string type = tool.at("type");
    const double d = tool.at("diameter_mm"), r = tool.at("corner_radius_mm");
    job.tool = type == "ball"   ? ball_cutter(d)
               : type == "flat" ? flat_cutter(d)
                                : bull_nose_cutter(d, r);
    const nlohmann::json p = nlohmann::json::parse(params_json);
    const nlohmann::json& t = p.at("transform");
    job.transform.scale = t.at("scale");
    job.transform.translate =
        Vec3(t.at("translate")[0], t.at("translate")[1], t.at("translate")[2]);
    if (!t.at("fit_xy").is_null()) job.transform.fit_xy_mm = t.at("fit_xy").get<double>();
    const auto number = [&](const char* key, double& out) {
      if (p.contains(key) && p[key].is_number()) out = p[key];
    };
    number("stock", job.pocket.stock);
    number("depth", job.pocket.depth);
    number("join_tolerance", job.pocket.join_tolerance);
    job.offset.stock = job.pocket.stock;
    job.offset.depth = job.pocket.depth;
    job.offset.join_tolerance = job.pocket.join_tolerance;
    job.pocket3d.stock = job.pocket.stock;
    job.pocket3d.join_tolerance = job.pocket.join_tolerance;
    number("scallop", job.pocket3d.scallop);
    number("eps", job.pocket3d.eps);
    number("delta", job.pocket3d.delta);
    number("tolerance", job.pocket3d.tolerance);
    if (p.contains("surface")) job.surface = p["surface"].get<std::string>();
    // The units the job gave ("drawing": none, the drawing's own are read again).
    if (p.contains("units") && p["units"].is_string() && p["units"] != "drawing")
      if (std::string e = parse_units(p["units"].get<std::string>(), job.units); !e.empty())
        throw std::invalid_argument("the job's params attribute has units " + e);
    number("stock", job.pencil.stock);
    number("stock", job.fillet.stock);
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(std::string("the job's tool or params attribute is not what "
                                            "ncpath writes: ") +
                                e.what());
  }
  return job;
}

void push_guard_stats(const ChordGuard& guard, std::vector<out::StatValue>& stats) {
  const ChordGuardStats& g = guard.stats();
  stats.push_back({"chord_guard_moves", static_cast<std::int64_t>(g.moves), ""});
  stats.push_back({"chord_guard_raised", static_cast<std::int64_t>(g.raised), ""});
  stats.push_back({"chord_guard_max_raise", g.max_raise, "mm"});
  stats.push_back({"chord_guard_lifted", static_cast<std::int64_t>(g.lifted), ""});
  stats.push_back({"chord_guard_points_added", static_cast<std::int64_t>(g.points_added), ""});
  stats.push_back({"chord_guard_max_lift", g.max_lift, "mm"});
  stats.push_back({"chord_guard_s", guard.seconds(), "s"});
}

std::string verification_failure(const VerifyReport& report) {
  if (report.worst.empty()) return "";
  return "failed verification: " + report.message();
}

}  // namespace ncpath::jobs
