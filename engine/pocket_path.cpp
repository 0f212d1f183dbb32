#include "engine/pocket_path.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "engine/pocket_stages.hpp"
#include "engine/run_control.hpp"
#include "kernels/pocket/entry.hpp"

namespace ncpath {

namespace {

using pocket_stage::ChunkBuilder;
using pocket_stage::Start;

void put_moves(ChunkBuilder& b, const std::vector<Move2>& moves, double z, double chord,
               PocketPathStats& st) {
  std::vector<Vec2> pts;
  for (const Move2& m : moves) {
    const bool cut = m.kind == MoveKind::kCut || m.kind == MoveKind::kCleanup;
    if (m.kind == MoveKind::kCleanup || m.kind == MoveKind::kCleanupLink)
      st.cleanup_length += length(m.seg);
    const PathKind kind = cut ? PathKind::kCut : PathKind::kLinkAtDepth;
    pts.clear();
    append_polyline(m.seg, chord, pts);
    for (std::size_t k = 1; k < pts.size(); ++k) b.move(Vec3(pts[k].x(), pts[k].y(), z), kind);
    b.move(Vec3(m.seg.b.x(), m.seg.b.y(), z), kind);
  }
}

}  // namespace

using pocket_stage::mm;

std::string validate(const PocketPathParams& p) {
  const double vals[] = {p.tool_radius,       p.stepover, p.stock,        p.tolerance,
                         p.chordal_tolerance, p.top,      p.depth,        p.stepdown,
                         p.clearance,         p.safe_z,   p.helix_radius, p.ramp_angle_deg};
  for (double v : vals)
    if (!std::isfinite(v)) return "pocket parameters must be finite numbers";
  if (!(p.tool_radius > 0)) return "tool diameter must be positive";
  if (!(p.stepover > 0)) return "stepover must be positive (got " + mm(p.stepover) + ")";
  if (p.stepover > 2 * p.tool_radius * (1 + 1e-12))
    return "stepover " + mm(p.stepover) + " is larger than the tool diameter " +
           mm(2 * p.tool_radius) + ": material would be left between passes";
  if (p.stock < 0) return "stock must not be negative";
  if (!(p.tolerance > 0) || !(p.chordal_tolerance > 0)) return "tolerances must be positive";
  if (!(p.depth > 0)) return "depth must be positive (got " + mm(p.depth) + ")";
  if (p.stepdown < 0) return "stepdown must not be negative (0: one pass at full depth)";
  if (p.clearance < 0) return "clearance must not be negative";
  if (p.safe_z < p.top + p.clearance)
    return "safe_z " + mm(p.safe_z) + " is below the stock top plus clearance";
  if (p.helix_radius < 0) return "helix radius must not be negative";
  if (!(p.ramp_angle_deg > 0 && p.ramp_angle_deg < 90))
    return "ramp angle must lie between 0 and 90 degrees";
  return "";
}

PocketPath plan_pocket(const std::vector<Region>& regions, const PocketPathParams& p) {
  if (const std::string m = validate(p); !m.empty()) throw std::invalid_argument(m);
  PocketPath out;
  PocketPathStats& st = out.stats;

  pocket_stage::Settings settings;
  settings.tool_radius = p.tool_radius;
  settings.stepover = p.stepover;
  settings.stock = p.stock;
  settings.tolerance = p.tolerance;
  settings.wall_margin = p.chordal_tolerance;  // the CL polylines' chords fall inside arcs
  settings.order = p.order;
  settings.milling = p.milling;
  settings.helix_radius = p.helix_radius;
  const pocket_stage::Plan plan_all = pocket_stage::plan_pocket_parts(regions, settings);
  const std::vector<std::vector<std::uint32_t>>& parts = plan_all.parts;
  const std::vector<Start>& starts = plan_all.starts;
  const std::vector<PlannedPath>& plans = plan_all.paths;
  static_cast<PocketPlanStats&>(st) = plan_all.stats;
  const bool climb = p.milling == Milling::kClimb;

  // Depth passes, entries, rapids.
  Stopwatch clock;
  std::vector<double> floors;
  const int passes =
      p.stepdown > 0 ? std::max(1, static_cast<int>(std::ceil(p.depth / p.stepdown - 1e-9))) : 1;
  for (int i = 1; i <= passes; ++i)
    floors.push_back(p.top - (i == passes ? p.depth : i * p.stepdown));
  st.depth_passes = static_cast<std::uint64_t>(passes);
  const double angle = p.ramp_angle_deg * std::numbers::pi / 180;
  const double feed_z = p.top + p.clearance;
  ChunkBuilder b(out.cl, st.cut_length, st.link_length, st.rapid_length);
  for (std::size_t k = 0; k < parts.size(); ++k) {
    const PlannedPath& plan = plans[k];
    const Start& s = starts[k];
    const Vec2 a = plan.start;
    if (k > 0) {
      b.move(Vec3(b.pos().x(), b.pos().y(), p.safe_z), PathKind::kRapid);
      ++st.retractions;
    }
    b.move(Vec3(a.x(), a.y(), p.safe_z), PathKind::kRapid);
    b.move(Vec3(a.x(), a.y(), feed_z), PathKind::kRapid);
    double z_from = feed_z;
    for (std::size_t i = 0; i < floors.size(); ++i) {
      const double z = floors[i];
      if (i > 0) put_moves(b, plan.back, z_from, p.chordal_tolerance, st);  // back to the start
      std::vector<Vec3> entry;
      if (s.kind == Start::kHelix) {
        entry = helix_points(s.helix_centre, a, z_from, z, angle, climb, p.chordal_tolerance);
        ++st.helix_entries;
      } else if (s.kind == Start::kRamp) {
        entry = ramp_points(plan.first_loop, z_from, z, angle, p.chordal_tolerance);
        ++st.ramp_entries;
      } else {
        entry = {Vec3(a.x(), a.y(), z_from), Vec3(a.x(), a.y(), z)};
        ++st.plunge_entries;
      }
      double entry_len = 0;
      for (std::size_t i = 0; i < entry.size(); ++i) {
        if (i > 0) entry_len += (entry[i] - entry[i - 1]).head<2>().norm();
        b.move(entry[i], PathKind::kCut);
      }
      put_moves(b, plan.moves, z, p.chordal_tolerance, st);
      st.slotting_length += plan.slotting_length + entry_len;
      z_from = z;
    }
  }
  if (!parts.empty()) b.move(Vec3(b.pos().x(), b.pos().y(), p.safe_z), PathKind::kRapid);
  st.path_s = clock.seconds();
  return out;
}

}  // namespace ncpath
