#include "engine/scan.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>
#include <stdexcept>

#include "engine/offset_elements_build.hpp"
#include "engine/chunk_stream.hpp"
#include "engine/parallel.hpp"
#include "kernels/cutters/drop_cutter.hpp"
#include "kernels/geom/tolerance.hpp"
#include "kernels/scan/envelope.hpp"

namespace ncpath {

std::string validate(const ScanParams& p) {
  std::ostringstream os;
  if (!(std::isfinite(p.interval) && p.interval > 0))
    os << "interval must be a positive number of mm, got " << p.interval;
  else if (!(std::isfinite(p.tolerance) && p.tolerance > 0))
    os << "tolerance must be a positive number of mm, got " << p.tolerance;
  else if (!(std::isfinite(p.margin) && p.margin >= 0))
    os << "margin must be >= 0 mm, got " << p.margin;
  else if (p.floor_z && !std::isfinite(*p.floor_z))
    os << "floor_z must be a finite number of mm";
  else if (p.chunk_planes == 0)
    os << "chunk_planes must be >= 1";
  else if (p.rect) {
    const auto& r = *p.rect;
    if (!(std::isfinite(r[0]) && std::isfinite(r[1]) && std::isfinite(r[2]) &&
          std::isfinite(r[3]) && r[2] >= r[0] && r[3] >= r[1]))
      os << "rect must be [x_min, y_min, x_max, y_max] with x_max >= x_min and y_max >= y_min";
  }
  return os.str();
}

namespace {

// One family's offset elements (in its frame: planes y = v, lines along x = u) and the index
// that finds the elements reaching a plane.
struct Family {
  const OffsetElements& el;
  const PlaneIndex& index;
};

Family family(const ScanElements& se, int f) { return {se.el[std::size_t(f)], se.index[std::size_t(f)]}; }

// Everything one plane produces, in the family frame (u, tip z) at v.
struct PlaneOut {
  std::vector<SlicePiece> pieces;
  PlaneCurve curve;
  std::vector<Vec2> polyline;  // lifted, in increasing u, end point included
  std::vector<std::uint8_t> contact;
  EnvelopeCounters counters;
};

// Pieces of the plane at v clipped to [u0, u1], plus the floor; envelope and curve.
void scan_plane(const Family& fam, double v, double u0, double u1, double floor_z,
                std::vector<std::uint32_t>& ids, PlaneOut& out) {
  ids.clear();
  fam.index.query(v, ids);
  out.pieces.clear();
  const OffsetElements& el = fam.el;
  const double R = el.radius;
  for (std::uint32_t id : ids) {
    // Elements whose x extent misses [u0, u1] give nothing there (a cheap test: windows of
    // pencil refinement are short).
    double lo, hi;
    element_extent(el, id, 0, lo, hi);
    if (hi < u0 || lo > u1) continue;
    slice_elements(el, v, id, id + 1, out.pieces);
  }
  std::size_t k = 0;
  for (SlicePiece& p : out.pieces) {
    p.x0 = std::max(p.x0, u0);
    p.x1 = std::min(p.x1, u1);
    if (p.x0 < p.x1) out.pieces[k++] = p;
  }
  out.pieces.resize(k);
  out.pieces.push_back(floor_piece(floor_z, R, v, u0, u1));
  std::vector<EnvelopeSpan> spans;
  upper_envelope(out.pieces, spans, &out.counters);
  plane_curve(out.pieces, spans, out.curve);
}

// Polyline of the curve's segments clipped to [a, b], lifted (see discretise_segment). A
// segment's end point is emitted when the next one does not start there (across a hole of
// the envelope, tol::kEnvelopeHole), so the tool crosses the hole at the higher height.
void polyline_between(const Family& fam, const PlaneOut& plane, double a, double b,
                      double tolerance, std::vector<Vec2>& pts, std::vector<std::uint8_t>& contact) {
  std::vector<CurveSegment> clipped;
  for (const CurveSegment& s : plane.curve.segments) {
    if (s.x1 < a || s.x0 > b || (s.vertical && (s.x0 <= a || s.x0 > b))) continue;
    CurveSegment c = s;
    if (!s.vertical) {
      const SlicePiece& pc = plane.pieces[s.piece];
      c.x0 = std::max(s.x0, a);
      c.x1 = std::min(s.x1, b);
      if (!(c.x0 < c.x1)) continue;
      c.z0 = tip_z(pc, c.x0);
      c.z1 = tip_z(pc, c.x1);
    }
    clipped.push_back(c);
  }
  std::vector<Vec2> raw;
  std::vector<double> lift;
  std::vector<std::uint8_t> kinds;
  for (std::size_t i = 0; i < clipped.size(); ++i) {
    const CurveSegment& c = clipped[i];
    const std::uint8_t code = contact_code(fam.el, plane.pieces[c.piece].element);
    discretise_segment(plane.pieces[c.piece], c, tolerance, raw, lift);
    const bool last = i + 1 == clipped.size();
    if (last || clipped[i + 1].x0 != c.x1) {
      // The end point: the curve's last point, or the near end of a hole's crossing.
      if (!(last && c.vertical)) {
        raw.emplace_back(c.x1, c.z1);
        lift.push_back(0);
      }
    }
    kinds.resize(raw.size(), code);
  }
  pts.resize(raw.size());
  for (std::size_t i = 0; i < raw.size(); ++i) {
    const double l = std::max(lift[i], i > 0 ? lift[i - 1] : 0.0);
    pts[i] = Vec2(raw[i].x(), raw[i].y() + l);
  }
  contact = std::move(kinds);
}

// Whether the cylinder section `pc` is a line over the segment: its middle within
// tol::kScanFlatSection of the chord (an edge nearly parallel to the plane: the ellipse's
// centre lies so far away that its record could not be evaluated to that accuracy).
bool flat_section(const SlicePiece& pc, const CurveSegment& s) {
  if (pc.kind != PieceKind::kCylinderEllipse || !(s.x1 > s.x0)) return false;
  const double xm = 0.5 * (s.x0 + s.x1);
  return std::abs(tip_z(pc, xm) - 0.5 * (s.z0 + s.z1)) <= tol::kScanFlatSection;
}

// Segment kind (PieceKind, or kScanSegmentVertical) and geometry as written.
std::uint8_t segment_kind(const SlicePiece& pc, const CurveSegment& s) {
  if (s.vertical) return kScanSegmentVertical;
  return flat_section(pc, s) ? std::uint8_t(PieceKind::kCylinderLine) : std::uint8_t(pc.kind);
}

std::array<double, 5> segment_geometry(const SlicePiece& pc, const CurveSegment& s) {
  std::array<double, 5> g{};
  const double R = pc.radius;
  if (s.vertical) {
    g[0] = s.x0;
    return g;
  }
  double slope = 0, intercept = 0;
  SectionEllipse e;
  if (flat_section(pc, s)) {
    slope = (s.z1 - s.z0) / (s.x1 - s.x0);
    g = {slope, s.z0 - slope * s.x0, 0, 0, 0};
  } else if (line_of(pc, slope, intercept)) {
    g = {slope, intercept - R, 0, 0, 0};
  } else if (pc.kind == PieceKind::kSphereArc) {
    const double d = pc.point.y() - pc.y0;
    g = {pc.point.x(), pc.point.z() - R, std::sqrt(std::max(0.0, (R - d) * (R + d))), 0, 0};
  } else if (ellipse_of(pc, e)) {
    g = {e.centre.x(), e.centre.y() - R, e.major, e.minor,
         std::atan2(e.major_axis.y(), e.major_axis.x())};
  }
  return g;
}

// The scanned rectangle: params.rect, or the part's xy box grown by the margin.
std::array<double, 4> scan_rect(const Aabb3& box, const ScanParams& p) {
  return p.rect.value_or(std::array<double, 4>{box.lo.x() - p.margin, box.lo.y() - p.margin,
                                               box.hi.x() + p.margin, box.hi.y() + p.margin});
}

}  // namespace

ScanElements build_scan_elements(const TriangleMesh& mesh, double radius,
                                 const std::array<std::vector<double>, 2>& only_at) {
  Stopwatch clock;
  ScanElements se;
  OffsetElements el = build_offset_elements_parallel(mesh, radius, false);
  if (el.facet_count() == 0) throw std::invalid_argument("the mesh has no usable facet");
  // A family sliced only along the other's side planes (only_at) keeps just the elements
  // near them.
  if (!only_at[0].empty()) {
    se.el[0] = elements_near_planes(el, 1, only_at[0]);
    se.el[1] = mirror_xy(std::move(el));
  } else {
    se.el[1] = mirror_xy(only_at[1].empty() ? el : elements_near_planes(el, 0, only_at[1]));
    se.el[0] = std::move(el);
  }
  par::overlap([&] { se.index[0] = build_plane_index(se.el[0], only_at[0]); },
               [&] { se.index[1] = build_plane_index(se.el[1], only_at[1]); });
  se.only_at = only_at;
  se.box = bounding_box(mesh);
  se.mesh_facets = mesh.facets.size();
  se.build_s = clock.seconds();
  return se;
}

std::vector<PlaneJunction> plane_junctions(const ScanElements& se, int f, double v, double u0,
                                           double u1, double floor_z) {
  PlaneOut plane;
  std::vector<std::uint32_t> ids;
  scan_plane(family(se, f), v, u0, u1, floor_z, ids, plane);
  std::vector<PlaneJunction> out;
  for (const CurveJunction& j : plane.curve.junctions) {
    PlaneJunction pj;
    auto w = [&](const Vec3& a) { return f == 0 ? a : Vec3(a.y(), a.x(), a.z()); };
    pj.position = w(Vec3(j.x, v, j.z));
    pj.b1 = w(j.b1);
    pj.b2 = w(j.b2);
    pj.kind = std::uint8_t(j.kind);
    pj.on_floor = j.element1 == kNoElement || j.element2 == kNoElement;
    pj.element1 = element_ref(family(se, f).el, j.element1);
    pj.element2 = element_ref(family(se, f).el, j.element2);
    out.push_back(pj);
  }
  return out;
}

ScanStats run_scan(const TriangleMesh& mesh, const Cutter& cutter, const ScanParams& p,
                   const std::function<void(const ScanChunk&)>& sink, RunControl& control) {
  if (std::string e = validate(cutter); !e.empty()) throw std::invalid_argument("tool: " + e);
  if (cutter.type != CutterType::kBall)
    throw std::invalid_argument("tool: curve-based scanning needs a ball-end mill");
  if (std::string e = validate(p); !e.empty()) throw std::invalid_argument(e);
  // A family that is not scanned is sliced only along the other's two side planes.
  const std::array<double, 4> rect = scan_rect(bounding_box(mesh), p);
  std::array<std::vector<double>, 2> only_at;
  if (p.families == ScanFamilies::kX) only_at[1] = {rect[0], rect[2]};
  if (p.families == ScanFamilies::kY) only_at[0] = {rect[1], rect[3]};
  const ScanElements se = build_scan_elements(mesh, cutter.radius, only_at);
  return run_scan(se, cutter, p, sink, control);
}

namespace {

// A family's (u, v, z) in world coordinates: family 0 runs along x (planes y = v), family 1
// along y (planes x = v, u and v swapped).
std::array<double, 3> world(int f, double u, double v, double z) {
  return f == 0 ? std::array<double, 3>{u, v, z} : std::array<double, 3>{v, u, z};
}

std::array<double, 3> world_vec(int f, const Vec3& b) {
  return f == 0 ? std::array<double, 3>{b.x(), b.y(), b.z()}
                : std::array<double, 3>{b.y(), b.x(), b.z()};
}

struct FamilyRun {
  int f;  // 0: x lines (planes y = v), 1: y lines (planes x = v)
  double u0, u1, v0;
  std::size_t planes;
  std::int64_t first_path;  // cut path index of its first line
};

// The families to scan (p.families) over rect, with their plane counts (in st) and first path.
std::vector<FamilyRun> plan_runs(const ScanElements& se, const ScanParams& p,
                                 const std::array<double, 4>& rect, ScanStats& st) {
  std::vector<FamilyRun> runs;
  std::int64_t paths = 0;
  for (int f : {0, 1}) {
    if ((f == 0 && p.families == ScanFamilies::kY) || (f == 1 && p.families == ScanFamilies::kX))
      continue;
    FamilyRun r{f, f == 0 ? rect[0] : rect[1], f == 0 ? rect[2] : rect[3],
                f == 0 ? rect[1] : rect[0], 0, paths};
    const std::vector<double>& side_at = se.only_at[std::size_t(1 - f)];
    if (!se.only_at[std::size_t(f)].empty() ||
        (!side_at.empty() && (std::find(side_at.begin(), side_at.end(), r.u0) == side_at.end() ||
                              std::find(side_at.begin(), side_at.end(), r.u1) == side_at.end())))
      throw std::logic_error("run_scan: the elements' plane indexes were built for other planes");
    const double extent = f == 0 ? rect[3] - rect[1] : rect[2] - rect[0];
    r.planes = std::size_t(std::floor(extent / p.interval + tol::kCountSlack)) + 1;
    paths += std::int64_t(r.planes);
    (f == 0 ? st.planes_x : st.planes_y) = r.planes;
    runs.push_back(r);
  }
  st.planes = st.planes_x + st.planes_y;
  return runs;
}

struct LineOut {
  ScanChunk chunk;
  std::uint64_t pieces = 0, decisions = 0, crossings = 0, cut = 0, link = 0, hidden = 0;
  std::uint64_t linear = 0;
  std::uint64_t kinds[3] = {0, 0, 0};
};

// The plane's exact segments and junctions as records of cut path `path`, in cutting order
// (reversed on a backward line).
void line_records(const Family& F, int f, const PlaneOut& plane, double v, std::int64_t path,
                  bool forward, LineOut& out) {
  ScanChunk& ch = out.chunk;
  const auto& segs = plane.curve.segments;
  for (std::size_t k = 0; k < segs.size(); ++k) {
    const CurveSegment& s = segs[forward ? k : segs.size() - 1 - k];
    const SlicePiece& pc = plane.pieces[s.piece];
    ScanSegmentRecord rec;
    rec.path = path;
    rec.kind = segment_kind(pc, s);
    rec.element = element_ref(F.el, pc.element);
    rec.start = world(f, s.x0, v, s.z0);
    rec.end = world(f, s.x1, v, s.z1);
    if (!forward) std::swap(rec.start, rec.end);
    rec.geometry = segment_geometry(pc, s);
    ch.segments.push_back(rec);
  }
  const auto& js = plane.curve.junctions;
  for (std::size_t k = 0; k < js.size(); ++k) {
    const CurveJunction& j = js[forward ? k : js.size() - 1 - k];
    ScanJunctionRecord rec;
    rec.path = path;
    rec.kind = std::uint8_t(j.kind);
    rec.position = world(f, j.x, v, j.z);
    rec.b1 = world_vec(f, forward ? j.b1 : j.b2);
    rec.b2 = world_vec(f, forward ? j.b2 : j.b1);
    rec.element1 = element_ref(F.el, forward ? j.element1 : j.element2);
    rec.element2 = element_ref(F.el, forward ? j.element2 : j.element1);
    rec.angle = std::acos(std::clamp(j.b1.dot(j.b2), -1.0, 1.0));
    ch.junctions.push_back(rec);
    ++out.kinds[std::size_t(j.kind)];
  }
}

}  // namespace

ScanStats run_scan(const ScanElements& se, const Cutter& cutter, const ScanParams& p,
                   const std::function<void(const ScanChunk&)>& sink, RunControl& control) {
  if (std::string e = validate(cutter); !e.empty()) throw std::invalid_argument("tool: " + e);
  if (cutter.type != CutterType::kBall || cutter.radius != se.el[0].radius)
    throw std::invalid_argument("tool: curve-based scanning needs the ball the elements are for");
  if (std::string e = validate(p); !e.empty()) throw std::invalid_argument(e);
  ScanStats st;
  const std::array<Family, 2> fam = {family(se, 0), family(se, 1)};
  st.elements_s = se.build_s;
  const OffsetElements& all = se.only_at[0].empty() ? se.el[0] : se.el[1];  // not a part
  st.facets = all.facet_count();
  st.edges = all.edge_count();
  st.vertices = all.vertex_count();
  st.facets_degenerate = se.mesh_facets - st.facets;

  const std::array<double, 4> rect = scan_rect(se.box, p);
  st.rect = rect;
  st.floor_z = p.floor_z.value_or(se.box.lo.z());

  const std::vector<FamilyRun> runs = plan_runs(se, p, rect, st);
  const std::uint64_t total_planes = st.planes;
  std::uint64_t done_planes = 0;

  for (std::size_t ri = 0; ri < runs.size(); ++ri) {
    const FamilyRun& run = runs[ri];
    const Family& F = fam[run.f];
    const Family& S = fam[1 - run.f];  // side planes: the other family at u0 and u1
    const double v_last = run.v0 + double(run.planes - 1) * p.interval;
    // Side curves (in S's frame: planes at u, parameter v).
    std::array<PlaneOut, 2> side;
    {
      std::vector<std::uint32_t> ids;
      scan_plane(S, run.u0, run.v0, v_last, st.floor_z, ids, side[0]);
      scan_plane(S, run.u1, run.v0, v_last, st.floor_z, ids, side[1]);
    }

    auto run_line = [&](std::size_t i, LineOut& out) {
      const double v = run.v0 + double(i) * p.interval;
      PlaneOut plane;
      std::vector<std::uint32_t> ids;
      scan_plane(F, v, run.u0, run.u1, st.floor_z, ids, plane);
      out.pieces += plane.pieces.size();
      out.decisions += plane.counters.decisions;
      out.crossings += plane.counters.crossings;
      out.hidden += plane.counters.hidden;
      for (const SlicePiece& pc : plane.pieces) out.linear += is_linear(pc);
      std::vector<Vec2> pts;
      std::vector<std::uint8_t> contact;
      polyline_between(F, plane, run.u0, run.u1, p.tolerance, pts, contact);
      const bool forward = i % 2 == 0;
      if (!forward) {
        std::reverse(pts.begin(), pts.end());
        std::reverse(contact.begin(), contact.end());
      }
      ScanChunk& ch = out.chunk;
      for (std::size_t k = 0; k < pts.size(); ++k) {
        const auto w = world(run.f, pts[k].x(), v, pts[k].y());
        ch.cl.xyz.insert(ch.cl.xyz.end(), w.begin(), w.end());
      }
      ch.cl.contact.insert(ch.cl.contact.end(), contact.begin(), contact.end());
      ch.cl.path_sizes.push_back(std::uint32_t(pts.size()));
      ch.cl.path_kinds.push_back(std::uint8_t(PathKind::kCut));
      out.cut += pts.size();
      line_records(F, run.f, plane, v, run.first_path + std::int64_t(i), forward, out);
      if (i + 1 == run.planes) return;
      // Link at depth along the side to the next line: the side plane's exact curve.
      const PlaneOut& sp = side[forward ? 1 : 0];
      std::vector<Vec2> lpts;
      std::vector<std::uint8_t> lcontact;
      polyline_between(S, sp, v, v + p.interval, p.tolerance, lpts, lcontact);
      const double u = forward ? run.u1 : run.u0;
      for (const Vec2& q : lpts) {
        const auto w = world(run.f, u, q.x(), q.y());
        ch.cl.xyz.insert(ch.cl.xyz.end(), w.begin(), w.end());
      }
      ch.cl.contact.insert(ch.cl.contact.end(), lcontact.begin(), lcontact.end());
      ch.cl.path_sizes.push_back(std::uint32_t(lpts.size()));
      ch.cl.path_kinds.push_back(std::uint8_t(PathKind::kLinkAtDepth));
      out.link += lpts.size();
    };

    // Chunks of planes computed in parallel while the previous chunk goes to the sink.
    const std::size_t per_chunk = p.chunk_planes;
    std::vector<LineOut> outs;
    auto compute_chunk = [&](std::size_t c0, ScanChunk& merged) {
      const std::size_t c1 = std::min(run.planes, c0 + per_chunk);
      outs.assign(c1 - c0, LineOut{});
      par::for_each(c1 - c0, 1, [&](std::size_t k) { run_line(c0 + k, outs[k]); });
      merged.cl.clear();
      merged.segments.clear();
      merged.junctions.clear();
      for (LineOut& o : outs) {
        merged.cl.append(o.chunk.cl);
        merged.segments.insert(merged.segments.end(), o.chunk.segments.begin(),
                               o.chunk.segments.end());
        merged.junctions.insert(merged.junctions.end(), o.chunk.junctions.begin(),
                                o.chunk.junctions.end());
        st.pieces += o.pieces;
        st.decisions += o.decisions;
        st.crossings += o.crossings;
        st.hidden += o.hidden;
        st.linear_pieces += o.linear;
        st.cut_points += o.cut;
        st.link_points += o.link;
        st.convex += o.kinds[0];
        st.sharp_concave += o.kinds[1];
        st.tangent += o.kinds[2];
        st.segments += o.chunk.segments.size();
        st.junctions += o.chunk.junctions.size();
      }
    };
    // Between families: a rapid from the last line's end to this family's first point.
    bool first = true;
    auto sink_run = [&](const ScanChunk& c) {
      if (first && ri > 0 && !c.cl.xyz.empty()) {
        ScanChunk hop;
        hop.cl.xyz = {c.cl.xyz[0], c.cl.xyz[1], c.cl.xyz[2]};
        hop.cl.contact = {c.cl.contact[0]};
        hop.cl.path_sizes = {1};
        hop.cl.path_kinds = {std::uint8_t(PathKind::kRapid)};
        sink(hop);
      }
      first = false;
      sink(c);
    };
    const std::uint64_t before = done_planes;
    stream_chunks<ScanChunk>(
        run.planes, per_chunk, compute_chunk, sink_run,
        [&](std::size_t done) {
          done_planes = before + done;
          if (control.progress) control.progress(done_planes, total_planes);
        },
        control, st.compute_s, st.sink_s);
  }
  return st;
}

}  // namespace ncpath
