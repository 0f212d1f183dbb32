// Throughput runner: one batch run with its jobs one at a time (concurrent_jobs = 1) and
// several at once (concurrent_jobs = 0: as many as threads), alternately in one process, so
// the machine's drift hits both alike. Prints each run's wall time and the ratio of the
// medians, and whether the two outputs hold the same jobs with the same statuses.
//
//   ncpath_batch_throughput [--batch FILE.toml] [--rounds 3] [--threads 0] [--out DIR]
//
// Without --batch it runs the documented case (docs/performance.md, "Batches"): 40 small
// jobs over 4 of the CGAL meshes (fandisk, anchor_dense, blade, lion-head), ten jobs each
// (raster, scan, zlevel, pencil and fillet with several tools), written to DIR/batch.toml.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "batch/cli/huge_pages.hpp"
#include "batch/jobs/job_runner.hpp"
#include "engine/run_control.hpp"

using namespace ncpath;

namespace {

// Ten jobs on one mesh: every mesh operation, several tools, small intervals' worth of work.
void add_mesh_jobs(std::ostream& os, const std::string& tag, const std::filesystem::path& mesh) {
  struct Job {
    const char* name;
    const char* op;
    const char* tool;
    const char* params;
  };
  const Job jobs[] = {
      {"raster-ball6", "raster", "ball:6", "{ interval = 1.0, step = 0.2 }"},
      {"raster-bull8-y", "raster", "bull:8:2", "{ interval = 1.5, step = 0.3, direction = \"y\" }"},
      {"raster-flat4", "raster", "flat:4", "{ interval = 2.0, step = 0.5 }"},
      {"scan-x", "scan", "ball:6", "{ families = \"x\", interval = 2 }"},
      {"scan-both", "scan", "ball:4", "{ families = \"both\", interval = 4 }"},
      {"zlevel", "zlevel", "ball:6", "{ step_down = 4 }"},
      {"zlevel-levels", "zlevel", "ball:4", "{ levels = [10.0, 20.0, 30.0] }"},
      {"pencil", "pencil", "ball:6", "{ interval = 1, step_down = 0 }"},
      {"pencil-ball3", "pencil", "ball:3", "{ interval = 1, step_down = 0 }"},
      {"fillet", "fillet", "ball:3", "{ reference = \"ball:8\", interval = 1, step_down = 0 }"},
  };
  for (const Job& j : jobs)
    os << "[[job]]\nname = \"" << tag << "-" << j.name << "\"\noperation = \"" << j.op
       << "\"\ninput = \"" << mesh.string() << "\"\ntool = \"" << j.tool
       << "\"\ntransform = { fit_xy = 100 }\nparams = " << j.params << "\n";
}

std::string default_batch() {
  const std::filesystem::path meshes =
      std::filesystem::path(NCPATH_SOURCE_DIR) / "datasets/cache/meshes";
  std::ostringstream os;
  os << "output = \"batch.h5\"\n";
  for (const char* m : {"fandisk", "anchor_dense", "blade", "lion-head"})
    add_mesh_jobs(os, m, meshes / (std::string(m) + ".off"));
  return os.str();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  cli::reexec_with_huge_pages(argv);  // as the ncpath command does
  CLI::App app{"ncpath batch throughput: jobs one at a time against several at once"};
  std::string batch_file;
  std::string out_dir = (std::filesystem::temp_directory_path() / "ncpath_batch_bench").string();
  int rounds = 3;
  int threads = 0;
  app.add_option("--batch", batch_file, "Batch file (default: the documented 40-job batch)");
  app.add_option("--rounds", rounds, "Runs of each kind")->capture_default_str();
  app.add_option("--threads", threads, "Threads, 0 = all cores")->capture_default_str();
  app.add_option("--out", out_dir, "Folder for the output files")->capture_default_str();
  CLI11_PARSE(app, argc, argv);

  jobs::BatchSpec batch;
  std::filesystem::create_directories(out_dir);
  try {
    if (batch_file.empty()) {  // written out too, for `ncpath run` by hand
      batch_file = (std::filesystem::path(out_dir) / "batch.toml").string();
      std::ofstream(batch_file) << default_batch();
    }
    batch = jobs::parse_batch_file(batch_file);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ncpath_batch_throughput: %s\n", e.what());
    return 2;
  }
  batch.threads = threads;
  std::vector<double> seconds[2];
  std::vector<std::string> statuses[2];
  for (int r = 0; r < rounds; ++r)
    for (int kind = 0; kind < 2; ++kind) {
      batch.concurrent_jobs = kind == 0 ? 1 : 0;
      batch.output = std::filesystem::path(out_dir) / (kind == 0 ? "one.h5" : "many.h5");
      Stopwatch clock;
      const std::vector<jobs::JobOutcome> outcomes = jobs::run_batch(batch, {});
      seconds[kind].push_back(clock.seconds());
      statuses[kind].clear();
      for (const jobs::JobOutcome& o : outcomes) statuses[kind].push_back(o.name + ":" + o.status);
      std::printf("round %d  %-13s %7.3f s\n", r + 1, kind == 0 ? "one at a time" : "concurrent",
                  seconds[kind].back());
    }
  std::size_t ok = 0;
  for (const std::string& s : statuses[1]) ok += s.size() > 3 && s.substr(s.size() - 3) == ":ok";
  std::printf("%zu jobs (%zu ok), threads %d: one at a time %.3f s, concurrent %.3f s (medians), "
              "speed-up %.2fx; same jobs and statuses: %s\n",
              batch.jobs.size(), ok, threads, median(seconds[0]), median(seconds[1]),
              median(seconds[0]) / median(seconds[1]),
              statuses[0] == statuses[1] ? "yes" : "NO");
  return statuses[0] == statuses[1] ? 0 : 1;
}
