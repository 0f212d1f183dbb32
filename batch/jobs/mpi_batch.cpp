#include "batch/jobs/mpi_batch.hpp"

#include <mpi.h>
#include <unistd.h>

#include <algorithm>
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
#include "batch/output/cl_writer.hpp"

namespace ncpath::jobs {
namespace {

namespace fs = std::filesystem;

constexpr int kTagAsk = 1;     // rank -> 0: give me a job (no data)
constexpr int kTagJob = 2;     // 0 -> rank: the job's index, or kNoJob: stop
constexpr int kTagResult = 3;  // rank -> 0: the outcome (JSON), then its file's bytes
constexpr int kTagBytes = 4;
constexpr std::int64_t kNoJob = -1;
constexpr std::size_t kMaxMessage = std::size_t(1) << 30;  // bytes per MPI message

// Set by SIGTERM or SIGINT on rank 0: mpirun sends SIGTERM when a rank has died (or the user
// stops the batch). Rank 0 then finishes the copy it is making, closes the file (whole jobs
// only, batch_complete = 0) and exits.
std::atomic<bool> g_stop{false};
extern "C" void on_stop_signal(int) { g_stop = true; }

// Job indices in hand-out order: the largest estimate first, then batch order.
std::vector<std::size_t> hand_out_order(const BatchSpec& batch) {
  std::vector<std::uint64_t> est;
  for (const JobSpec& j : batch.jobs) est.push_back(estimate_job_bytes(j));
  std::vector<std::size_t> order(batch.jobs.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return est[a] > est[b]; });
  return order;
}

// Runs job i of the batch alone into a CL file of its own at `path`: the job's datasets are
// those a whole batch writes (run_batch writes each job the same whatever runs beside it).
JobOutcome run_alone(const BatchSpec& batch, std::size_t i, const fs::path& path, int rank) {
  BatchSpec one = batch;
  one.mpi_rank = rank;
  one.jobs = {batch.jobs[i]};
  one.output = path;
  one.concurrent_jobs = 1;
  try {
    return run_batch(one, BatchObserver{}).at(0);
  } catch (const std::exception& e) {
    JobOutcome o;
    o.name = batch.jobs[i].name;
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

// Where this process writes job i's own CL file: the temporary folder, so that a rank
// stopped half-way leaves nothing next to the output.
fs::path job_file(std::size_t i) {
  return fs::temp_directory_path() /
         ("ncpath-" + std::to_string(::getpid()) + "-" + std::to_string(i) + ".h5");
}

// The file's bytes; empty when it does not exist (the job could not create it).
std::string read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return {};
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// A rank other than 0: asks for jobs until told to stop, runs each, sends back its outcome
// and its CL file.
void work(const BatchSpec& batch, int rank) {
  for (;;) {
    MPI_Send(nullptr, 0, MPI_BYTE, 0, kTagAsk, MPI_COMM_WORLD);
    std::int64_t job = kNoJob;
    MPI_Recv(&job, 1, MPI_INT64_T, 0, kTagJob, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    if (job < 0) return;
    const fs::path path = job_file(std::size_t(job));
    const JobOutcome o = run_alone(batch, std::size_t(job), path, rank);
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

// Rank 0: hands jobs out, runs some itself, copies every job into the output in batch order.
class Coordinator {
 public:
  Coordinator(const BatchSpec& batch, const BatchObserver& obs, int ranks)
      : batch_(batch),
        obs_(obs),
        ranks_(ranks),
        order_(hand_out_order(batch)),
        have_(batch.jobs.size(), false) {
    result_.outcomes.resize(batch.jobs.size());
    result_.rank.assign(batch.jobs.size(), 0);
  }

  MpiBatchResult run() {
    std::optional<out::ClFile> file;
    try {
      file.emplace(batch_.output, NCPATH_VERSION);
      file->mark_batch(std::int64_t(batch_.jobs.size()), false);
      file_ = &*file;
    } catch (...) {
      error_ = std::current_exception();  // nothing is handed out; the ranks are stopped
    }
    local_running_ = !error_;
    std::thread local;
    if (local_running_) local = std::thread([this] { run_local(); });
    int stopped = 0;  // ranks told to stop
    while (stopped < ranks_ - 1 || busy()) {
      if (g_stop) stop_now(file);
      take_local_results();
      int flag = 0;
      MPI_Status st;
      MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &st);
      if (!flag) {
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
        continue;
      }
      if (st.MPI_TAG == kTagAsk) {
        MPI_Recv(nullptr, 0, MPI_BYTE, st.MPI_SOURCE, kTagAsk, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        const std::int64_t job = take();
        MPI_Send(&job, 1, MPI_INT64_T, st.MPI_SOURCE, kTagJob, MPI_COMM_WORLD);
        stopped += job < 0;
      } else if (st.MPI_TAG == kTagResult) {
        receive_result(st);
      }
    }
    if (local.joinable()) local.join();
    take_local_results();
    if (error_) std::rethrow_exception(error_);
    file->mark_batch(std::int64_t(batch_.jobs.size()), true);
    file->close();
    return std::move(result_);
  }

 private:
  void remove_spools() const {
    for (std::size_t i = 0; i < have_.size(); ++i) {
      std::error_code ec;
      fs::remove(job_file(i), ec);
    }
  }

  std::int64_t take() {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (error_ || g_stop || next_ >= order_.size()) return kNoJob;
    return std::int64_t(order_[next_++]);
  }

  // Removes the spool files, closes the file with the jobs copied so far (batch_complete
  // stays 0) and ends the process at once: the job rank 0 runs and the other ranks are not
  // waited for. The spool files go first: mpirun sends SIGKILL a second after SIGTERM, and
  // closing may wait for HDF5 while the job running here writes; once more after closing,
  // as that job may have created its file meanwhile (take() hands out no job once g_stop is
  // set). A SIGKILL can still leave one in the temporary folder.
  [[noreturn]] void stop_now(std::optional<out::ClFile>& file) {
    remove_spools();
    try {
      if (file) file->close();
    } catch (...) {
    }
    remove_spools();
    std::fprintf(stderr, "ncpath-mpi: stopped by a signal; %zu of %zu jobs are in %s\n", copied_,
                 have_.size(), batch_.output.string().c_str());
    std::_Exit(3);
  }

  // Whether rank 0 still runs a job, or a job handed out has not come back.
  bool busy() {
    const std::lock_guard<std::mutex> lock(mutex_);
    return local_running_ || next_ > finished_;
  }

  void run_local() {
    for (std::int64_t job; (job = take()) >= 0;) {
      const JobOutcome o = run_alone(batch_, std::size_t(job), job_file(std::size_t(job)), 0);
      const std::lock_guard<std::mutex> lock(mutex_);
      local_done_.emplace_back(std::size_t(job), o);
    }
    const std::lock_guard<std::mutex> lock(mutex_);
    local_running_ = false;
  }

  void take_local_results() {
    std::vector<std::pair<std::size_t, JobOutcome>> done;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      done.swap(local_done_);
    }
    for (auto& [i, o] : done) finished(i, std::move(o), 0);
  }

  void receive_result(const MPI_Status& st) {
    int len = 0;
    MPI_Get_count(&st, MPI_CHAR, &len);
    std::string head(std::size_t(len), '\0');
    MPI_Recv(head.data(), len, MPI_CHAR, st.MPI_SOURCE, kTagResult, MPI_COMM_WORLD,
             MPI_STATUS_IGNORE);
    const nlohmann::json j = nlohmann::json::parse(head);
    const auto i = j.at("index").get<std::size_t>();
    auto left = j.at("bytes").get<std::size_t>();
    std::ofstream out(job_file(i), std::ios::binary | std::ios::trunc);
    std::string buf;
    while (left > 0) {
      buf.resize(std::min(kMaxMessage, left));
      MPI_Recv(buf.data(), int(buf.size()), MPI_BYTE, st.MPI_SOURCE, kTagBytes, MPI_COMM_WORLD,
               MPI_STATUS_IGNORE);
      out.write(buf.data(), std::streamsize(buf.size()));
      left -= buf.size();
    }
    out.close();
    finished(i, outcome_of(j), st.MPI_SOURCE);
  }

  void finished(std::size_t i, JobOutcome o, int rank) {
    result_.outcomes[i] = std::move(o);
    result_.rank[i] = rank;
    have_[i] = true;
    ++finished_;
    if (obs_.job_finished) obs_.job_finished(i, result_.outcomes[i]);
    try {
      if (!error_) copy_in_order();
    } catch (...) {
      const std::lock_guard<std::mutex> lock(mutex_);
      error_ = std::current_exception();  // no more jobs are handed out
    }
  }

  // Copies the finished jobs into the output, in batch order, up to the first not finished.
  void copy_in_order() {
    for (; copied_ < have_.size() && have_[copied_]; ++copied_) {
      const JobSpec& job = batch_.jobs[copied_];
      const fs::path from = job_file(copied_);
      if (fs::exists(from)) {
        file_->copy_job(from, job.name);
      } else {  // the job could not create its file: its status alone
        out::JobInfo info;
        info.operation = operation_name(job.operation);
        info.input_path = job.input.string();
        out::ClJob cl = file_->begin_job(job.name, info);
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
  const std::vector<std::size_t> order_;
  std::vector<bool> have_;
  MpiBatchResult result_;
  out::ClFile* file_ = nullptr;
  std::size_t finished_ = 0, copied_ = 0;
  std::mutex mutex_;  // next_, local_done_, local_running_, error_
  std::size_t next_ = 0;
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
