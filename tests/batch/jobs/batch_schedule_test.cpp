// Which jobs of a batch run at the same time (batch/jobs/batch_schedule.hpp): batch order,
// the slot count and the memory budget, and a job over the budget still runs alone; the
// sizes users write; the memory estimate from the input's facet count.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "batch/io/mesh_reader.hpp"
#include "batch/io/stl_writer.hpp"
#include "batch/jobs/batch_schedule.hpp"
#include "tests/batch/output/h5_read.hpp"
#include "tests/support/meshes.hpp"

namespace ncpath::jobs {
namespace {

using V = std::vector<std::size_t>;

TEST(Admission, StartsInOrderUpToTheSlots) {
  Admission a({10, 10, 10, 10}, 1000, 2);
  EXPECT_EQ(a.start_ready(), (V{0, 1}));
  EXPECT_EQ(a.start_ready(), V{});  // both slots taken
  a.finished(1);                    // out of order
  EXPECT_EQ(a.start_ready(), V{2});
  a.finished(0);
  a.finished(2);
  EXPECT_EQ(a.start_ready(), V{3});
  a.finished(3);
  EXPECT_EQ(a.start_ready(), V{});
  EXPECT_EQ(a.started(), 4u);
  EXPECT_EQ(a.running(), 0u);
}

TEST(Admission, KeepsTheRunningJobsWithinTheBudget) {
  Admission a({60, 50, 30, 10}, 100, 4);
  EXPECT_EQ(a.start_ready(), V{0});  // 60 + 50 > 100: job 1 waits, and so do the later ones
  a.finished(0);
  EXPECT_EQ(a.start_ready(), (V{1, 2, 3}));  // 50 + 30 + 10 <= 100
}

TEST(Admission, AJobOverTheBudgetStillRunsAlone) {
  Admission a({10, 500, 10}, 100, 2);
  EXPECT_EQ(a.start_ready(), V{0});
  a.finished(0);
  EXPECT_EQ(a.start_ready(), V{1});  // alone, though over the budget
  EXPECT_EQ(a.start_ready(), V{});   // nothing joins it
  a.finished(1);
  EXPECT_EQ(a.start_ready(), V{2});
}

TEST(Admission, OneSlotIsOneAtATime) {
  Admission a({1, 1, 1}, 1000, 1);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(a.start_ready(), V{i});
    EXPECT_EQ(a.start_ready(), V{});
    a.finished(i);
  }
  EXPECT_THROW(a.finished(1), std::logic_error);  // not running
}

TEST(ByteSize, ReadsWhatUsersWrite) {
  std::uint64_t b = 0;
  EXPECT_EQ(parse_byte_size("8G", b), "");
  EXPECT_EQ(b, 8ull << 30);
  EXPECT_EQ(parse_byte_size("512M", b), "");
  EXPECT_EQ(b, 512ull << 20);
  EXPECT_EQ(parse_byte_size("1.5GiB", b), "");
  EXPECT_EQ(b, 3ull << 29);
  EXPECT_EQ(parse_byte_size("2048", b), "");
  EXPECT_EQ(b, 2048u);
  EXPECT_EQ(parse_byte_size("4 kb", b), "");
  EXPECT_EQ(b, 4096u);
  EXPECT_EQ(parse_byte_size("1T", b), "");
  EXPECT_EQ(b, 1ull << 40);
  for (const char* bad : {"", "abc", "-1G", "0", "8X", "8G x", "8iB", "nan", "1e30"})
    EXPECT_NE(parse_byte_size(bad, b), "") << bad;
}

TEST(MemoryEstimate, CountsTheFacetsOfABinaryStlExactly) {
  const auto dir = out::test::out_dir("MemoryEstimate_Stl");
  const TriangleMesh m = test::height_field(12, 17, [](double x, double) { return x / 10; });
  io::write_binary_stl(dir / "m.stl", m);
  EXPECT_EQ(io::facet_count_hint(dir / "m.stl"), m.facets.size());
  JobSpec raster;
  raster.operation = Operation::kRaster;
  raster.input = dir / "m.stl";
  JobSpec pencil = raster;
  pencil.operation = Operation::kPencil;
  JobSpec pocket = raster;
  pocket.operation = Operation::kPocket;
  // Per facet: the pencil holds more than the raster; a pocket job has its base only.
  const std::uint64_t base = estimate_job_bytes(pocket);
  EXPECT_GT(estimate_job_bytes(raster), base + 500 * m.facets.size());
  EXPECT_GT(estimate_job_bytes(pencil), estimate_job_bytes(raster));
  JobSpec broken = pencil;
  broken.error = "bad";
  EXPECT_EQ(estimate_job_bytes(broken), base);
  JobSpec missing = pencil;
  missing.input = dir / "none.stl";
  EXPECT_EQ(estimate_job_bytes(missing), base);
}

TEST(MemoryEstimate, TextMeshesAreCountedOnTheHighSide) {
  const auto dir = out::test::out_dir("MemoryEstimate_Text");
  const TriangleMesh m = test::height_field(30, 30, [](double x, double y) { return x * y; });
  // ASCII STL and OFF with short numbers: the fewest bytes per facet.
  std::ofstream stl(dir / "m.stl");
  stl.precision(6);
  stl << "solid m\n";
  for (const auto& f : m.facets) {
    stl << "facet normal 0 0 1\nouter loop\n";
    for (const std::uint32_t v : f) {
      const Vec3& p = m.vertices[v];
      stl << "vertex " << p.x() << " " << p.y() << " " << p.z() << "\n";
    }
    stl << "endloop\nendfacet\n";
  }
  stl << "endsolid m\n";
  stl.close();
  std::ofstream off(dir / "m.off");
  off.precision(6);
  off << "OFF\n" << m.vertices.size() << " " << m.facets.size() << " 0\n";
  for (const Vec3& p : m.vertices) off << p.x() << " " << p.y() << " " << p.z() << "\n";
  for (const auto& f : m.facets) off << "3 " << f[0] << " " << f[1] << " " << f[2] << "\n";
  off.close();
  ASSERT_EQ(io::read_mesh(dir / "m.stl").mesh.facets.size(), m.facets.size());
  EXPECT_GE(io::facet_count_hint(dir / "m.stl"), m.facets.size());
  EXPECT_LE(io::facet_count_hint(dir / "m.stl"), 3 * m.facets.size());
  ASSERT_EQ(io::read_mesh(dir / "m.off").mesh.facets.size(), m.facets.size());
  EXPECT_EQ(io::facet_count_hint(dir / "m.off"), m.facets.size());  // from the header
  // A header behind comments, counts on the keyword's line.
  std::ofstream(dir / "c.off") << "# scanned\nOFF # plain\n# counts:\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n"
                                  "3 0 1 2\n";
  EXPECT_EQ(io::facet_count_hint(dir / "c.off"), 1u);
}

}  // namespace
}  // namespace ncpath::jobs
