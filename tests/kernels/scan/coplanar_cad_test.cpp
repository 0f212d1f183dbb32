// Coplanar regions of the offset elements (kernels/mesh/offset_elements: share_coplanar_offsets,
// drop_straight_vertices, Coplanar) and their effect on the drive-plane scan (plane_slice,
// envelope), on a CAD pocket whose flat faces are split into many triangles. The split
// pocket must give the same CL curve as the unsplit one:
//   - the edges inside a face and the vertices inside a face or a straight edge line are
//     dropped (Coplanar::kMerge) and kept with Coplanar::kKeep; the facets of one face share
//     one normal bitwise;
//   - the exact curve equals the brute-force drop-cutter of the unsplit pocket within
//     1e-9 mm, including drive planes through vertices exactly, and has no kink (bi-contact
//     vectors apart by more than 1e-6 rad) that the unsplit pocket's curve lacks, nor two
//     junctions at one x except around a vertical segment.
// Which facet, edge or vertex lies inside which face is known from the construction, never
// from the kernel. The subdivided terrain cases are in coplanar_terrain_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "kernels/mesh/offset_elements.hpp"
#include "tests/kernels/scan/coplanar_test_support.hpp"
#include "tests/kernels/scan/scan_test_support.hpp"

namespace ncpath {
namespace {

using namespace coplanar_test;
using namespace scan_test;

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
        EXPECT_TRUE(el.offset_tri(f) == kept.offset_tri(f)) << name << " facet " << f;
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
