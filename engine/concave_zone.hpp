#pragma once
// The concave zone of a mesh for a ball of radius R (issue 17): a conservative screen for
// where a ball clear of the mesh can touch it at two points whose contact normals are at
// least min_angle apart (a pencil bi-contact), so that the pencil's z-levels and its drive
// planes looking for creases slice only the part of the mesh around those places.
//
// Why it is conservative. A ball clear of the mesh touching it at p1 and p2 with contact
// normals n1, n2 (unit, contact to centre) has its centre at c = p1 + R n1 = p2 + R n2. The
// contact normal at a point of
//   - a facet's interior is the facet's normal (on the side the ball is);
//   - an edge lies on the arc between its two facets' normals, and the edge must be convex
//     seen from the ball (a ball touching a concave edge cuts a facet);
//   - a vertex lies in the hull of its facets' normals, when its star is a disk wound
//     consistently (the polar of the material's tangent cone; docs/architecture.md, "The
//     concave zone"), and not every edge there may rise above the ball's tangent plane.
// So each element (facet, edge, vertex) and side gives a centre ball that holds every c
// its contacts can give: the element's bounding sphere moved by R along the cone's axis,
// grown by 2 R sin(half-angle / 2). An element whose cone is unknown (an edge used by one or
// three facets, a vertex whose star is not such a disk) gives a ball of radius R + its size
// around itself. A ball from above touches with n.z >= 0: cones entirely below are dropped.
// On a closed component (every vertex regular) the ball is outside, on the side the normals
// point to when the signed volume is positive; elsewhere both sides count.
//
// Two centre balls pair when they meet (within `slack`) and their cones can be min_angle
// apart. The zone is the balls that pair: every bi-contact centre of at least min_angle lies
// in one of them. Kept is every facet within R of a zone ball and every facet above those
// (z-levels and drive planes slice the drop-cutter surface, whose highest element there may
// lie far above): sliced, the kept facets have at every centre inside a zone ball the
// junctions of the whole mesh.
#include <cstdint>
#include <utility>
#include <vector>

#include "kernels/geom/vec.hpp"
#include "kernels/mesh/triangle_mesh.hpp"

namespace ncpath {

// The kept facets as a mesh of their own (their vertices and facets in mesh order): its offset
// elements are the kept facets' whole neighbourhoods, the edges and vertices at the border
// untrimmed by facets left out. `facet` and `vertex` name each one's index in the mesh.
struct KeptSubmesh {
  TriangleMesh mesh;
  std::vector<std::uint32_t> facet, vertex;
  // An element of the submesh (kind 0 facet, 1 edge, 2 vertex; engine/offset_elements_build.hpp
  // ElementRef's fields) as the mesh's.
  template <class Ref>
  Ref in_mesh(Ref r) const {
    if (r.kind == 0) r.a = facet[std::size_t(r.a)];
    if (r.kind == 1 || r.kind == 2) r.a = vertex[std::size_t(r.a)];
    if (r.kind == 1) r.b = vertex[std::size_t(r.b)];
    return r;
  }
};

struct ConcaveZone {
  struct Ball {
    Vec3 at;
    double reach = 0;  // mm
  };
  std::vector<Ball> balls;  // where bi-contact centres can be
  // The search stopped: the zone is wide (see concave_zone); nothing is kept, holds() is false.
  bool wide = false;
  KeptSubmesh kept;               // empty when wide or when no ball pairs (a convex part)
  std::uint64_t elements = 0;     // centre balls looked at
  std::uint64_t keep_facets = 0;  // kept.facet.size(), or every facet when wide
  double build_s = 0;

  // Whether a ball centre at c lies in a zone ball (grown by `slack`).
  bool holds(const Vec3& c) const;

  // A uniform grid over the zone balls for holds(): built by concave_zone().
  struct Lookup {
    Vec3 lo;
    double h = 1;
    std::int64_t n[3] = {1, 1, 1};
    std::vector<std::pair<std::uint32_t, std::uint32_t>> entries;  // (cell, ball), sorted
  } lookup;
  double slack = 0;
};

// `slack` (mm) widens the tests: contacts within it of the mesh count (the pencil's tolerance
// for a contact on the part). When more than `max_paired_share` of the centre balls pair (a
// wide zone: bunny00 at 200 mm, ball 5, pairs 23 % of them and keeps 53 % of the facets; its
// Loop x2 scan 12 % and 20 %), the search stops and the zone is `wide`.
ConcaveZone concave_zone(const TriangleMesh& mesh, double radius, double min_angle, double slack,
                         double max_paired_share = 1);

}  // namespace ncpath
