#pragma once
// Which bi-contacts of the pencil-cut (engine/pencil.hpp) are creases of the part, the same
// however the part is turned about z.
//
// A ball can touch two surfaces without standing in a crease: hanging over the part's
// outline it rests on an edge of the outline and leans on a wall behind it (a wall standing
// less than R inside a plate's edge, the plate's top edge below it), or sits on the two top
// edges at a V-groove's open end. Such a ball *hangs*: its centre's vertical misses the part
// (within tol::kPencilOutline) and one of its contacts lies on a sharp convex edge or vertex,
// where the part turns away from the contact normal by at least half the pencil's angle
// threshold. A ball beside the part touching two faces (a vertical corner reached from
// outside the outline), or over the part touching a convex edge (the arc around a boss's
// vertical edge at its foot), is in a crease. Deciding this per candidate keeps the drive
// planes' extent out of the answer: they reach a ball's radius beyond the part's box, so
// every pose finds every bi-contact, and the same ones are dropped in every pose.
#include <array>
#include <cstdint>
#include <map>
#include <span>
#include <vector>

#include "engine/mesh_distance.hpp"
#include "engine/pencil.hpp"
#include "engine/pencil_crease.hpp"
#include "kernels/mesh/triangle_mesh.hpp"

namespace ncpath {

// How far the drive planes reach beyond the part's xy box (mm): more than the margin and the
// ball's radius, by the whole intervals up to it and one more (the planes stand where they
// would without the reach, and a radius grown by rounding does not move them). Every ball
// that touches the part lies inside.
double pencil_reach(const PencilParams& p, double radius);

class HangingTest {
 public:
  // The facets around every edge and vertex that `refs` name are looked up once here.
  HangingTest(const TriangleMesh& mesh, const MeshDistance& distance, double min_angle,
              std::span<const ElementPair> refs);

  // Whether the ball with tool tip `tip` (centre tip + radius z; only its vertical matters)
  // and contact vectors b1 on refs[0], b2 on refs[1] hangs over the part's outline.
  bool hanging(const Vec3& tip, const Vec3& b1, const Vec3& b2, const ElementPair& refs) const;

  // The crease points that do not hang (for crease_end).
  CreaseFilter filter() const;

 private:
  bool over_part(const Vec3& q) const;
  bool sharp(const ElementRef& e, const Vec3& b) const;

  const TriangleMesh& mesh_;
  const MeshDistance& distance_;
  Aabb3 box_;
  double cos_half_;  // cos(min_angle / 2)
  std::map<std::array<double, 3>, std::vector<std::uint32_t>> facets_at_;  // vertex -> facets
};

}  // namespace ncpath
