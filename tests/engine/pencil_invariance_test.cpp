// Representation invariance of the pencil-cut and its z-levels (issue 17, item 1): the same
// part written the ways exporters write it (float32, 6-17 significant digits, vertex noise
// 1e-13..1e-7 mm, turned about z by an arbitrary angle, 1 m from the origin, facets
// reversed) gives 0 open z-level chains, a traced length within 1 % and a path count within
// 10 % of the full-precision run. Oracles independent of the pencil code: every pencil point's
// bi-contact angle recomputed by brute force from the part as given (the directions from the
// facets' closest points to the ball centre), and the brute-force no-gouge check of the paths
// against the part as given (not the conditioned one).
#include <gtest/gtest.h>

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

#include "engine/pencil.hpp"
#include "kernels/mesh/closest_point.hpp"
#include "tests/engine/mesh_test_support.hpp"

namespace ncpath {
namespace {

using Variant = std::pair<std::string, std::function<void(TriangleMesh&)>>;

void each_coordinate(TriangleMesh& m, const std::function<double(double)>& f) {
  for (Vec3& v : m.vertices)
    for (int k = 0; k < 3; ++k) v[k] = f(v[k]);
}

double round_digits(double x, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, x);
  return std::strtod(buf, nullptr);
}

std::vector<Variant> variants() {
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
      out.push_back({"noise " + std::to_string(e) + " seed " + std::to_string(seed),
                     [e, seed](TriangleMesh& m) {
                       std::mt19937_64 bits(seed);
                       std::uniform_real_distribution<double> u(-e, e);
                       each_coordinate(m, [&](double x) { return x + u(bits); });
                     }});
  out.push_back({"turn 37.3", [](TriangleMesh& m) {
                   const double a = 37.3 * std::numbers::pi / 180;
                   const double ca = std::cos(a), sa = std::sin(a);
                   for (Vec3& v : m.vertices) v = Vec3(ca * v.x() - sa * v.y(), sa * v.x() + ca * v.y(), v.z());
                 }});
  out.push_back({"far", [](TriangleMesh& m) {
                   for (Vec3& v : m.vertices) v += Vec3(1000, -1000, 0);
                 }});
  out.push_back({"reversed", [](TriangleMesh& m) {
                   for (auto& f : m.facets) std::swap(f[1], f[2]);
                 }});
  return out;
}

// Largest angle between the directions from the part's contacts to the ball centre c: the
// closest points of facets within R + reach of c (brute force over all facets).
double brute_bicontact_angle(const TriangleMesh& m, const Vec3& c, double R, double reach) {
  std::vector<Vec3> dirs;
  for (const auto& f : m.facets) {
    const Vec3 &a = m.vertices[f[0]], &b = m.vertices[f[1]], &d = m.vertices[f[2]];
    if ((b - a).cross(d - a).squaredNorm() == 0) continue;
    Vec3 q;
    if (point_triangle_closest(c, a, b, d, q) <= R + reach) dirs.push_back((c - q).normalized());
  }
  double best = 0;
  for (std::size_t i = 0; i < dirs.size(); ++i)
    for (std::size_t j = i + 1; j < dirs.size(); ++j)
      best = std::max(best, std::acos(std::clamp(dirs[i].dot(dirs[j]), -1.0, 1.0)));
  return best;
}

// The oracles on one run: every 25th pencil point's angle seen on the part as given
// (contacts within the job's tolerance and the conditioning's move), and no gouge.
void expect_sound(const TriangleMesh& m, const PencilResult& r, const PencilParams& p, double R) {
  EXPECT_LE(r.stats.condition.max_move, tol::kConditionMove);
  const double min_angle = p.min_angle_deg * std::numbers::pi / 180;
  const double reach = p.tolerance + r.stats.condition.max_move;
  for (std::size_t k = 0; k < r.points.size(); k += 25) {
    const Vec3 centre = r.points[k].position + Vec3(0, 0, R);
    EXPECT_GE(brute_bicontact_angle(m, centre, R, reach), min_angle - 1e-3)
        << "point " << k << " family " << int(r.points[k].family) << " angle "
        << r.points[k].angle << " at " << r.points[k].position.transpose();
  }
  test_meshes::expect_no_gouge(m, r.paths, R);
}

void expect_invariant(const std::string& name) {
  const TriangleMesh mesh = test_meshes::load(name);
  const Cutter ball = ball_cutter(5);  // diameter 5 mm
  const double R = ball.radius;
  const PencilParams p;  // interval 0.5, step-down 1, 20 degrees, tolerance 0.01
  RunControl control;
  const PencilResult full = run_pencil(mesh, ball, p, control);
  ASSERT_EQ(full.stats.zlevel_open_chains, 0u);
  ASSERT_GT(full.stats.paths, 0u);
  expect_sound(mesh, full, p, R);
  for (const auto& [label, change] : variants()) {
    SCOPED_TRACE(name + ", " + label);
    TriangleMesh m = mesh;
    change(m);
    const PencilResult r = run_pencil(m, ball, p, control);
    EXPECT_EQ(r.stats.zlevel_open_chains, 0u);
    EXPECT_NEAR(r.stats.traced_length / full.stats.traced_length, 1.0, 0.01);
    // A turn moves the drive planes across the part: where a crease stretch is found in one
    // pose and not the other, a piece splits off or joins (fandisk turned 37.3 degrees: a
    // 1.3 mm piece 2 mm beyond a path's end is bridged). Known limit of the tracing, not of
    // the contours: one path either way is allowed there.
    const double slack = label.starts_with("turn") ? (1 + 1e-9) / double(full.stats.paths) : 0.0;
    EXPECT_NEAR(double(r.stats.paths) / double(full.stats.paths), 1.0, std::max(0.1, slack));
    expect_sound(m, r, p, R);
  }
}

TEST(PencilInvariance, FandiskCad) { expect_invariant("fandisk"); }

}  // namespace
}  // namespace ncpath
