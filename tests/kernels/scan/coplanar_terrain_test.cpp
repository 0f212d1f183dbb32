// Coplanar regions of the offset elements (kernels/mesh/offset_elements: share_coplanar_offsets,
// drop_straight_vertices, Coplanar) and their effect on the drive-plane scan (plane_slice,
// envelope), on a random terrain whose facets are each split into 16 (midpoint subdivision,
// twice). The split mesh must give the same CL curve as the unsplit one:
//   - the edges inside an original facet and the vertices inside a facet or on an original
//     edge are dropped (Coplanar::kMerge) and kept with Coplanar::kKeep; the children of one
//     facet share one normal bitwise, so their offset triangles share corners bitwise;
//   - the exact curve equals the brute-force drop-cutter of the unsplit mesh within 1e-9 mm,
//     including drive planes through vertices exactly, and has no kink (bi-contact vectors
//     apart by more than 1e-6 rad) that the unsplit mesh's curve lacks, nor two junctions at
//     one x except around a vertical segment.
// Which facet, edge or vertex lies inside which original facet is known from the
// construction, never from the kernel. The CAD pocket cases are in coplanar_cad_test.cpp.
#include <gtest/gtest.h>

#include <cstdint>
#include <map>
#include <random>
#include <sstream>
#include <unordered_map>
#include <vector>

#include "kernels/mesh/offset_elements.hpp"
#include "kernels/mesh/subdivide.hpp"
#include "tests/kernels/scan/coplanar_test_support.hpp"
#include "tests/kernels/scan/scan_test_support.hpp"

namespace ncpath {
namespace {

using namespace coplanar_test;
using namespace scan_test;

// Vertex slot of el by point index.
std::unordered_map<std::uint32_t, std::uint32_t> vertex_index(const OffsetElements& el) {
  std::unordered_map<std::uint32_t, std::uint32_t> out;
  for (std::uint32_t v = 0; v < el.vertex_count(); ++v) out[el.vertex_source[v]] = v;
  return out;
}

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
        const auto [it, fresh] = corner.emplace(v, merged.offset_tri(c)[k]);
        if (!fresh) {
          EXPECT_TRUE(it->second == merged.offset_tri(c)[k])
              << "offset corner of vertex " << v << " in child " << c;
        }
        const auto [jt, fresh_kept] = corner_kept.emplace(v, kept.offset_tri(c)[k]);
        if (!fresh_kept) corners_apart_kept += !(jt->second == kept.offset_tri(c)[k]);
      }
    }
  }
  // Without merging, the children's normals differ by rounding: (b) is not vacuous.
  EXPECT_GT(normals_rounded_apart, 0);
  EXPECT_GT(corners_apart_kept, 0);

  // (c) kKeep drops nothing: inner edges stay flat and reachable (bent less than
  // tol::kFlatEdgeKeep), every vertex with a reachable edge stays, normals are the facets'
  // own. Edges outside the regions are as reachable in both builds; their wedges are the same
  // up to the normal a region gives one of their facets (the wedge side follows it, within
  // tol::kCoplanarSine of the facet's own plane).
  for (std::uint32_t e = 0; e < kept.edge_count(); ++e) {
    if (interior[e]) {
      EXPECT_EQ(kept.edge_reachable[e], 1) << "inner edge " << e;
      EXPECT_EQ(kept.edge_flat[e], 1) << "inner edge " << e;
      EXPECT_EQ(kept.edge_kind[e], EdgeKind::kFlat) << "inner edge " << e;
    } else {
      EXPECT_EQ(kept.edge_reachable[e], merged.edge_reachable[e]) << "edge " << e;
      for (int i = 0; i < 2; ++i)
        EXPECT_LE((kept.edge_wedge[e][i] - merged.edge_wedge[e][i]).norm(), tol::kCoplanarSine)
            << "edge " << e;
    }
  }
  // (d) A kept edge's wedge sides are the planes of the edge and its facets' offset normals
  // (the region's, under kMerge): each side w is perpendicular to one facet's normal and
  // points into that facet, so a cylinder hands over exactly where the offset triangle is.
  for (std::uint32_t e = 0; e < merged.edge_count(); ++e) {
    if (merged.edge_facet_count[e] != 2 || merged.edge_wedge[e][0].isZero()) continue;
    const auto [a, b] = merged.edge_vertices[e];
    int sides = 0;
    for (std::uint32_t f = 0; f < merged.facet_count(); ++f) {
      const auto& fv = merged.facet_vertices[f];
      const bool has_a = fv[0] == a || fv[1] == a || fv[2] == a;
      const bool has_b = fv[0] == b || fv[1] == b || fv[2] == b;
      if (!has_a || !has_b) continue;
      const std::uint32_t o = fv[0] != a && fv[0] != b ? fv[0] : fv[1] != a && fv[1] != b ? fv[1] : fv[2];
      const Vec3 into = merged.points[o] - merged.points[a];
      for (const Vec3& w : merged.edge_wedge[e])
        sides += std::abs(w.dot(merged.facet_normal[f])) <= 1e-15 && w.dot(into) > 0;
    }
    EXPECT_GE(sides, 2) << "edge " << e;
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
  for (int k = 0; k < 12; ++k) ys.push_back(fine.offset_tri(pick_facet(rng))[k % 3].y());

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

}  // namespace
}  // namespace ncpath
