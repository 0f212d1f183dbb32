#pragma once
// The job's placement of an input mesh (uniform scale, optional fit of the xy footprint,
// translation) and the facet measures the readers and writers need (degenerate facets,
// facet normals). Pure geometry: no I/O, no exceptions; outcomes are data.
#include <cstdint>
#include <optional>
#include <string>

#include "kernels/geom/tolerance.hpp"
#include "kernels/geom/vec.hpp"
#include "kernels/mesh/triangle_mesh.hpp"

namespace ncpath {

// p' = s * p + translate, with s = scale * (fit_xy_mm ? *fit_xy_mm / L : 1), where L is the
// longest side of the xy bounding box of the vertices referenced by facets. The scale is
// uniform and about the origin, so "fit xy to N mm" makes the longest xy side N mm (CGAL
// meshes come unit-sized).
struct MeshTransform {
  double scale = 1;                 // dimensionless, finite, > 0 (job key `scale`)
  Vec3 translate = Vec3::Zero();    // mm, finite, applied after scaling (key `translate`)
  std::optional<double> fit_xy_mm;  // mm, finite, > 0 when set (key `fit_xy`)
};

// Empty when the transform's own values are usable; otherwise a sentence that starts with
// the offending key, e.g. "scale: must be a finite number > 0, got -2".
std::string validate(const MeshTransform& transform);

struct TransformOutcome {
  std::string error;  // empty on success; starts with the key, like validate()
  double scale = 0;   // s that was applied (dimensionless); 0 on error
  bool ok() const { return error.empty(); }
};

// Applies the transform to every vertex of the mesh, in place. On error (invalid values, or
// fit_xy on a mesh without facets or with zero xy extent, or a result that overflows) the
// mesh is left unchanged.
TransformOutcome apply_transform(const MeshTransform& transform, TriangleMesh& mesh);

// Doubled facet area |(b - a) x (c - a)|, mm^2.
double facet_area2(const Vec3& a, const Vec3& b, const Vec3& c);

// True when facet_area2 < area2_tol, or when it is NaN (a facet with no usable normal).
bool is_degenerate_facet(const Vec3& a, const Vec3& b, const Vec3& c,
                         double area2_tol = tol::kDegenerateArea2);

// Unit normal of the facet (a, b, c) by the right-hand rule; zero when it is degenerate.
Vec3 facet_unit_normal(const Vec3& a, const Vec3& b, const Vec3& c,
                       double area2_tol = tol::kDegenerateArea2);

// Number of facets of the mesh that are degenerate.
std::uint64_t count_degenerate_facets(const TriangleMesh& mesh,
                                      double area2_tol = tol::kDegenerateArea2);

// Removes the degenerate facets (keeping the order of the others; vertices are untouched)
// and returns how many were removed.
std::uint64_t remove_degenerate_facets(TriangleMesh& mesh,
                                       double area2_tol = tol::kDegenerateArea2);

}  // namespace ncpath
