#pragma once
// Inside engine/concave_zone.cpp: the centre balls of a mesh's elements (facet interiors,
// edges, vertices), built in engine/concave_zone_balls.cpp from the mesh's local geometry.
#include <array>
#include <cstdint>
#include <numbers>
#include <vector>

#include "kernels/geom/vec.hpp"
#include "kernels/mesh/triangle_mesh.hpp"

namespace ncpath::concave_zone_detail {

constexpr std::uint32_t kNone = ~std::uint32_t(0);

// Where contacts on one element (on one side) put the ball centre: within `reach` of `at`.
struct CentreBall {
  Vec3 at;
  double reach = 0;
  Vec3 axis = Vec3::UnitZ();                                // the side's normal cone
  double half_angle = std::numbers::pi;                     // pi: unknown (any normal)
  std::array<std::uint32_t, 3> verts{kNone, kNone, kNone};  // the element's mesh vertices
  bool unbounded() const { return half_angle >= std::numbers::pi; }
};

// Every element's balls, in facet order (its interior, then its edges), then vertex order.
std::vector<CentreBall> centre_balls(const TriangleMesh& mesh, double R);

}  // namespace ncpath::concave_zone_detail
