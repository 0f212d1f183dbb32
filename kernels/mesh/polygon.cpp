#include "kernels/mesh/polygon.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

namespace ncpath {
namespace {

// The check proper; when corner_list is given, the indices of the corners are appended.
PolygonCheck analyse(std::span<const Vec3> poly, double zero_edge, double straight_turn,
                     std::vector<std::uint32_t>* corner_list) {
  PolygonCheck out;
  const std::size_t n = poly.size();
  if (n < 3) return out;  // kTooFewVertices

  Vec3 lo = poly[0], hi = poly[0];
  for (std::size_t i = 0; i < n; ++i) {
    if (!poly[i].allFinite()) {
      out.status = PolygonStatus::kNonFinite;
      out.vertex = static_cast<std::uint32_t>(i);
      return out;
    }
    lo = lo.cwiseMin(poly[i]);
    hi = hi.cwiseMax(poly[i]);
  }
  const double size = (hi - lo).maxCoeff();

  for (std::size_t i = 0; i < n; ++i) {
    if ((poly[(i + 1) % n] - poly[i]).norm() <= zero_edge * size) {
      out.status = PolygonStatus::kZeroLengthEdge;
      out.vertex = static_cast<std::uint32_t>(i);
      return out;
    }
  }

  // Newell normal, about the first vertex so that far-from-origin polygons keep their digits.
  Vec3 newell = Vec3::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 a = poly[i] - poly[0];
    const Vec3 b = poly[(i + 1) % n] - poly[0];
    newell.x() += (a.y() - b.y()) * (a.z() + b.z());
    newell.y() += (a.z() - b.z()) * (a.x() + b.x());
    newell.z() += (a.x() - b.x()) * (a.y() + b.y());
  }
  const double twice_area = newell.norm();
  // A collinear polygon still gets a rounding-noise normal; below this it has no plane.
  if (!(twice_area > straight_turn * size * size)) {
    // No net area. On one line it is degenerate; with width (a symmetric bow-tie whose two
    // lobes cancel) it overlaps itself, which must not pass as a harmless zero-area facet.
    std::size_t far = 0;
    for (std::size_t i = 1; i < n; ++i)
      if ((poly[i] - poly[0]).squaredNorm() > (poly[far] - poly[0]).squaredNorm()) far = i;
    const Vec3 dir = (poly[far] - poly[0]).normalized();
    double width = 0;
    for (std::size_t i = 0; i < n; ++i)
      width = std::max(width, (poly[i] - poly[0]).cross(dir).norm());
    out.status = width > straight_turn * size ? PolygonStatus::kSelfIntersecting
                                              : PolygonStatus::kDegenerate;
    return out;
  }
  const Vec3 nz = newell / twice_area;
  out.normal = nz;

  // Right-handed frame (u, v, nz): counter-clockwise in (u, v) is the Newell orientation.
  Eigen::Index axis;
  nz.cwiseAbs().minCoeff(&axis);
  const Vec3 u = Vec3::Unit(axis).cross(nz).normalized();
  const Vec3 v = nz.cross(u);
  auto project = [&](std::size_t i) {
    const Vec3 d = poly[i] - poly[0];
    return Vec2(d.dot(u), d.dot(v));
  };

  double winding = 0;  // sum of the signed turning angles of the corners, rad
  std::uint32_t first_corner = 0;
  Vec2 prev = project(n - 1);
  Vec2 cur = project(0);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 next = project((i + 1) % n);
    const Vec2 e_in = cur - prev;
    const Vec2 e_out = next - cur;
    const double lengths = e_in.norm() * e_out.norm();
    const double cross = e_in.x() * e_out.y() - e_in.y() * e_out.x();
    const double dot = e_in.dot(e_out);
    if (!(lengths > 0)) {  // an edge along the normal of a twisted polygon
      out.status = PolygonStatus::kDegenerate;
      out.vertex = static_cast<std::uint32_t>(i);
      return out;
    }
    const double sine = cross / lengths;
    if (std::abs(sine) < straight_turn) {
      if (dot < 0) {  // the boundary doubles back on itself
        out.status = PolygonStatus::kNonConvex;
        out.vertex = static_cast<std::uint32_t>(i);
        return out;
      }
      // straight: not a corner
    } else if (sine < 0) {
      out.status = PolygonStatus::kNonConvex;
      out.vertex = static_cast<std::uint32_t>(i);
      return out;
    } else {
      if (out.corners == 0) first_corner = static_cast<std::uint32_t>(i);
      ++out.corners;
      winding += std::atan2(cross, dot);
      if (corner_list) corner_list->push_back(static_cast<std::uint32_t>(i));
    }
    prev = cur;
    cur = next;
  }
  if (out.corners < 3) {
    out.status = PolygonStatus::kDegenerate;
    return out;
  }
  // All turns agree, so the winding is 2*pi*k; k > 1 is a star. Halfway to 4*pi decides.
  if (winding > 3 * std::numbers::pi) {
    out.status = PolygonStatus::kSelfIntersecting;
    out.vertex = first_corner;
    return out;
  }
  out.status = PolygonStatus::kConvex;
  return out;
}

}  // namespace

PolygonCheck check_convex_polygon(std::span<const Vec3> polygon, double zero_edge,
                                  double straight_turn) {
  return analyse(polygon, zero_edge, straight_turn, nullptr);
}

PolygonTriangulation triangulate_convex_polygon(std::span<const Vec3> polygon, double zero_edge,
                                                double straight_turn) {
  PolygonTriangulation out;
  std::vector<std::uint32_t> corners;
  corners.reserve(polygon.size());
  out.check = analyse(polygon, zero_edge, straight_turn, &corners);
  if (!out.check.convex()) return out;
  out.triangles.reserve(corners.size() - 2);
  for (std::size_t j = 1; j + 1 < corners.size(); ++j)
    out.triangles.push_back({corners[0], corners[j], corners[j + 1]});
  return out;
}

const char* polygon_status_text(PolygonStatus status) {
  switch (status) {
    case PolygonStatus::kConvex:
      return "is convex";
    case PolygonStatus::kTooFewVertices:
      return "has fewer than 3 vertices";
    case PolygonStatus::kNonFinite:
      return "has a non-finite coordinate (NaN or infinity)";
    case PolygonStatus::kZeroLengthEdge:
      return "has a zero-length edge";
    case PolygonStatus::kDegenerate:
      return "has no area (all its vertices lie on one line)";
    case PolygonStatus::kNonConvex:
      return "is not convex (a turn goes the other way or the boundary doubles back)";
    case PolygonStatus::kSelfIntersecting:
      return "is self-intersecting (its boundary winds around more than once, like a star)";
  }
  return "unknown polygon status";
}

}  // namespace ncpath
