// Pencil-cut (engine/pencil.hpp) on two cylinders meeting: solid cylinders of radius Rc with
// axes along x and y at z = 0, set in a floor at z = 0, over |x|, |y| <= L; the part's top is
// z = max(h(x), h(y)), h(s) = sqrt(Rc^2 - s^2) for |s| < Rc, else 0.
//
// Analytic answer for a ball of radius R. The ball centre surface is the union of the offset
// cylinders of radius rho = Rc + R and the offset floor z = R. Its creases are
//   - the four half-diagonals |x| = |y| = s, ball centre zc = sqrt(rho^2 - s^2), contacts
//     b1 = (0, y, zc) / rho and b2 = (x, 0, zc) / rho, so cos(beta) = 1 - s^2 / rho^2; they
//     run from s = 0 down to the offset floor at s = c_f = sqrt(rho^2 - R^2) (tip z 0);
//   - the eight cylinder-floor lines |y| = c_f, |x| from c_f to L (and x <-> y), tip z 0,
//     cos(beta) = R / rho (the floor is part of the mesh here, so these are creases too).
// With the threshold min_angle, the diagonals carry pencil points for s >= rho
// sqrt(1 - cos(min_angle)) only.
//
// The mesh is exact along the axes: each cross-section is the inscribed polygon with kSides
// sides over the half circle, and the grid lines (the same abscissae in x and y) sit at its
// vertices, so each facet lies in one prism face, diagonal grid points lie on |x| = |y|, and
// cells on the diagonals are split along them. The mesh is mirror-symmetric in x = y and
// x = -y (exactly, in floating point), so its creases lie exactly on the diagonals; faceting
// only moves them in height, by at most the sagitta scaled by rho / zc.
#include "engine/pencil.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include "tests/engine/mesh_test_support.hpp"

namespace ncpath {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kRc = 10;  // mm, cylinder radius
constexpr double kL = 25;   // mm, half extent of the part in x and y
// Polygon sides over the half circle (2 degrees each; sagitta 1.5 um). 180 sides quadruple
// the facets and take the run from 2.5 s to 9 s, mostly in the engine's drop-cutter check.
constexpr int kSides = 90;
constexpr double kR = 3;  // mm, ball radius
constexpr double kRho = kRc + kR;
// Checked range of the diagonal arms: |x|, |y| <= Rc, the tip at least
// sqrt(rho^2 - Rc^2) - R = 5.3 mm above the floor (the arms reach the floor at c_f = 12.6).
constexpr double kCheck = kRc;

// Side angle of the polygon (rad), and its sagitta: how far inside the circle it lies (mm).
const double kSide = kPi / kSides;
const double kSagitta = kRc * (1 - std::cos(kSide / 2));
const double kFloorCrease = std::sqrt(kRho * kRho - kR * kR);  // c_f, mm

// The two prisms' union over the grid described in the file comment. Abscissae: the polygon
// vertices Rc cos(k pi / kSides), plus floor lines out to L; built for x >= 0 and mirrored so
// that the set is exactly symmetric.
TriangleMesh two_cylinders() {
  std::vector<double> pos, height;  // x >= 0, ascending
  for (int k = kSides / 2; k >= 0; --k) {
    const double phi = k * kSide;
    pos.push_back(k == kSides / 2 ? 0.0 : kRc * std::cos(phi));
    height.push_back(k == 0 ? 0.0 : kRc * std::sin(phi));
  }
  for (int k = 1; k <= 6; ++k) {
    pos.push_back(kRc + (kL - kRc) * k / 6);
    height.push_back(0);
  }
  std::vector<double> a, h;
  for (std::size_t i = pos.size(); i-- > 1;) {
    a.push_back(-pos[i]);
    h.push_back(height[i]);
  }
  a.insert(a.end(), pos.begin(), pos.end());
  h.insert(h.end(), height.begin(), height.end());

  const std::uint32_t n = std::uint32_t(a.size());
  TriangleMesh m;
  for (std::uint32_t j = 0; j < n; ++j)
    for (std::uint32_t i = 0; i < n; ++i) m.vertices.emplace_back(a[i], a[j], std::max(h[i], h[j]));
  auto id = [n](std::uint32_t i, std::uint32_t j) { return j * n + i; };
  for (std::uint32_t j = 0; j + 1 < n; ++j)
    for (std::uint32_t i = 0; i + 1 < n; ++i) {
      // Split along the direction of the nearer crease line: x = y where the cell's centre
      // has x y > 0 (the cells on the diagonal are split on it), else x = -y.
      if ((a[i] + a[i + 1]) * (a[j] + a[j + 1]) > 0) {
        m.facets.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
        m.facets.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
      } else {
        m.facets.push_back({id(i, j), id(i + 1, j), id(i, j + 1)});
        m.facets.push_back({id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
      }
    }
  return m;
}

// Tip height on a diagonal arm at |x| = |y| = s for an offset radius r: rho for the true
// cylinders; rho - sagitta bounds the faceted part's from below (its polygon contains the
// circle of radius Rc - sagitta).
double arm_tip_z(double s, double r) { return std::sqrt(std::max(0.0, r * r - s * s)) - kR; }

// The smallest s at which an arm point can have a measured angle >= min_angle (rad): each
// measured contact vector is a facet normal (or points away from a polygon vertex) and so lies
// within half a side angle of the true one, the angle within a side angle; and on the faceted
// crease the centre's distance r from the axes is at least rho - sagitta, s = r sqrt(1 - cos).
double arm_start(double min_angle) {
  return (kRho - kSagitta) * std::sqrt(1 - std::cos(min_angle - kSide)) - 1e-6;
}

// 3-D distance from a tool-tip point to the analytic creases (arms from s0 to c_f, floor
// lines), arms sampled every 1e-4 mm.
double crease_distance(const Vec3& q, double s0) {
  const double ax = std::abs(q.x()), ay = std::abs(q.y());
  double d = INFINITY;
  const int n = int((kFloorCrease - s0) / 1e-4);
  for (int k = 0; k <= n; ++k) {
    const double s = s0 + (kFloorCrease - s0) * k / n;
    d = std::min(d, (Vec3(ax, ay, q.z()) - Vec3(s, s, arm_tip_z(s, kRho))).norm());
  }
  for (const Vec2& l : {Vec2(ax, ay), Vec2(ay, ax)})  // floor: |second| = c_f, |first| >= c_f
    d = std::min(d, Vec3(std::max(0.0, kFloorCrease - l.x()), l.y() - kFloorCrease, q.z()).norm());
  return d;
}

// Which of the true contact vectors at ball centre c a measured one is: 0 the cylinder along
// x, 1 the one along y, 2 the floor; -1 when none is within half a side angle (+ 1e-9 rad).
int analytic_contact(const Vec3& c, const Vec3& b, Vec3& truth) {
  const Vec3 cand[3] = {Vec3(0, c.y(), c.z()).normalized(), Vec3(c.x(), 0, c.z()).normalized(),
                        Vec3(0, 0, 1)};
  for (int k = 0; k < 3; ++k)
    if (std::acos(std::clamp(b.normalized().dot(cand[k]), -1.0, 1.0)) <= kSide / 2 + 1e-9) {
      truth = cand[k];
      return k;
    }
  return -1;
}

// Assertion on every pencil point (angle >= min_angle): both contact vectors are the true
// ones within half a side angle, on two different surfaces; the angle is the true angle at
// that centre within a side angle; a point on an arm (both cylinders) lies at s >= arm_start.
void check_pencil_points(const PencilResult& r, double min_angle) {
  for (const PencilPoint& pt : r.points) {
    const Vec3 c = pt.position + Vec3(0, 0, kR);
    Vec3 t1, t2;
    const int k1 = analytic_contact(c, pt.b1, t1), k2 = analytic_contact(c, pt.b2, t2);
    ASSERT_TRUE(k1 >= 0 && k2 >= 0 && k1 != k2)
        << "contacts " << pt.b1.transpose() << " / " << pt.b2.transpose() << " at "
        << pt.position.transpose();
    const double beta = std::acos(std::clamp(t1.dot(t2), -1.0, 1.0));
    EXPECT_NEAR(pt.angle, beta, kSide + 1e-9) << "at " << pt.position.transpose();
    EXPECT_GE(pt.angle, min_angle);
    if (k1 != 2 && k2 != 2) {
      EXPECT_GE(0.5 * (std::abs(pt.position.x()) + std::abs(pt.position.y())), arm_start(min_angle))
          << "pencil point below the threshold radius at " << pt.position.transpose();
    }
  }
}

PencilParams params(double min_angle_deg) {
  PencilParams p;
  p.interval = 0.5;
  p.step_down = 0;  // every crease here is a graph over x or y: the drive planes cross it
  p.min_angle_deg = min_angle_deg;
  p.tolerance = 0.01;
  return p;
}

TEST(PencilCylinders, FourDiagonalArmsOnTheAnalyticCrease) {
  const TriangleMesh mesh = two_cylinders();
  const PencilParams p = params(20);
  const double min_angle = p.min_angle_deg * kPi / 180;
  RunControl control;
  const PencilResult r = run_pencil(mesh, ball_cutter(2 * kR), p, control);
  ASSERT_FALSE(r.paths.empty());
  // 1. Path points on the arms (|x|, |y| <= kCheck):
  //    - on the diagonal within 1e-6 mm: the faceted crease is exactly on it (symmetry), the
  //      refined points are exact crease points (Newton to 1e-10 mm) and lifts are vertical;
  //    - tip z between the faceted crease's lower bound (inscribed circle, rho - sagitta:
  //      at most sagitta * rho / zc = 0.0024 mm below the true crease here) and the true
  //      crease + kLift: refinement leaves every chord within the tolerance of the crease
  //      (perpendicular to the chord, in the crease's vertical plane), which below the
  //      concave-down crease is a vertical dip of at most tolerance / cos(slope), and a lift
  //      raises a chord's ends by its dip; the slope is largest at the outer end of the last
  //      chord, s <= kCheck + interval (44 degrees: kLift = 1.39 tolerance);
  //    - s past the threshold radius (arm_start).
  //    Every other path point (nearer the floor) within kFar of the analytic creases (3-D):
  //    the same dip bound with the arms' slope at the floor, 71 degrees (3.07 tolerance), plus
  //    the faceting's vertical offset, at most sagitta * rho / R there.
  auto slope = [](double s) { return std::atan(s / (std::sqrt(2.0) * (arm_tip_z(s, kRho) + kR))); };
  const double kXy = 1e-6;
  const double kLift = p.tolerance / std::cos(slope(kCheck + p.interval));
  const double kFar = p.tolerance / std::cos(slope(kFloorCrease)) + kSagitta * kRho / kR;
  const double s_start = arm_start(min_angle);
  const double s_thr = kRho * std::sqrt(1 - std::cos(min_angle));  // 3.19 mm
  // Per arm (quadrant of the signs of x and y): the s intervals of its chords.
  std::vector<std::pair<double, double>> covered[4];
  auto quadrant = [](const Vec3& q) { return (q.x() > 0 ? 1 : 0) + (q.y() > 0 ? 2 : 0); };
  for (const auto& path : r.paths)
    for (std::size_t i = 0; i < path.size(); ++i) {
      const Vec3& q = path[i];
      const double ax = std::abs(q.x()), ay = std::abs(q.y()), s = 0.5 * (ax + ay);
      if (std::max(ax, ay) <= kCheck) {
        EXPECT_LE(std::abs(ax - ay), kXy) << "off the diagonal: " << q.transpose();
        EXPECT_GE(q.z(), arm_tip_z(s, kRho - kSagitta) - 1e-6) << "below: " << q.transpose();
        EXPECT_LE(q.z(), arm_tip_z(s, kRho) + kLift) << "above: " << q.transpose();
        EXPECT_GE(s, s_start) << "below the threshold radius: " << q.transpose();
      } else {
        EXPECT_LE(crease_distance(q, s_start), kFar) << "off the creases: " << q.transpose();
      }
      if (i == 0) continue;
      const Vec3& o = path[i - 1];
      // Chords along an arm (loosely: 2. is about finding the arms, 1. about precision).
      if (quadrant(o) != quadrant(q) || std::abs(std::abs(o.x()) - std::abs(o.y())) > 0.1 ||
          std::abs(ax - ay) > 0.1)
        continue;
      const double so = 0.5 * (std::abs(o.x()) + std::abs(o.y()));
      covered[quadrant(q)].emplace_back(std::min(so, s), std::max(so, s));
    }

  // 2. Each arm traced over most of [s_thr, kCheck] (the first drive plane past s_thr is at
  //    most an interval away, the crease end is found between planes).
  for (int a = 0; a < 4; ++a) {
    auto& iv = covered[a];
    std::sort(iv.begin(), iv.end());
    double len = 0, reach = s_thr;
    for (const auto& [lo, hi] : iv) {
      const double l = std::max(lo, reach), h = std::min(hi, kCheck);
      if (h > l) len += h - l;
      reach = std::max(reach, hi);
    }
    EXPECT_GE(len, 0.8 * (kCheck - s_thr))
        << "arm " << a << " (x " << (a & 1 ? "+" : "-") << ", y " << (a & 2 ? "+" : "-") << ")";
  }

  // 3. Pencil points: true contacts and angle, none before the threshold radius.
  check_pencil_points(r, min_angle);
  // 4. No gouge.
  test_meshes::expect_no_gouge(mesh, r.paths, kR);
}

TEST(PencilCylinders, NoArmAboveItsLargestAngle) {
  // 5. Over |x|, |y| <= kCheck the arms' angle is at most acos(1 - kCheck^2 / rho^2) = 65.9
  // degrees, below 70 by more than the faceting (a side angle, 2 degrees): no pencil point,
  // no path there. Beyond, the arms reach 86.9 degrees at the floor (70 from s = 10.5) and
  // the cylinder-floor lines have acos(R / rho) = 76.7: those are still found.
  const TriangleMesh mesh = two_cylinders();
  const PencilParams p = params(70);
  const double min_angle = p.min_angle_deg * kPi / 180;
  const double beta_max = std::acos(1 - kCheck * kCheck / (kRho * kRho));
  ASSERT_LT(beta_max + kSide, min_angle);
  RunControl control;
  const PencilResult r = run_pencil(mesh, ball_cutter(2 * kR), p, control);
  EXPECT_FALSE(r.paths.empty());  // the threshold is not above everything
  for (const auto& path : r.paths)
    for (const Vec3& q : path)
      EXPECT_GT(std::max(std::abs(q.x()), std::abs(q.y())), kCheck) << q.transpose();
  for (const PencilPoint& pt : r.points)
    EXPECT_GT(std::max(std::abs(pt.position.x()), std::abs(pt.position.y())), kCheck)
        << pt.position.transpose();
  check_pencil_points(r, min_angle);
}

}  // namespace
}  // namespace ncpath
