// Every mesh operation on random parts, checked by the verifier in the job (the oracle of
// record, issue 16): terrains of random bumps with a steep block and a pocket cut in, turned
// about z by a random angle, moved far from the origin, vertices noised, written as binary
// STL; raster (ball, flat, bull-nose), scan, zlevel, pencil and fillet must all end ok (a
// gouge over 1e-6 mm would make the job failed_verification) with verify_max_gouge 0.
// Seeds: NCPATH_FUZZ_SEEDS="first:count", else the CI's fixed range.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <random>

#include "batch/io/stl_writer.hpp"
#include "tests/batch/cli_run.hpp"
#include "tests/batch/output/h5_read.hpp"
#include "tests/support/meshes.hpp"

namespace ncpath {
namespace {

namespace h5 = out::test;
using test::CmdResult;
using test::ncpath;

// A 60 mm terrain: a few random bumps, a steep block (walls 70-85 degrees) and a pocket.
TriangleMesh random_part(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  const auto u = [&](double a, double b) {
    return a + (b - a) * static_cast<double>(rng() >> 11) * 0x1.0p-53;
  };
  struct Bump {
    double x, y, h, w;
  };
  std::vector<Bump> bumps;
  for (int k = 0; k < 4; ++k) bumps.push_back({u(5, 55), u(5, 55), u(-6, 10), u(4, 12)});
  const double bx = u(10, 35), by = u(10, 35), bw = u(8, 16), bh = u(5, 15);
  const double px = u(15, 45), py = u(15, 45), pr = u(4, 9), pd = u(2, 6);
  const double jitter = std::pow(10.0, -u(6, 11));  // vertex noise, 1e-11 to 1e-6 mm
  TriangleMesh m = test::height_field(48, 60, [&](double x, double y) {
    double z = 10;
    for (const Bump& b : bumps)
      z += b.h * std::exp(-((x - b.x) * (x - b.x) + (y - b.y) * (y - b.y)) / (b.w * b.w));
    if (x > bx && x < bx + bw && y > by && y < by + bw) z += bh;  // the block
    if (std::hypot(x - px, y - py) < pr) z -= pd;                 // the pocket
    return z;
  });
  const double a = u(0, 2 * 3.14159265358979), c = std::cos(a), s = std::sin(a);
  const Vec3 t(u(-1000, 1000), u(-1000, 1000), u(-50, 50));
  for (Vec3& v : m.vertices) {
    v = Vec3(c * v.x() - s * v.y(), s * v.x() + c * v.y(), v.z()) + t;
    v += Vec3(u(-jitter, jitter), u(-jitter, jitter), u(-jitter, jitter));
  }
  return m;
}

std::pair<std::uint64_t, std::uint64_t> seed_range(std::uint64_t first, std::uint64_t count) {
  if (const char* env = std::getenv("NCPATH_FUZZ_SEEDS")) {
    unsigned long long a = 0, n = 0;
    if (std::sscanf(env, "%llu:%llu", &a, &n) == 2) return {a, n};
  }
  return {first, count};
}

TEST(VerifyRandomMesh, EveryOperationPassesTheVerifier) {
  const auto dir = h5::out_dir("verify_random_mesh");
  const auto [first, count] = seed_range(1, 2);
  for (std::uint64_t seed = first; seed < first + count; ++seed) {
    const auto stl = dir / ("part" + std::to_string(seed) + ".stl");
    io::write_binary_stl(stl, random_part(seed));
    const std::string mesh = " --mesh " + stl.string() + " --quiet";
    const std::pair<const char*, std::string> runs[] = {
        {"raster", "raster --tool ball:6 --interval 1.5 --step 0.3"},
        {"raster", "raster --tool flat:6 --interval 1.5 --step 0.3 --direction y"},
        {"raster", "raster --tool bull:8:2 --interval 2 --step 0.4 --adaptive 0.01"},
        {"scan", "scan --tool ball:6 --families both --interval 2"},
        {"zlevel", "zlevel --tool ball:6 --step-down 3"},
        {"pencil", "pencil --tool ball:4 --interval 1 --step-down 2"},
        {"fillet", "fillet --tool ball:2 --reference ball:8 --interval 1 --step-down 0"},
    };
    int k = 0;
    for (const auto& [job, args] : runs) {
      const auto out = dir / ("s" + std::to_string(seed) + "_" + std::to_string(k++) + ".h5");
      const CmdResult r = ncpath(args + mesh + " --out " + out.string());
      ASSERT_EQ(r.exit_code, 0) << "seed " << seed << ": " << args << "\n" << r.output;
      h5::Id f = h5::open_read(out);
      h5::Id g(H5Gopen2(f, ("/jobs/" + std::string(job)).c_str(), H5P_DEFAULT));
      EXPECT_EQ(h5::attr_str(g, "status"), "ok") << "seed " << seed << ": " << args;
      const auto gouge = h5::read_all<double>(
          f, "/jobs/" + std::string(job) + "/stats/verify_max_gouge", H5T_NATIVE_DOUBLE);
      ASSERT_EQ(gouge.size(), 1u);
      EXPECT_EQ(gouge[0], 0) << "seed " << seed << ": " << args;
      const auto moves = h5::read_all<std::int64_t>(
          f, "/jobs/" + std::string(job) + "/stats/verify_moves", H5T_NATIVE_INT64);
      EXPECT_GT(moves[0], 0) << "seed " << seed << ": " << args;
    }
  }
}

}  // namespace
}  // namespace ncpath
