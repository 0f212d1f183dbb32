// Coplanar regions of the offset elements (kernels/mesh/offset_elements: share_coplanar_offsets,
// drop_straight_vertices, Coplanar) and their effect on the drive-plane scan (plane_slice,
// envelope). A mesh whose flat faces are split into many triangles (midpoint subdivision, a
// CAD pocket) must give the same CL curve as the unsplit mesh:
//   - the edges inside a face and the vertices inside a face or a straight edge line are
//     dropped (Coplanar::kMerge) and kept with Coplanar::kKeep; the facets of one face share
//     one normal bitwise, so their offset triangles share corners bitwise;
//   - the exact curve equals the brute-force drop-cutter of the unsplit mesh within 1e-9 mm,
//     including drive planes through vertices exactly, and has no kink (bi-contact vectors
//     apart by more than 1e-6 rad) that the unsplit mesh's curve lacks, nor two junctions at
//     one x except around a vertical segment.
// Which facet, edge or vertex lies inside which face is known from the construction, never
// from the kernel.
#include "kernels/mesh/offset_elements.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <unordered_map>
#include <vector>

#include "kernels/mesh/subdivide.hpp"
#include "kernels/scan/envelope.hpp"
#include "tests/kernels/scan/scan_test_support.hpp"

namespace ncpath {
namespace {

using namespace scan_test;

constexpr double kCurveTol = 1e-9;    // mm: curve vs drop-cutter
constexpr double kKinkAngle = 1e-6;   // rad: bi-contact vectors this far apart make a kink
constexpr double kKinkMatchX = 1e-7;  // mm: a kink of one curve found at this x in the other

std::uint64_t key(std::uint32_t u, std::uint32_t v) {
  return (std::uint64_t{std::min(u, v)} << 32) | std::max(u, v);
}

// Edge index of el by vertex pair.
std::unordered_map<std::uint64_t, std::uint32_t> edge_index(const OffsetElements& el) {
  std::unordered_map<std::uint64_t, std::uint32_t> out;
  for (std::uint32_t e = 0; e < el.edge_count(); ++e)
    out[key(el.edge_vertices[e][0], el.edge_vertices[e][1])] = e;
  return out;
}

// Vertex slot of el by point index.
std::unordered_map<std::uint32_t, std::uint32_t> vertex_index(const OffsetElements& el) {
  std::unordered_map<std::uint32_t, std::uint32_t> out;
  for (std::uint32_t v = 0; v < el.vertex_count(); ++v) out[el.vertex_source[v]] = v;
  return out;
}

double angle_between(const Vec3& a, const Vec3& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

// ---- the drive-plane scan, as engine/scan.cpp does it ----

struct Plane {
  std::vector<SlicePiece> pieces;
  std::vector<EnvelopeSpan> spans;
  PlaneCurve curve;
};

// Elements whose trimmed y reach holds y0 (the engine's plane index), sliced with trimming,
// clipped to [x_lo, x_hi], plus the floor.
Plane scan_plane(const OffsetElements& el, double y0, double floor_z, double x_lo, double x_hi) {
  Plane p;
  for (std::uint32_t id = 0; id < el.element_count(); ++id) {
    double lo, hi;
    if (element_y_reach(el, id, lo, hi) && lo <= y0 && y0 <= hi)
      slice_elements(el, y0, id, id + 1, p.pieces);
  }
  std::erase_if(p.pieces, [&](SlicePiece& pc) {
    pc.x0 = std::max(pc.x0, x_lo);
    pc.x1 = std::min(pc.x1, x_hi);
    return !(pc.x0 < pc.x1);
  });
  p.pieces.push_back(floor_piece(floor_z, el.radius, y0, x_lo, x_hi));
  upper_envelope(p.pieces, p.spans);
  plane_curve(p.pieces, p.spans, p.curve);
  return p;
}

// Tip z of the curve at x: the highest non-vertical segment holding x.
double curve_z(const Plane& p, double x) {
  double best = -INFINITY;
  for (const CurveSegment& s : p.curve.segments)
    if (!s.vertical && x >= s.x0 && x <= s.x1) best = std::max(best, tip_z(p.pieces[s.piece], x));
  return best;
}

struct Worst {
  double err = 0;
  std::string where;
  int checks = 0;
  void add(double got, double want, const std::string& label, double x) {
    ++checks;
    const double e = std::abs(got - want);
    if (!(e <= err)) {
      err = e;
      std::ostringstream s;
      s.precision(17);
      s << label << " x " << x << " curve " << got << " drop-cutter " << want;
      where = s.str();
    }
  }
};

// The curve against the oracle at segment middles and ends, 1e-6 mm either side of each
// jump (vertical segment), and at `samples` random x. Skipped: x within kSteepGap of a jump
// or of a segment end where the piece's slope exceeds kSteepSlope (an arc ending with a
// vertical tangent). There the height is ill-conditioned: where an arc ends is rounded to
// ~1e-15 mm, and the arc rises by sqrt(2 R dx) over dx, ~1e-7 mm; kSteepGap further out
// the slope is at most sqrt(R / (2 kSteepGap)) ~ 4e4 and the same rounding moves z by
// ~1e-11 mm.
constexpr double kSteepGap = 1e-9, kSteepSlope = 1e6;
template <class Oracle>
void compare_with_oracle(const Plane& p, Oracle&& want, double x_lo, double x_hi, int samples,
                         std::mt19937_64& rng, const std::string& label, Worst& worst) {
  const auto& segs = p.curve.segments;
  std::vector<double> steep;
  for (const CurveSegment& s : segs) {
    if (s.vertical) {
      steep.push_back(s.x0);
      continue;
    }
    for (double x : {s.x0, s.x1})
      if (!(std::abs(slope(p.pieces[s.piece], x)) <= kSteepSlope)) steep.push_back(x);
  }
  auto check = [&](double got, double x, const char* what) {
    for (double xs : steep)
      if (std::abs(x - xs) <= kSteepGap) return;
    worst.add(got, want(x), label + what, x);
  };
  for (const CurveSegment& s : segs) {
    if (s.vertical) {
      for (double x : {s.x0 - 1e-6, s.x0 + 1e-6})
        if (x > x_lo && x < x_hi) check(curve_z(p, x), x, " near jump");
      continue;
    }
    const double xm = 0.5 * (s.x0 + s.x1);
    check(tip_z(p.pieces[s.piece], xm), xm, " mid");
    check(s.z0, s.x0, " start");
    check(s.z1, s.x1, " end");
  }
  std::uniform_real_distribution<double> rx(x_lo, x_hi);
  for (int k = 0; k < samples; ++k) {
    const double x = rx(rng);
    check(curve_z(p, x), x, " random");
  }
}

// Two junctions share an x only at the two ends of a vertical segment.
void expect_distinct_junctions(const Plane& p, const std::string& label) {
  const auto& js = p.curve.junctions;
  for (std::size_t k = 0; k + 1 < js.size(); ++k) {
    if (js[k + 1].x > js[k].x) continue;
    EXPECT_TRUE(p.curve.segments[js[k].segment].vertical)
        << label << ": two junctions at x " << js[k].x << " (elements " << js[k].element1 << ","
        << js[k].element2 << " and " << js[k + 1].element1 << "," << js[k + 1].element2 << ")";
  }
}

double junction_angle(const CurveJunction& j) { return angle_between(j.b1, j.b2); }

// |difference of the two pieces' slopes| at a junction (infinite at a vertical segment).
double slope_gap(const Plane& p, const CurveJunction& j) {
  const auto& segs = p.curve.segments;
  if (segs[j.segment].vertical || (j.segment > 0 && segs[j.segment - 1].vertical)) return INFINITY;
  if (j.segment == 0) return INFINITY;
  const double a = slope(p.pieces[segs[j.segment - 1].piece], j.x);
  const double b = slope(p.pieces[segs[j.segment].piece], j.x);
  return std::abs(a - b);
}

// Every kink of `a` (bi-contact vectors more than `min_angle` apart) has a junction of the
// same kind in `b` at the same x, bent more than kKinkAngle / 10 (a margin so that a kink
// right at kKinkAngle cannot flip). x within kKinkMatchX, or within what the envelope's tie
// rule allows at a shallow crossing (tol::kEnvelopeTie over the slope difference; at most
// 1e-4 mm, where the slopes agree).
void expect_kinks_in(const Plane& a, const Plane& b, double min_angle, const std::string& label,
                     int& kinks) {
  for (const CurveJunction& j : a.curve.junctions) {
    if (!(junction_angle(j) > min_angle)) continue;
    ++kinks;
    const double tol_x = std::min(kKinkMatchX + 2 * tol::kEnvelopeTie / slope_gap(a, j), 1e-4);
    bool found = false;
    for (const CurveJunction& k : b.curve.junctions)
      found = found || (std::abs(k.x - j.x) <= tol_x && k.kind == j.kind &&
                        junction_angle(k) > 0.1 * kKinkAngle);
    EXPECT_TRUE(found) << label << ": kink at x " << j.x << " z " << j.z << " angle "
                       << junction_angle(j) << " kind " << junction_kind_name(j.kind)
                       << " elements " << j.element1 << "," << j.element2;
  }
}

// The split mesh's curve has no kink the unsplit one lacks (kKinkAngle), and keeps the
// unsplit one's creases. The second direction only counts kinks above kCreaseAngle: the
// envelope's tie rule (tol::kEnvelopeTie) can hand a stretch where two arcs touch to the
// lower element id and switch where they part by 1e-10 mm, a junction bent by about
// sqrt(2 tie / R) ~ 1e-5 rad that depends on element ids; the unsplit mesh is the
// reference here, not the subject.
constexpr double kCreaseAngle = 1e-3;
void expect_same_kinks(const Plane& split, const Plane& unsplit, const std::string& label,
                       int& kinks) {
  expect_kinks_in(split, unsplit, kKinkAngle, label + " split kink missing in unsplit", kinks);
  expect_kinks_in(unsplit, split, kCreaseAngle, label + " unsplit crease missing in split", kinks);
}

// ---- 1, 2: a random terrain subdivided twice ----

// The terrain, subdivided twice, and what lies where: children of original facet i are
// facets 16 i .. 16 i + 15 (subdivide_midpoint puts the children of i at 4 i .. 4 i + 3).
struct Refined {
  TriangleMesh coarse, fine;
  std::uint32_t coarse_vertices = 0;
  // Fine edges lying on an original edge -> that edge's key in coarse.
  std::unordered_map<std::uint64_t, std::uint64_t> on_edge;
  std::vector<std::uint64_t> interior_edges;  // fine edges inside an original facet
  std::vector<std::uint32_t> facet_inner_vertices, edge_inner_vertices;
};

// Midpoint of edge {u, v} of `parent` in its subdivision `child`, read off the children.
std::unordered_map<std::uint64_t, std::uint32_t> midpoints(const TriangleMesh& parent,
                                                           const TriangleMesh& child) {
  std::unordered_map<std::uint64_t, std::uint32_t> mid;
  for (std::size_t i = 0; i < parent.facets.size(); ++i) {
    const auto& f = parent.facets[i];
    mid[key(f[0], f[1])] = child.facets[4 * i][1];  // (a, m_ab, m_ca)
    mid[key(f[2], f[0])] = child.facets[4 * i][2];
    mid[key(f[1], f[2])] = child.facets[4 * i + 1][2];  // (m_ab, b, m_bc)
  }
  return mid;
}

Refined refine(const TriangleMesh& coarse) {
  Refined r;
  r.coarse = coarse;
  r.coarse_vertices = std::uint32_t(coarse.vertices.size());
  const TriangleMesh mid_mesh = subdivide_midpoint(coarse);
  r.fine = subdivide_midpoint(mid_mesh);
  const auto m1 = midpoints(coarse, mid_mesh), m2 = midpoints(mid_mesh, r.fine);
  std::map<std::uint64_t, int> seen;
  for (std::size_t i = 0; i < coarse.facets.size(); ++i) {
    const auto& f = coarse.facets[i];
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = f[k], b = f[(k + 1) % 3];
      const std::uint32_t m = m1.at(key(a, b)), q1 = m2.at(key(a, m)), q2 = m2.at(key(m, b));
      for (std::uint64_t e : {key(a, q1), key(q1, m), key(m, q2), key(q2, b)})
        r.on_edge[e] = key(a, b);
      if (seen[key(a, b)]++ == 0)
        r.edge_inner_vertices.insert(r.edge_inner_vertices.end(), {m, q1, q2});
    }
    // The inner vertices: midpoints of the middle child's edges.
    const auto& mid_child = mid_mesh.facets[4 * i + 3];
    for (int k = 0; k < 3; ++k)
      r.facet_inner_vertices.push_back(m2.at(key(mid_child[k], mid_child[(k + 1) % 3])));
  }
  std::map<std::uint64_t, int> inner;
  for (std::size_t c = 0; c < r.fine.facets.size(); ++c) {
    const auto& f = r.fine.facets[c];
    for (int k = 0; k < 3; ++k) {
      const std::uint64_t e = key(f[k], f[(k + 1) % 3]);
      if (!r.on_edge.count(e)) ++inner[e];
    }
  }
  for (const auto& [e, n] : inner) {
    EXPECT_EQ(n, 2) << "an inner edge of an original facet has two children";
    r.interior_edges.push_back(e);
  }
  return r;
}

TEST(Coplanar, SubdividedTerrainDropsInnerElements) {
  std::mt19937_64 rng(2024);
  const Refined r = refine(random_terrain(rng, 12));
  const double R = 1.25;
  const std::size_t nf0 = r.coarse.facets.size();
  ASSERT_EQ(r.interior_edges.size(), 18 * nf0);  // 48 half-edges, 12 on the sides, per facet
  const OffsetElements coarse = build_offset_elements(r.coarse, R, Coplanar::kMerge);
  const OffsetElements merged = build_offset_elements(r.fine, R, Coplanar::kMerge);
  const OffsetElements kept = build_offset_elements(r.fine, R, Coplanar::kKeep);
  ASSERT_EQ(merged.facet_count(), r.fine.facets.size());  // no degenerate facets
  ASSERT_EQ(kept.facet_count(), r.fine.facets.size());
  ASSERT_EQ(merged.edge_count(), kept.edge_count());
  ASSERT_EQ(merged.vertex_count(), kept.vertex_count());
  for (std::uint32_t s = 0; s < merged.facet_count(); ++s) ASSERT_EQ(merged.facet_source[s], s);
  const auto merged_edges = edge_index(merged), coarse_edges = edge_index(coarse);
  const auto merged_verts = vertex_index(merged), coarse_verts = vertex_index(coarse);

  // (a) kMerge: edges inside an original facet and vertices inside a facet or an original
  // edge are unreachable (and give no y reach, so the scan never sees them).
  std::vector<std::uint8_t> interior(merged.edge_count(), 0);
  for (std::uint64_t k : r.interior_edges) {
    const std::uint32_t e = merged_edges.at(k);
    interior[e] = 1;
    double lo, hi;
    EXPECT_FALSE(element_reachable(merged, merged.edge_id(e))) << "inner edge " << e;
    EXPECT_FALSE(element_y_reach(merged, merged.edge_id(e), lo, hi)) << "inner edge " << e;
  }
  ASSERT_FALSE(r.facet_inner_vertices.empty());
  ASSERT_FALSE(r.edge_inner_vertices.empty());
  for (const auto* list : {&r.facet_inner_vertices, &r.edge_inner_vertices})
    for (std::uint32_t v : *list)
      EXPECT_FALSE(element_reachable(merged, merged.vertex_id(merged_verts.at(v))))
          << "vertex " << v << " at " << r.fine.vertices[v].transpose();
  // Everything else is as on the unsplit mesh: a piece of an original edge is reachable as
  // that edge is (the same two planes meet there); original vertices likewise.
  for (const auto& [k, orig] : r.on_edge)
    EXPECT_EQ(merged.edge_reachable[merged_edges.at(k)],
              coarse.edge_reachable[coarse_edges.at(orig)]);
  for (std::uint32_t v = 0; v < r.coarse_vertices; ++v) {
    if (!coarse_verts.count(v)) continue;  // unreferenced
    EXPECT_EQ(merged.vertex_reachable[merged_verts.at(v)],
              coarse.vertex_reachable[coarse_verts.at(v)])
        << "original vertex " << v;
  }

  // (b) One normal per original facet, bitwise, close to the facet's own; the offset
  // triangles of its children meet at bitwise equal corners.
  int normals_rounded_apart = 0, corners_apart_kept = 0;
  for (std::size_t i = 0; i < nf0; ++i) {
    const auto& f = r.coarse.facets[i];
    Vec3 n0;
    ASSERT_TRUE(upward_unit_normal(r.coarse.vertices[f[0]], r.coarse.vertices[f[1]],
                                   r.coarse.vertices[f[2]], n0));
    const Vec3 n = merged.facet_normal[16 * i];
    EXPECT_LT((n - n0).norm(), 1e-12) << "facet " << i;
    std::unordered_map<std::uint32_t, Vec3> corner, corner_kept;
    for (std::size_t c = 16 * i; c < 16 * i + 16; ++c) {
      EXPECT_TRUE(merged.facet_normal[c] == n) << "child " << c << " of facet " << i;
      normals_rounded_apart += !(kept.facet_normal[c] == n);
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t v = merged.facet_vertices[c][k];
        const auto [it, fresh] = corner.emplace(v, merged.facet_tri[c][k]);
        if (!fresh) {
          EXPECT_TRUE(it->second == merged.facet_tri[c][k])
              << "offset corner of vertex " << v << " in child " << c;
        }
        const auto [jt, fresh_kept] = corner_kept.emplace(v, kept.facet_tri[c][k]);
        if (!fresh_kept) corners_apart_kept += !(jt->second == kept.facet_tri[c][k]);
      }
    }
  }
  // Without merging, the children's normals differ by rounding: (b) is not vacuous.
  EXPECT_GT(normals_rounded_apart, 0);
  EXPECT_GT(corners_apart_kept, 0);

  // (c) kKeep drops nothing: inner edges stay flat and reachable (bent less than
  // tol::kFlatEdgeKeep), every vertex with a reachable edge stays, normals are the facets'
  // own. Edges outside the regions are the same in both builds.
  for (std::uint32_t e = 0; e < kept.edge_count(); ++e) {
    if (interior[e]) {
      EXPECT_EQ(kept.edge_reachable[e], 1) << "inner edge " << e;
      EXPECT_EQ(kept.edge_flat[e], 1) << "inner edge " << e;
      EXPECT_EQ(kept.edge_kind[e], EdgeKind::kFlat) << "inner edge " << e;
    } else {
      EXPECT_EQ(kept.edge_reachable[e], merged.edge_reachable[e]) << "edge " << e;
      EXPECT_TRUE(kept.edge_wedge[e][0] == merged.edge_wedge[e][0] &&
                  kept.edge_wedge[e][1] == merged.edge_wedge[e][1])
          << "edge " << e;
    }
  }
  // Midpoints have flat inner edges, so they stay; an original corner keeps the edges it had
  // (no inner edge reaches it), so it is reachable as on the unsplit mesh (a pit is not).
  const auto kept_verts = vertex_index(kept);
  for (const auto* list : {&r.facet_inner_vertices, &r.edge_inner_vertices})
    for (std::uint32_t v : *list)
      EXPECT_EQ(kept.vertex_reachable[kept_verts.at(v)], 1) << "vertex " << v;
  for (std::uint32_t v = 0; v < r.coarse_vertices; ++v) {
    if (!coarse_verts.count(v)) continue;
    EXPECT_EQ(kept.vertex_reachable[kept_verts.at(v)], coarse.vertex_reachable[coarse_verts.at(v)])
        << "original vertex " << v;
  }
  for (std::uint32_t c = 0; c < kept.facet_count(); ++c) {
    const auto& f = r.fine.facets[c];
    Vec3 n;
    ASSERT_TRUE(
        upward_unit_normal(r.fine.vertices[f[0]], r.fine.vertices[f[1]], r.fine.vertices[f[2]], n));
    EXPECT_TRUE(kept.facet_normal[c] == n) << "facet " << c;
  }
}

// The scan of `r.fine` (merged) against the drop-cutter of `r.coarse` and against the scan of
// `r.coarse`, over random planes and planes exactly through vertices of the split mesh
// (midpoints on original edges and inside facets, original corners) and through corners of
// its offset triangles.
void check_split_terrain(const Refined& r, double R, std::mt19937_64& rng) {
  const double floor_z = -0.5, x_lo = -1.5, x_hi = 21.5;
  const OffsetElements fine = build_offset_elements(r.fine, R, Coplanar::kMerge);
  const OffsetElements coarse = build_offset_elements(r.coarse, R, Coplanar::kMerge);
  const auto facets = prepare_all(r.coarse);  // the oracle sees the unsplit mesh only
  const Cutter ball = ball_cutter(2 * R);

  std::vector<double> ys;
  std::uniform_real_distribution<double> ry(-1, 21);
  for (int k = 0; k < 20; ++k) ys.push_back(ry(rng));
  std::uniform_int_distribution<std::size_t> pick_edge(0, r.edge_inner_vertices.size() - 1),
      pick_inner(0, r.facet_inner_vertices.size() - 1), pick_corner(0, r.coarse_vertices - 1),
      pick_facet(0, fine.facet_count() - 1);
  auto y_of = [&](std::uint32_t v) { return r.fine.vertices[v].y(); };
  for (int k = 0; k < 12; ++k) ys.push_back(y_of(r.edge_inner_vertices[pick_edge(rng)]));
  for (int k = 0; k < 6; ++k) ys.push_back(y_of(r.facet_inner_vertices[pick_inner(rng)]));
  for (int k = 0; k < 6; ++k) ys.push_back(y_of(std::uint32_t(pick_corner(rng))));
  for (int k = 0; k < 12; ++k) ys.push_back(fine.facet_tri[pick_facet(rng)][k % 3].y());

  Worst worst;
  int kinks = 0;
  for (double y0 : ys) {
    std::ostringstream label;
    label.precision(17);
    label << "R " << R << " plane y " << y0;
    const Plane pf = scan_plane(fine, y0, floor_z, x_lo, x_hi);
    const Plane pc = scan_plane(coarse, y0, floor_z, x_lo, x_hi);
    ASSERT_EQ(pf.curve.run_starts.size(), 1u) << label.str();
    auto want = [&](double x) { return std::max(floor_z, drop_all(ball, facets, x, y0)); };
    compare_with_oracle(pf, want, x_lo, x_hi, 200, rng, label.str(), worst);
    expect_distinct_junctions(pf, label.str());
    expect_same_kinks(pf, pc, label.str(), kinks);
  }
  EXPECT_LE(worst.err, kCurveTol) << worst.where;
  EXPECT_GE(worst.checks, int(ys.size()) * 250);
  EXPECT_GT(kinks, int(ys.size()));  // the terrain has valleys: kinks are compared
}

TEST(Coplanar, SubdividedTerrainCurveEqualsOriginal) {
  std::mt19937_64 rng(2024);
  const Refined r = refine(random_terrain(rng, 12));
  check_split_terrain(r, 1.25, rng);
  std::mt19937_64 rng2(515);
  check_split_terrain(refine(random_terrain(rng2, 10)), 2.5, rng2);
}

// ---- 3: a CAD pocket with flat faces split into many triangles ----

// A 20 x 20 plate, top z = 3, with a 10 x 10 pocket of floor z = 0 and vertical walls (the
// coarse version is envelope_test's box pocket). Floor n x n cells, walls n x k cells, the
// top ring n trapezoids a side; each cell split along a random diagonal, each triangle wound
// at random. Face tags: 0 floor, 1-4 walls, 5 top. Placed by `pose`: tilted about x, then
// turned about z (turned only, the walls stay vertical up to rounding, with n.z of either
// sign; tilted, the floor and top get normals that differ by rounding).
struct Pose {
  double turn = 0, tilt = 0;  // rad
  Vec3 operator()(const Vec3& p) const {
    const double ct = std::cos(tilt), st = std::sin(tilt);
    const Vec3 q(p.x(), ct * p.y() - st * p.z(), st * p.y() + ct * p.z());
    const double c = std::cos(turn), s = std::sin(turn);
    return Vec3(c * q.x() - s * q.y(), s * q.x() + c * q.y(), q.z());
  }
  bool exact() const { return turn == 0 && tilt == 0; }
};

struct Pocket {
  TriangleMesh mesh;
  std::vector<int> face;
  std::vector<Vec3> plan;  // vertex positions before the pose (exact grid values)
};

Pocket cad_pocket(int n, int k, const Pose& pose, std::mt19937_64& rng) {
  Pocket pk;
  std::map<std::array<double, 3>, std::uint32_t> ids;
  auto vid = [&](double x, double y, double z) {
    const auto [it, fresh] = ids.emplace(std::array<double, 3>{x, y, z}, 0);
    if (fresh) {
      it->second = std::uint32_t(pk.plan.size());
      pk.plan.emplace_back(x, y, z);
    }
    return it->second;
  };
  std::bernoulli_distribution coin(0.5);
  auto tri = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c, int face) {
    if (coin(rng)) std::swap(b, c);
    pk.mesh.facets.push_back({a, b, c});
    pk.face.push_back(face);
  };
  auto quad = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d, int face) {
    if (coin(rng)) {
      tri(a, b, c, face);
      tri(a, c, d, face);
    } else {
      tri(a, b, d, face);
      tri(b, c, d, face);
    }
  };
  const double in = 5, out = 10, top = 3;
  // Grid values: integers over the cell count, exact for the sizes used here.
  auto at = [&](double lo, double hi, int i, int cells) { return lo + (hi - lo) * i / cells; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double x0 = at(-in, in, i, n), x1 = at(-in, in, i + 1, n);
      const double y0 = at(-in, in, j, n), y1 = at(-in, in, j + 1, n);
      quad(vid(x0, y0, 0), vid(x1, y0, 0), vid(x1, y1, 0), vid(x0, y1, 0), 0);
    }
  // Side s runs along the pocket's boundary counter-clockwise, corner s to corner s + 1;
  // point t / n of the way along it on the square of half-width r.
  const double cx[5] = {-1, 1, 1, -1, -1}, cy[5] = {-1, -1, 1, 1, -1};
  for (int s = 0; s < 4; ++s) {
    auto side = [&](double r, int t, double z) {
      return vid(r * (cx[s] * (n - t) + cx[s + 1] * t) / n,
                 r * (cy[s] * (n - t) + cy[s + 1] * t) / n, z);
    };
    for (int i = 0; i < n; ++i) {
      for (int h = 0; h < k; ++h) {
        const double z0 = at(0, top, h, k), z1 = at(0, top, h + 1, k);
        quad(side(in, i, z0), side(in, i + 1, z0), side(in, i + 1, z1), side(in, i, z1), 1 + s);
      }
      quad(side(in, i, top), side(in, i + 1, top), side(out, i + 1, top), side(out, i, top), 5);
    }
  }
  for (const Vec3& p : pk.plan) pk.mesh.vertices.push_back(pose(p));
  return pk;
}

TriangleMesh coarse_pocket(const Pose& pose) {
  TriangleMesh m;
  const double o = 10, i = 5, top = 3;
  for (const Vec3& p : {Vec3(-o, -o, top), Vec3(o, -o, top), Vec3(o, o, top), Vec3(-o, o, top),
                        Vec3(-i, -i, top), Vec3(i, -i, top), Vec3(i, i, top), Vec3(-i, i, top),
                        Vec3(-i, -i, 0), Vec3(i, -i, 0), Vec3(i, i, 0), Vec3(-i, i, 0)})
    m.vertices.push_back(pose(p));
  m.facets = {{0, 1, 5},  {0, 5, 4},  {1, 2, 6},  {1, 6, 5},   {2, 3, 7}, {2, 7, 6},
              {3, 0, 4},  {3, 4, 7},  {8, 9, 10}, {8, 10, 11}, {4, 5, 9}, {4, 9, 8},
              {5, 6, 10}, {5, 10, 9}, {6, 7, 11}, {6, 11, 10}, {7, 4, 8}, {7, 8, 11}};
  return m;
}

// The pocket with n x n floor cells and k wall rows (n in {4, 5, 8, 10} and k in {3, 4}
// keep the grid values exact), scanned with a ball of radius R < 4.
void check_pocket(const Pose& pose, int n, int k, double R, std::mt19937_64& rng) {
  const double floor_z = -50, x_lo = -9, x_hi = 9;
  {
    std::ostringstream pose_label;
    pose_label << "turn " << pose.turn << " tilt " << pose.tilt << " n " << n << " k " << k << " R "
               << R;
    const std::string name = pose_label.str();
    const Pocket pk = cad_pocket(n, k, pose, rng);
    const OffsetElements el = build_offset_elements(pk.mesh, R, Coplanar::kMerge);
    const OffsetElements kept = build_offset_elements(pk.mesh, R, Coplanar::kKeep);
    ASSERT_EQ(el.facet_count(), pk.mesh.facets.size()) << name;

    // Facets of each edge and of each vertex, from the mesh.
    std::map<std::uint64_t, std::vector<std::uint32_t>> users;
    std::vector<std::vector<int>> vertex_faces(pk.plan.size());
    for (std::uint32_t f = 0; f < pk.mesh.facets.size(); ++f)
      for (int k = 0; k < 3; ++k) {
        users[key(pk.mesh.facets[f][k], pk.mesh.facets[f][(k + 1) % 3])].push_back(f);
        vertex_faces[pk.mesh.facets[f][k]].push_back(pk.face[f]);
      }
    const auto edges = edge_index(el);
    auto on_border = [](const Vec3& p) { return std::max(std::abs(p.x()), std::abs(p.y())) == 5; };
    auto plate_corner = [](const Vec3& p) {
      return p.z() == 3 && std::abs(p.x()) == 10 && std::abs(p.y()) == 10;
    };
    auto continues_rim = [&](std::uint32_t v) {
      const Vec3& c = pk.plan[v];
      for (const auto& [k, fs] : users) {
        const auto a = std::uint32_t(k >> 32), b = std::uint32_t(k);
        if (a != v && b != v) continue;
        const Vec3& q = pk.plan[a == v ? b : a];
        if (q.z() == 3 && (q.x() == c.x() || q.y() == c.y()) && !on_border(q)) return true;
      }
      return false;
    };
    int inside[6] = {0, 0, 0, 0, 0, 0}, reachable_edges = 0;
    for (const auto& [k, fs] : users) {
      const std::uint32_t e = edges.at(k);
      const Vec3 &a = pk.plan[std::uint32_t(k >> 32)], &b = pk.plan[std::uint32_t(k)];
      const bool rim = a.z() == 3 && b.z() == 3 && on_border(a) && on_border(b);
      const bool same_face = fs.size() == 2 && pk.face[fs[0]] == pk.face[fs[1]];
      if (same_face) {
        ++inside[pk.face[fs[0]]];
        EXPECT_FALSE(element_reachable(el, el.edge_id(e)))
            << name << " face " << pk.face[fs[0]] << " inner edge " << a.transpose() << " - "
            << b.transpose();
        EXPECT_TRUE(element_reachable(kept, kept.edge_id(e))) << name << " kKeep drops nothing";
      }
      if (!pose.exact() && !same_face) continue;
      // Exact pose: only the rim (convex) and the plate's outer boundary can be touched
      // from above. Turned, the walls are vertical up to rounding only and may overhang by
      // ~1e-17 rad: the valleys at their foot and their vertical corners then have a wedge
      // holding a direction with d.z ~ +1e-17 and edge_wedge_reachable keeps them (harmless:
      // such a cylinder is trimmed to the far side of the wall, below the top).
      const bool want = rim || fs.size() == 1;
      reachable_edges += want;
      EXPECT_EQ(element_reachable(el, el.edge_id(e)), want)
          << name << " edge " << a.transpose() << " - " << b.transpose();
    }
    for (int f = 0; f < 6; ++f) EXPECT_GT(inside[f], 0) << name << " face " << f;
    if (pose.exact()) {
      EXPECT_EQ(reachable_edges, 4 * n * 2);
    }
    // Vertices inside one face (or on the straight outer boundary) are dropped, the plate's
    // corners kept. Exact pose: only the pocket's and the plate's corners remain (the others
    // lie inside a face, on a straight rim or boundary line, or on concave edges only).
    for (std::uint32_t v = 0; v < el.vertex_count(); ++v) {
      const Vec3& p = pk.plan[el.vertex_source[v]];
      const auto& fs = vertex_faces[el.vertex_source[v]];
      const bool one_face = std::all_of(fs.begin(), fs.end(), [&](int f) { return f == fs[0]; });
      const bool reachable = element_reachable(el, el.vertex_id(v));
      if (one_face) {
        EXPECT_EQ(reachable, plate_corner(p)) << name << " vertex " << p.transpose();
      }
      const bool pocket_corner = p.z() == 3 && std::abs(p.x()) == 5 && std::abs(p.y()) == 5;
      // A top-ring edge continuing a rim line beyond the pocket's corner (with n = 4 the
      // ring's diagonal can run from (-5, -5) to (-5, -10)) makes the corner "straight" and
      // drop_straight_vertices drops it; rightly, since the flat top then limits its cone to
      // the vertical, which the offset triangles cover. Not asserted there.
      if (pocket_corner && continues_rim(el.vertex_source[v])) continue;
      if (pose.exact()) {
        EXPECT_EQ(reachable, pocket_corner || plate_corner(p))
            << name << " vertex " << p.transpose();
      }
    }
    // One normal per non-vertical face, bitwise (and not by accident when tilted: the
    // facets' own normals differ by rounding); vertical faces keep their own, of either
    // sign, and are joined anyway.
    int opposite = 0, rounded_apart = 0;
    std::array<Vec3, 6> face_normal;
    face_normal.fill(Vec3::Zero());
    for (std::uint32_t f = 0; f < el.facet_count(); ++f) {
      const int g = pk.face[f];
      if (el.facet_vertical[f]) {
        EXPECT_TRUE(el.facet_normal[f] == kept.facet_normal[f]) << name << " facet " << f;
        EXPECT_TRUE(el.facet_tri[f] == kept.facet_tri[f]) << name << " facet " << f;
        continue;
      }
      if (face_normal[g].isZero()) face_normal[g] = el.facet_normal[f];
      EXPECT_TRUE(el.facet_normal[f] == face_normal[g]) << name << " face " << g << " facet " << f;
      rounded_apart += !(kept.facet_normal[f] == face_normal[g]);
    }
    if (pose.tilt != 0) {
      EXPECT_GT(rounded_apart, 0) << name;
    }
    for (const auto& [k, fs] : users)
      if (fs.size() == 2 && pk.face[fs[0]] == pk.face[fs[1]] && el.facet_vertical[fs[0]])
        opposite += el.facet_normal[fs[0]].dot(el.facet_normal[fs[1]]) < 0;
    EXPECT_GT(opposite, 0) << name;
    if (pose.tilt == 0) {
      for (std::uint32_t f = 0; f < el.facet_count(); ++f)
        EXPECT_EQ(el.facet_vertical[f] != 0, pk.face[f] >= 1 && pk.face[f] <= 4) << name;
    }

    // The curve equals the drop-cutter of the unsplit pocket; planes through the grid
    // vertices (floor vertices and edges, the wall planes, rim vertices whose spheres are
    // dropped), tangent to the rim, and random ones.
    const TriangleMesh coarse_mesh = coarse_pocket(pose);
    const OffsetElements coarse = build_offset_elements(coarse_mesh, R, Coplanar::kMerge);
    const auto facets = prepare_all(coarse_mesh);
    const Cutter ball = ball_cutter(2 * R);
    std::vector<double> ys = {-5 + R, 5 - R, -5 - R, 0.35};
    for (std::uint32_t v = 0; v < pk.mesh.vertices.size(); v += 3)
      ys.push_back(pk.mesh.vertices[v].y());
    std::uniform_real_distribution<double> ry(-9.5, 9.5);
    for (int k = 0; k < 10; ++k) ys.push_back(ry(rng));
    std::sort(ys.begin(), ys.end());
    ys.erase(std::unique(ys.begin(), ys.end()), ys.end());
    Worst worst;
    int kinks = 0, across = 0;
    for (double y0 : ys) {
      std::ostringstream label;
      label.precision(17);
      label << name << " plane y " << y0;
      const Plane p = scan_plane(el, y0, floor_z, x_lo, x_hi);
      ASSERT_EQ(p.curve.run_starts.size(), 1u) << label.str();
      auto want = [&](double x) { return std::max(floor_z, drop_all(ball, facets, x, y0)); };
      compare_with_oracle(p, want, x_lo, x_hi, 200, rng, label.str(), worst);
      expect_distinct_junctions(p, label.str());
      const Plane pc = scan_plane(coarse, y0, floor_z, x_lo, x_hi);
      expect_same_kinks(p, pc, label.str(), kinks);
      if (pose.exact() && std::abs(y0) < 5 - R - 1e-9) {
        // Across the pocket: the ball rolls over the rim, drops onto the floor at x =
        // -5 + R and climbs out at 5 - R; the floor and the top are flat. Exactly two kinks
        // (floor against the falls), at z = 0.
        ++across;
        std::vector<const CurveJunction*> kinked;
        for (const CurveJunction& j : p.curve.junctions)
          if (junction_angle(j) > kKinkAngle) kinked.push_back(&j);
        ASSERT_EQ(kinked.size(), 2u) << label.str();
        EXPECT_NEAR(kinked[0]->x, -5 + R, 1e-12) << label.str();
        EXPECT_NEAR(kinked[1]->x, 5 - R, 1e-12) << label.str();
        for (const CurveJunction* j : kinked) EXPECT_NEAR(j->z, 0, 1e-12) << label.str();
        for (double x : {-4.0 + R, -1.0, 0.3, 4.9 - R})
          EXPECT_NEAR(curve_z(p, x), 0, 1e-12) << label.str();
      }
      if (pose.exact() && std::abs(y0) > 5 + R + 1e-9) {
        // Over the top only: flat, no kink at all.
        for (const CurveJunction& j : p.curve.junctions)
          EXPECT_LE(junction_angle(j), kKinkAngle) << label.str() << " x " << j.x;
      }
    }
    EXPECT_LE(worst.err, kCurveTol) << worst.where;
    EXPECT_GT(kinks, 0) << name;
    if (pose.exact()) {
      EXPECT_GE(across, 3) << name;  // grid planes through the floor at least
    }
  }
}

TEST(Coplanar, CadPocketDropsFaceInteriorsAndMatchesDropCutter) {
  std::mt19937_64 rng(99);
  for (const Pose pose : {Pose{0, 0}, Pose{0.3, 0}, Pose{0.3, 0.15}})
    check_pocket(pose, 5, 3, 1.25, rng);
}

// Known issue (kernels/scan/envelope, not the coplanar rule; disabled so as not to fail the
// suite): a drive plane exactly through a convex rim corner of the turned pocket. Both rim
// cylinders pass through the corner tangent to the top and stay within tol::kEnvelopeTie of
// each other for ~2e-5 mm past it; the tie goes to the lower element id, here the lower
// cylinder, and where the two part by 1e-10 mm the curve gets a junction classified
// sharp-concave with bi-contact vectors 1.8e-5 rad apart (and a step of ~8e-11 mm) on a
// convex corner. Heights stay within the documented tie; the unsplit 18-facet pocket shows
// it as well (and the split one or not, by element ids), so it is no artefact of splitting.
TEST(Coplanar, DISABLED_RimCornerPlaneHasNoTieKink) {
  const Pose pose{0.98, 0};
  const OffsetElements el = build_offset_elements(coarse_pocket(pose), 1.25);
  const Vec3 corner = pose(Vec3(5, -5, 3));
  const Plane p = scan_plane(el, corner.y(), -50, -9, 9);
  for (const CurveJunction& j : p.curve.junctions)
    if (std::abs(j.x - corner.x()) < 1e-3) {
      EXPECT_LE(junction_angle(j), kKinkAngle)
          << "x " << j.x << " z " << j.z << " kind " << junction_kind_name(j.kind) << " elements "
          << j.element1 << "," << j.element2;
    }
}

}  // namespace
}  // namespace ncpath
