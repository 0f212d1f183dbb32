#include "kernels/mesh/mesh_transform.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

#include <Eigen/Geometry>

namespace ncpath {
namespace {

// Shortest round-trip text of a double, for messages ("2.5", "-0.001", "nan").
std::string num(double x) {
  char buf[32];
  const auto res = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, res.ptr);
}

}  // namespace

std::string validate(const MeshTransform& t) {
  if (!std::isfinite(t.scale) || !(t.scale > 0))
    return "scale: must be a finite number > 0, got " + num(t.scale);
  if (t.fit_xy_mm && (!std::isfinite(*t.fit_xy_mm) || !(*t.fit_xy_mm > 0)))
    return "fit_xy: must be a finite length > 0 mm, got " + num(*t.fit_xy_mm);
  if (!t.translate.allFinite())
    return "translate: must be three finite numbers (mm), got [" + num(t.translate.x()) + ", " +
           num(t.translate.y()) + ", " + num(t.translate.z()) + "]";
  return {};
}

TransformOutcome apply_transform(const MeshTransform& t, TriangleMesh& mesh) {
  TransformOutcome out;
  out.error = validate(t);
  if (!out.error.empty()) return out;

  const Aabb3 box = bounding_box(mesh);
  double s = t.scale;
  if (t.fit_xy_mm) {
    if (box.empty()) {
      out.error = "fit_xy: the mesh has no facets, so it has no xy extent to fit to " +
                  num(*t.fit_xy_mm) + " mm";
      return out;
    }
    const double longest = std::max(box.hi.x() - box.lo.x(), box.hi.y() - box.lo.y());
    if (!(longest > 0) || !std::isfinite(longest)) {
      out.error = "fit_xy: the mesh has zero extent in x and y (a vertical line or a point), " +
                  std::string("it cannot be fitted to ") + num(*t.fit_xy_mm) + " mm";
      return out;
    }
    s *= *t.fit_xy_mm / longest;
  }
  if (!(s > 0) || !std::isfinite(s)) {
    out.error = "scale: the combined scale factor " + num(s) + " is not a finite number > 0";
    return out;
  }
  // The referenced vertices map inside [s*lo + t, s*hi + t]; if that box overflows, refuse
  // before touching the mesh.
  if (!box.empty() &&
      !((s * box.lo + t.translate).allFinite() && (s * box.hi + t.translate).allFinite())) {
    out.error =
        "scale: the transformed mesh overflows double precision (scale factor " + num(s) + ")";
    return out;
  }
  for (Vec3& p : mesh.vertices) p = s * p + t.translate;
  out.scale = s;
  return out;
}

double facet_area2(const Vec3& a, const Vec3& b, const Vec3& c) {
  return (b - a).cross(c - a).norm();
}

bool is_degenerate_facet(const Vec3& a, const Vec3& b, const Vec3& c, double area2_tol) {
  return !(facet_area2(a, b, c) >= area2_tol);
}

Vec3 facet_unit_normal(const Vec3& a, const Vec3& b, const Vec3& c, double area2_tol) {
  const Vec3 n = (b - a).cross(c - a);
  const double len = n.norm();
  if (!(len >= area2_tol) || len == 0) return Vec3::Zero();
  return n / len;
}

std::uint64_t count_degenerate_facets(const TriangleMesh& mesh, double area2_tol) {
  std::uint64_t count = 0;
  for (const auto& f : mesh.facets)
    count += is_degenerate_facet(mesh.vertices[f[0]], mesh.vertices[f[1]], mesh.vertices[f[2]],
                                 area2_tol);
  return count;
}

std::uint64_t remove_degenerate_facets(TriangleMesh& mesh, double area2_tol) {
  std::size_t kept = 0;
  for (std::size_t i = 0; i < mesh.facets.size(); ++i) {
    const auto& f = mesh.facets[i];
    if (!is_degenerate_facet(mesh.vertices[f[0]], mesh.vertices[f[1]], mesh.vertices[f[2]],
                             area2_tol))
      mesh.facets[kept++] = f;
  }
  const std::uint64_t removed = mesh.facets.size() - kept;
  mesh.facets.resize(kept);
  return removed;
}

}  // namespace ncpath
