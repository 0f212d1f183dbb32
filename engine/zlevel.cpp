#include "engine/zlevel.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>
#include <stdexcept>

#include "engine/offset_elements_build.hpp"
#include "engine/chunk_stream.hpp"
#include "engine/parallel.hpp"
#include "kernels/geom/tolerance.hpp"
#include "kernels/scan/zlevel.hpp"

namespace ncpath {

std::string validate(const ZLevelOpParams& p) {
  std::ostringstream os;
  if (!(std::isfinite(p.step_down) && p.step_down >= 0))
    os << "step_down must be a positive number of mm, got " << p.step_down;
  else if (p.step_down == 0 && p.levels.empty())
    os << "give the levels (tool-tip z, mm) or a step_down";
  else if (p.step_down > 0 && !p.levels.empty())
    os << "give either levels or step_down, not both";
  else if (!(std::isfinite(p.tolerance) && p.tolerance > 0))
    os << "tolerance must be a positive number of mm, got " << p.tolerance;
  else if (p.chunk_levels == 0)
    os << "chunk_levels must be >= 1";
  else
    for (double z : p.levels)
      if (!std::isfinite(z)) {
        os << "levels must be finite numbers of mm";
        break;
      }
  return os.str();
}

namespace {

struct LevelOut {
  ZLevelChunk chunk;
  std::uint64_t candidates = 0, open_chains = 0, holes = 0, points = 0;
  std::uint64_t kinds[3] = {0, 0, 0};
};

// An element of the sliced mesh as the given mesh's (the concave zone's copy maps back).
ElementRef mesh_ref(const OffsetElements& el, const ZLevelOpParams& p, std::uint32_t id) {
  const ElementRef r = element_ref(el, id);
  return p.zone ? p.zone->kept.in_mesh(r) : r;
}

// One contour's segment records (path `path`, tip z) and its closed polyline: each segment
// from its start, arcs by their circumscribed polygon within the tolerance and the arc's
// clearance, with the contact code of each point.
void contour_segments(const OffsetElements& el, const ZLevelOpParams& p, const ZContour& con,
                      std::int64_t path, double z, std::vector<Vec2>& pts,
                      std::vector<std::uint8_t>& contact, ZLevelChunk& ch) {
  pts.clear();
  contact.clear();
  for (const ContourSeg& s : con.segs) {
    circumscribed(s, std::min(p.tolerance, s.clearance), pts);
    contact.resize(pts.size(), contact_code(el, s.element));
    ZLevelSegmentRecord rec;
    rec.path = path;
    rec.kind = std::uint8_t(s.kind);
    rec.shadow = s.shadow;
    rec.element = mesh_ref(el, p, s.element);
    rec.start = {s.a.x(), s.a.y(), z};
    rec.end = {s.b.x(), s.b.y(), z};
    if (s.kind != ContourSegKind::kLine)
      rec.geometry = {s.centre.x(), s.centre.y(), s.r1, s.r2, std::atan2(s.axis.y(), s.axis.x()),
                      s.t0, s.t1};
    ch.segments.push_back(rec);
  }
  if (pts.empty()) return;
  pts.push_back(pts.front());  // closed
  contact.push_back(contact.front());
}

// The closed polyline as a cut path at z, after a one-point rapid to its start unless it is
// the job's first path.
void append_cut(const std::vector<Vec2>& pts, const std::vector<std::uint8_t>& contact, double z,
                bool lead_rapid, ZLevelChunk& ch) {
  if (lead_rapid) {
    ch.cl.xyz.insert(ch.cl.xyz.end(), {pts[0].x(), pts[0].y(), z});
    ch.cl.contact.push_back(contact[0]);
    ch.cl.path_sizes.push_back(1);
    ch.cl.path_kinds.push_back(std::uint8_t(PathKind::kRapid));
  }
  for (const Vec2& q : pts) ch.cl.xyz.insert(ch.cl.xyz.end(), {q.x(), q.y(), z});
  ch.cl.contact.insert(ch.cl.contact.end(), contact.begin(), contact.end());
  ch.cl.path_sizes.push_back(std::uint32_t(pts.size()));
  ch.cl.path_kinds.push_back(std::uint8_t(PathKind::kCut));
}

// The contour's junctions (those in the concave zone, when one is given) as records at tip z;
// zc is the ball centres' height the kernel used.
void contour_junctions(const OffsetElements& el, const ZLevelOpParams& p, const ZContour& con,
                       std::int64_t path, double z, double zc, LevelOut& out) {
  for (const ZJunction& j : con.junctions) {
    if (p.zone && !p.zone->holds(Vec3(j.position.x(), j.position.y(), zc))) continue;
    ZLevelJunctionRecord rec;
    rec.path = path;
    rec.kind = std::uint8_t(j.kind);
    rec.position = {j.position.x(), j.position.y(), z};
    rec.b1 = {j.b1.x(), j.b1.y(), j.b1.z()};
    rec.b2 = {j.b2.x(), j.b2.y(), j.b2.z()};
    rec.element1 = mesh_ref(el, p, j.e1);
    rec.element2 = mesh_ref(el, p, j.e2);
    rec.angle = std::acos(std::clamp(j.b1.dot(j.b2), -1.0, 1.0));
    out.chunk.junctions.push_back(rec);
    ++out.kinds[std::size_t(j.kind)];
  }
}

// Facets and reachable edges, highest reach first (ties by id). Unreachable edges are left
// out: the kernel skips them (OffsetElements::edge_reachable), and their end vertices come
// from the reachable edges there (a vertex is reachable only through one of its edges, which
// reaches at least as high).
std::vector<std::uint32_t> by_reach(const OffsetElements& el, const std::vector<double>& reach) {
  const std::size_t nfe = el.facet_count() + el.edge_count();
  std::vector<std::uint32_t> by_top;
  by_top.reserve(nfe);
  for (std::uint32_t id = 0; id < nfe; ++id)
    if (id < el.facet_count() || el.edge_reachable.size() != el.edge_count() ||
        el.edge_reachable[id - el.facet_count()])
      by_top.push_back(id);
  par::sort(by_top.begin(), by_top.end(), [&](std::uint32_t a, std::uint32_t b) {
    return reach[a] != reach[b] ? reach[a] > reach[b] : a < b;
  });
  return by_top;
}

// The tool-tip levels, highest first: the given ones, or every step_down below the top.
std::vector<double> tip_levels(const ZLevelOpParams& p, double top_z, double bottom_z) {
  std::vector<double> levels = p.levels;
  if (p.step_down > 0)
    for (int k = 1; top_z - k * p.step_down > bottom_z; ++k)
      levels.push_back(top_z - k * p.step_down);
  std::sort(levels.begin(), levels.end(), std::greater<>());
  return levels;
}

}  // namespace

ZLevelOpStats run_zlevel(const TriangleMesh& mesh, const Cutter& cutter,
                         const ZLevelOpParams& p,
                         const std::function<void(const ZLevelChunk&)>& sink,
                         RunControl& control, const ConditionedMesh* conditioned) {
  if (std::string e = validate(cutter); !e.empty()) throw std::invalid_argument("tool: " + e);
  if (cutter.type != CutterType::kBall)
    throw std::invalid_argument("tool: z-level contouring needs a ball-end mill");
  if (std::string e = validate(p); !e.empty()) throw std::invalid_argument(e);
  ZLevelOpStats st;
  Stopwatch el_clock;
  ConditionedMesh own;
  if (p.condition && !conditioned) own = condition_for_slicing(mesh);
  const ConditionedMesh& cond = conditioned ? *conditioned : own;
  if (p.condition) st.condition = cond.stats;
  const TriangleMesh& part = p.condition ? cond.mesh : mesh;
  // Sliced for the ball grown by the largest move (same centres: kernel tip = z - grow).
  const double grow = st.condition.max_move, R = cutter.radius + grow;
  const TriangleMesh& sliced = p.zone ? p.zone->kept.mesh : part;
  const OffsetElements el = build_offset_elements_parallel(sliced, R, false, Coplanar::kVertical);
  if (el.facet_count() == 0) throw std::invalid_argument("the mesh has no usable facet");
  st.facets = el.facet_count();
  st.edges = el.edge_count();
  st.vertices = el.vertex_count();
  // Facets and edges by their reach (the highest ball-centre height at which their region
  // can be non-empty, kernels/scan/zlevel.hpp ZLevelElementBoxes): a level's candidates are a
  // prefix (the kernel's own test then drops those exactly at their reach where it is strict).
  const ZLevelElementBoxes boxes = zlevel_element_boxes(el);
  ZLevelParams kernel;
  kernel.boxes = &boxes;
  const std::vector<double>& reach = boxes.reach;
  const std::vector<std::uint32_t> by_top = by_reach(el, reach);
  const Aabb3 box = bounding_box(mesh);
  st.top_z = box.hi.z();
  st.bottom_z = box.lo.z();
  st.elements_s = el_clock.seconds();

  const std::vector<double> levels = tip_levels(p, st.top_z, st.bottom_z);
  st.levels = levels.size();

  // The levels of a chunk know the region of the previous chunk's last level to lie inside
  // theirs (kernels/scan/zlevel.hpp ZLevelInside): the same for any thread count. Their
  // candidates leave out the elements lying deep inside that region (zlevel_filter_deep).
  ZLevelInside inside, next_inside;
  par::PerThread<ZLevelWorkspace> workspaces;  // each thread's kernel buffers, level to level
  std::size_t chunk_end = 0;
  std::vector<std::uint32_t> filtered;  // by_top[0, filtered_n) less the deep ones
  std::size_t filtered_n = 0;
  const std::vector<std::uint32_t>* cand = &by_top;
  auto prefix = [&](const std::vector<std::uint32_t>& ids, double z) {
    const double zc = z + el.radius;  // as the kernel computes it
    return std::size_t(
        std::lower_bound(ids.begin(), ids.end(), zc,
                         [&](std::uint32_t id, double c) { return reach[id] >= c; }) -
        ids.begin());
  };
  // Cut path index of each level's first contour is only known after the levels before it:
  // records are numbered per chunk and shifted when the chunk is merged.
  auto run_level = [&](std::size_t i, LevelOut& out) {
    const double z = levels[i], zk = z - grow;
    const std::size_t n = prefix(*cand, zk);
    ZLevelParams kp = kernel;
    kp.workspace = &workspaces.local();
    kp.clearance_cap = p.tolerance;
    kp.inside = &inside;
    const ZLevelResult r =
        zlevel_contours(el, std::span<const std::uint32_t>(cand->data(), n), zk, kp);
    if (i + 1 == chunk_end) next_inside = zlevel_inside(r, 0.5 * el.radius);
    out.candidates = n;
    out.open_chains = r.stats.open_chains;
    ZLevelChunk& ch = out.chunk;
    std::vector<Vec2> pts;
    std::vector<std::uint8_t> contact;
    for (std::size_t c = 0; c < r.contours.size(); ++c) {
      const ZContour& con = r.contours[c];
      const auto path = std::int64_t(c);  // shifted later
      contour_segments(el, p, con, path, z, pts, contact, ch);
      if (pts.empty()) continue;
      append_cut(pts, contact, z, !ch.cl.path_sizes.empty() || i > 0, ch);
      out.points += pts.size();
      ch.contour_level.push_back(z);
      ch.contour_hole.push_back(con.hole);
      out.holes += con.hole;
      contour_junctions(el, p, con, path, z, zk + el.radius, out);
    }
  };

  std::int64_t next_path = 0;
  std::vector<LevelOut> outs;
  auto compute_chunk = [&](std::size_t c0, ZLevelChunk& merged) {
    const std::size_t c1 = std::min(levels.size(), c0 + p.chunk_levels);
    outs.assign(c1 - c0, LevelOut{});
    chunk_end = c1;
    next_inside = ZLevelInside{};
    cand = &by_top;
    if (!inside.empty()) {
      // Elements left out for an earlier chunk's region stay out (they lie at least half as
      // deep in this one); those not tested yet join in by_top order.
      if (inside.blocked_cells > 0) {
        filtered.clear();
        filtered_n = 0;
      }
      const std::size_t n = prefix(by_top, levels[c1 - 1] - grow);
      std::vector<std::uint32_t> test(filtered);
      test.insert(test.end(), by_top.begin() + std::ptrdiff_t(filtered_n),
                  by_top.begin() + std::ptrdiff_t(std::max(n, filtered_n)));
      filtered_n = std::max(n, filtered_n);
      constexpr std::size_t kBlock = 16384;
      const std::size_t blocks = (test.size() + kBlock - 1) / kBlock;
      std::vector<std::vector<std::uint32_t>> kept(blocks);
      par::for_each(blocks, 1, [&](std::size_t b) {
        const std::size_t b0 = b * kBlock, b1 = std::min(test.size(), b0 + kBlock);
        zlevel_filter_deep(el, std::span<const std::uint32_t>(test.data() + b0, b1 - b0), inside,
                           kept[b]);
      });
      filtered.clear();
      for (const auto& k : kept) filtered.insert(filtered.end(), k.begin(), k.end());
      cand = &filtered;
    }
    par::for_each(c1 - c0, 1, [&](std::size_t k) { run_level(c0 + k, outs[k]); });
    std::swap(inside, next_inside);
    merged = ZLevelChunk{};
    for (LevelOut& o : outs) {
      ZLevelChunk& ch = o.chunk;
      for (auto& s : ch.segments) s.path += next_path;
      for (auto& j : ch.junctions) j.path += next_path;
      next_path += std::int64_t(ch.contour_level.size());
      merged.cl.append(ch.cl);
      merged.segments.insert(merged.segments.end(), ch.segments.begin(), ch.segments.end());
      merged.junctions.insert(merged.junctions.end(), ch.junctions.begin(), ch.junctions.end());
      merged.contour_level.insert(merged.contour_level.end(), ch.contour_level.begin(),
                                  ch.contour_level.end());
      merged.contour_hole.insert(merged.contour_hole.end(), ch.contour_hole.begin(),
                                 ch.contour_hole.end());
      st.contours += ch.contour_level.size();
      st.holes += o.holes;
      st.segments += ch.segments.size();
      st.junctions += ch.junctions.size();
      st.convex += o.kinds[0];
      st.sharp_concave += o.kinds[1];
      st.tangent += o.kinds[2];
      st.candidates += o.candidates;
      st.open_chains += o.open_chains;
      st.points += o.points;
    }
  };
  stream_chunks<ZLevelChunk>(
      levels.size(), p.chunk_levels, compute_chunk, sink,
      [&](std::size_t done) {
        if (control.progress) control.progress(done, levels.size());
      },
      control, st.compute_s, st.sink_s);
  return st;
}

}  // namespace ncpath
