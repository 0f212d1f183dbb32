// Real scanned/CAD meshes from Debian's libcgal-demo (datasets/fetch-cgal-meshes.sh):
// the Embree index and the raster both equal the brute-force scan at >= 10,000 points per
// cutter (the raster's: every k-th of its points, k chosen for about 12,000, spread over
// the whole raster).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <random>

#include "batch/io/mesh_reader.hpp"
#include "engine/drop_index.hpp"
#include "engine/raster.hpp"
#include "kernels/mesh/mesh_transform.hpp"
#include "tests/engine/mesh_test_support.hpp"

namespace ncpath {
namespace {

using test_meshes::load;

const Cutter kCutters[] = {ball_cutter(5), flat_cutter(6), bull_nose_cutter(8, 1.5)};

class RealMesh : public testing::TestWithParam<const char*> {};

TEST_P(RealMesh, EmbreeIndexEqualsBruteForce) {
  const TriangleMesh mesh = load(GetParam());
  const FacetTable table = build_facet_table(mesh);
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> X(table.box.lo.x(), table.box.hi.x());
  std::uniform_real_distribution<double> Y(table.box.lo.y(), table.box.hi.y());
  for (const Cutter& c : kCutters) {
    const DropIndex index(mesh, c);
    int touched = 0;
    for (int i = 0; i < 10000; ++i) {
      const double x = X(rng), y = Y(rng);
      const CutterContact fast = index.query(x, y);
      const CutterContact slow = drop_brute_force(table, c, x, y);
      ASSERT_EQ(fast.kind == ContactKind::kNone, slow.kind == ContactKind::kNone);
      if (slow.kind == ContactKind::kNone) continue;
      ++touched;
      ASSERT_NEAR(fast.tip_z, slow.tip_z, 1e-9)
          << GetParam() << " " << cutter_type_name(c.type) << " at " << x << "," << y;
    }
    EXPECT_GT(touched, 3000);
  }
}

TEST_P(RealMesh, RasterEqualsBruteForce) {
  const TriangleMesh mesh = load(GetParam());
  const FacetTable table = build_facet_table(mesh);
  for (const Cutter& c : kCutters) {
    RasterParams p;
    p.interval = 2.0;
    p.step = 1.0;  // ~ 100 x 200 = 20,000 points
    p.adaptive_tolerance = 0.05;
    RunControl control;
    std::size_t checked = 0;
    double floor_z = 0;
    std::vector<double> xyz;
    const RasterStats st = run_raster(
        mesh, c, p, [&](const ClChunk& ch) { xyz.insert(xyz.end(), ch.xyz.begin(), ch.xyz.end()); },
        control);
    floor_z = st.floor_z;
    const std::size_t stride = 3 * std::max<std::size_t>(1, xyz.size() / 3 / 12000);
    for (std::size_t k = 0; k < xyz.size(); k += stride) {
      const CutterContact bf = drop_brute_force(table, c, xyz[k], xyz[k + 1]);
      ASSERT_NEAR(xyz[k + 2], std::max(bf.tip_z, floor_z), 1e-9)
          << GetParam() << " " << cutter_type_name(c.type) << " at " << xyz[k] << "," << xyz[k + 1];
      ++checked;
    }
    EXPECT_GE(checked, 10000u);
  }
}

INSTANTIATE_TEST_SUITE_P(Cgal, RealMesh, testing::Values("bunny00", "fandisk"));

}  // namespace
}  // namespace ncpath
