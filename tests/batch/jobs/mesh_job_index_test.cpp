// Pencil and fillet jobs ask for the mesh's swept-tool index (the chord guard's, shared with
// the verifier) only once their computation has ended, so that the index and the
// computation's own structures (elements, drop and distance indexes) never take memory at
// once: this is what makes a 20 M-facet pencil fit (docs/performance.md "Memory per facet").
// The index source records how far the job had got when it was called, from the job's
// progress reports (the job reports done = total once its computation has ended).
#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <vector>

#include "batch/jobs/fillet_job.hpp"
#include "batch/jobs/pencil_job.hpp"
#include "tests/kernels/scan/scan_test_support.hpp"

namespace ncpath::jobs {
namespace {

struct Watch {
  std::uint64_t done = 0, total = 0;  // the latest progress report
  int calls = 0;                      // index requests
  bool after_compute = false;         // the first request came after the computation ended
};

void watch(RunControl& control, Watch& w) {
  control.progress = [&w](std::uint64_t done, std::uint64_t total) {
    w.done = done;
    w.total = total;
  };
}

SweptIndexSource source(Watch& w, const TriangleMesh& mesh) {
  return [&w, &mesh] {
    if (w.calls++ == 0) w.after_compute = w.total > 0 && w.done == w.total;
    return std::make_shared<const MeshVerifier>(mesh);
  };
}

std::filesystem::path temp_file(const char* name) {
  return std::filesystem::temp_directory_path() / name;
}

TEST(MeshJobIndex, PencilAsksForTheSweptIndexAfterItsComputation) {
  const TriangleMesh mesh = scan_test::box_pocket();
  JobSpec job;
  job.operation = Operation::kPencil;
  job.tool = ball_cutter(2.5);
  job.pencil.step_down = 0.3;
  Watch w;
  RunControl control;
  watch(control, w);
  const auto path = temp_file("ncpath_mesh_job_index_pencil.h5");
  out::ClFile file(path, "0");
  out::ClJob cl = file.begin_job("pencil", {"pencil", "box", "", "{}", "{}"});
  std::vector<out::StatValue> stats;
  const PencilJobSummary s =
      run_pencil_job(job, mesh, source(w, mesh), cl, nullptr, control, stats);
  EXPECT_GT(s.points, 0u);
  EXPECT_EQ(w.calls, 1);
  EXPECT_TRUE(w.after_compute);
  cl.close();
  file.close();
  std::filesystem::remove(path);
}

TEST(MeshJobIndex, FilletAsksForTheSweptIndexAfterItsComputation) {
  const TriangleMesh mesh = scan_test::box_pocket();
  JobSpec job;
  job.operation = Operation::kFillet;
  job.tool = ball_cutter(1);
  job.fillet.reference_diameter = 2.5;
  job.fillet.pencil.step_down = 0.3;
  Watch w;
  RunControl control;
  watch(control, w);
  const auto path = temp_file("ncpath_mesh_job_index_fillet.h5");
  out::ClFile file(path, "0");
  out::ClJob cl = file.begin_job("fillet", {"fillet", "box", "", "{}", "{}"});
  std::vector<out::StatValue> stats;
  const FilletJobSummary s =
      run_fillet_job(job, mesh, source(w, mesh), cl, nullptr, control, stats);
  EXPECT_GT(s.points, 0u);
  EXPECT_EQ(w.calls, 1);
  EXPECT_TRUE(w.after_compute);
  cl.close();
  file.close();
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace ncpath::jobs
