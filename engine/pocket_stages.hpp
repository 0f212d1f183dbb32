#pragma once
// Stages shared by flat-bottom pockets (engine/pocket_path.hpp) and sculptured-bottom
// pockets (engine/pocket3d.hpp): offset levels, level regions, uncut regions and clean-up
// loops, unreachable area, parts with their start and planned planar path. Internal to the
// engine.
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "engine/cl_chunk.hpp"
#include "engine/pocket_offset.hpp"
#include "engine/pocket_path.hpp"
#include "kernels/pocket/path_plan.hpp"

namespace ncpath::pocket_stage {

// Where a part starts and how the tool gets down there.
struct Start {
  std::uint32_t root = 0;
  Vec2 point = Vec2::Zero();
  Vec2 helix_centre = Vec2::Zero();
  enum Kind { kHelix, kRamp, kPlunge } kind = kPlunge;
};

struct Settings {
  double tool_radius = 3, stepover = 1.5, stock = 0, tolerance = 0.01;
  double wall_margin = 0;        // mm: PocketOffsetParams::wall_margin
  const StepFn* step = nullptr;  // per-level steps (then stepover is only the fallback)
  bool half_step_last = false;   // with step: a half step where the full one leaves nothing
  CutOrder order = CutOrder::kOutward;
  Milling milling = Milling::kClimb;
  double helix_radius = 0;  // 0: half the tool radius
  bool helix = true;        // false: ramp or plunge only
};

struct Plan {
  PocketOffsetResult off;
  std::vector<CleanupLoop> cleanups;
  std::vector<std::vector<std::uint32_t>> parts;
  std::vector<Start> starts;       // per part
  std::vector<PlannedPath> paths;  // per part
  // Everything but lengths and retractions, which come from the CL points.
  PocketPlanStats stats;
};

// Offsets, uncut regions (per band, skipped where the band's step is at most R), unreachable
// area, parts, starts and planned paths. Throws RegionTooSmall for a region with no level.
Plan plan_pocket_parts(const std::vector<Region>& regions, const Settings& s);

// "2.5 mm": a length for parameter messages.
std::string mm(double v);

// Writes moves into a chunk as paths of one kind each; consecutive paths share the junction
// point; lengths per kind into the stats.
class ChunkBuilder {
 public:
  ChunkBuilder(ClChunk& cl, double& cut, double& link, double& rapid)
      : cl_(cl), cut_(cut), link_(link), rapid_(rapid) {}
  // Per-point payload (e.g. CC point and normal): `width` doubles per CL point, NaN where a
  // move gives none.
  void set_payload(std::vector<double>* out, int width) {
    payload_ = out;
    width_ = width;
    last_.assign(static_cast<std::size_t>(width), std::numeric_limits<double>::quiet_NaN());
  }
  void move(const Vec3& p, PathKind kind, const double* payload = nullptr);
  const Vec3& pos() const { return pos_; }
  bool started() const { return has_pos_; }

 private:
  void put(const Vec3& p);
  ClChunk& cl_;
  double &cut_, &link_, &rapid_;
  Vec3 pos_ = Vec3::Zero();
  PathKind kind_ = PathKind::kCut;
  bool has_pos_ = false, open_ = false;
  std::vector<double>* payload_ = nullptr;
  int width_ = 0;
  std::vector<double> last_;  // payload of pos_
};

}  // namespace ncpath::pocket_stage
