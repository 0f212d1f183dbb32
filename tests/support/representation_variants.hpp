#pragma once
// One part written the ways exporters write it (issue 17's invariance): the variants the
// pencil and fillet invariance tests run and ncpath_pencil_invariance measures, all applied
// to the vertices in mm after the job's fit:
//   float32        each coordinate rounded to float (binary STL)
//   digits N       rounded to N significant decimal digits (ASCII STL, OFF), N = 6 ... 17
//   noise E seed S each coordinate moved by a uniform amount in [-E, E], E = 1e-13 ... 1e-7
//   turn 37.3      turned about the z axis through the origin by 37.3 degrees
//   far            translated by (1000, -1000, 0) mm
//   reversed       every facet's winding reversed
// and, for the robustness tests of issue 34 (more_representation_variants):
//   noise 1e-5     as above, 1e-6 and 1e-5 mm
//   turn 90        turned by 90 degrees
//   shuffled       facets in a random order
//   soup           every facet with its own three vertices (an STL file as read, unwelded)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <numbers>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "kernels/mesh/triangle_mesh.hpp"

namespace ncpath::test {

using Variant = std::pair<std::string, std::function<void(TriangleMesh&)>>;

inline void each_coordinate(TriangleMesh& m, const std::function<double(double)>& f) {
  for (Vec3& v : m.vertices)
    for (int k = 0; k < 3; ++k) v[k] = f(v[k]);
}

inline double round_digits(double x, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, x);
  return std::strtod(buf, nullptr);
}

inline std::string noise_label(double e, unsigned seed) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "noise %.0e seed %u", e, seed);
  return buf;
}

inline std::vector<Variant> representation_variants() {
  std::vector<Variant> out;
  out.push_back({"float32", [](TriangleMesh& m) {
                   each_coordinate(m, [](double x) { return double(static_cast<float>(x)); });
                 }});
  for (int digits : {6, 9, 12, 15, 17})
    out.push_back({"digits " + std::to_string(digits), [digits](TriangleMesh& m) {
                     each_coordinate(m, [digits](double x) { return round_digits(x, digits); });
                   }});
  for (double e : {1e-13, 1e-11, 1e-9, 1e-7})
    for (unsigned seed : {1u, 2u})
      out.push_back({noise_label(e, seed), [e, seed](TriangleMesh& m) {
                       std::mt19937_64 bits(seed);
                       std::uniform_real_distribution<double> u(-e, e);
                       each_coordinate(m, [&](double x) { return x + u(bits); });
                     }});
  out.push_back({"turn 37.3", [](TriangleMesh& m) {
                   const double a = 37.3 * std::numbers::pi / 180;
                   const double ca = std::cos(a), sa = std::sin(a);
                   for (Vec3& v : m.vertices)
                     v = Vec3(ca * v.x() - sa * v.y(), sa * v.x() + ca * v.y(), v.z());
                 }});
  out.push_back({"far", [](TriangleMesh& m) {
                   for (Vec3& v : m.vertices) v += Vec3(1000, -1000, 0);
                 }});
  out.push_back({"reversed", [](TriangleMesh& m) {
                   for (auto& f : m.facets) std::swap(f[1], f[2]);
                 }});
  return out;
}

inline std::vector<Variant> more_representation_variants() {
  std::vector<Variant> out = representation_variants();
  for (double e : {1e-6, 1e-5})
    out.push_back({noise_label(e, 3), [e](TriangleMesh& m) {
                     std::mt19937_64 bits(3);
                     std::uniform_real_distribution<double> u(-e, e);
                     each_coordinate(m, [&](double x) { return x + u(bits); });
                   }});
  out.push_back({"turn 90", [](TriangleMesh& m) {
                   for (Vec3& v : m.vertices) v = Vec3(-v.y(), v.x(), v.z());
                 }});
  out.push_back({"shuffled", [](TriangleMesh& m) {
                   std::mt19937_64 bits(7);
                   std::shuffle(m.facets.begin(), m.facets.end(), bits);
                 }});
  out.push_back({"soup", [](TriangleMesh& m) {
                   TriangleMesh s;
                   for (const auto& f : m.facets) {
                     const auto base = std::uint32_t(s.vertices.size());
                     for (std::uint32_t v : f) s.vertices.push_back(m.vertices[v]);
                     s.facets.push_back({base, base + 1, base + 2});
                   }
                   m = std::move(s);
                 }});
  return out;
}

}  // namespace ncpath::test
