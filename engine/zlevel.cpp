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

// Polyline of one contour segment from a (included) towards b (excluded): lines exactly,
// arcs by their circumscribed polygon (see zlevel.hpp), never inside the region.
void arc_outside(const ContourSeg& s, double tol, std::vector<Vec2>& out) {
  out.push_back(s.a);
  if (s.kind == ContourSegKind::kLine) return;
  const double span = s.t1 - s.t0;
  const double r = std::max(s.r1, s.r2);
  // k = 1 / cos(dt / 2) - 1 <= tol / r.
  const double max_dt = 2 * std::acos(1 / (1 + tol / r));
  const int n = std::max(1, int(std::ceil(std::abs(span) / max_dt - tol::kCountSlack)));
  if (n > 100000) return;  // a near-line (huge ellipse): its chord is within rounding
  const double dt = span / n, k = 1 / std::cos(dt / 2);
  const Vec2 perp(-s.axis.y(), s.axis.x());
  for (int j = 1; j <= n; ++j) {
    const double t = s.t0 + (j - 0.5) * dt;
    out.push_back(s.centre + k * (s.r1 * std::cos(t) * s.axis + s.r2 * std::sin(t) * perp));
  }
}

struct LevelOut {
  ZLevelChunk chunk;
  std::uint64_t candidates = 0, open_chains = 0, repaired_links = 0, holes = 0, points = 0;
  std::uint64_t kinds[3] = {0, 0, 0};
};

}  // namespace

ZLevelOpStats run_zlevel(const TriangleMesh& mesh, const Cutter& cutter,
                         const ZLevelOpParams& p,
                         const std::function<void(const ZLevelChunk&)>& sink,
                         RunControl& control) {
  if (std::string e = validate(cutter); !e.empty()) throw std::invalid_argument("tool: " + e);
  if (cutter.type != CutterType::kBall)
    throw std::invalid_argument("tool: z-level contouring needs a ball-end mill");
  if (std::string e = validate(p); !e.empty()) throw std::invalid_argument(e);
  ZLevelOpStats st;
  const double R = cutter.radius;

  Stopwatch el_clock;
  const OffsetElements el = build_offset_elements_parallel(mesh, R, false, Coplanar::kVertical);
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
  const std::size_t nfe = el.facet_count() + el.edge_count();
  const std::vector<double>& reach = boxes.reach;
  std::vector<std::uint32_t> by_top(nfe);
  std::iota(by_top.begin(), by_top.end(), 0u);
  par::sort(by_top.begin(), by_top.end(), [&](std::uint32_t a, std::uint32_t b) {
    return reach[a] != reach[b] ? reach[a] > reach[b] : a < b;
  });
  const Aabb3 box = bounding_box(mesh);
  st.top_z = box.hi.z();
  st.bottom_z = box.lo.z();
  st.elements_s = el_clock.seconds();

  std::vector<double> levels = p.levels;
  if (p.step_down > 0)
    for (int k = 1; st.top_z - k * p.step_down > st.bottom_z; ++k)
      levels.push_back(st.top_z - k * p.step_down);
  std::sort(levels.begin(), levels.end(), std::greater<>());
  st.levels = levels.size();

  // Cut path index of each level's first contour is only known after the levels before it:
  // records are numbered per chunk and shifted when the chunk is merged.
  auto run_level = [&](std::size_t i, LevelOut& out) {
    const double z = levels[i];
    const double zc = z + el.radius;  // as the kernel computes it
    const auto n = std::size_t(
        std::lower_bound(by_top.begin(), by_top.end(), zc,
                         [&](std::uint32_t id, double c) { return reach[id] >= c; }) -
        by_top.begin());
    const ZLevelResult r =
        zlevel_contours(el, std::span<const std::uint32_t>(by_top.data(), n), z, kernel);
    out.candidates = n;
    out.open_chains = r.stats.open_chains;
    out.repaired_links = r.stats.repaired_links;
    ZLevelChunk& ch = out.chunk;
    std::vector<Vec2> pts;
    for (std::size_t c = 0; c < r.contours.size(); ++c) {
      const ZContour& con = r.contours[c];
      const auto path = std::int64_t(c);  // shifted later
      pts.clear();
      std::vector<std::uint8_t> contact;
      for (const ContourSeg& s : con.segs) {
        const std::size_t before = pts.size();
        arc_outside(s, p.tolerance, pts);
        contact.resize(pts.size(), contact_code(el, s.element));
        (void)before;
        ZLevelSegmentRecord rec;
        rec.path = path;
        rec.kind = std::uint8_t(s.kind);
        rec.shadow = s.shadow;
        rec.element = element_ref(el, s.element);
        rec.start = {s.a.x(), s.a.y(), z};
        rec.end = {s.b.x(), s.b.y(), z};
        if (s.kind != ContourSegKind::kLine)
          rec.geometry = {s.centre.x(), s.centre.y(), s.r1, s.r2,
                          std::atan2(s.axis.y(), s.axis.x()), s.t0, s.t1};
        ch.segments.push_back(rec);
      }
      if (pts.empty()) continue;
      pts.push_back(pts.front());  // closed
      contact.push_back(contact.front());
      if (!ch.cl.path_sizes.empty() || i > 0) {
        ch.cl.xyz.insert(ch.cl.xyz.end(), {pts[0].x(), pts[0].y(), z});
        ch.cl.contact.push_back(contact[0]);
        ch.cl.path_sizes.push_back(1);
        ch.cl.path_kinds.push_back(std::uint8_t(PathKind::kRapid));
      }
      for (const Vec2& q : pts) ch.cl.xyz.insert(ch.cl.xyz.end(), {q.x(), q.y(), z});
      ch.cl.contact.insert(ch.cl.contact.end(), contact.begin(), contact.end());
      ch.cl.path_sizes.push_back(std::uint32_t(pts.size()));
      ch.cl.path_kinds.push_back(std::uint8_t(PathKind::kCut));
      out.points += pts.size();
      ch.contour_level.push_back(z);
      ch.contour_hole.push_back(con.hole);
      out.holes += con.hole;
      for (const ZJunction& j : con.junctions) {
        ZLevelJunctionRecord rec;
        rec.path = path;
        rec.kind = std::uint8_t(j.kind);
        rec.position = {j.position.x(), j.position.y(), j.position.z()};
        rec.b1 = {j.b1.x(), j.b1.y(), j.b1.z()};
        rec.b2 = {j.b2.x(), j.b2.y(), j.b2.z()};
        rec.element1 = element_ref(el, j.e1);
        rec.element2 = element_ref(el, j.e2);
        rec.angle = std::acos(std::clamp(j.b1.dot(j.b2), -1.0, 1.0));
        ch.junctions.push_back(rec);
        ++out.kinds[std::size_t(j.kind)];
      }
    }
  };

  std::int64_t next_path = 0;
  std::vector<LevelOut> outs;
  auto compute_chunk = [&](std::size_t c0, ZLevelChunk& merged) {
    const std::size_t c1 = std::min(levels.size(), c0 + p.chunk_levels);
    outs.assign(c1 - c0, LevelOut{});
    par::for_each(c1 - c0, 1, [&](std::size_t k) { run_level(c0 + k, outs[k]); });
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
      st.repaired_links += o.repaired_links;
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
