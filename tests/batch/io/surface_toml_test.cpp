#include "batch/io/surface_toml.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "batch/io/profile_toml.hpp"
#include "kernels/curves/nurbs.hpp"
#include "kernels/pocket/chain.hpp"
#include "tests/batch/io/dxf_test_util.hpp"

namespace ncpath::io {
namespace {

std::string error_of(const std::string& text) {
  try {
    parse_surface_toml(text, "s.toml");
  } catch (const ReadError& e) {
    return e.what();
  }
  return "(no error)";
}

// Cubic Bernstein polynomials at t: the independent oracle for Bezier patches.
std::array<double, 4> bernstein3(double t) {
  const double s = 1 - t;
  return {s * s * s, 3 * t * s * s, 3 * t * t * s, t * t * t};
}

// The bicubic Bezier patch with 4 x 4 control points net[i][j] (i along u) at (s, t).
Vec3 bezier_patch_point(const std::array<std::array<Vec3, 4>, 4>& net, double s, double t) {
  const auto bu = bernstein3(s), bv = bernstein3(t);
  Vec3 p = Vec3::Zero();
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) p += bu[i] * bv[j] * net[i][j];
  return p;
}

// "ctrl = [...]" on one line: nx * ny points, x = 10 i, y = 10 j, z = z(i, j), row-major by i.
std::string ctrl_line(int nx, int ny, const std::function<double(int, int)>& z) {
  std::ostringstream s;
  s << "ctrl = [";
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j)
      s << (i || j ? ", " : "") << "[" << 10 * i << ", " << 10 * j << ", " << z(i, j) << "]";
  s << "]";
  return s.str();
}

// A valid bilinear surface, one key per line (lines 1-6).
constexpr const char* kBilinear =
    "[nurbs_surface]\n"
    "degree_u = 1\n"
    "degree_v = 1\n"
    "nu = 2\n"
    "nv = 2\n"
    "ctrl = [[0, 0, 0], [0, 10, 0], [10, 0, 0], [10, 10, 1]]\n";

// kBilinear with the line "key = ..." replaced by `line` (removed when empty), or `line`
// appended (line 7) when there is no such key.
std::string edit(const std::string& key, const std::string& line) {
  std::istringstream in(kBilinear);
  std::string out, l;
  bool found = false;
  while (std::getline(in, l)) {
    if (l.starts_with(key + " =")) {
      found = true;
      if (!line.empty()) out += line + "\n";
    } else {
      out += l + "\n";
    }
  }
  return found ? out : out + line + "\n";
}

TEST(SurfaceToml, NativeRationalWithKnots) {
  const NurbsSurface s = parse_surface_toml(R"(units = "mm"
[nurbs_surface]
degree_u = 1
degree_v = 1
nu = 2
nv = 2
ctrl = [[0, 0, 1], [0, 10, 2], [20, 0, 3], [20, 10, 5]]
weights = [1, 2, 3, 4]
knots_u = [0, 0, 2, 2]
knots_v = [-1, -1, 1, 1]
)",
                                            "s.toml");
  EXPECT_EQ(s.degree_u, 1);
  EXPECT_EQ(s.degree_v, 1);
  EXPECT_EQ(s.nu, 2);
  EXPECT_EQ(s.nv, 2);
  ASSERT_EQ(s.ctrl.size(), 4u);
  EXPECT_EQ(s.ctrl[1], Vec3(0, 10, 2));  // row-major by u: (i, j) = (0, 1)
  EXPECT_EQ(s.ctrl[2], Vec3(20, 0, 3));
  EXPECT_EQ(s.weights, (std::vector<double>{1, 2, 3, 4}));
  EXPECT_EQ(s.knots_u, (std::vector<double>{0, 0, 2, 2}));
  EXPECT_EQ(s.knots_v, (std::vector<double>{-1, -1, 1, 1}));
  const SurfaceDomain d = domain(s);
  EXPECT_EQ(d.u1, 2);
  EXPECT_EQ(d.v0, -1);
  // Rational bilinear oracle at u = 0.6 (a = 0.3 of [0, 2]), v = 0.2 (b = 0.6 of [-1, 1]).
  const double a = 0.3, b = 0.6;
  const double n[4] = {(1 - a) * (1 - b), (1 - a) * b, a * (1 - b), a * b};
  Vec3 num = Vec3::Zero();
  double den = 0;
  for (int k = 0; k < 4; ++k) num += n[k] * s.weights[k] * s.ctrl[k], den += n[k] * s.weights[k];
  EXPECT_LT((surface_point(s, 0.6, 0.2) - num / den).norm(), 1e-12);
}

TEST(SurfaceToml, NativeDefaults) {
  const NurbsSurface s = parse_surface_toml(
      "[nurbs_surface]\ndegree_u = 3\ndegree_v = 2\nnu = 5\nnv = 3\n" +
          ctrl_line(5, 3, [](int i, int j) { return 0.5 * i - 0.25 * j * j; }) + "\n",
      "s.toml");
  EXPECT_EQ(s.knots_u, (std::vector<double>{0, 0, 0, 0, 0.5, 1, 1, 1, 1}));
  EXPECT_EQ(s.knots_v, (std::vector<double>{0, 0, 0, 1, 1, 1}));
  EXPECT_EQ(s.weights, std::vector<double>(15, 1.0));
  ASSERT_EQ(s.ctrl.size(), 15u);
  EXPECT_EQ(s.ctrl[4 * 3 + 2], Vec3(40, 20, 2 - 1));  // (i, j) = (4, 2)
}

TEST(SurfaceToml, BezierGridMatchesBernsteinFormula) {
  // 2 x 1 patches: 7 x 4 control points, x = 10 i, y = 10 j, an uneven z.
  auto z = [](int i, int j) { return 0.25 * i * i - 0.5 * j + ((i * j) % 3); };
  const NurbsSurface s = parse_surface_toml(
      "[bezier_grid]\npatches_u = 2\npatches_v = 1\n" + ctrl_line(7, 4, z) + "\n", "s.toml");
  EXPECT_EQ(s.degree_u, 3);
  EXPECT_EQ(s.degree_v, 3);
  EXPECT_EQ(s.nu, 7);
  EXPECT_EQ(s.nv, 4);
  EXPECT_EQ(s.knots_u, (std::vector<double>{0, 0, 0, 0, 1, 1, 1, 2, 2, 2, 2}));
  EXPECT_EQ(s.knots_v, (std::vector<double>{0, 0, 0, 0, 1, 1, 1, 1}));
  for (const auto& [u, v] : {std::pair{0.4, 0.7}, std::pair{1.3, 0.6}, std::pair{2.0, 0.0}}) {
    const int patch = std::min(static_cast<int>(u), 1);
    std::array<std::array<Vec3, 4>, 4> net;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) {
        const int gi = 3 * patch + i;
        net[i][j] = Vec3(10 * gi, 10 * j, z(gi, j));
      }
    const Vec3 want = bezier_patch_point(net, u - patch, v);
    EXPECT_LT((surface_point(s, u, v) - want).norm(), 1e-12) << "u " << u << " v " << v;
  }
}

TEST(SurfaceToml, ReadsFile) {
  const auto path = test::write_temp("bottom.toml", kBilinear);
  EXPECT_EQ(read_surface_toml(path).ctrl.size(), 4u);
  try {
    read_surface_toml(path.parent_path() / "no_such_surface.toml");
    ADD_FAILURE() << "expected a ReadError";
  } catch (const ReadError& e) {
    EXPECT_EQ(e.problem().rfind("cannot open", 0), 0u) << e.problem();  // and why
    EXPECT_EQ(e.location(), "");
  }
}

TEST(SurfaceToml, StructureErrors) {
  EXPECT_EQ(error_of("surface = 1\n"),
            "s.toml: line 1: surface: unknown key (expected [nurbs_surface], [bezier_grid] or "
            "units)");
  EXPECT_EQ(error_of(std::string("units = \"inch\"\n") + kBilinear),
            "s.toml: line 1: units: only \"mm\" is supported");
  EXPECT_EQ(error_of("units = \"mm\"\n"),
            "s.toml: no surface (add [nurbs_surface] or [bezier_grid])");
  EXPECT_EQ(error_of(std::string(kBilinear) + "[bezier_grid]\npatches_u = 1\n"),
            "s.toml: line 7: bezier_grid: give exactly one of [nurbs_surface] and [bezier_grid]");
  EXPECT_EQ(error_of("[[nurbs_surface]]\ndegree_u = 1\n"),
            "s.toml: line 1: nurbs_surface: must be a table: write [nurbs_surface]");
  const std::string syntax = error_of("[nurbs_surface]\nctrl = [[0, 0, 0],\n");
  EXPECT_EQ(syntax.find("s.toml: line "), 0u) << syntax;
  EXPECT_NE(syntax.find("TOML syntax"), std::string::npos) << syntax;
}

TEST(SurfaceToml, NativeKeyAndTypeErrors) {
  EXPECT_EQ(error_of(kBilinear), "(no error)");
  EXPECT_EQ(error_of(edit("nu", "")), "s.toml: line 1: nurbs_surface: missing key 'nu'");
  EXPECT_EQ(error_of(edit("ctrl", "")), "s.toml: line 1: nurbs_surface: missing key 'ctrl'");
  EXPECT_EQ(error_of(edit("knot_u", "knot_u = [0, 0, 1, 1]")),
            "s.toml: line 7: nurbs_surface: unknown key 'knot_u' (expected degree_u, degree_v, "
            "nu, nv, ctrl, weights, knots_u, knots_v)");
  EXPECT_EQ(error_of(edit("degree_u", "degree_u = 2.5")),
            "s.toml: line 2: nurbs_surface: 'degree_u' must be an integer from 1 to 30");
  EXPECT_EQ(error_of(edit("degree_v", "degree_v = \"1\"")),
            "s.toml: line 3: nurbs_surface: 'degree_v' must be an integer from 1 to 30");
  EXPECT_EQ(error_of(edit("nv", "nv = 0")),
            "s.toml: line 5: nurbs_surface: 'nv' must be an integer from 1 to 1000000");
  EXPECT_EQ(error_of(edit("degree_u", "degree_u = 2")),
            "s.toml: line 4: nurbs_surface: nu = 2 is too few control points for degree_u = 2 "
            "(needs at least 3)");
  EXPECT_EQ(error_of(edit("ctrl", "ctrl = 5")),
            "s.toml: line 6: nurbs_surface: 'ctrl' must be an array of [x, y, z]");
  // ctrl not triples, or not finite numbers: the line of the point itself.
  EXPECT_EQ(error_of(edit("ctrl",
                          "ctrl = [\n  [0, 0, 0],\n  [0, 10, 0],\n  [10, 0],\n  [10, 10, "
                          "1],\n]")),
            "s.toml: line 9: nurbs_surface: 'ctrl' point 2 must be [x, y, z] (finite numbers)");
  EXPECT_EQ(error_of(edit("ctrl", "ctrl = [[0, 0, 0], [0, 10, 0, 1], [10, 0, 0], [10, 10, 1]]")),
            "s.toml: line 6: nurbs_surface: 'ctrl' point 1 must be [x, y, z] (finite numbers)");
  EXPECT_EQ(error_of(edit("ctrl", "ctrl = [[0, 0, 0], [0, 10, \"a\"], [10, 0, 0], [10, 10, 1]]")),
            "s.toml: line 6: nurbs_surface: 'ctrl' point 1 must be [x, y, z] (finite numbers)");
  EXPECT_EQ(error_of(edit("ctrl", "ctrl = [[0, 0, 0], [0, 10, 0], [10, 0, nan], [10, 10, 1]]")),
            "s.toml: line 6: nurbs_surface: 'ctrl' point 2 must be [x, y, z] (finite numbers)");
  EXPECT_EQ(error_of(edit("weights", "weights = [1, 1, \"x\", 1]")),
            "s.toml: line 7: nurbs_surface: 'weights' must be an array of finite numbers");
  EXPECT_EQ(error_of(edit("knots_v", "knots_v = [0, 0, inf, 1]")),
            "s.toml: line 7: nurbs_surface: 'knots_v' must be an array of finite numbers");
}

TEST(SurfaceToml, CountMismatches) {
  EXPECT_EQ(error_of(edit("ctrl", "ctrl = [[0, 0, 0], [0, 10, 0], [10, 0, 0]]")),
            "s.toml: line 6: nurbs_surface: ctrl has 3 points, nu * nv = 4");
  EXPECT_EQ(error_of(edit("weights", "weights = [1, 1, 1]")),
            "s.toml: line 7: nurbs_surface: weights has 3 values, nu * nv = 4");
  EXPECT_EQ(error_of(edit("knots_u", "knots_u = [0, 0, 1]")),
            "s.toml: line 7: nurbs_surface: knots_u has 3 knots, nu + degree_u + 1 = 4");
  EXPECT_EQ(error_of(edit("knots_v", "knots_v = [0, 0, 0, 1, 1, 1]")),
            "s.toml: line 7: nurbs_surface: knots_v has 6 knots, nv + degree_v + 1 = 4");
  EXPECT_EQ(error_of("[bezier_grid]\npatches_u = 1\npatches_v = 1\n" +
                     ctrl_line(5, 3, [](int, int) { return 0.0; }) + "\n"),
            "s.toml: line 4: bezier_grid: ctrl has 15 points, (3 * patches_u + 1) * (3 * "
            "patches_v + 1) = 16");
  EXPECT_EQ(error_of("[bezier_grid]\npatches_u = 1\npatches_v = 0\nctrl = []\n"),
            "s.toml: line 3: bezier_grid: 'patches_v' must be an integer from 1 to 1000000");
  EXPECT_EQ(error_of("[bezier_grid]\npatches_u = 1\npatches_v = 1\nweights = []\n"),
            "s.toml: line 4: bezier_grid: unknown key 'weights' (expected patches_u, patches_v, "
            "ctrl)");
  EXPECT_EQ(error_of("[bezier_grid]\npatches_v = 1\nctrl = []\n"),
            "s.toml: line 1: bezier_grid: missing key 'patches_u'");
}

// Whole-surface checks come from the kernel (validate, check_height_field): the reader adds
// the file, the table's line and its name.
TEST(SurfaceToml, KernelChecksWrapped) {
  auto expect = [](const std::string& text, const std::string& part) {
    const std::string e = error_of(text);
    EXPECT_EQ(e.find("s.toml: line 1: nurbs_surface: "), 0u) << e;
    EXPECT_NE(e.find(part), std::string::npos) << "lacks \"" << part << "\": " << e;
  };
  expect(edit("weights", "weights = [1, 0, 1, 1]"), "weights[1] (i = 0, j = 1) is not > 0");
  expect(edit("weights", "weights = [1, 1, -2, 1]"), "weights[2] (i = 1, j = 0) is not > 0");
  expect(edit("knots_u", "knots_u = [0, 0, 1, 0.5]"), "knots_u decrease at index 3");
  expect(edit("knots_v", "knots_v = [0, 0.5, 1, 1]"), "knots_v is not clamped");
  expect(edit("knots_v", "knots_v = [1, 1, 1, 1]"), "knots_v range is empty");
  // An S in x along u (x control values 0, 30, -20, 10): the plan map folds over itself.
  const std::string fold =
      "[nurbs_surface]\ndegree_u = 3\ndegree_v = 1\nnu = 4\nnv = 2\n"
      "ctrl = [[0, 0, 0], [0, 10, 0], [30, 0, 1], [30, 10, 1], [-20, 0, 2], [-20, 10, 2], "
      "[10, 0, 3], [10, 10, 3]]\n";
  expect(fold, "not a height field: ");
  expect(fold, "folds over itself");
  // x = 10 (2u - 1)^3 (control values -10, 10, -10, 10): x'(1/2) = 0, a vertical tangent plane.
  expect(
      "[nurbs_surface]\ndegree_u = 3\ndegree_v = 1\nnu = 4\nnv = 2\n"
      "ctrl = [[-10, 0, 0], [-10, 10, 0], [10, 0, 1], [10, 10, 1], [-10, 0, 2], [-10, 10, 2], "
      "[10, 0, 3], [10, 10, 3]]\n",
      "not a height field: the surface has a vertical tangent plane");
  // The same net with x increasing (0, 10, 20, 30) is fine: the fold, not the data, is refused.
  EXPECT_EQ(error_of("[nurbs_surface]\ndegree_u = 3\ndegree_v = 1\nnu = 4\nnv = 2\n"
                     "ctrl = [[0, 0, 0], [0, 10, 0], [10, 0, 1], [10, 10, 1], [20, 0, 2], "
                     "[20, 10, 2], [30, 0, 3], [30, 10, 3]]\n"),
            "(no error)");
}

// The seed-000 case study inputs (datasets/pockets/): they read, have the advertised make-up,
// and the bottom is a convex dome under the whole pocket.
TEST(SurfaceToml, Seed000Dataset) {
  const std::filesystem::path dir = std::filesystem::path(NCPATH_SOURCE_DIR) / "datasets/pockets";
  const ProfileSoup soup = read_profile_toml(dir / "seed000.toml");
  const ChainResult chained = chain_and_nest(soup.curves, soup.nurbs, soup.sources);
  ASSERT_EQ(chained.error, "");
  ASSERT_EQ(chained.regions.size(), 1u);
  const Region& region = chained.regions[0];
  ASSERT_EQ(region.boundary.curves.size(), 12u);
  ASSERT_EQ(region.islands.size(), 1u);
  ASSERT_EQ(region.islands[0].curves.size(), 8u);

  // Kinds, plan box and area (lines and arcs exactly, NURBS by fine polylines).
  struct Stats {
    int lines = 0, arcs = 0, nurbs = 0, rational = 0;
    double area = 0;
    Vec2 lo = Vec2::Constant(1e9), hi = Vec2::Constant(-1e9);
  };
  auto stats = [](const Profile& p) {
    Stats st;
    double area2 = 0;
    for (const ProfileCurve& c : p.curves) {
      std::vector<Vec2> pts;
      if (c.nurbs >= 0) {
        const Nurbs2& n = p.nurbs[c.nurbs];
        ++st.nurbs;
        st.rational +=
            std::any_of(n.weights.begin(), n.weights.end(), [](double w) { return w != 1.0; });
        pts = nurbs_polyline(n, 1e-5);
        for (std::size_t k = 0; k + 1 < pts.size(); ++k)
          area2 += pts[k].x() * pts[k + 1].y() - pts[k + 1].x() * pts[k].y();
      } else {
        (c.seg.kind == SegKind::kLine ? st.lines : st.arcs) += 1;
        area2 += area2_contribution(c.seg);
        Vec2 lo, hi;
        bounds(c.seg, lo, hi);
        pts = {lo, hi};
      }
      for (const Vec2& q : pts) st.lo = st.lo.cwiseMin(q), st.hi = st.hi.cwiseMax(q);
    }
    st.area = std::abs(area2) / 2;
    return st;
  };
  const Stats b = stats(region.boundary), i = stats(region.islands[0]);
  EXPECT_EQ(b.lines, 5);
  EXPECT_EQ(b.arcs, 4);
  EXPECT_EQ(b.nurbs, 3);
  EXPECT_EQ(b.rational, 1);
  EXPECT_EQ(i.lines, 3);
  EXPECT_EQ(i.arcs, 4);
  EXPECT_EQ(i.nurbs, 1);
  EXPECT_LT((b.lo - Vec2(0, 0)).norm(), 1e-6);
  EXPECT_LT((b.hi - Vec2(200, 200)).norm(), 1e-6);
  EXPECT_LT((i.lo - Vec2(95, 60)).norm(), 1e-6);
  EXPECT_LT((i.hi - Vec2(150, 110)).norm(), 1e-6);
  EXPECT_NEAR(b.area, 33497.5, 0.1);  // as stated in the file's header
  EXPECT_NEAR(i.area, 2433.1, 0.1);

  // Bottom: one bicubic patch over [-20, 220]^2; independent Bernstein evaluation.
  const NurbsSurface s = read_surface_toml(dir / "seed000_bottom.toml");
  ASSERT_EQ(s.nu, 4);
  ASSERT_EQ(s.nv, 4);
  std::array<std::array<Vec3, 4>, 4> net;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) net[r][c] = s.ctrl[r * 4 + c];
  EXPECT_LT((bezier_patch_point(net, 0.5, 0.5) - Vec3(100, 100, -10)).norm(), 1e-12);
  EXPECT_LT((surface_point(s, 0.3, 0.8) - bezier_patch_point(net, 0.3, 0.8)).norm(), 1e-9);
  // The xy net is even, so (x, y) -> (u, v) is linear; the pocket's box lies 20 mm inside.
  auto z_at = [&](double x, double y) {
    return bezier_patch_point(net, (x + 20) / 240, (y + 20) / 240).z();
  };
  EXPECT_NEAR(z_at(0, 100), -30.486, 1e-3);
  EXPECT_NEAR(z_at(100, 0), -28.75, 1e-9);
  // Convex seen from above (z concave) along x, y and both diagonals, top below z = 0.
  const double h = 2.5;
  double zmax = -1e9;
  for (double x = 0; x <= 200; x += 5)
    for (double y = 0; y <= 200; y += 5) {
      const double z = z_at(x, y);
      zmax = std::max(zmax, z);
      for (const Vec2& d : {Vec2(h, 0), Vec2(0, h), Vec2(h, h), Vec2(h, -h)})
        EXPECT_LT(z_at(x + d.x(), y + d.y()) - 2 * z + z_at(x - d.x(), y - d.y()), 0)
            << x << ", " << y;
    }
  EXPECT_NEAR(zmax, -10, 1e-9);
}

}  // namespace
}  // namespace ncpath::io
