#pragma once
// Exact closest point of a triangle mesh, and the first contact of a ball moved along a ray,
// accelerated by an Embree 3 BVH.
//
// Each non-degenerate facet is an Embree user primitive with its (padded float) box. A
// closest-point query is an rtcPointQuery whose callback computes the exact point-triangle
// closest point in double and shrinks the query sphere to the best distance so far; Embree
// only prunes, so the answer equals a brute-force scan over all facets (ties: the lowest
// facet index). march() sphere-traces with those distances and finishes each approach with
// an exact swept-ball test over the facets in reach, so it neither overshoots nor crawls at
// grazing incidence.
//
// Built once per mesh and shared read-only: closest() and march() are thread-safe.
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>

#include "kernels/geom/vec.hpp"
#include "kernels/mesh/closest_point.hpp"  // the single-facet routines it runs
#include "kernels/mesh/triangle_mesh.hpp"

namespace ncpath {

class MeshDistance {
 public:
  static constexpr std::uint32_t kNoFacet = std::numeric_limits<std::uint32_t>::max();

  // Copies what it needs from the mesh (which need not outlive the index). Degenerate
  // triangles (doubled area below tol::kDegenerateArea2, as prepare_facet) and triangles with
  // non-finite vertices are skipped: they are never reported. Throws std::runtime_error
  // when Embree cannot build the BVH.
  explicit MeshDistance(const TriangleMesh& mesh);
  ~MeshDistance();
  MeshDistance(const MeshDistance&) = delete;
  MeshDistance& operator=(const MeshDistance&) = delete;

  struct Closest {
    double distance = std::numeric_limits<double>::infinity();  // mm; +inf when none
    Vec3 point = Vec3::Zero();                                  // on the facet, mm
    std::uint32_t facet = kNoFacet;                             // index into mesh.facets
  };

  // Closest point of the mesh to p among facets at distance <= max_distance (mm). Exact in
  // double (the same value as a scan over all facets with the same point-triangle routine);
  // among equal distances the lowest facet index wins.
  Closest closest(const Vec3& p,
                  double max_distance = std::numeric_limits<double>::infinity()) const;

  // A ball of radius `radius` (mm, >= 0) whose centre moves along origin + s * dir (dir a
  // unit vector, s in mm): the first s in (0, s_max] at which the centre's distance to the
  // mesh drops to `radius`, or nullopt when it does not before s_max. Requires
  // closest(origin).distance > radius; returns 0 when the ball already touches at origin.
  // Exact to rounding (~1e-12 mm at non-grazing incidence, ~1e-16 * size / sin(angle) when
  // the ray meets the grown surface at a small angle): far from the mesh it takes sphere-
  // tracing steps of (distance - radius), which cannot overshoot since the distance is
  // 1-Lipschitz; near it, the first contact is solved per facet (offset faces, edge
  // cylinders, vertex spheres) over the facets in reach.
  std::optional<double> march(const Vec3& origin, const Vec3& dir, double radius,
                              double s_max) const;

  std::uint64_t facet_count() const;  // non-degenerate facets in the BVH
  std::uint64_t skipped() const;      // facets skipped as degenerate or non-finite

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ncpath
