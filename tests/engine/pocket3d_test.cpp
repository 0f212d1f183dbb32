// Sculptured-bottom pockets (issue 7) against independent answers: analytic ball drops on
// planes and cylinders, the same path as the flat pocket on a flat bottom, a dense
// independent no-gouge check (exact distance from the ball centre to the analytic bottom
// and the walls), the realised scallop between neighbouring passes on a dense grid, the
// geometry of the scallop formula, and bad surfaces.
#include "engine/pocket3d.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <map>
#include <numbers>

#include "engine/parallel.hpp"
#include "engine/pocket_path.hpp"
#include "tests/kernels/surface/surface_test_util.hpp"
#include "tests/support/shapes2d.hpp"

namespace ncpath {
namespace {

constexpr double kPi = std::numbers::pi;

// The cylinder (x - cx)^2 + (z - cz)^2 = rho^2, upper part (vault, sign = +1) or lower part
// (trough, sign = -1) over x in cx +- rho sin(60 deg), y in [y0, y1]: an exact rational
// quadratic arc of 120 degrees extruded along y.
NurbsSurface cylinder(double cx, double cz, double rho, double y0, double y1, double sign = 1) {
  NurbsSurface s;
  s.degree_u = 2;
  s.degree_v = 1;
  s.nu = 3;
  s.nv = 2;
  const double h = kPi / 3;  // half angle
  const Vec2 p0(cx - rho * std::sin(h), cz + sign * rho * std::cos(h));
  const Vec2 p2(cx + rho * std::sin(h), cz + sign * rho * std::cos(h));
  const Vec2 p1(cx, cz + sign * rho / std::cos(h));  // tangents' crossing
  const double w1 = std::cos(h);
  for (const auto& [p, w] : {std::pair(p0, 1.0), std::pair(p1, w1), std::pair(p2, 1.0)})
    for (double y : {y0, y1}) {
      s.ctrl.emplace_back(p.x(), y, p.y());
      s.weights.push_back(w);
    }
  s.knots_u = {0, 0, 0, 1, 1, 1};
  s.knots_v = {0, 0, 1, 1};
  return s;
}

Region disc_pocket(const Vec2& c, double r) {
  Region g;
  g.boundary = profile_of(test::circle(c, r, true));
  return g;
}

Pocket3dParams params(double r, double h) {
  Pocket3dParams p;
  p.tool_radius = r;
  p.scallop = h;
  p.eps = 0.01;
  p.delta = 0.01;
  p.top = 0;
  p.safe_z = 20;
  return p;
}

// Points of cutting and linking paths.
template <class F>
void for_cut_points(const Pocket3dPath& out, F&& f) {
  std::size_t o = 0;
  for (std::size_t i = 0; i < out.cl.path_sizes.size(); ++i) {
    const std::size_t n = out.cl.path_sizes[i];
    if (out.cl.path_kinds[i] != static_cast<std::uint8_t>(PathKind::kRapid))
      for (std::size_t k = 0; k < n; ++k)
        f(Vec3(out.cl.xyz[3 * (o + k)], out.cl.xyz[3 * (o + k) + 1], out.cl.xyz[3 * (o + k) + 2]),
          o + k);
    o += n;
  }
}

// Consecutive points of cutting and linking paths (the straight moves), sampled every
// `step` mm, skipping the vertical plunge.
template <class F>
void for_move_samples(const Pocket3dPath& out, double step, F&& f) {
  std::size_t o = 0;
  for (std::size_t i = 0; i < out.cl.path_sizes.size(); ++i) {
    const std::size_t n = out.cl.path_sizes[i];
    if (out.cl.path_kinds[i] != static_cast<std::uint8_t>(PathKind::kRapid))
      for (std::size_t k = 0; k + 1 < n; ++k) {
        const Vec3 a(out.cl.xyz[3 * (o + k)], out.cl.xyz[3 * (o + k) + 1],
                     out.cl.xyz[3 * (o + k) + 2]);
        const Vec3 b(out.cl.xyz[3 * (o + k + 1)], out.cl.xyz[3 * (o + k + 1) + 1],
                     out.cl.xyz[3 * (o + k + 1) + 2]);
        if ((b - a).head<2>().norm() < 1e-12) continue;  // plunge
        const int m = std::max(1, static_cast<int>(std::ceil((b - a).norm() / step)));
        for (int j = 0; j <= m; ++j) f(a + (b - a) * (static_cast<double>(j) / m));
      }
    o += n;
  }
}

TEST(Pocket3d, ScallopChordMatchesTheCuspGeometry) {
  // Two ball centres on a circle of radius rho + R (about the curvature centre O), their
  // chord from the formula; the cusp (the balls' lower crossing) must sit at rho + h from O.
  const double r = 6, h = 0.4;
  for (double rho : {20.0, 50.0, 400.0, -30.0, -80.0}) {
    const double chord = scallop_chord(r, h, rho);
    const double a = rho + r;
    const double half = std::asin(chord / (2 * std::abs(a)));
    const double sgn = rho > 0 ? 1 : -1;
    // Centres in the plane of O: angle +-half from the vertical through O.
    const Vec2 c1(std::abs(a) * std::sin(half), sgn * std::abs(a) * std::cos(half));
    const Vec2 c2(-c1.x(), c1.y());
    // Lower crossing of the two circles of radius R: on x = 0, below the centres.
    const double cusp_y = c1.y() - std::sqrt(r * r - c1.x() * c1.x());
    // Distance from O to the cusp minus rho (dome: above the surface by h; bowl: surface at
    // |rho| below O... measured along the radius it is |rho| - |cusp|).
    const double height = rho > 0 ? std::abs(cusp_y) - rho : -rho - std::abs(cusp_y);
    EXPECT_NEAR(height, h, 1e-9) << "rho " << rho;
    (void)c2;
  }
  EXPECT_NEAR(scallop_chord(r, h, std::numeric_limits<double>::infinity()),
              2 * std::sqrt(2 * r * h - h * h), 1e-12);
}

Region rect_pocket(double x0, double y0, double x1, double y1) {
  Region g;
  g.boundary = profile_of(test::rectangle(x0, y0, x1, y1, true));
  return g;
}

TEST(Pocket3d, InclinedPlaneGivesTheAnalyticDrop) {
  const double a = 0.2, b = -0.1, c = -8, r = 3;
  const NurbsSurface s = test::tilted_plane(a, b, c, -5, -5, 75, 55);
  const Pocket3dParams p = params(r, 0.2);
  const Pocket3dPath out = plan_pocket3d({rect_pocket(0, 0, 60, 40)}, s, p);
  // Centre = contact + R n, n = (-a, -b, 1) / |.|: the tip is R (|(a, b, 1)| - 1) above
  // the plane.
  const double lift = r * (std::sqrt(1 + a * a + b * b) - 1);
  std::size_t n = 0;
  for_cut_points(out, [&](const Vec3& q, std::size_t) {
    if (q.z() > p.top + p.clearance - 1e-9) return;  // the plunge's top
    EXPECT_NEAR(q.z(), a * q.x() + b * q.y() + c + lift, 1e-7) << q.transpose();
    ++n;
  });
  EXPECT_GT(n, 40u);
  EXPECT_EQ(out.stats.lifted_points, 0u);  // linear along every move: nothing to raise
  EXPECT_EQ(out.stats.retractions, 0u);
  EXPECT_EQ(out.cc.size(), out.cl.xyz.size());
}

// Distance from q to the polylines of the kCut / kLinkAtDepth paths of `cl` at height z.
double distance_to_paths(const ClChunk& cl, const Vec2& q, double z) {
  double best = 1e300;
  std::size_t o = 0;
  for (std::size_t i = 0; i < cl.path_sizes.size(); ++i) {
    const std::size_t n = cl.path_sizes[i];
    if (cl.path_kinds[i] != static_cast<std::uint8_t>(PathKind::kRapid))
      for (std::size_t k = 0; k + 1 < n; ++k) {
        const double za = cl.xyz[3 * (o + k) + 2], zb = cl.xyz[3 * (o + k + 1) + 2];
        if (std::abs(za - z) > 1e-9 || std::abs(zb - z) > 1e-9) continue;
        const Vec2 a(cl.xyz[3 * (o + k)], cl.xyz[3 * (o + k) + 1]);
        const Vec2 b(cl.xyz[3 * (o + k + 1)], cl.xyz[3 * (o + k + 1) + 1]);
        const Vec2 ab = b - a;
        const double t =
            ab.squaredNorm() > 0 ? std::clamp((q - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0;
        best = std::min(best, (a + t * ab - q).norm());
      }
    o += n;
  }
  return best;
}

TEST(Pocket3d, FlatBottomIsTheFlatPocketPath) {
  const double r = 3, h = 0.2, depth = 5;
  const NurbsSurface s = test::tilted_plane(0, 0, -depth, -5, -5, 75, 55);
  Pocket3dParams p = params(r, h);
  p.eps = 0.002;
  p.half_step_last = false;  // the flat pocket's levels exactly
  const std::vector<Region> pocket = {rect_pocket(0, 0, 60, 40)};
  const Pocket3dPath out = plan_pocket3d(pocket, s, p);
  PocketPathParams f;
  f.tool_radius = r;
  f.stepover = scallop_chord(r, h, std::numeric_limits<double>::infinity());
  f.depth = depth;
  f.chordal_tolerance = 0.001;
  f.safe_z = 20;
  f.helix_radius = 1e-4;
  const PocketPath flat = plan_pocket(pocket, f);
  EXPECT_EQ(out.stats.loops, flat.stats.loops);
  EXPECT_EQ(out.stats.links, flat.stats.links);
  EXPECT_NEAR(out.stats.min_interval, f.stepover, 1e-12);
  EXPECT_NEAR(out.stats.max_interval, f.stepover, 1e-12);
  // Every CL point of the flat pocket's path at the floor lies on this path (same loops,
  // links, order; the flat path's helix entry is a circle of 1e-4 mm around the start, where
  // this path plunges). This path also has the scallop's clean-up curves (uncut regions of
  // the bands eroded by half the step, issue 16), which a flat end mill (eroded by R) does
  // not need: its points off the flat path are allowed only when there are more of those.
  std::size_t n = 0;
  const ClChunk& fc = flat.cl;
  for (std::size_t i = 0; i < fc.point_count(); ++i) {
    if (std::abs(fc.xyz[3 * i + 2] + depth) > 1e-9) continue;
    const Vec2 q(fc.xyz[3 * i], fc.xyz[3 * i + 1]);
    EXPECT_LT(distance_to_paths(out.cl, q, -depth), p.eps + 2e-3) << q.transpose();
    ++n;
  }
  EXPECT_GT(n, 50u);
  std::size_t off_path = 0;
  for_cut_points(out, [&](const Vec3& q, std::size_t) {
    if (std::abs(q.z() + depth) > 1e-9) return;
    off_path += distance_to_paths(flat.cl, q.head<2>(), -depth) > p.eps + 2e-3;
  });
  if (off_path > 0) {
    EXPECT_GT(out.stats.cleanup_curves, flat.stats.cleanup_curves);
  }
}

// A vault (convex) and a trough (concave) cylinder under a disc pocket.
// A cap of the sphere of radius rho about (cx, cy, cz) around its top (sign = +1, a dome) or
// bottom (sign = -1, a bowl), exact: the inverse stereographic map (2u, 2v, 1 - u^2 - v^2) /
// (1 + u^2 + v^2) over [-a, a]^2 is rational of degree 2 in u and in v; its homogeneous
// coordinates are turned into Bernstein form by interpolation at t = 0, 1/2, 1.
NurbsSurface sphere_cap(double cx, double cy, double cz, double rho, double a, double sign) {
  NurbsSurface s;
  s.degree_u = s.degree_v = 2;
  s.nu = s.nv = 3;
  s.knots_u = s.knots_v = {0, 0, 0, 1, 1, 1};
  const double t[3] = {0, 0.5, 1};
  const double inv[3][3] = {{1, 0, 0}, {-0.5, 2, -0.5}, {0, 0, 1}};  // Bernstein^-1 at t
  Eigen::Vector4d f[3][3];  // homogeneous (x w, y w, z w, w) at the 3 x 3 parameters
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const double u = -a + 2 * a * t[i], v = -a + 2 * a * t[j], w = 1 + u * u + v * v;
      f[i][j] = Eigen::Vector4d(rho * 2 * u + cx * w, rho * 2 * v + cy * w,
                                sign * rho * (1 - u * u - v * v) + cz * w, w);
    }
  for (int k = 0; k < 3; ++k)
    for (int l = 0; l < 3; ++l) {
      Eigen::Vector4d b = Eigen::Vector4d::Zero();
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) b += inv[k][i] * inv[l][j] * f[i][j];
      s.ctrl.emplace_back(b.x() / b.w(), b.y() / b.w(), b.z() / b.w());
      s.weights.push_back(b.w());
    }
  return s;
}

// A vault (convex) or trough (concave) cylinder, or a dome or bowl sphere cap, under a
// disc pocket.
void check_curved(double sign, bool sphere) {
  const double r = 3, h = 0.2, rho = 50, cx = 30, cy = 20, cz = sign > 0 ? -60 : 40;
  const NurbsSurface s =
      sphere ? sphere_cap(cx, cy, cz, rho, 0.5, sign) : cylinder(cx, cz, rho, -5, 45, sign);
  Pocket3dParams p = params(r, h);
  const Vec2 centre(30, 20);
  const double wall = 18;
  const Pocket3dPath out = plan_pocket3d({disc_pocket(centre, wall)}, s, p);
  // Plan distance to the axis (cylinder) or centre (sphere).
  const auto plan_d2 = [&](double x, double y) {
    return (x - cx) * (x - cx) + (sphere ? (y - cy) * (y - cy) : 0.0);
  };
  // Ball centre on the surface offset by R: radius rho + R (convex) or rho - R (concave).
  const double rc = sign > 0 ? rho + r : rho - r;
  const auto tip = [&](double x, double y) {
    return cz + sign * std::sqrt(rc * rc - plan_d2(x, y)) - r;
  };
  const auto bottom = [&](double x, double y) {
    return cz + sign * std::sqrt(rho * rho - plan_d2(x, y));
  };
  // CL points: never below the analytic drop, at most delta above it.
  for_cut_points(out, [&](const Vec3& q, std::size_t) {
    if (q.z() > p.top + p.clearance - 1e-9) return;
    EXPECT_GE(q.z(), tip(q.x(), q.y()) - 1e-7) << q.transpose();
    EXPECT_LE(q.z(), tip(q.x(), q.y()) + p.delta + 1e-7) << q.transpose();
  });
  // Moves: the ball (centre R above the tip) never enters the cylinder or the wall.
  double worst = 1e9, worst_wall = -1e9;
  std::vector<Vec3> centres;
  double above = 0;  // largest height of a move over the drop curve: within delta
  for_move_samples(out, 0.02, [&](const Vec3& q) {
    const Vec3 c = q + Vec3(0, 0, r);
    above = std::max(above, q.z() - tip(q.x(), q.y()));
    const double axis = std::sqrt(plan_d2(c.x(), c.y()) + (c.z() - cz) * (c.z() - cz));
    worst = std::min(worst, sign > 0 ? axis - rho - r : rho - r - axis);
    worst_wall = std::max(worst_wall, (c.head<2>() - centre).norm() + r - wall);
    centres.push_back(c);
  });
  EXPECT_GE(worst, -1e-6) << "gouge into the bottom";
  EXPECT_LE(above, p.delta + 1e-9);
  // Plan: chords between points of one loop (concentric circles here) stay within eps of it.
  double plan_dev = 0;
  std::size_t o = 0;
  for (std::size_t i = 0; i < out.cl.path_sizes.size(); ++i) {
    const std::size_t n = out.cl.path_sizes[i];
    if (out.cl.path_kinds[i] == static_cast<std::uint8_t>(PathKind::kCut))
      for (std::size_t k = 0; k + 1 < n; ++k) {
        const Vec2 a(out.cl.xyz[3 * (o + k)], out.cl.xyz[3 * (o + k) + 1]);
        const Vec2 b(out.cl.xyz[3 * (o + k + 1)], out.cl.xyz[3 * (o + k + 1) + 1]);
        const double ra = (a - centre).norm(), rb = (b - centre).norm();
        if (std::abs(ra - rb) > 1e-9 || (a - b).norm() < 1e-9) continue;  // not one circle
        plan_dev = std::max(plan_dev, ra - (0.5 * (a + b) - centre).norm());
      }
    o += n;
  }
  EXPECT_LE(plan_dev, p.eps + 1e-9);
  EXPECT_GT(plan_dev, 0.25 * p.eps);  // the chords do use the tolerance
  EXPECT_LE(worst_wall, 1e-6) << "gouge into the wall";
  // Realised scallop on a grid inside the first level (R from the wall), the centre
  // included: the lowest ball surface above each point minus the bottom there.
  ASSERT_GT(out.stats.levels, 3u);
  // Bucket the sampled centres by plan cell.
  const double cell = 1;
  std::map<std::pair<int, int>, std::vector<Vec3>> grid;
  for (const Vec3& c : centres)
    grid[{static_cast<int>(std::floor(c.x() / cell)), static_cast<int>(std::floor(c.y() / cell))}]
        .push_back(c);
  double max_scallop = 0;
  Vec2 worst_at = Vec2::Zero();
  for (double x = centre.x() - wall; x <= centre.x() + wall; x += 0.25)
    for (double y = centre.y() - wall; y <= centre.y() + wall; y += 0.25) {
      const double d = (Vec2(x, y) - centre).norm();
      if (d > wall - r - 1e-9) continue;
      double left = 1e300;
      for (int i = -4; i <= 4; ++i)
        for (int j = -4; j <= 4; ++j) {
          auto it = grid.find({static_cast<int>(std::floor(x / cell)) + i,
                               static_cast<int>(std::floor(y / cell)) + j});
          if (it == grid.end()) continue;
          for (const Vec3& c : it->second) {
            const double dd = (c.head<2>() - Vec2(x, y)).squaredNorm();
            if (dd < r * r) left = std::min(left, c.z() - std::sqrt(r * r - dd));
          }
        }
      if (left - bottom(x, y) > max_scallop) {
        max_scallop = left - bottom(x, y);
        worst_at = Vec2(x, y);
      }
    }
  EXPECT_LE(max_scallop, h + p.delta + 1e-3) << "at " << worst_at.transpose();
  EXPECT_GT(max_scallop, 0.5 * h);  // the passes are not needlessly close either
  // 1 and 2 threads: the same bytes.
  Pocket3dPath one;
  {
    par::ThreadLimit limit(1);
    one = plan_pocket3d({disc_pocket(centre, wall)}, s, p);
  }
  EXPECT_EQ(one.cl.xyz, out.cl.xyz);
  EXPECT_EQ(one.cl.path_sizes, out.cl.path_sizes);
  ASSERT_EQ(one.cc.size(), out.cc.size());  // NaN != NaN: compare the bytes
  EXPECT_EQ(0, std::memcmp(one.cc.data(), out.cc.data(), out.cc.size() * sizeof(double)));
}

TEST(Pocket3d, VaultCylinderNoGougeAndScallopWithinH) { check_curved(1, false); }
TEST(Pocket3d, TroughCylinderNoGougeAndScallopWithinH) { check_curved(-1, false); }
TEST(Pocket3d, DomeSphereCapNoGougeAndScallopWithinH) { check_curved(1, true); }
TEST(Pocket3d, BowlSphereCapNoGougeAndScallopWithinH) { check_curved(-1, true); }

TEST(Pocket3d, BadSurfacesAndPocketsOffTheSurface) {
  const std::vector<Region> pocket = {rect_pocket(0, 0, 60, 40)};
  const Pocket3dParams p = params(3, 0.2);
  const auto message = [&](const NurbsSurface& s) -> std::string {
    try {
      plan_pocket3d(pocket, s, p);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  };
  NurbsSurface knots = test::tilted_plane(0, 0, -5, -5, -5, 75, 55);
  knots.knots_u.push_back(1);
  EXPECT_NE(message(knots).find("bottom surface"), std::string::npos) << message(knots);
  NurbsSurface weight = test::tilted_plane(0, 0, -5, -5, -5, 75, 55);
  weight.weights[1] = 0;
  EXPECT_NE(message(weight).find("weight"), std::string::npos) << message(weight);
  // A net that doubles back in x: folds over itself in plan.
  NurbsSurface fold;
  fold.degree_u = 2;
  fold.degree_v = 1;
  fold.nu = 3;
  fold.nv = 2;
  for (double x : {-5.0, 90.0, 20.0})
    for (double y : {-5.0, 55.0}) fold.ctrl.emplace_back(x, y, -5);
  fold.weights.assign(6, 1.0);
  fold.knots_u = {0, 0, 0, 1, 1, 1};
  fold.knots_v = {0, 0, 1, 1};
  EXPECT_NE(message(fold).find("height field"), std::string::npos) << message(fold);
  // A surface that does not reach under the whole pocket.
  EXPECT_NE(message(test::tilted_plane(0, 0, -5, 0, 0, 30, 30)).find("outside"), std::string::npos);
  Pocket3dParams bad = p;
  bad.scallop = 0;
  EXPECT_NE(validate(bad).find("scallop"), std::string::npos);
  bad = p;
  bad.eps = -1;
  EXPECT_NE(validate(bad).find("eps"), std::string::npos);
}

}  // namespace
}  // namespace ncpath
