#include "engine/pocket_stages.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "engine/parallel.hpp"
#include "engine/run_control.hpp"
#include "kernels/curves/intersect.hpp"
#include "kernels/geom/tolerance.hpp"
#include "kernels/pocket/seg_grid.hpp"
#include "kernels/pocket/uncut.hpp"

namespace ncpath::pocket_stage {

namespace {

double region_area(const std::vector<OffsetLoop>& loops) {
  double a = 0;
  for (const OffsetLoop& l : loops) a -= l.area2 / 2;  // material on the right: cw adds
  return a;
}

// Level regions of the offset loops: loops of one input region and level, grouped into a
// clockwise loop and its holes. group[l] indexes `members`.
struct LevelGroups {
  std::vector<std::uint32_t> group;
  std::vector<std::vector<std::uint32_t>> members;
};

LevelGroups level_groups(const PocketOffsetResult& off) {
  LevelGroups g;
  g.group.assign(off.loops.size(), 0);
  for (std::size_t i = 0; i < off.loops.size();) {
    std::size_t j = i;
    while (j < off.loops.size() && off.loops[j].region == off.loops[i].region &&
           off.loops[j].level == off.loops[i].level)
      ++j;
    std::vector<const OffsetLoop*> level;
    for (std::size_t k = i; k < j; ++k) level.push_back(&off.loops[k].loop);
    for (const std::vector<std::uint32_t>& members : group_regions(level)) {
      std::vector<std::uint32_t> global;
      for (std::uint32_t m : members) {
        global.push_back(static_cast<std::uint32_t>(i + m));
        g.group[i + m] = static_cast<std::uint32_t>(g.members.size());
      }
      g.members.push_back(std::move(global));
    }
    i = j;
  }
  return g;
}

// Uncut regions of every band (a level group and the next level inside it) as clean-up
// loops, with the area before and after clean-up.
struct Uncut {
  std::vector<CleanupLoop> loops;
  double before = 0, after = 0;
};

// radius: what the tool clears around its centre (R for flat bottoms). With per-level steps
// (a ball's scallop, step_fn) it is half the band's step instead: two passes a step apart
// leave at most the scallop height between them, so the band's points farther than half the
// step from both of its loops are where the bound breaks (loops spreading apart around
// corners); their clean-up curves are run like a flat pocket's.
Uncut uncut_regions(const PocketOffsetResult& off, const LevelGroups& groups, double radius,
                    double centre_step, const StepFn* step_fn) {
  std::vector<std::vector<std::uint32_t>> inner(groups.members.size());
  for (std::uint32_t l = 0; l < off.loops.size(); ++l)
    if (!off.loops[l].loop.parents.empty())
      inner[groups.group[off.loops[l].loop.parents[0]]].push_back(l);
  struct Band {
    std::vector<CleanupLoop> loops;
    double before = 0, after = 0;
  };
  std::vector<Band> bands(groups.members.size());
  par::for_each(bands.size(), 1, [&](std::size_t g) {
    std::vector<const OffsetLoop*> outer_loops, inner_loops;
    std::vector<std::uint32_t> index;  // uncut_between's parents -> loop indices
    for (std::uint32_t l : groups.members[g]) {
      outer_loops.push_back(&off.loops[l].loop);
      index.push_back(l);
    }
    for (std::uint32_t l : inner[g]) {
      inner_loops.push_back(&off.loops[l].loop);
      index.push_back(l);
    }
    // Every point of a band lies within the step of its outer level: a step up to R leaves
    // nothing (the centre band's step is the one that emptied the next level).
    double step = inner[g].empty() ? centre_step : off.loops[inner[g][0]].step;
    double band_radius = radius;
    if (step_fn) {
      if (inner[g].empty()) step = (*step_fn)(off.loops[index[0]].level, outer_loops);
      band_radius = 0.5 * step * (1 + tol::kScallopBand);
    }
    if (step <= band_radius) return;
    const std::vector<OffsetLoop> u = uncut_between(outer_loops, inner_loops, band_radius);
    if (u.empty()) return;
    Band& b = bands[g];
    b.before = region_area(u);
    // What a tool running along the clean-up loops leaves: the region eroded by R.
    std::vector<std::vector<Seg2>> segs;
    for (const OffsetLoop& l : u) segs.push_back(l.segs);
    b.after = region_area(offset_loops(segs, band_radius).loops);
    for (const OffsetLoop& l : u) {
      CleanupLoop c{l.segs, {}};
      for (std::uint32_t p : l.parents) c.bounds.push_back(index[p]);
      if (c.bounds.empty()) c.bounds = index;
      b.loops.push_back(std::move(c));
    }
  });
  Uncut out;
  for (Band& b : bands) {
    out.before += b.before;
    out.after += b.after;
    for (CleanupLoop& c : b.loops) out.loops.push_back(std::move(c));
  }
  return out;
}

// A helix of radius r (halved once if it does not fit) in the level region `members`,
// touching one of `roots` (loops of the region).
bool find_helix(const PocketOffsetResult& off, const std::vector<std::uint32_t>& members,
                const std::vector<std::uint32_t>& roots, double r, Start& s) {
  std::vector<std::vector<Seg2>> segs;
  for (std::uint32_t l : members) segs.push_back(off.loops[l].loop.segs);
  for (int attempt = 0; attempt < 2; ++attempt, r *= 0.5) {
    const OffsetResult centres = offset_loops(segs, r);
    for (std::uint32_t root : roots) {
      pocket_detail::SegGrid grid(off.loops[root].loop.segs, r);
      for (const OffsetLoop& c : centres.loops)
        for (const Seg2& v : c.segs) {
          std::uint32_t k = 0;
          double d = 0;
          if (!grid.nearest_within(v.a, r + tol::kLinkSlack, k, d)) continue;
          const Seg2& on = off.loops[root].loop.segs[k];
          s.root = root;
          s.point = point_at(on, parameter_of(on, v.a));
          s.helix_centre = v.a;
          s.kind = Start::kHelix;
          return true;
        }
    }
  }
  return false;
}

Start choose_start(const PocketOffsetResult& off, const LevelGroups& groups,
                   const std::vector<std::uint32_t>& part, const Settings& p) {
  Start s;
  std::vector<std::uint32_t> roots;
  if (p.order == CutOrder::kOutward) {
    // The deepest level's first region; the helix may touch any of its loops.
    std::uint32_t deepest = part[0];
    for (std::uint32_t l : part)
      if (off.loops[l].level > off.loops[deepest].level) deepest = l;
    roots = groups.members[groups.group[deepest]];
  } else {
    // Seed 000: islands first (a counter-clockwise loop of level 1), else the boundary's.
    std::uint32_t first = part[0];
    for (std::uint32_t l : part)
      if (off.loops[l].level == 1 && off.loops[l].loop.area2 > 0) {
        first = l;
        break;
      }
    roots = {first};
  }
  const double r = p.helix_radius > 0 ? p.helix_radius : 0.5 * p.tool_radius;
  if (p.helix && find_helix(off, groups.members[groups.group[roots[0]]], roots, r, s)) return s;
  s.root = roots[0];
  s.point = off.loops[s.root].loop.segs.front().a;
  s.kind =
      loop_length(off.loops[s.root].loop.segs) >= 2 * p.tool_radius ? Start::kRamp : Start::kPlunge;
  return s;
}

std::string region_name(const std::vector<Region>& regions, std::size_t r) {
  std::ostringstream os;
  os << "region " << r;
  if (!regions[r].boundary.curves.empty()) {
    const Vec2 a = regions[r].boundary.curves.front().seg.a;
    os << " (boundary starting at (" << a.x() << ", " << a.y() << "))";
  }
  return os.str();
}

}  // namespace

Plan plan_pocket_parts(const std::vector<Region>& regions, const Settings& p) {
  Plan out;
  Stopwatch clock;
  PocketOffsetParams op;
  op.tool_radius = p.tool_radius;
  op.stepover = p.stepover;
  op.stock = p.stock;
  op.tolerance = p.tolerance;
  op.wall_margin = p.wall_margin;
  op.half_step_last = p.half_step_last;
  out.off = offset_pocket(regions, op, p.step);
  const PocketOffsetResult& off = out.off;
  std::vector<bool> fits(regions.size(), false);
  for (const PocketLoop& l : off.loops) fits[l.region] = true;
  for (std::size_t r = 0; r < regions.size(); ++r)
    if (!fits[r]) {
      std::ostringstream os;
      os << region_name(regions, r) << ": the tool (diameter " << 2 * p.tool_radius << " mm, stock "
         << p.stock << " mm) does not fit in the pocket";
      throw RegionTooSmall(r, os.str());
    }
  const LevelGroups groups = level_groups(off);
  out.stats.offset_s = clock.seconds();

  clock = Stopwatch();
  // With per-level steps the step that emptied the innermost level is not kept: compute
  // the centre bands.
  Uncut uncut =
      uncut_regions(off, groups, p.tool_radius,
                    p.step ? std::numeric_limits<double>::infinity() : p.stepover, p.step);
  out.stats.uncut_area_before = uncut.before;
  // Unreachable: the region (less the stock) minus the tool swept around level 1, which is
  // the region eroded by R + stock already.
  std::vector<double> unreachable(regions.size(), 0);
  par::for_each(regions.size(), 1, [&](std::size_t r) {
    std::vector<std::vector<Seg2>> shapes{profile_segments(regions[r].boundary, p.tolerance)};
    for (const Profile& island : regions[r].islands)
      shapes.push_back(profile_segments(island, p.tolerance));
    double area = 0;
    if (p.stock > 0) {
      area = region_area(offset_loops(shapes, p.stock).loops);
    } else {
      for (const std::vector<Seg2>& l : shapes) area -= loop_area2(l) / 2;
    }
    std::vector<std::vector<Seg2>> first;
    for (const PocketLoop& l : off.loops)
      if (l.region == r && l.level == 1) first.push_back(l.loop.segs);
    // Level 1 lies the one-sided margins farther from the walls (engine/pocket_offset.hpp):
    // the band they leave is tolerance, not a corner the tool cannot reach.
    bool nurbs = !regions[r].boundary.nurbs.empty();
    for (const Profile& island : regions[r].islands) nurbs = nurbs || !island.nurbs.empty();
    const double margin = p.wall_margin + (nurbs ? p.tolerance : 0);
    unreachable[r] = std::max(0.0, area - region_area(dilate(first, p.tool_radius + margin)));
  });
  for (double a : unreachable) out.stats.unreachable_area += a;
  out.cleanups = std::move(uncut.loops);
  out.stats.uncut_s = clock.seconds();

  clock = Stopwatch();
  std::vector<PlanLoop> loops(off.loops.size());
  for (std::size_t l = 0; l < off.loops.size(); ++l)
    loops[l] = {&off.loops[l].loop.segs, off.loops[l].level, off.loops[l].loop.parents,
                groups.group[l], off.loops[l].step};
  const std::vector<SameLevelEdge> extra = same_level_edges(loops);
  out.parts = connected_parts(loops, extra);
  out.starts.resize(out.parts.size());
  out.paths.resize(out.parts.size());
  PlanParams pp;
  pp.tool_radius = p.tool_radius;
  pp.stepover = p.stepover;
  pp.outward = p.order == CutOrder::kOutward;
  pp.climb = p.milling == Milling::kClimb;
  par::for_each(out.parts.size(), 1, [&](std::size_t k) {
    out.starts[k] = choose_start(off, groups, out.parts[k], p);
    out.paths[k] = plan_part(loops, extra, out.cleanups, out.parts[k], out.starts[k].root,
                             out.starts[k].point, pp);
  });
  double unattached = 0;
  for (const PlannedPath& plan : out.paths)
    for (std::uint32_t u : plan.unattached)
      unattached += std::abs(loop_area2(out.cleanups[u].segs)) / 2;
  out.stats.uncut_area_after = uncut.after + unattached;
  out.stats.link_s = clock.seconds();
  out.stats.loops = off.loops.size();
  out.stats.levels = off.levels;
  out.stats.open_fragments = off.open_fragments;
  out.stats.components = out.parts.size();
  for (const PlannedPath& plan : out.paths) {
    out.stats.links += plan.links;
    out.stats.cleanup_curves += plan.cleanup_curves;
  }
  return out;
}

std::string mm(double v) {
  std::ostringstream os;
  os << v << " mm";
  return os.str();
}

void ChunkBuilder::move(const Vec3& p, PathKind kind, const double* payload) {
  const auto set_last = [&] {
    for (int k = 0; k < width_; ++k)
      last_[static_cast<std::size_t>(k)] =
          payload ? payload[k] : std::numeric_limits<double>::quiet_NaN();
  };
  if (!has_pos_) {
    pos_ = p;
    has_pos_ = true;
    open_ = false;
    set_last();
    return;
  }
  if ((p - pos_).norm() == 0) return;
  if (!open_ || kind != kind_) {
    cl_.path_sizes.push_back(0);
    cl_.path_kinds.push_back(static_cast<std::uint8_t>(kind));
    put(pos_);
    kind_ = kind;
    open_ = true;
  }
  const double len = (p - pos_).norm();
  (kind == PathKind::kCut ? cut_ : kind == PathKind::kRapid ? rapid_ : link_) += len;
  set_last();
  put(p);
  pos_ = p;
}

void ChunkBuilder::put(const Vec3& p) {
  cl_.xyz.insert(cl_.xyz.end(), {p.x(), p.y(), p.z()});
  cl_.contact.push_back(0);
  ++cl_.path_sizes.back();
  if (payload_) payload_->insert(payload_->end(), last_.begin(), last_.end());
}

}  // namespace ncpath::pocket_stage
