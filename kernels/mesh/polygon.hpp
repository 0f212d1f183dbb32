#pragma once
// Convexity check and fan triangulation of one planar-ish polygon in 3-D, as found in the
// faces of an OFF file. The polygon is projected onto the plane of its Newell normal and
// judged there; nothing is thrown, every outcome is data.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "kernels/geom/tolerance.hpp"
#include "kernels/geom/vec.hpp"

namespace ncpath {

enum class PolygonStatus : std::uint8_t {
  kConvex = 0,        // strictly convex, possibly with straight (collinear) vertices
  kTooFewVertices,    // fewer than 3 vertices
  kNonFinite,         // a coordinate is NaN or infinite
  kZeroLengthEdge,    // edge from `vertex` to the next one has (relative) zero length
  kDegenerate,        // no area: fewer than 3 corners, all vertices on one line
  kNonConvex,         // the turn at `vertex` goes the other way, or doubles back
  kSelfIntersecting,  // the boundary winds more than once (star), or its lobes cancel
                      // to zero net area (symmetric bow-tie)
};

struct PolygonCheck {
  PolygonStatus status = PolygonStatus::kTooFewVertices;
  // Index (into the polygon) of the first offending vertex: the start of the zero-length
  // edge, the first turn against the Newell orientation, the first corner of a star; 0 when
  // it does not apply.
  std::uint32_t vertex = 0;
  // Corners: vertices that really turn. Straight vertices are skipped by the fan, so a
  // convex polygon gives corners - 2 triangles.
  std::uint32_t corners = 0;
  Vec3 normal = Vec3::Zero();  // unit Newell normal (orientation of the vertex order)

  bool convex() const { return status == PolygonStatus::kConvex; }
};

// Decides whether the polygon (vertices in boundary order, closing edge implied, mm) is
// convex when projected onto the plane of its Newell normal. A vertex is straight when its
// turn has |sin| < straight_turn and it keeps going forward; all other turns must have the
// same sign and add up to one full turn (this rejects stars such as the pentagram). Edges
// shorter than zero_edge * (longest bounding-box side) are zero-length. Planarity is not
// checked: a twisted polygon is judged by its projection.
PolygonCheck check_convex_polygon(std::span<const Vec3> polygon,
                                  double zero_edge = tol::kPolygonZeroEdge,
                                  double straight_turn = tol::kPolygonStraightTurn);

struct PolygonTriangulation {
  PolygonCheck check;
  // Local vertex indices into the polygon, in the polygon's own winding: a fan from the
  // first corner over the corners only (straight vertices are not used, so no triangle has
  // zero area). Empty unless check.convex().
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

// check_convex_polygon, then the fan triangulation of a convex polygon.
PolygonTriangulation triangulate_convex_polygon(std::span<const Vec3> polygon,
                                                double zero_edge = tol::kPolygonZeroEdge,
                                                double straight_turn = tol::kPolygonStraightTurn);

// A clause for messages, e.g. "is not convex (a turn goes the other way ...)", so that
// "face 3 " + polygon_status_text(status) reads as a sentence.
const char* polygon_status_text(PolygonStatus status);

}  // namespace ncpath
