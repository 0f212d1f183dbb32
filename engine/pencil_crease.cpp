#include "engine/pencil_crease.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

#include "kernels/geom/tolerance.hpp"
#include "kernels/mesh/closest_point.hpp"
#include "kernels/scan/envelope.hpp"

namespace ncpath {

namespace {

// The junction on plane v of a's family nearest to `near` (within w of it along the plane),
// sharp concave, off the floor, with angle >= min_angle and tangent within kCreaseMinCos of t.
bool nearest_crease(const ScanElements& se, const PencilCandidate& a, double v, const Vec3& near,
                    double w, const Vec3& t, double min_angle, double floor_z,
                    PencilCandidate& out, ElementPair* refs = nullptr) {
  const double u = a.family == 0 ? near.x() : near.y();
  double best = w;
  bool found = false;
  for (const PlaneJunction& j : plane_junctions(se, a.family, v, u - w, u + w, floor_z)) {
    if (j.kind != std::uint8_t(JunctionKind::kSharpConcave) || j.on_floor) continue;
    if (bicontact_angle(j.b1, j.b2) < min_angle) continue;
    if (std::abs(crease_tangent(j.b1, j.b2).dot(t)) < kCreaseMinCos) continue;
    const double d = (j.position - near).norm();
    if (d < best) {
      best = d;
      out = {j.position, j.b1, j.b2, a.family, a.layer};
      if (refs) *refs = {j.element1, j.element2};
      found = true;
    }
  }
  return found;
}

}  // namespace

bool crease_between(const ScanElements& se, const PencilCandidate& a, const PencilCandidate& b,
                    double min_angle, double floor_z, PencilCandidate& out) {
  const Vec3 n = layer_normal(a.family);
  const double v = 0.5 * (a.p.dot(n) + b.p.dot(n));
  const double w = std::max(0.5 * (b.p - a.p).norm(), 0.05);
  return nearest_crease(se, a, v, 0.5 * (a.p + b.p), w, crease_tangent(a.b1, a.b2), min_angle,
                        floor_z, out);
}

bool crease_on_plane(const ScanElements& se, const PencilCandidate& a, double v, double min_angle,
                     double floor_z, PencilCandidate& out, ElementPair* refs) {
  const Vec3 n = layer_normal(a.family), t = crease_tangent(a.b1, a.b2);
  if (!(std::abs(t.dot(n)) > tol::kPencilAlongPlane)) return false;  // along the planes
  const Vec3 q = a.p + t * ((v - a.p.dot(n)) / t.dot(n));
  const double w = std::max((q - a.p).norm(), 0.05);
  return nearest_crease(se, a, v, q, w, t, min_angle, floor_z, out, refs);
}

bool crease_end(const ScanElements& se, const PencilCandidate& end, double dir, double spacing,
                double v_min, double v_max, const CreaseFilter& keep, double min_angle,
                double floor_z, PencilCandidate& out, ElementPair& out_refs) {
  const double v0 = end.p.dot(layer_normal(end.family));
  double lo = 0, hi = std::min(spacing, dir > 0 ? v_max - v0 : v0 - v_min);
  if (!(hi > 0)) return false;
  bool found = false;
  PencilCandidate from = end;
  for (int it = 0; it < 7; ++it) {
    const double mid = 0.5 * (lo + hi);
    PencilCandidate c;
    ElementPair r;
    if (crease_on_plane(se, from, v0 + dir * mid, min_angle, floor_z, c, &r) && keep(c, r)) {
      out = c;
      out_refs = r;
      from = c;
      found = true;
      lo = mid;
    } else {
      hi = mid;
    }
  }
  return found;
}

namespace {

// The closest point of a mesh element (facet, edge or vertex: kind 0, 1, 2) to a point.
std::function<Vec3(const Vec3&)> closest_of(const TriangleMesh& mesh, const ElementRef& e) {
  const auto& V = mesh.vertices;
  if (e.kind == 0) {
    const auto& f = mesh.facets[std::size_t(e.a)];
    return [&V, f](const Vec3& q) {
      Vec3 c;
      point_triangle_closest(q, V[f[0]], V[f[1]], V[f[2]], c);
      return c;
    };
  }
  if (e.kind == 1) {
    const Vec3 a = V[std::size_t(e.a)], b = V[std::size_t(e.b)];
    return [a, b](const Vec3& q) {
      Vec3 c;
      point_segment_closest(q, a, b, c);
      return c;
    };
  }
  const Vec3 v = V[std::size_t(e.a)];
  return [v](const Vec3&) { return v; };
}

Vec3 crease_tangent_of(const PencilCandidate& c) { return crease_tangent(c.b1, c.b2); }

}  // namespace

bool chord_wants_refining(const PencilCandidate& a, const PencilCandidate& b, double tolerance,
                          int depth, const DropIndex& index, double floor_z) {
  if (depth >= 16) return false;
  const bool loose =
      (b.p - a.p).norm() >= 2 * tolerance &&
      chord_error(a.p, crease_tangent_of(a), b.p, crease_tangent_of(b)) > tolerance;
  return loose ||
         !(depth >= 8 || surface_deficit(index, floor_z, 0.5 * (a.p + b.p)) <= 0.5 * tolerance);
}

void refine_on_planes(const ScanElements& se, const DropIndex& index, const PencilCandidate& a,
                      const PencilCandidate& b, double tolerance, double min_angle,
                      double floor_z, int depth, std::vector<PencilCandidate>& out,
                      std::uint64_t& added) {
  if (a.family == 2 || !chord_wants_refining(a, b, tolerance, depth, index, floor_z)) return;
  PencilCandidate c;
  if (!crease_between(se, a, b, min_angle, floor_z, c)) return;
  ++added;
  refine_on_planes(se, index, a, c, tolerance, min_angle, floor_z, depth + 1, out, added);
  out.push_back(c);
  refine_on_planes(se, index, c, b, tolerance, min_angle, floor_z, depth + 1, out, added);
}

void ZLevelCreaseRefine::operator()(const PencilCandidate& a, const ElementPair& ea,
                                    const PencilCandidate& b, const ElementPair& eb, int depth,
                                    std::vector<PencilCandidate>& out,
                                    std::uint64_t& added) const {
  const auto& refine_z = *this;
  auto closest = [&](const ElementRef& e) { return closest_of(mesh, e); };
  if (!chord_wants_refining(a, b, tolerance, depth, index, floor_z)) return;
  const double zm = 0.5 * (a.p.z() + b.p.z());
  const Vec2 guess = 0.5 * (a.p.head<2>() + b.p.head<2>());
  // The crease of a's elements, else of b's (a crease may pass from one pair to another
  // between them, e.g. from two walls to their rim edges).
  for (const ElementPair* e : {&ea, &eb}) {
    const ElementPair& el = *e;
    if (el[0].kind > 2 || el[1].kind > 2) continue;
    Vec2 xy;
    if (!crease_at_height(closest(el[0]), closest(el[1]), guess, zm + R, R,
                          (b.p - a.p).norm(), xy))
      continue;
    const Vec3 q(xy.x(), xy.y(), zm);
    // On the CL surface: the drop-cutter reaches it there (upper semicontinuous: at a
    // wall's foot it reports the wall's top) and the point is not inside the part.
    const double top = std::max(floor_z, index.query(q.x(), q.y()).tip_z);
    if (top < zm - tol::kSweepSlack || !reachable(part, q)) continue;
    const Vec3 centre = q + Vec3(0, 0, R);
    PencilCandidate c = a;
    c.p = q;
    c.b1 = (centre - closest(el[0])(centre)).normalized();
    c.b2 = (centre - closest(el[1])(centre)).normalized();
    ++added;
    refine_z(a, ea, c, el, depth + 1, out, added);
    out.push_back(c);
    refine_z(c, el, b, eb, depth + 1, out, added);
    return;
  }
  // Under an overhang or along walls (z-level junctions of shadowed elements) the
  // contacts are on walls below the elements: the crease follows a's tangent, straight
  // (vertical between two walls). Kept when that point is on the CL surface.
  for (const PencilCandidate* e : {&a, &b}) {
    const Vec3 t = crease_tangent_of(*e);
    if (!(std::abs(t.z()) > 0.5)) continue;
    const Vec3 q = e->p + t * ((zm - e->p.z()) / t.z());
    const double top = std::max(floor_z, index.query(q.x(), q.y()).tip_z);
    if ((q - e->p).norm() > (b.p - a.p).norm() || top < zm - tol::kSweepSlack ||
        !reachable(part, q))
      continue;
    PencilCandidate c = *e;
    c.p = q;
    ++added;
    refine_z(a, ea, c, e == &a ? ea : eb, depth + 1, out, added);
    out.push_back(c);
    refine_z(c, e == &a ? ea : eb, b, eb, depth + 1, out, added);
    return;
  }
}

}  // namespace ncpath
