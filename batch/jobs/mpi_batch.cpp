#include "batch/jobs/mpi_batch.hpp"

#include <mpi.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <nlohmann/json.hpp>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>

#include "batch/jobs/batch_schedule.hpp"
#include "batch/jobs/split_job.hpp"
#include "batch/output/cl_writer.hpp"

namespace ncpath::jobs {
namespace {

namespace fs = std::filesystem;

constexpr int kTagAsk = 1;     // rank -> 0: give me a job (no data)
constexpr int kTagJob = 2;     // 0 -> rank: a TaskMessage; its task kNoJob: stop
constexpr int kTagResult = 3;  // rank -> 0: the outcome (JSON), then its file's bytes
constexpr int kTagBytes = 4;
constexpr std::int64_t kNoJob = -1;
constexpr std::size_t kMaxMessage = std::size_t(1) << 30;  // bytes per MPI message

// Set by SIGTERM or SIGINT on rank 0: mpirun sends SIGTERM when a rank has died (or the user
// stops the batch). Rank 0 then finishes the copy it is making, closes the file (whole jobs
// only, batch_complete = 0) and exits.
std::atomic<bool> g_stop{false};
extern "C" void on_stop_signal(int) { g_stop = true; }

// What a rank is handed: a whole job, or band `band` of `bands` of a job split across the
// ranks (bands == 0: whole).
struct Task {
  std::size_t job = 0;
  std::uint32_t band = 0, bands = 0;
};

// The batch's tasks: a splittable job (split_job.hpp) whose estimate (estimate_job_bytes) is
// more than its share of the batch (Σ / ranks) becomes one band per rank, as it alone would
// hold up the end of the batch; every other job is one task.
std::vector<Task> batch_tasks(const BatchSpec& batch, int ranks) {
  std::vector<std::uint64_t> est;
  for (const JobSpec& j : batch.jobs) est.push_back(estimate_job_bytes(j));
  const std::uint64_t total = std::accumulate(est.begin(), est.end(), std::uint64_t{0});
  const auto bands = static_cast<std::uint32_t>(ranks);
  std::vector<Task> tasks;
  for (std::size_t i = 0; i < batch.jobs.size(); ++i) {
    const bool split = ranks > 1 && splittable(batch.jobs[i]) && est[i] > total / bands;
    if (!split) tasks.push_back({i, 0, 0});
    for (std::uint32_t b = 0; split && b < bands; ++b) tasks.push_back({i, b, bands});
  }
  return tasks;
}

// Task indices in hand-out order: the largest estimate first (a band: its job's over the
// bands), then batch order.
std::vector<std::size_t> hand_out_order(const BatchSpec& batch, const std::vector<Task>& tasks) {
  std::vector<std::uint64_t> est;
  for (const Task& t : tasks)
    est.push_back(estimate_job_bytes(batch.jobs[t.job]) / std::max<std::uint32_t>(1, t.bands));
  std::vector<std::size_t> order(tasks.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return est[a] > est[b]; });
  return order;
}

// Runs a task alone into a CL file of its own at `path`: the job's (or band's) datasets are
// those a whole batch writes (run_batch writes each job the same whatever runs beside it).
JobOutcome run_alone(const BatchSpec& batch, const Task& task, const fs::path& path, int rank) {
  const JobSpec& job = batch.jobs[task.job];
  BatchSpec one = batch;
  one.mpi_rank = rank;
  one.jobs = {task.bands ? band_job(job, task.band, task.bands) : job};
  one.output = path;
  one.concurrent_jobs = 1;
  try {
    return run_batch(one, BatchObserver{}).at(0);
  } catch (const std::exception& e) {
    JobOutcome o;
    o.name = job.name;
    o.status = "io_error";
    o.message = e.what();
    return o;
  }
}

std::string outcome_json(std::size_t index, const JobOutcome& o, std::size_t bytes) {
  const nlohmann::json j = {{"index", index},
                            {"name", o.name},
                            {"status", o.status},
                            {"message", o.message},
                            {"points", o.points},
                            {"seconds", o.seconds},
                            {"compute_s", o.compute_s},
                            {"peak_rss_bytes", o.peak_rss_bytes},
                            {"bytes", bytes}};
  return j.dump();
}

JobOutcome outcome_of(const nlohmann::json& j) {
  JobOutcome o;
  o.name = j.at("name").get<std::string>();
  o.status = j.at("status").get<std::string>();
  o.message = j.at("message").get<std::string>();
  o.points = j.at("points").get<std::uint64_t>();
  o.seconds = j.at("seconds").get<double>();
  o.compute_s = j.at("compute_s").get<double>();
  o.peak_rss_bytes = j.at("peak_rss_bytes").get<std::uint64_t>();
  return o;
}

// Where this process writes a task's own CL file (`kind` "t": task i; "j": job i, a split
// job joined from its bands): the temporary folder, so that a rank stopped half-way leaves
// nothing next to the output.
fs::path spool_file(const char* kind, std::size_t i) {
  return fs::temp_directory_path() /
         ("ncpath-" + std::to_string(::getpid()) + "-" + kind + std::to_string(i) + ".h5");
}
fs::path task_file(std::size_t i) { return spool_file("t", i); }
fs::path joined_file(std::size_t i) { return spool_file("j", i); }

// The file's bytes; empty when it does not exist (the job could not create it).
std::string read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return {};
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// A task as rank 0 sends it: its index, job, band and bands. The task list is rank 0's alone
// (its estimates read the input files, which another rank may see otherwise).
using TaskMessage = std::array<std::int64_t, 4>;
TaskMessage task_message(std::int64_t index, const std::vector<Task>& tasks) {
  if (index < 0) return {kNoJob, 0, 0, 0};
  const Task& t = tasks[std::size_t(index)];
  return {index, std::int64_t(t.job), t.band, t.bands};
}

// A rank other than 0: asks for tasks until told to stop, runs each, sends back its outcome
// and its CL file.
void work(const BatchSpec& batch, int rank) {
  for (;;) {
    MPI_Send(nullptr, 0, MPI_BYTE, 0, kTagAsk, MPI_COMM_WORLD);
    TaskMessage m{kNoJob, 0, 0, 0};
    MPI_Recv(m.data(), 4, MPI_INT64_T, 0, kTagJob, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    const std::int64_t job = m[0];
    if (job < 0) return;
    const Task task{std::size_t(m[1]), std::uint32_t(m[2]), std::uint32_t(m[3])};
    const fs::path path = task_file(std::size_t(job));
    const JobOutcome o = run_alone(batch, task, path, rank);
    const std::string bytes = read_bytes(path);
    std::error_code ec;
    fs::remove(path, ec);
    const std::string head = outcome_json(std::size_t(job), o, bytes.size());
    MPI_Send(head.data(), int(head.size()), MPI_CHAR, 0, kTagResult, MPI_COMM_WORLD);
    for (std::size_t off = 0; off < bytes.size(); off += kMaxMessage) {
      const std::size_t n = std::min(kMaxMessage, bytes.size() - off);
      MPI_Send(bytes.data() + off, int(n), MPI_BYTE, 0, kTagBytes, MPI_COMM_WORLD);
    }
  }
}

// Rank 0: hands tasks out, runs some itself, joins the bands of split jobs, copies every job
// into the output in batch order.
class Coordinator {
 public:
  Coordinator(const BatchSpec& batch, const BatchObserver& obs, int ranks)
      : batch_(batch),
        obs_(obs),
        ranks_(ranks),
        tasks_(batch_tasks(batch, ranks)),
        order_(hand_out_order(batch, tasks_)),
        task_outcome_(tasks_.size()),
        task_rank_(tasks_.size(), 0),
        jobs_(batch.jobs.size()) {
    result_.outcomes.resize(batch.jobs.size());
    result_.where.resize(batch.jobs.size());
    for (std::size_t t = 0; t < tasks_.size(); ++t) jobs_[tasks_[t].job].tasks.push_back(t);
    for (JobState& j : jobs_) j.remaining = j.tasks.size();
  }

  MpiBatchResult run() {
    std::optional<out::ClFile> file;
    try {
      file.emplace(batch_.output, NCPATH_VERSION);
      file->mark_batch(std::int64_t(batch_.jobs.size()), false);
    } catch (...) {
      error_ = std::current_exception();  // nothing is handed out; the ranks are stopped
    }
    local_running_ = !error_;
    std::thread local;
    if (local_running_) local = std::thread([this] { run_local(); });
    int stopped = 0;  // ranks told to stop
    while (stopped < ranks_ - 1 || busy()) {
      if (g_stop) stop_now(file);
      take_local_results(file);
      int flag = 0;
      MPI_Status st;
      MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &st);
      if (!flag) {
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
        continue;
      }
      if (st.MPI_TAG == kTagAsk) {
        MPI_Recv(nullptr, 0, MPI_BYTE, st.MPI_SOURCE, kTagAsk, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        const std::int64_t task = take();
        const TaskMessage m = task_message(task, tasks_);
        MPI_Send(m.data(), 4, MPI_INT64_T, st.MPI_SOURCE, kTagJob, MPI_COMM_WORLD);
        stopped += task < 0;
      } else if (st.MPI_TAG == kTagResult) {
        receive_result(st, file);
      }
    }
    if (local.joinable()) local.join();
    take_local_results(file);
    if (error_) std::rethrow_exception(error_);
    file->mark_batch(std::int64_t(batch_.jobs.size()), true);
    file->close();
    return std::move(result_);
  }

 private:
  struct JobState {
    std::vector<std::size_t> tasks;  // its tasks: one, or its bands in band order
    std::size_t remaining = 0;       // tasks not back yet
    std::optional<std::chrono::steady_clock::time_point> started;  // first task handed out
    fs::path file;  // its CL file, once every task is back
    bool done = false;
  };

  void remove_spools() const {
    std::error_code ec;
    for (std::size_t t = 0; t < tasks_.size(); ++t) fs::remove(task_file(t), ec);
    for (std::size_t j = 0; j < jobs_.size(); ++j) fs::remove(joined_file(j), ec);
  }

  std::int64_t take() {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (error_ || g_stop || next_ >= order_.size()) return kNoJob;
    const std::size_t t = order_[next_++];
    JobState& j = jobs_[tasks_[t].job];
    if (!j.started) j.started = std::chrono::steady_clock::now();
    return std::int64_t(t);
  }

  // Removes the spool files, closes the file with the jobs copied so far (batch_complete
  // stays 0) and ends the process at once: the task rank 0 runs and the other ranks are not
  // waited for. The spool files go first: mpirun sends SIGKILL a second after SIGTERM, and
  // closing may wait for HDF5 while the task running here writes; once more after closing,
  // as that task may have created its file meanwhile (take() hands out nothing once g_stop
  // is set). A SIGKILL can still leave one in the temporary folder.
  [[noreturn]] void stop_now(std::optional<out::ClFile>& file) {
    remove_spools();
    try {
      if (file) file->close();
    } catch (...) {
    }
    remove_spools();
    std::fprintf(stderr, "ncpath-mpi: stopped by a signal; %zu of %zu jobs are in %s\n", copied_,
                 jobs_.size(), batch_.output.string().c_str());
    std::_Exit(3);
  }

  // Whether rank 0 still runs a task, or a task handed out has not come back.
  bool busy() {
    const std::lock_guard<std::mutex> lock(mutex_);
    return local_running_ || next_ > finished_;
  }

  void run_local() {
    for (std::int64_t t; (t = take()) >= 0;) {
      const JobOutcome o = run_alone(batch_, tasks_[std::size_t(t)], task_file(std::size_t(t)), 0);
      const std::lock_guard<std::mutex> lock(mutex_);
      local_done_.emplace_back(std::size_t(t), o);
    }
    const std::lock_guard<std::mutex> lock(mutex_);
    local_running_ = false;
  }

  void take_local_results(std::optional<out::ClFile>& file) {
    std::vector<std::pair<std::size_t, JobOutcome>> done;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      done.swap(local_done_);
    }
    for (auto& [t, o] : done) task_finished(t, std::move(o), 0, file);
  }

  void receive_result(const MPI_Status& st, std::optional<out::ClFile>& file) {
    int len = 0;
    MPI_Get_count(&st, MPI_CHAR, &len);
    std::string head(std::size_t(len), '\0');
    MPI_Recv(head.data(), len, MPI_CHAR, st.MPI_SOURCE, kTagResult, MPI_COMM_WORLD,
             MPI_STATUS_IGNORE);
    const nlohmann::json j = nlohmann::json::parse(head);
    const auto t = j.at("index").get<std::size_t>();
    auto left = j.at("bytes").get<std::size_t>();
    std::ofstream out(task_file(t), std::ios::binary | std::ios::trunc);
    std::string buf;
    while (left > 0) {
      buf.resize(std::min(kMaxMessage, left));
      MPI_Recv(buf.data(), int(buf.size()), MPI_BYTE, st.MPI_SOURCE, kTagBytes, MPI_COMM_WORLD,
               MPI_STATUS_IGNORE);
      out.write(buf.data(), std::streamsize(buf.size()));
      left -= buf.size();
    }
    out.close();
    task_finished(t, outcome_of(j), st.MPI_SOURCE, file);
  }

  void task_finished(std::size_t t, JobOutcome o, int rank, std::optional<out::ClFile>& file) {
    task_outcome_[t] = std::move(o);
    task_rank_[t] = rank;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      ++finished_;
    }
    const std::size_t i = tasks_[t].job;
    if (--jobs_[i].remaining == 0) job_finished(i);
    try {
      if (!error_) copy_in_order(*file);
    } catch (...) {
      const std::lock_guard<std::mutex> lock(mutex_);
      error_ = std::current_exception();  // no more tasks are handed out
    }
  }

  // Every task of job i is back: its file is the task's, or the one its bands are joined
  // into here.
  void job_finished(std::size_t i) {
    JobState& j = jobs_[i];
    const std::size_t t0 = j.tasks.front();
    if (tasks_[t0].bands == 0) {
      j.file = task_file(t0);
      result_.outcomes[i] = task_outcome_[t0];
      result_.where[i] = "rank " + std::to_string(task_rank_[t0]);
    } else {
      join(i);
    }
    j.done = true;
    if (obs_.job_finished) obs_.job_finished(i, result_.outcomes[i]);
  }

  void join(std::size_t i) {
    JobState& j = jobs_[i];
    std::vector<Band> bands;
    std::string ranks;
    for (const std::size_t t : j.tasks) {
      bands.push_back({task_file(t), task_outcome_[t], task_rank_[t]});
      ranks += ' ';
      ranks += std::to_string(task_rank_[t]);
    }
    std::chrono::steady_clock::time_point started;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      started = *j.started;
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    j.file = joined_file(i);
    JobOutcome& o = result_.outcomes[i];
    try {
      out::ClFile joined(j.file, NCPATH_VERSION);
      o = join_bands(joined, batch_.jobs[i], bands, seconds);
      joined.close();
    } catch (const std::exception& e) {  // the job alone fails: its status, no datasets
      std::error_code ec;
      fs::remove(j.file, ec);
      o = JobOutcome{batch_.jobs[i].name, "internal_error",
                     std::string("joining the bands failed: ") + e.what()};
    }
    result_.where[i] = std::to_string(bands.size()) + " bands on ranks" + ranks;
    for (const Band& b : bands) {
      std::error_code ec;
      fs::remove(b.file, ec);
    }
  }

  // Copies the finished jobs into the output, in batch order, up to the first not finished.
  void copy_in_order(out::ClFile& file) {
    for (; copied_ < jobs_.size() && jobs_[copied_].done; ++copied_) {
      const JobSpec& job = batch_.jobs[copied_];
      const fs::path& from = jobs_[copied_].file;
      if (fs::exists(from)) {
        file.copy_job(from, job.name);
      } else {  // the job could not create its file: its status alone
        out::JobInfo info;
        info.operation = operation_name(job.operation);
        info.input_path = job.input.string();
        out::ClJob cl = file.begin_job(job.name, info);
        cl.set_status(result_.outcomes[copied_].status, result_.outcomes[copied_].message);
        cl.close();
      }
      std::error_code ec;
      fs::remove(from, ec);
    }
  }

  const BatchSpec& batch_;
  const BatchObserver& obs_;
  const int ranks_;
  const std::vector<Task> tasks_;
  const std::vector<std::size_t> order_;
  std::vector<JobOutcome> task_outcome_;  // the MPI thread's, like what follows up to mutex_
  std::vector<int> task_rank_;
  MpiBatchResult result_;
  std::size_t copied_ = 0;
  std::mutex mutex_;  // next_, finished_, jobs_[].started, local_done_, local_running_, error_
  std::vector<JobState> jobs_;
  std::size_t next_ = 0, finished_ = 0;
  bool local_running_ = false;
  std::vector<std::pair<std::size_t, JobOutcome>> local_done_;
  std::exception_ptr error_;
};

}  // namespace

MpiBatchResult run_batch_mpi(const BatchSpec& batch, const BatchObserver& observer) {
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  if (rank != 0) {
    work(batch, rank);
    return {};
  }
  std::signal(SIGTERM, on_stop_signal);
  std::signal(SIGINT, on_stop_signal);
  if (const auto dir = batch.output.parent_path(); !dir.empty()) {
    std::error_code ec;
    fs::create_directories(dir, ec);
  }
  return Coordinator(batch, observer, size).run();
}

}  // namespace ncpath::jobs
