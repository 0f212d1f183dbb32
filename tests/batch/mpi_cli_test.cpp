// ncpath-mpi end to end (batch/jobs/mpi_batch.hpp): a batch spread over 1, 2 and 3 MPI ranks
// on this machine writes the same datasets, in the same order, as one ncpath process; a job
// that fails fails alone; the file says the batch is complete; a rank killed half-way leaves
// a readable file with the jobs copied so far.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <thread>

#include "batch/io/stl_writer.hpp"
#include "tests/batch/cli_run.hpp"
#include "tests/batch/output/h5_read.hpp"
#include "tests/support/meshes.hpp"

namespace ncpath {
namespace {

namespace h5 = out::test;
using test::CmdResult;

// `mpirun -np ranks ncpath-mpi args` (oversubscribed: more ranks than cores is fine here).
CmdResult mpirun(int ranks, const std::string& args) {
  return test::run_command("mpirun --oversubscribe --allow-run-as-root -np " +
                           std::to_string(ranks) + " " + NCPATH_BINARY_DIR + "/batch/ncpath-mpi " +
                           args);
}

std::filesystem::path fixture_dir() { return test::part_dir("mpi_"); }

// Statistics differ: timings, and what a job shared with others (mesh_shared,
// conditioned_shared, ...), which depends on the jobs that ran in the same process.
bool statistic(const std::string& name) { return name.find("/stats/") != std::string::npos; }

// Job names in the order the file holds them (creation order).
std::vector<std::string> job_order(const std::filesystem::path& file) {
  h5::Id f = h5::open_read(file);
  h5::Id jobs(H5Gopen2(f, "/jobs", H5P_DEFAULT));
  std::vector<std::string> names;
  H5Literate(
      jobs, H5_INDEX_CRT_ORDER, H5_ITER_INC, nullptr,
      [](hid_t, const char* name, const H5L_info_t*, void* out) -> herr_t {
        static_cast<std::vector<std::string>*>(out)->push_back(name);
        return 0;
      },
      &names);
  return names;
}

TEST(MpiCli, RanksWriteWhatOneProcessWrites) {
  const auto dir = fixture_dir();
  test::write_seven_job_batch(dir);
  const std::string batch = (dir / "batch.toml").string();
  const CmdResult one =
      test::ncpath("run " + batch + " --quiet --threads 1 --concurrent-jobs 1 --out " +
                   (dir / "one.h5").string());
  ASSERT_EQ(one.exit_code, 1) << one.output;  // the missing input fails
  const std::vector<std::string> order = job_order(dir / "one.h5");
  ASSERT_EQ(order.size(), 7u);
  for (int ranks : {1, 2, 3}) {
    SCOPED_TRACE(testing::Message() << ranks << " ranks");
    const auto out = dir / ("np" + std::to_string(ranks) + ".h5");
    const CmdResult r =
        mpirun(ranks, "run " + batch + " --quiet --threads 1 --out " + out.string());
    EXPECT_EQ(r.exit_code, 1) << r.output;
    EXPECT_NE(r.output.find("7 job(s), 6 ok, 1 failed"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("on rank " + std::to_string(ranks - 1)), std::string::npos)
        << r.output;  // every rank ran a job (seven jobs, handed out one at a time)
    EXPECT_TRUE(h5::same_content(dir / "one.h5", out, statistic));
    EXPECT_EQ(job_order(out), order);
    h5::Id f = h5::open_read(out);
    h5::Id missing(H5Gopen2(f, "/jobs/missing", H5P_DEFAULT));
    EXPECT_EQ(h5::attr_str(missing, "status"), "invalid_input");
    EXPECT_EQ(h5::attr_i64(f, "batch_jobs"), 7);
    EXPECT_EQ(h5::attr_i64(f, "batch_complete"), 1);
  }
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    EXPECT_EQ(entry.path().string().find(".spool-"), std::string::npos) << entry.path();
}

// One raster job, more than its share of the batch, runs as one band per rank
// (batch/jobs/split_job.hpp): the file holds what one process writes, the statistics that
// count are the same, and the job says which ranks ran its bands.
TEST(MpiCli, OneLargeRasterJobSplitsAcrossTheRanks) {
  const auto dir = fixture_dir();
  const std::string job = "raster --mesh " + (dir / "part.stl").string() +
                          " --tool ball:3 --interval 0.2 --step 0.05 --margin 2 --quiet"
                          " --threads 1 --out ";
  const CmdResult one = test::ncpath(job + (dir / "one.h5").string());
  ASSERT_EQ(one.exit_code, 0) << one.output;
  h5::Id whole = h5::open_read(dir / "one.h5");
  const auto stat = [](hid_t f, const std::string& name) {
    return h5::read_all<std::int64_t>(f, "/jobs/raster/stats/" + name, H5T_NATIVE_INT64).at(0);
  };
  for (int ranks : {2, 3}) {
    SCOPED_TRACE(testing::Message() << ranks << " ranks");
    const auto out = dir / ("np" + std::to_string(ranks) + ".h5");
    const CmdResult r = mpirun(ranks, job + out.string());
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find(std::to_string(ranks) + " bands on ranks "), std::string::npos)
        << r.output;
    EXPECT_TRUE(h5::same_content(dir / "one.h5", out, statistic));
    h5::Id f = h5::open_read(out);
    EXPECT_EQ(stat(f, "mpi_bands"), ranks);
    for (const char* name : {"points", "lines", "chord_guard_lifted", "verify_moves"})
      EXPECT_EQ(stat(f, name), stat(whole, name)) << name;
  }
}

// The pid of the ncpath-mpi process of MPI rank `rank` whose command line holds `marker`,
// or 0 when there is none (yet).
pid_t rank_pid(int rank, const std::string& marker) {
  const std::string want = "OMPI_COMM_WORLD_RANK=" + std::to_string(rank);
  for (const auto& e : std::filesystem::directory_iterator("/proc")) {
    const std::string name = e.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    const std::string cmd = test::slurp(e.path() / "cmdline");
    if (cmd.find("ncpath-mpi") == std::string::npos || cmd.find(marker) == std::string::npos)
      continue;
    const std::string env = test::slurp(e.path() / "environ");
    for (std::size_t p = 0; p < env.size();) {
      const std::size_t end = std::min(env.find('\0', p), env.size());
      if (env.compare(p, end - p, want) == 0) return pid_t(std::stoi(name));
      p = end + 1;
    }
  }
  return 0;
}

// Waits (up to 60 s) until no rank of the run whose command line holds `marker` is left.
// mpirun can return before rank 0, stopped by its SIGTERM, has closed the output file, and
// HDF5 locks a file while it is open (a test that opened it at once failed once in CI with
// "unable to lock the file").
void wait_for_ranks(int ranks, const std::string& marker) {
  auto alive = [&] {
    for (int r = 0; r < ranks; ++r)
      if (rank_pid(r, marker) != 0) return true;
    return false;
  };
  for (int i = 0; i < 600 && alive(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
}

// Twelve raster jobs on three ranks; rank 2 is killed once four jobs have come back to
// rank 0 (its progress lines). mpirun then stops the others (SIGTERM): rank 0 closes the
// file with the jobs copied so far, each whole, and batch_complete = 0; no spool file is
// left behind.
TEST(MpiCli, AKilledRankLeavesTheFinishedJobsReadable) {
  const auto dir = fixture_dir();
  {
    std::ofstream b(dir / "batch.toml");
    b << "output = \"x.h5\"\n";
    for (int k = 0; k < 12; ++k)
      b << "[[job]]\nname = \"r" << k << "\"\ninput = \"part.stl\"\ntool = \"ball:4\"\n"
        << "params = { interval = 0.1, step = 0.05 }\n";
  }
  const auto out = dir / "killed.h5";
  const std::string cmd = "mpirun --oversubscribe --allow-run-as-root -np 3 " +
                          std::string(NCPATH_BINARY_DIR) + "/batch/ncpath-mpi run " +
                          (dir / "batch.toml").string() + " --threads 1 --out " + out.string() +
                          " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  ASSERT_NE(p, nullptr);
  std::string output;
  std::array<char, 4096> buf;
  int back = 0;
  bool killed = false;
  while (fgets(buf.data(), buf.size(), p)) {
    output += buf.data();
    if (buf[0] == '[' && ++back >= 4 && !killed) {
      if (const pid_t victim = rank_pid(2, out.string()); victim != 0)
        killed = ::kill(victim, SIGKILL) == 0;
    }
  }
  const int status = pclose(p);
  wait_for_ranks(3, out.string());
  ASSERT_TRUE(killed) << output;
  EXPECT_FALSE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << output;
  h5::Id f = h5::open_read(out);
  EXPECT_EQ(h5::attr_i64(f, "batch_jobs"), 12);
  EXPECT_EQ(h5::attr_i64(f, "batch_complete"), 0) << output;
  const std::vector<std::string> names = job_order(out);
  EXPECT_GE(names.size(), 1u) << output;
  EXPECT_LT(names.size(), 12u) << output;
  for (std::size_t k = 0; k < names.size(); ++k) {
    EXPECT_EQ(names[k], "r" + std::to_string(k));  // batch order, from the first job on
    h5::Id g(H5Gopen2(f, ("/jobs/" + names[k]).c_str(), H5P_DEFAULT));
    EXPECT_EQ(h5::attr_str(g, "status"), "ok");
    EXPECT_GT(h5::read_all<double>(f, "/jobs/" + names[k] + "/cl/points", H5T_NATIVE_DOUBLE).size(),
              100u);
  }
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    EXPECT_EQ(entry.path().string().find(".spool-"), std::string::npos) << entry.path();
}

}  // namespace
}  // namespace ncpath
