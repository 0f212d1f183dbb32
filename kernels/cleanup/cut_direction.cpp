#include "kernels/cleanup/cut_direction.hpp"

#include <cassert>
#include <cmath>

namespace ncpath {

const char* cut_direction_name(CutDirection direction) {
  switch (direction) {
    case CutDirection::kAny:
      return "any";
    case CutDirection::kClimb:
      return "climb";
    case CutDirection::kConventional:
      return "conventional";
  }
  return "?";
}

bool parse_cut_direction(std::string_view text, CutDirection& out) {
  if (text == "any")
    out = CutDirection::kAny;
  else if (text == "climb")
    out = CutDirection::kClimb;
  else if (text == "conventional")
    out = CutDirection::kConventional;
  else
    return false;
  return true;
}

Vec2 material_vector(const Vec3& b1, const Vec3& b2) {
  return Vec2(-(b1.x() + b2.x()), -(b1.y() + b2.y()));
}

CutSideScore cut_side_score(std::span<const Vec3> path,
                            std::span<const std::array<Vec3, 2>> normals) {
  assert(path.size() == normals.size());
  CutSideScore s;
  if (path.size() != normals.size()) return s;
  for (std::size_t i = 1; i < path.size(); ++i) {
    const Vec2 t = (path[i] - path[i - 1]).head<2>();
    const Vec2 m = 0.5 * (material_vector(normals[i - 1][0], normals[i - 1][1]) +
                          material_vector(normals[i][0], normals[i][1]));
    s.score += t.y() * m.x() - t.x() * m.y();  // (t x z) . m
    s.xy_length += t.norm();
  }
  return s;
}

int cut_side(const CutSideScore& s, double neutral) {
  if (!(std::abs(s.score) > neutral * s.xy_length)) return 0;
  return s.score > 0 ? 1 : -1;
}

bool reverse_for(CutDirection direction, int side) {
  if (direction == CutDirection::kAny || side == 0) return false;
  return (direction == CutDirection::kClimb) != (side > 0);
}

}  // namespace ncpath
