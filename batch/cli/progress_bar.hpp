#pragma once
// A one-line progress bar on stderr, redrawn at most every 100 ms, with the time left in the
// current stage. Silent unless stderr is a terminal and the user did not ask for --quiet.
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <map>
#include <mutex>
#include <string>

namespace ncpath::cli {

class ProgressBar {
 public:
  explicit ProgressBar(bool enabled);
  // A new stage; the ETA counts from `started`.
  void start(const std::string& label,
             std::chrono::steady_clock::time_point started = std::chrono::steady_clock::now());
  void update(std::uint64_t done, std::uint64_t total);
  void finish();  // clears the line

 private:
  bool enabled_;
  std::string label_;
  std::chrono::steady_clock::time_point last_{};
  std::chrono::steady_clock::time_point started_{};
};

// The progress of a batch whose jobs may run at the same time, on one line:
// "[3/10 done, 2 running] name [####......]  40% ETA 12s", the bar of the job that reported
// last. Thread-safe: jobs report from their own threads.
class BatchProgress {
 public:
  BatchProgress(bool enabled, std::size_t jobs);
  void started(std::size_t index, const std::string& name);
  void update(std::size_t index, std::uint64_t done, std::uint64_t total);
  void finished(std::size_t index);
  void clear();

 private:
  struct Running {
    std::string name;
    std::chrono::steady_clock::time_point started;
  };
  void show(std::size_t index);  // holding mutex_

  std::mutex mutex_;
  ProgressBar bar_;
  std::size_t jobs_;
  std::size_t done_ = 0;
  std::map<std::size_t, Running> running_;
  std::size_t shown_ = 0;  // the job whose bar is on the line
  bool stale_ = true;      // jobs started or ended since the line's label was made
  std::chrono::steady_clock::time_point drawn_{};
};

// "ETA 1m05s" for a stage `elapsed_s` into it with `done` of `total` units done (the rest at
// the same pace); "" before the first unit or at the end.
std::string eta_text(double elapsed_s, std::uint64_t done, std::uint64_t total);

// True when stderr is a terminal.
bool stderr_is_terminal();

}  // namespace ncpath::cli
