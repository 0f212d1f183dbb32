// Pencil and fillet jobs ask for the mesh's swept-tool index (the chord guard's, shared with
// the verifier) only once their computation has ended, so that the index and the
// computation's own structures (elements, drop and distance indexes) never take memory at
// once: this is what makes a 20 M-facet pencil fit (docs/performance.md "Memory per facet").
// The index source records how far the job had got when it was called, from the job's
// progress reports (the job reports done = total once its computation has ended).
#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <string>
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

// Runs the job on a box pocket with a watched index source: the job writes points, and asks
// for the index once, after its computation.
template <class RunJob>
void expect_index_after_computation(const JobSpec& job, RunJob run_job) {
  const TriangleMesh mesh = scan_test::box_pocket();
  Watch w;
  RunControl control;
  watch(control, w);
  const std::string name = operation_name(job.operation);
  const auto path = std::filesystem::temp_directory_path() / ("ncpath_index_" + name + ".h5");
  {
    out::ClFile file(path, "0");
    out::ClJob cl = file.begin_job(name, {name, "box", "", "{}", "{}"});
    std::vector<out::StatValue> stats;
    EXPECT_GT(run_job(job, mesh, source(w, mesh), cl, control, stats).points, 0u);
    cl.close();
    file.close();
  }
  EXPECT_EQ(w.calls, 1);
  EXPECT_TRUE(w.after_compute);
  std::filesystem::remove(path);
}

TEST(MeshJobIndex, PencilAsksForTheSweptIndexAfterItsComputation) {
  JobSpec job;
  job.operation = Operation::kPencil;
  job.tool = ball_cutter(2.5);
  job.pencil.step_down = 0.3;
  expect_index_after_computation(job, [](const JobSpec& j, const TriangleMesh& m,
                                         const SweptIndexSource& s, out::ClJob& cl,
                                         RunControl& c, std::vector<out::StatValue>& st) {
    return run_pencil_job(j, m, s, cl, nullptr, c, st);
  });
}

TEST(MeshJobIndex, FilletAsksForTheSweptIndexAfterItsComputation) {
  JobSpec job;
  job.operation = Operation::kFillet;
  job.tool = ball_cutter(1);
  job.fillet.reference_diameter = 2.5;
  job.fillet.pencil.step_down = 0.3;
  expect_index_after_computation(job, [](const JobSpec& j, const TriangleMesh& m,
                                         const SweptIndexSource& s, out::ClJob& cl,
                                         RunControl& c, std::vector<out::StatValue>& st) {
    return run_fillet_job(j, m, s, cl, nullptr, c, st);
  });
}

}  // namespace
}  // namespace ncpath::jobs
