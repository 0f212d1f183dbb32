#include "engine/pocket_path.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "engine/parallel.hpp"
#include "engine/pocket_offset.hpp"
#include "engine/run_control.hpp"
#include "kernels/curves/intersect.hpp"
#include "kernels/geom/tolerance.hpp"
#include "kernels/pocket/entry.hpp"
#include "kernels/pocket/path_plan.hpp"
#include "kernels/pocket/seg_grid.hpp"
#include "kernels/pocket/uncut.hpp"

namespace ncpath {

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

Uncut uncut_regions(const PocketOffsetResult& off, const LevelGroups& groups, double radius) {
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
    if (band_cut(outer_loops, inner_loops, radius)) return;
    const std::vector<OffsetLoop> u = uncut_between(outer_loops, inner_loops, radius);
    if (u.empty()) return;
    Band& b = bands[g];
    b.before = region_area(u);
    // What a tool running along the clean-up loops leaves: the region eroded by R.
    std::vector<std::vector<Seg2>> segs;
    for (const OffsetLoop& l : u) segs.push_back(l.segs);
    b.after = region_area(offset_loops(segs, radius).loops);
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

// Where a part starts and how the tool gets down there.
struct Start {
  std::uint32_t root = 0;
  Vec2 point = Vec2::Zero();
  Vec2 helix_centre = Vec2::Zero();
  enum Kind { kHelix, kRamp, kPlunge } kind = kPlunge;
};

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
                   const std::vector<std::uint32_t>& part, const PocketPathParams& p) {
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
  if (find_helix(off, groups.members[groups.group[roots[0]]], roots, r, s)) return s;
  s.root = roots[0];
  s.point = off.loops[s.root].loop.segs.front().a;
  s.kind =
      loop_length(off.loops[s.root].loop.segs) >= 2 * p.tool_radius ? Start::kRamp : Start::kPlunge;
  return s;
}

// Writes moves into the chunk as paths of one kind each; consecutive paths share the
// junction point. Lengths per kind from the points written.
class ChunkBuilder {
 public:
  ChunkBuilder(ClChunk& cl, PocketPathStats& st) : cl_(cl), st_(st) {}
  void move(const Vec3& p, PathKind kind) {
    if (!has_pos_) {
      pos_ = p;
      has_pos_ = true;
      open_ = false;
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
    (kind == PathKind::kCut     ? st_.cut_length
     : kind == PathKind::kRapid ? st_.rapid_length
                                : st_.link_length) += len;
    put(p);
    pos_ = p;
  }
  const Vec3& pos() const { return pos_; }

 private:
  void put(const Vec3& p) {
    cl_.xyz.insert(cl_.xyz.end(), {p.x(), p.y(), p.z()});
    cl_.contact.push_back(0);
    ++cl_.path_sizes.back();
  }
  ClChunk& cl_;
  PocketPathStats& st_;
  Vec3 pos_ = Vec3::Zero();
  PathKind kind_ = PathKind::kCut;
  bool has_pos_ = false, open_ = false;
};

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

namespace {
std::string mm(double v) {
  std::ostringstream os;
  os << v << " mm";
  return os.str();
}
}  // namespace

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

  Stopwatch clock;
  PocketOffsetParams op;
  op.tool_radius = p.tool_radius;
  op.stepover = p.stepover;
  op.stock = p.stock;
  op.tolerance = p.tolerance;
  const PocketOffsetResult off = offset_pocket(regions, op);
  std::vector<bool> fits(regions.size(), false);
  for (const PocketLoop& l : off.loops) fits[l.region] = true;
  for (std::size_t r = 0; r < regions.size(); ++r)
    if (!fits[r]) {
      std::ostringstream os;
      os << region_name(regions, r) << ": the tool (diameter " << 2 * p.tool_radius << " mm, stock "
         << p.stock << " mm) does not fit in the pocket";
      throw RegionTooSmall(r, os.str());
    }
  st.loops = off.loops.size();
  st.levels = off.levels;
  st.open_fragments = off.open_fragments;
  const LevelGroups groups = level_groups(off);
  st.offset_s = clock.seconds();

  clock = Stopwatch();
  // Every point between two levels lies within the stepover of the outer one, so with a
  // stepover up to the tool radius nothing is left uncut and the stage is skipped.
  const Uncut uncut =
      p.stepover > p.tool_radius ? uncut_regions(off, groups, p.tool_radius) : Uncut{};
  st.uncut_area_before = uncut.before;
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
    unreachable[r] = std::max(0.0, area - region_area(dilate(first, p.tool_radius)));
  });
  for (double a : unreachable) st.unreachable_area += a;
  st.uncut_s = clock.seconds();

  clock = Stopwatch();
  std::vector<PlanLoop> loops(off.loops.size());
  for (std::size_t l = 0; l < off.loops.size(); ++l)
    loops[l] = {&off.loops[l].loop.segs, off.loops[l].level, off.loops[l].loop.parents,
                groups.group[l]};
  const std::vector<SameLevelEdge> extra = same_level_edges(loops);
  const std::vector<std::vector<std::uint32_t>> parts = connected_parts(loops, extra);
  std::vector<Start> starts(parts.size());
  std::vector<PlannedPath> plans(parts.size());
  PlanParams pp;
  pp.tool_radius = p.tool_radius;
  pp.stepover = p.stepover;
  pp.outward = p.order == CutOrder::kOutward;
  pp.climb = p.milling == Milling::kClimb;
  par::for_each(parts.size(), 1, [&](std::size_t k) {
    starts[k] = choose_start(off, groups, parts[k], p);
    plans[k] = plan_part(loops, extra, uncut.loops, parts[k], starts[k].root, starts[k].point, pp);
  });
  double unattached = 0;
  for (const PlannedPath& plan : plans)
    for (std::uint32_t u : plan.unattached)
      unattached += std::abs(loop_area2(uncut.loops[u].segs)) / 2;
  st.uncut_area_after = uncut.after + unattached;
  st.link_s = clock.seconds();

  // Depth passes, entries, rapids.
  clock = Stopwatch();
  std::vector<double> floors;
  const int passes =
      p.stepdown > 0 ? std::max(1, static_cast<int>(std::ceil(p.depth / p.stepdown - 1e-9))) : 1;
  for (int i = 1; i <= passes; ++i)
    floors.push_back(p.top - (i == passes ? p.depth : i * p.stepdown));
  st.depth_passes = static_cast<std::uint64_t>(passes);
  st.components = parts.size();
  const double angle = p.ramp_angle_deg * std::numbers::pi / 180;
  const double feed_z = p.top + p.clearance;
  ChunkBuilder b(out.cl, st);
  for (std::size_t k = 0; k < parts.size(); ++k) {
    const PlannedPath& plan = plans[k];
    const Start& s = starts[k];
    st.links += plan.links;
    st.cleanup_curves += plan.cleanup_curves;
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
        entry = helix_points(s.helix_centre, a, z_from, z, angle, pp.climb, p.chordal_tolerance);
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
