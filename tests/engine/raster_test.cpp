// Raster: every CL point equals brute force (raised to the floor), the layout is the
// documented zig-zag, output bytes do not depend on the thread count, adaptive sampling
// meets its tolerance.
#include "engine/raster.hpp"

#include <gtest/gtest.h>

#include <cstring>

#include "engine/drop_index.hpp"
#include "engine/parallel.hpp"
#include "tests/support/meshes.hpp"

namespace ncpath {
namespace {

struct Collected {
  ClChunk all;
  int chunks = 0;
};

RasterStats run(const TriangleMesh& mesh, const Cutter& c, const RasterParams& p, Collected& out) {
  RunControl control;
  return run_raster(
      mesh, c, p,
      [&](const ClChunk& ch) {
        ++out.chunks;
        out.all.append(ch);
      },
      control);
}

TriangleMesh bumpy() {
  // Smooth bumps plus a sharp ridge and a hole; lies in [0, 50]^2.
  return test::height_field(60, 50, [](double x, double y) {
    double z = 3 * std::sin(x / 6) * std::cos(y / 7) + 4;
    if (std::abs(x - 25) < 1) z += 5;
    if (std::hypot(x - 12, y - 35) < 4) z -= 3;
    return z;
  });
}

TEST(Raster, EveryPointEqualsBruteForce) {
  const TriangleMesh mesh = bumpy();
  const FacetTable table = build_facet_table(mesh);
  for (const Cutter& c : {ball_cutter(6), flat_cutter(4), bull_nose_cutter(6, 1.5)})
    for (ScanDirection dir : {ScanDirection::kX, ScanDirection::kY}) {
      RasterParams p;
      p.direction = dir;
      p.interval = 1.7;
      p.step = 0.45;
      p.margin = 4;
      p.chunk_lines = 5;
      Collected out;
      const RasterStats st = run(mesh, c, p, out);
      ASSERT_GT(out.chunks, 1);
      ASSERT_EQ(out.all.xyz.size(), 3 * (st.cut_points + st.link_points));
      for (std::size_t k = 0; k < out.all.contact.size(); ++k) {
        const double x = out.all.xyz[3 * k], y = out.all.xyz[3 * k + 1];
        const CutterContact bf = drop_brute_force(table, c, x, y);
        const double expect = std::max(bf.tip_z, st.floor_z);
        ASSERT_NEAR(out.all.xyz[3 * k + 2], expect, 1e-9)
            << cutter_type_name(c.type) << " dir " << int(dir) << " at " << x << "," << y;
        ASSERT_EQ(out.all.contact[k] == 0, !(bf.tip_z > st.floor_z));
      }
    }
}

TEST(Raster, ZigZagLayoutAndCounts) {
  const TriangleMesh mesh = bumpy();
  RasterParams p;
  p.interval = 2.5;  // 50 / 2.5 = 20 -> 21 lines
  p.step = 0.5;      // 50 / 0.5 = 100 -> 101 samples
  Collected out;
  const RasterStats st = run(mesh, ball_cutter(5), p, out);
  EXPECT_EQ(st.lines, 21u);
  EXPECT_EQ(st.cut_points, 21u * 101u);
  ASSERT_EQ(out.all.path_sizes.size(), 21u + 20u);  // lines and the links between them
  std::size_t at = 0;
  for (std::size_t k = 0; k < out.all.path_sizes.size(); ++k) {
    const bool cut = k % 2 == 0;
    EXPECT_EQ(out.all.path_kinds[k], cut ? 0 : 1);
    const std::size_t n = out.all.path_sizes[k];
    if (cut) {
      const std::size_t line = k / 2;
      EXPECT_EQ(n, 101u);
      const double x_first = out.all.xyz[3 * at], y = out.all.xyz[3 * at + 1];
      EXPECT_NEAR(y, 2.5 * line, 1e-12);
      EXPECT_NEAR(x_first, line % 2 == 0 ? 0.0 : 50.0, 1e-12);  // odd lines run backwards
    } else {
      // A link starts where the previous line ended and ends where the next one starts.
      EXPECT_EQ(out.all.xyz[3 * at], out.all.xyz[3 * (at - 1)]);
      EXPECT_EQ(out.all.xyz[3 * at + 1], out.all.xyz[3 * (at - 1) + 1]);
      const std::size_t end = at + n - 1;
      EXPECT_EQ(out.all.xyz[3 * end + 1], out.all.xyz[3 * (end + 1) + 1]);
    }
    at += n;
  }
}

TEST(Raster, OneAndManyThreadsGiveIdenticalBytes) {
  const TriangleMesh mesh = test::random_soup(4000, 80, 20, 3, 21);
  RasterParams p;
  p.interval = 0.9;
  p.step = 0.3;
  p.adaptive_tolerance = 0.01;
  p.chunk_lines = 7;
  Collected one, many;
  {
    par::ThreadLimit limit(1);
    run(mesh, bull_nose_cutter(4, 1), p, one);
  }
  {
    par::ThreadLimit limit(4);
    run(mesh, bull_nose_cutter(4, 1), p, many);
  }
  ASSERT_EQ(one.all.xyz.size(), many.all.xyz.size());
  EXPECT_EQ(
      0, std::memcmp(one.all.xyz.data(), many.all.xyz.data(), one.all.xyz.size() * sizeof(double)));
  EXPECT_EQ(one.all.contact, many.all.contact);
  EXPECT_EQ(one.all.path_sizes, many.all.path_sizes);
}

// After adaptive sampling, the CL curve at the middle of every move is within the
// tolerance of the straight move, unless the move is already at the minimum spacing.
TEST(Raster, AdaptiveSamplingMeetsTolerance) {
  const TriangleMesh mesh = bumpy();
  const FacetTable table = build_facet_table(mesh);
  const Cutter c = ball_cutter(4);
  RasterParams p;
  p.interval = 5;
  p.step = 1.0;
  p.adaptive_tolerance = 0.005;
  p.min_step = 0.01;
  Collected out;
  const RasterStats st = run(mesh, c, p, out);
  EXPECT_GT(st.adaptive_points, 100u);
  std::size_t at = 0, checked = 0;
  for (std::size_t k = 0; k < out.all.path_sizes.size(); ++k) {
    const std::size_t n = out.all.path_sizes[k];
    if (out.all.path_kinds[k] == 0)
      for (std::size_t i = at; i + 1 < at + n; ++i) {
        const double* a = &out.all.xyz[3 * i];
        const double* b = &out.all.xyz[3 * (i + 1)];
        if (std::abs(b[0] - a[0]) < 2 * p.min_step) continue;
        const double xm = 0.5 * (a[0] + b[0]), ym = 0.5 * (a[1] + b[1]);
        const double zm = std::max(drop_brute_force(table, c, xm, ym).tip_z, st.floor_z);
        EXPECT_LE(std::abs(zm - 0.5 * (a[2] + b[2])), p.adaptive_tolerance + 1e-9);
        ++checked;
      }
    at += n;
  }
  EXPECT_GT(checked, 1000u);
}

TEST(Raster, NothingToTouchGivesFloorAndKindNone) {
  const TriangleMesh mesh = test::height_field(4, 10, [](double, double) { return 2.0; });
  RasterParams p;
  p.interval = 1;
  p.step = 1;
  p.rect = std::array<double, 4>{30, 30, 35, 35};  // far from the part
  p.floor_z = -4;
  Collected out;
  const RasterStats st = run(mesh, ball_cutter(2), p, out);
  EXPECT_EQ(st.floor_points, out.all.contact.size());
  for (std::size_t k = 0; k < out.all.contact.size(); ++k) {
    EXPECT_EQ(out.all.contact[k], 0);
    EXPECT_EQ(out.all.xyz[3 * k + 2], -4.0);
  }
}

TEST(Raster, BadParametersAreRejectedByName) {
  RasterParams p;
  p.step = 0;
  EXPECT_NE(validate(p).find("step"), std::string::npos);
  p = {};
  p.interval = -1;
  EXPECT_NE(validate(p).find("interval"), std::string::npos);
  p = {};
  p.rect = std::array<double, 4>{1, 1, 0, 2};
  EXPECT_NE(validate(p).find("rect"), std::string::npos);
}

TEST(Raster, CancelStopsTheRun) {
  const TriangleMesh mesh = bumpy();
  RunControl control;
  control.cancel = true;
  EXPECT_THROW(run_raster(
                   mesh, ball_cutter(4), RasterParams{}, [](const ClChunk&) {}, control),
               Cancelled);
}

}  // namespace
}  // namespace ncpath
