#pragma once
// Value types shared by all kernels. Double precision, millimetres, right-handed, tool
// axis +Z.
#include <Eigen/Core>

namespace ncpath {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;

}  // namespace ncpath
