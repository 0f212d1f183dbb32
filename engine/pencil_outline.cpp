#include "engine/pencil_outline.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <set>

#include "kernels/geom/tolerance.hpp"

namespace ncpath {

namespace {

std::array<double, 3> key(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace

double pencil_reach(const PencilParams& p, double radius) {
  return (std::floor((p.margin + radius) / p.interval) + 1) * p.interval;
}

HangingTest::HangingTest(const TriangleMesh& mesh, const MeshDistance& distance,
                         double min_angle, std::span<const ElementPair> refs)
    : mesh_(mesh), distance_(distance), box_(bounding_box(mesh)),
      cos_half_(std::cos(0.5 * min_angle)) {
  std::set<std::array<double, 3>> wanted;
  for (const ElementPair& r : refs)
    for (const ElementRef& e : r) {
      if (e.kind == 1 || e.kind == 2) wanted.insert(key(mesh.vertices[std::size_t(e.a)]));
      if (e.kind == 1) wanted.insert(key(mesh.vertices[std::size_t(e.b)]));
    }
  for (std::uint32_t f = 0; f < mesh.facets.size(); ++f)
    for (std::uint32_t v : mesh.facets[f]) {
      const auto k = key(mesh.vertices[v]);
      if (wanted.count(k)) facets_at_[k].push_back(f);
    }
}

bool HangingTest::hanging(const Vec3& tip, const Vec3& b1, const Vec3& b2,
                          const ElementPair& refs) const {
  return (sharp(refs[0], b1) || sharp(refs[1], b2)) && !over_part(tip);
}

CreaseFilter HangingTest::filter() const {
  return [this](const PencilCandidate& c, const ElementPair& r) {
    return !hanging(c.p, c.b1, c.b2, r);
  };
}

// The vertical through q, from above the part to below it, passes within kPencilOutline of
// the part (a ball of that radius moved down it touches the part).
bool HangingTest::over_part(const Vec3& q) const {
  const double r = tol::kPencilOutline;
  const double above = box_.hi.z() + 1, depth = box_.hi.z() - box_.lo.z() + 2;
  return distance_.march(Vec3(q.x(), q.y(), above), -Vec3::UnitZ(), r, depth).has_value();
}

// A contact on an edge or vertex where some facet around it turns at least half the angle
// threshold away from the contact normal b (either facet orientation), or where the surface
// ends (an edge of one facet, a vertex on such an edge: an open mesh's boundary).
bool HangingTest::sharp(const ElementRef& e, const Vec3& b) const {
  if (e.kind != 1 && e.kind != 2) return false;
  const auto& V = mesh_.vertices;
  const Vec3& at = V[std::size_t(e.a)];
  const auto it = facets_at_.find(key(at));
  if (it == facets_at_.end()) return false;
  const Vec3* other = e.kind == 1 ? &V[std::size_t(e.b)] : nullptr;
  std::map<std::array<double, 3>, int> uses;  // the element's other ends: facets using each
  for (std::uint32_t f : it->second) {
    const auto& t = mesh_.facets[f];
    if (other && V[t[0]] != *other && V[t[1]] != *other && V[t[2]] != *other) continue;
    for (std::uint32_t v : t)
      if (V[v] != at) ++uses[key(V[v])];
    const Vec3 n = (V[t[1]] - V[t[0]]).cross(V[t[2]] - V[t[0]]);
    const double len = n.norm();
    if (len > 0 && std::abs(n.dot(b)) < cos_half_ * len) return true;
  }
  if (other) return uses[key(*other)] == 1;
  return std::any_of(uses.begin(), uses.end(), [](const auto& u) { return u.second == 1; });
}

}  // namespace ncpath
