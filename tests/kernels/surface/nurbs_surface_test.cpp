// kernels/surface/nurbs_surface*.cpp and height_field.cpp: evaluation against the Cox-de Boor
// recursion, direct Bernstein sums and analytic planes, spheres and cylinders; derivatives
// against central differences; normal curvature against analytic values; Bezier patches and
// their halves against the surface; validation messages; the height-field check on good and
// bad bottoms; the plan outline.
#include "kernels/surface/nurbs_surface.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "tests/kernels/surface/surface_test_util.hpp"

namespace ncpath {
namespace {

using test::kSqrtHalf;
using test::make_surface;

constexpr double kPi = std::numbers::pi;

// Random rational surface of degrees (p, q) with interior knots of multiplicity 1..degree.
NurbsSurface random_surface(int p, int q, std::mt19937& rng) {
  std::uniform_real_distribution<double> U(-10, 10), W(0.3, 3), K(0.05, 1);
  auto knots = [&](int deg, int& n) {
    std::vector<double> k(deg + 1, 0.0);
    double t = 0;
    for (int span = 0; span < 3; ++span) {
      t += K(rng);
      const int mult = 1 + static_cast<int>(rng() % deg);
      k.insert(k.end(), mult, t);
    }
    t += K(rng);
    k.insert(k.end(), deg + 1, t);
    n = static_cast<int>(k.size()) - deg - 1;
    return k;
  };
  int nu = 0, nv = 0;
  std::vector<double> ku = knots(p, nu), kv = knots(q, nv);
  NurbsSurface s = make_surface(p, q, nu, nv, ku, kv);
  for (Vec3& c : s.ctrl) c = Vec3(U(rng), U(rng), U(rng));
  for (double& w : s.weights) w = W(rng);
  return s;
}

std::vector<std::pair<double, double>> random_params(const NurbsSurface& s, int n,
                                                     std::mt19937& rng) {
  const SurfaceDomain d = domain(s);
  std::uniform_real_distribution<double> U(0, 1);
  std::vector<std::pair<double, double>> out;
  for (int i = 0; i < n; ++i)
    out.emplace_back(d.u0 + U(rng) * (d.u1 - d.u0), d.v0 + U(rng) * (d.v1 - d.v0));
  // The corners and knot values, where spans change.
  out.emplace_back(d.u0, d.v0);
  out.emplace_back(d.u1, d.v1);
  out.emplace_back(d.u0, d.v1);
  out.emplace_back(s.knots_u[s.degree_u + 1], s.knots_v[s.degree_v + 1]);
  return out;
}

TEST(SurfaceEval, MatchesCoxDeBoorForManyDegrees) {
  std::mt19937 rng(3);
  for (int p = 1; p <= 5; ++p)
    for (int q = 1; q <= 4; ++q) {
      const NurbsSurface s = random_surface(p, q, rng);
      ASSERT_EQ(validate(s), "") << p << " " << q;
      for (auto [u, v] : random_params(s, 40, rng))
        EXPECT_NEAR((surface_point(s, u, v) - test::cox_de_boor(s, u, v)).norm(), 0, 1e-11)
            << "p=" << p << " q=" << q << " u=" << u << " v=" << v;
    }
}

TEST(SurfaceEval, PlanarControlNetGivesThePlane) {
  // Any rational surface whose control points lie on a plane lies on it; the bilinear one
  // with unit weights is the bilinear interpolation of its corners.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> U(-20, 20);
  const double a = 0.3, b = -0.7, c = 4;
  NurbsSurface s = random_surface(3, 2, rng);
  for (Vec3& p : s.ctrl) p.z() = a * p.x() + b * p.y() + c;
  for (auto [u, v] : random_params(s, 200, rng)) {
    const Vec3 p = surface_point(s, u, v);
    EXPECT_NEAR(p.z(), a * p.x() + b * p.y() + c, 1e-12);
    // Tangents lie in the plane too.
    const SurfacePoint sp = evaluate(s, u, v);
    EXPECT_NEAR(sp.su.z() - a * sp.su.x() - b * sp.su.y(), 0, 1e-9 * (1 + sp.su.norm()));
    EXPECT_NEAR(sp.sv.z() - a * sp.sv.x() - b * sp.sv.y(), 0, 1e-9 * (1 + sp.sv.norm()));
  }
  NurbsSurface bl = make_surface(1, 1, 2, 2, {0, 0, 2, 2}, {-1, -1, 1, 1});
  const Vec3 c00(0, 0, 1), c01(1, 5, 2), c10(7, 1, 0), c11(8, 8, 3);
  bl.ctrl = {c00, c01, c10, c11};
  for (auto [u, v] : random_params(bl, 100, rng)) {
    const double s0 = u / 2, t0 = (v + 1) / 2;
    const Vec3 expect = (1 - s0) * ((1 - t0) * c00 + t0 * c01) + s0 * ((1 - t0) * c10 + t0 * c11);
    EXPECT_NEAR((surface_point(bl, u, v) - expect).norm(), 0, 1e-13);
  }
}

TEST(SurfaceEval, RationalSphereAndCylinderAreExact) {
  std::mt19937 rng(11);
  const double r = 7.25;
  for (double sign : {1.0, -1.0}) {
    const NurbsSurface h = test::hemisphere(r, sign);
    ASSERT_EQ(validate(h), "");
    for (auto [u, v] : random_params(h, 500, rng)) {
      const Vec3 p = surface_point(h, u, v);
      EXPECT_NEAR(p.norm(), r, 1e-12);
      EXPECT_GE(sign * p.z(), -1e-12);
    }
  }
  const NurbsSurface c = test::half_cylinder(3.5, 20, 1);
  ASSERT_EQ(validate(c), "");
  for (auto [u, v] : random_params(c, 500, rng)) {
    const Vec3 p = surface_point(c, u, v);
    EXPECT_NEAR(p.tail<2>().norm(), 3.5, 1e-12);
    EXPECT_NEAR(p.x(), -20 + 40 * u, 1e-12);
  }
}

TEST(SurfaceEval, DerivativesMatchCentralDifferences) {
  std::mt19937 rng(17);
  for (int p = 1; p <= 4; ++p) {
    const NurbsSurface s = random_surface(p, 3, rng);
    const SurfaceDomain d = domain(s);
    const double h = 1e-5;
    std::uniform_real_distribution<double> U(0, 1);
    for (int k = 0; k < 60; ++k) {
      double u = d.u0 + U(rng) * (d.u1 - d.u0), v = d.v0 + U(rng) * (d.v1 - d.v0);
      // Stay inside one knot span: differences across a knot see another polynomial.
      auto near_knot = [&](const std::vector<double>& K, double t) {
        for (double x : K)
          if (std::abs(x - t) < 3 * h) return true;
        return false;
      };
      if (near_knot(s.knots_u, u) || near_knot(s.knots_v, v)) continue;
      const SurfacePoint sp = evaluate(s, u, v);
      auto P = [&](double a, double b) { return surface_point(s, a, b); };
      auto Su = [&](double a, double b) { return evaluate(s, a, b).su; };
      auto Sv = [&](double a, double b) { return evaluate(s, a, b).sv; };
      const Vec3 fu = (P(u + h, v) - P(u - h, v)) / (2 * h);
      const Vec3 fv = (P(u, v + h) - P(u, v - h)) / (2 * h);
      const Vec3 fuu = (Su(u + h, v) - Su(u - h, v)) / (2 * h);
      const Vec3 fuv = (Su(u, v + h) - Su(u, v - h)) / (2 * h);
      const Vec3 fvu = (Sv(u + h, v) - Sv(u - h, v)) / (2 * h);
      const Vec3 fvv = (Sv(u, v + h) - Sv(u, v - h)) / (2 * h);
      const double scale =
          1 + sp.su.norm() + sp.sv.norm() + sp.suu.norm() + sp.svv.norm() + sp.suv.norm();
      const double tol = 1e-5 * scale;
      EXPECT_NEAR((sp.su - fu).norm(), 0, tol) << p;
      EXPECT_NEAR((sp.sv - fv).norm(), 0, tol) << p;
      EXPECT_NEAR((sp.suu - fuu).norm(), 0, tol) << p;
      EXPECT_NEAR((sp.suv - fuv).norm(), 0, tol) << p;
      EXPECT_NEAR((sp.suv - fvu).norm(), 0, tol) << p;
      EXPECT_NEAR((sp.svv - fvv).norm(), 0, tol) << p;
    }
  }
}

TEST(SurfaceEval, BicubicGridMatchesBernsteinSums) {
  const test::BicubicGrid g = test::wavy_grid(3, 60, 4, 1.5, 23);
  const NurbsSurface s = bezier_grid_surface(3, 3, g.ctrl);
  ASSERT_EQ(validate(s), "");
  EXPECT_EQ(s.knots_u, (std::vector<double>{0, 0, 0, 0, 1, 1, 1, 2, 2, 2, 3, 3, 3, 3}));
  std::mt19937 rng(29);
  for (auto [u, v] : random_params(s, 500, rng))
    EXPECT_NEAR((surface_point(s, u, v) - g.point(u, v)).norm(), 0, 1e-12) << u << " " << v;
  EXPECT_THROW(bezier_grid_surface(2, 3, g.ctrl), std::invalid_argument);
  EXPECT_THROW(bezier_grid_surface(0, 3, g.ctrl), std::invalid_argument);
}

// ---- normals and normal curvature ----

std::vector<std::pair<double, double>> directions(std::mt19937& rng) {
  std::vector<std::pair<double, double>> d = {{1, 0}, {0, 1}, {1, 1}, {1, -1}};
  std::uniform_real_distribution<double> A(0, 2 * kPi);
  for (int i = 0; i < 6; ++i) {
    const double a = A(rng);
    d.emplace_back(std::cos(a), std::sin(a));
  }
  return d;
}

TEST(SurfaceCurvature, DomeIsPositiveBowlNegative) {
  std::mt19937 rng(31);
  const double r = 4.5;
  std::uniform_real_distribution<double> U(0.1, 0.9), V(0, 1);
  for (double sign : {1.0, -1.0}) {
    const NurbsSurface h = test::hemisphere(r, sign);
    for (int k = 0; k < 100; ++k) {
      const double u = U(rng), v = V(rng);
      const SurfacePoint sp = evaluate(h, u, v);
      const Vec3 n = upward_normal(sp);
      EXPECT_NEAR(n.norm(), 1, 1e-12);
      EXPECT_GT(n.z(), 0);
      // Upward normal of the dome points away from the centre, of the bowl towards it.
      EXPECT_NEAR((n - sign * sp.p / r).norm(), 0, 1e-10);
      for (auto [du, dv] : directions(rng))
        EXPECT_NEAR(normal_curvature(sp, du, dv), sign / r, 1e-10) << sign << " " << u << " " << v;
    }
  }
}

TEST(SurfaceCurvature, CylinderAcrossAndAlongAndPlane) {
  std::mt19937 rng(37);
  std::uniform_real_distribution<double> U(0, 1), V(0.1, 0.9);
  for (double sign : {1.0, -1.0}) {
    const NurbsSurface c = test::half_cylinder(2.5, 10, sign);
    for (int k = 0; k < 50; ++k) {
      const SurfacePoint sp = evaluate(c, U(rng), V(rng));
      EXPECT_NEAR(normal_curvature(sp, 0, 1), sign / 2.5, 1e-10);  // across (around)
      EXPECT_NEAR(normal_curvature(sp, 1, 0), 0, 1e-12);           // along the axis
      // Euler: kappa(theta) = k1 cos^2 + k2 sin^2 in the orthonormal principal frame.
      const Vec3 e1 = sp.su.normalized(), e2 = sp.sv.normalized();
      const double th = 2 * kPi * U(rng);
      const Vec3 t = std::cos(th) * e1 + std::sin(th) * e2;
      // (du, dv) with su du + sv dv = t (su and sv are orthogonal here).
      const double du = t.dot(sp.su) / sp.su.squaredNorm(), dv = t.dot(sp.sv) / sp.sv.squaredNorm();
      const double s2 = std::sin(th) * std::sin(th);
      EXPECT_NEAR(normal_curvature(sp, du, dv), sign / 2.5 * s2, 1e-10);
    }
  }
  std::mt19937 rng2(41);
  NurbsSurface s = random_surface(3, 3, rng2);
  for (Vec3& p : s.ctrl) p.z() = 0.2 * p.x() - 0.1 * p.y();
  for (auto [u, v] : random_params(s, 50, rng2)) {
    const SurfacePoint sp = evaluate(s, u, v);
    for (auto [du, dv] : directions(rng2)) EXPECT_NEAR(normal_curvature(sp, du, dv), 0, 1e-9);
  }
}

TEST(SurfaceCurvature, PoleNormalIsTheLimit) {
  // At the hemisphere's pole su x sv = 0; the normal is still the limit (0, 0, 1).
  const NurbsSurface h = test::hemisphere(3, 1);
  for (double v : {0.0, 0.1, 0.37, 0.9}) {
    const SurfacePoint sp = evaluate(h, 1.0, v);
    EXPECT_NEAR((upward_normal(sp) - Vec3(0, 0, 1)).norm(), 0, 1e-12) << v;
  }
}

// ---- Bezier patches ----

TEST(SurfaceBezier, PatchesReproduceTheSurface) {
  std::mt19937 rng(43);
  for (int p = 1; p <= 4; ++p)
    for (int q = 1; q <= 3; ++q) {
      const NurbsSurface s = random_surface(p, q, rng);
      const std::vector<BezierPatch> patches = bezier_patches(s);
      // Three spans each way with distinct knots.
      ASSERT_EQ(patches.size(), 16u) << p << " " << q;
      std::uniform_real_distribution<double> U(0, 1);
      for (const BezierPatch& bp : patches) {
        ASSERT_EQ(bp.ctrl.size(), static_cast<std::size_t>((p + 1) * (q + 1)));
        for (int k = 0; k < 20; ++k) {
          const double a = U(rng), b = U(rng);
          const Vec3 x = patch_point(bp, a, b);
          const Vec3 y =
              test::cox_de_boor(s, bp.u0 + a * (bp.u1 - bp.u0), bp.v0 + b * (bp.v1 - bp.v0));
          EXPECT_NEAR((x - y).norm(), 0, 1e-12) << p << " " << q;
          // Convex hull property: the box holds the patch.
          EXPECT_TRUE((x.array() >= bp.lo.array() - 1e-12).all());
          EXPECT_TRUE((x.array() <= bp.hi.array() + 1e-12).all());
        }
      }
    }
}

TEST(SurfaceBezier, SplitHalvesReproduceTheParent) {
  std::mt19937 rng(47);
  const NurbsSurface s = random_surface(3, 2, rng);
  std::uniform_real_distribution<double> U(0, 1);
  for (const BezierPatch& bp : bezier_patches(s)) {
    for (int mode = 0; mode < 3; ++mode) {
      BezierPatch a, b;
      if (mode == 2) {
        split_patch(bp, a, b);  // longer parameter side
      } else {
        split_patch(bp, mode == 0, a, b);
      }
      const bool along_u = mode == 0 || (mode == 2 && bp.u1 - bp.u0 >= bp.v1 - bp.v0);
      if (along_u) {
        EXPECT_EQ(a.u0, bp.u0);
        EXPECT_EQ(a.u1, b.u0);
        EXPECT_EQ(b.u1, bp.u1);
        EXPECT_NEAR(a.u1, 0.5 * (bp.u0 + bp.u1), 1e-15);
      } else {
        EXPECT_NEAR(a.v1, 0.5 * (bp.v0 + bp.v1), 1e-15);
        EXPECT_EQ(b.v0, a.v1);
      }
      for (int k = 0; k < 30; ++k) {
        const double x = U(rng), y = U(rng);
        for (int half = 0; half < 2; ++half) {
          const BezierPatch& h = half == 0 ? a : b;
          const double px = along_u ? 0.5 * (x + half) : x, py = along_u ? y : 0.5 * (y + half);
          const Vec3 c = patch_point(h, x, y), pp = patch_point(bp, px, py);
          EXPECT_NEAR((c - pp).norm(), 0, 1e-12);
          EXPECT_TRUE((c.array() >= h.lo.array() - 1e-12).all());
          EXPECT_TRUE((c.array() <= h.hi.array() + 1e-12).all());
        }
      }
      // Halves' boxes are inside the parent's.
      EXPECT_TRUE((a.lo.array() >= bp.lo.array() - 1e-12).all());
      EXPECT_TRUE((b.hi.array() <= bp.hi.array() + 1e-12).all());
    }
  }
  // In place: a aliases the parent.
  BezierPatch p = bezier_patches(s)[5], b;
  const BezierPatch orig = p;
  split_patch(p, true, p, b);
  EXPECT_NEAR((patch_point(p, 1, 0.3) - patch_point(orig, 0.5, 0.3)).norm(), 0, 1e-12);
  EXPECT_NEAR((patch_point(b, 0, 0.3) - patch_point(orig, 0.5, 0.3)).norm(), 0, 1e-12);
}

// ---- validation ----

TEST(SurfaceValidate, EachDefectIsNamed) {
  std::mt19937 rng(53);
  const NurbsSurface good = random_surface(2, 3, rng);
  ASSERT_EQ(validate(good), "");
  auto expect = [&](NurbsSurface s, const std::string& word, const char* what) {
    const std::string e = validate(s);
    EXPECT_NE(e.find(word), std::string::npos) << what << ": \"" << e << "\"";
  };
  NurbsSurface s = good;
  s.degree_u = 0;
  expect(s, "degree_u", "degree 0");
  s = good;
  s.degree_v = -1;
  expect(s, "degree_v", "negative degree");
  s = good;
  s.ctrl.pop_back();
  expect(s, "ctrl", "control count");
  s = good;
  s.weights.push_back(1);
  expect(s, "weights", "weight count");
  s = good;
  s.knots_u.push_back(s.knots_u.back());
  expect(s, "knots_u", "knot count u");
  s = good;
  s.knots_v.erase(s.knots_v.begin());
  expect(s, "knots_v", "knot count v");
  s = good;
  s.weights[4] = 0;
  expect(s, "weights[4]", "zero weight");
  s = good;
  s.weights[2] = -1;
  expect(s, "not > 0", "negative weight");
  s = good;
  std::swap(s.knots_u[4], s.knots_u[5]);
  if (s.knots_u[4] == s.knots_u[5]) s.knots_u[4] += 0.01;
  s.knots_u[5] = s.knots_u[4] - 0.001;
  expect(s, "decrease", "decreasing knots");
  s = good;
  s.knots_v[0] -= 0.5;
  expect(s, "not clamped", "unclamped start");
  s = good;
  s.knots_u.back() += 0.5;
  expect(s, "not clamped", "unclamped end");
  s = good;
  s.ctrl[3].y() = std::nan("");
  expect(s, "ctrl[3]", "NaN control point");
  s = good;
  s.weights[1] = std::numeric_limits<double>::infinity();
  expect(s, "weights[1]", "infinite weight");
  s = good;
  s.knots_v[5] = std::nan("");
  expect(s, "knots_v[5]", "NaN knot");
  s = good;
  s.nu += 1;
  expect(s, "nu * nv", "nu does not match the net");
  // Interior knot of multiplicity > degree.
  NurbsSurface m = make_surface(2, 1, 6, 2, {0, 0, 0, 1, 1, 1, 2, 2, 2}, {0, 0, 1, 1});
  expect(m, "multiplicity", "discontinuous knot");
}

// ---- height field ----

NurbsSurface grid_from(int pu, int pv, const std::function<Vec3(double, double)>& f) {
  // Bicubic grid whose control points sample f at the control grid's positions.
  std::vector<Vec3> ctrl;
  const int nu = 3 * pu + 1, nv = 3 * pv + 1;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j)
      ctrl.push_back(f(static_cast<double>(i) / (nu - 1), static_cast<double>(j) / (nv - 1)));
  return bezier_grid_surface(pu, pv, ctrl);
}

// Parses the first "(u, v) = (a, b)" of a message.
bool parse_uv(const std::string& msg, double& u, double& v) {
  const auto k = msg.find("(u, v) = (");
  return k != std::string::npos && std::sscanf(msg.c_str() + k, "(u, v) = (%lf, %lf)", &u, &v) == 2;
}

TEST(HeightField, PlaneAndDomePass) {
  const NurbsSurface plane =
      grid_from(2, 3, [](double a, double b) { return Vec3(40 * a, 30 * b, 2 + a - b); });
  EXPECT_EQ(check_height_field(plane), "");
  // Dome z = 10 - (x^2 + y^2) / 20 over [-10, 10]^2 as an exact biquadratic.
  NurbsSurface dome = make_surface(2, 2, 3, 3, {0, 0, 0, 1, 1, 1}, {0, 0, 0, 1, 1, 1});
  const double xs[3] = {-10, 0, 10};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      // Bernstein coefficients of x^2 on [-10, 10]: 100, -100, 100.
      const double cx = i == 1 ? -100 : 100, cy = j == 1 ? -100 : 100;
      dome.ctrl[i * 3 + j] = Vec3(xs[i], xs[j], 10 - (cx + cy) / 20);
    }
  ASSERT_EQ(validate(dome), "");
  for (double u : {0.1, 0.5, 0.8}) {
    const Vec3 p = surface_point(dome, u, 0.3);
    EXPECT_NEAR(p.z(), 10 - (p.x() * p.x() + p.y() * p.y()) / 20, 1e-12);
  }
  EXPECT_EQ(check_height_field(dome), "");
  // Reversed u (negative Jacobian everywhere) is still a height field.
  NurbsSurface rev = dome;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) rev.ctrl[i * 3 + j] = dome.ctrl[(2 - i) * 3 + j];
  EXPECT_EQ(check_height_field(rev), "");
  // A steep but not vertical wavy surface with creases passes.
  const test::BicubicGrid g = test::wavy_grid(4, 60, 8, 1.0, 5);
  EXPECT_EQ(check_height_field(bezier_grid_surface(4, 4, g.ctrl)), "");
}

TEST(HeightField, FoldIsReportedWhereItFolds) {
  // Control points that double back in x: x rises, comes back (x'(u) < 0 in the middle) and
  // rises again, so the plan map folds along the lines where x'(u) = 0.
  NurbsSurface s = make_surface(3, 1, 4, 2, {0, 0, 0, 0, 1, 1, 1, 1}, {0, 0, 1, 1});
  const double x[4] = {0, 30, -10, 20}, z[4] = {0, 4, 4, 0};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 2; ++j) s.ctrl[i * 2 + j] = Vec3(x[i], 10 * j, z[i]);
  const std::string msg = check_height_field(s);
  EXPECT_NE(msg.find("folds"), std::string::npos) << msg;
  double u = -1, v = -1;
  ASSERT_TRUE(parse_uv(msg, u, v)) << msg;
  // x'(u) = 0 where 3 [(1-u)^2 30 + 2 u (1-u) (-40) + u^2 30] = 0: 140 u^2 - 140 u + 30 = 0.
  const double r1 = 0.5 - std::sqrt(140.0 * 140 - 4 * 140 * 30) / 280, r2 = 1 - r1;
  EXPECT_LT(std::min(std::abs(u - r1), std::abs(u - r2)), 1e-6) << msg;
  EXPECT_NE(msg.find("plan (x, y) = ("), std::string::npos) << msg;
}

TEST(HeightField, VerticalTangentPlaneIsReported) {
  // Quarter cylinder wall: the arc from the top (y = 0, z = 5) down to the side (y = 5,
  // z = 0), where its tangent plane is vertical (on the border v = 1).
  NurbsSurface s = make_surface(1, 2, 2, 3, {0, 0, 1, 1}, {0, 0, 0, 1, 1, 1});
  const double arc[3][3] = {{0, 5, 1}, {5, 5, kSqrtHalf}, {5, 0, 1}};
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 3; ++j) {
      s.ctrl[i * 3 + j] = Vec3(20 * i, arc[j][0], arc[j][1]);
      s.weights[i * 3 + j] = arc[j][2];
    }
  std::string msg = check_height_field(s);
  EXPECT_NE(msg.find("vertical"), std::string::npos) << msg;
  double u = -1, v = -1;
  ASSERT_TRUE(parse_uv(msg, u, v)) << msg;
  EXPECT_NEAR(v, 1, 1e-9) << msg;
  // Interior vertical line: x(u) = 20 (u - 0.4)^3 + ... has x'(0.4) = 0 with x' >= 0.
  NurbsSurface t = make_surface(3, 1, 4, 2, {0, 0, 0, 0, 1, 1, 1, 1}, {0, 0, 1, 1});
  // x = 100 (u - 0.4)^3 = -6.4 + 48 u - 120 u^2 + 100 u^3; Bernstein coefficients of
  // sum a_i u^i: b_k = sum_{i <= k} C(k, i) / C(3, i) a_i.
  const double a0 = -6.4, a1 = 48, a2 = -120, a3 = 100;
  const double b[4] = {a0, a0 + a1 / 3, a0 + 2 * a1 / 3 + a2 / 3, a0 + a1 + a2 + a3};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 2; ++j) t.ctrl[i * 2 + j] = Vec3(b[i], 10 * j, 0.5 * i);
  for (double uu : {0.1, 0.4, 0.7})
    EXPECT_NEAR(surface_point(t, uu, 0).x(), 100 * std::pow(uu - 0.4, 3), 1e-12);
  msg = check_height_field(t);
  EXPECT_NE(msg.find("vertical"), std::string::npos) << msg;
  ASSERT_TRUE(parse_uv(msg, u, v)) << msg;
  EXPECT_NEAR(u, 0.4, 2e-3) << msg;
}

TEST(HeightField, OverlapWithoutFoldIsReported) {
  // A ramp strip wound 1.2 turns around the z axis: the Jacobian keeps its sign, but the strip
  // lies over itself in plan.
  const NurbsSurface s = grid_from(12, 1, [](double a, double b) {
    const double th = 2.4 * kPi * a, rho = 10 + 5 * b;
    return Vec3(rho * std::cos(th), rho * std::sin(th), 3 * th);
  });
  const std::string msg = check_height_field(s);
  EXPECT_NE(msg.find("overlaps itself"), std::string::npos) << msg;
  double u = -1, v = -1;
  ASSERT_TRUE(parse_uv(msg, u, v)) << msg;
  // The same strip over one turn only is fine.
  const NurbsSurface ok = grid_from(12, 1, [](double a, double b) {
    const double th = 1.6 * kPi * a, rho = 10 + 5 * b;
    return Vec3(rho * std::cos(th), rho * std::sin(th), 3 * th);
  });
  EXPECT_EQ(check_height_field(ok), "");
}

TEST(HeightField, InvalidSurfaceIsReported) {
  NurbsSurface s;
  EXPECT_NE(check_height_field(s).find("invalid surface"), std::string::npos);
}

// ---- plan outline ----

double signed_area(const std::vector<Vec2>& p) {
  double a = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec2 &x = p[i], &y = p[(i + 1) % p.size()];
    a += x.x() * y.y() - x.y() * y.x();
  }
  return a / 2;
}

TEST(PlanOutline, HemisphereIsACircleCounterClockwise) {
  for (double sign : {1.0, -1.0}) {
    // The border of the hemisphere's domain is the equator plus a meridian run out to the
    // pole and back (a spike of zero area).
    const NurbsSurface h = test::hemisphere(10, sign);
    const double tol = 1e-3;
    const std::vector<Vec2> o = plan_outline(h, tol);
    ASSERT_GE(o.size(), 8u);
    EXPECT_GT(signed_area(o), 0);
    for (const Vec2& p : o) EXPECT_LE(p.norm(), 10 + 1e-12);
    // Area of the circle less the chordal sliver (<= perimeter * tol).
    EXPECT_NEAR(signed_area(o), kPi * 100, 2 * kPi * 10 * tol) << sign;
  }
}

TEST(PlanOutline, ReversedParameterisationIsStillCounterClockwise) {
  // A parallelogram (linear in u and v, which the grid reproduces exactly), parameterised
  // both ways round.
  const NurbsSurface a =
      grid_from(2, 2, [](double u, double v) { return Vec3(30 * u + 10 * v, 20 * v, u * v); });
  const NurbsSurface b =
      grid_from(2, 2, [](double u, double v) { return Vec3(30 * v + 10 * u, 20 * u, u * v); });
  for (const NurbsSurface* s : {&a, &b}) {
    const std::vector<Vec2> o = plan_outline(*s, 1e-4);
    EXPECT_GT(signed_area(o), 0);
    EXPECT_NEAR(signed_area(o), 600, 0.01);
    for (std::size_t i = 0; i < o.size(); ++i) EXPECT_NE(o[i], o[(i + 1) % o.size()]);
  }
}

}  // namespace
}  // namespace ncpath
