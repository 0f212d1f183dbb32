#include "batch/cli/progress_bar.hpp"

#include <unistd.h>

#include <cstdio>

namespace ncpath::cli {

bool stderr_is_terminal() { return isatty(STDERR_FILENO) == 1; }

ProgressBar::ProgressBar(bool enabled) : enabled_(enabled) {}

std::string eta_text(double elapsed_s, std::uint64_t done, std::uint64_t total) {
  if (done == 0 || done >= total || !(elapsed_s >= 0)) return "";
  const double left = elapsed_s * static_cast<double>(total - done) / static_cast<double>(done);
  const auto s = static_cast<long long>(left + 0.5);
  char buf[48];
  if (s >= 3600)
    std::snprintf(buf, sizeof buf, "ETA %lldh%02lldm", s / 3600, s / 60 % 60);
  else if (s >= 60)
    std::snprintf(buf, sizeof buf, "ETA %lldm%02llds", s / 60, s % 60);
  else
    std::snprintf(buf, sizeof buf, "ETA %llds", s);
  return buf;
}

void ProgressBar::start(const std::string& label, std::chrono::steady_clock::time_point started) {
  label_ = label;
  last_ = {};
  started_ = started;
}

void ProgressBar::update(std::uint64_t done, std::uint64_t total) {
  if (!enabled_ || total == 0) return;
  const auto now = std::chrono::steady_clock::now();
  if (done < total && now - last_ < std::chrono::milliseconds(100)) return;
  last_ = now;
  constexpr int kWidth = 30;
  const int fill = static_cast<int>(kWidth * done / total);
  std::string bar(fill, '#');
  bar.resize(kWidth, '.');
  const double elapsed = std::chrono::duration<double>(now - started_).count();
  std::fprintf(stderr, "\r%s [%s] %3d%% %s\033[K", label_.c_str(), bar.c_str(),
               static_cast<int>(100 * done / total), eta_text(elapsed, done, total).c_str());
  std::fflush(stderr);
}

void ProgressBar::finish() {
  if (!enabled_) return;
  std::fprintf(stderr, "\r\033[K");
  std::fflush(stderr);
}

BatchProgress::BatchProgress(bool enabled, std::size_t jobs) : bar_(enabled), jobs_(jobs) {}

void BatchProgress::show(std::size_t index) {
  const Running& r = running_.at(index);
  shown_ = index;
  stale_ = false;
  bar_.start("[" + std::to_string(done_) + "/" + std::to_string(jobs_) + " done, " +
                 std::to_string(running_.size()) + " running] " + r.name,
             r.started);
}

void BatchProgress::started(std::size_t index, const std::string& name) {
  const std::lock_guard<std::mutex> lock(mutex_);
  running_[index] = {name, std::chrono::steady_clock::now()};
  stale_ = true;
}

void BatchProgress::update(std::size_t index, std::uint64_t done, std::uint64_t total) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (running_.count(index) == 0) return;
  // At most every 100 ms whichever job reports (switching the bar's job would redraw).
  const auto now = std::chrono::steady_clock::now();
  if (done < total && now - drawn_ < std::chrono::milliseconds(100)) return;
  drawn_ = now;
  if (stale_ || shown_ != index) show(index);
  bar_.update(done, total);
}

void BatchProgress::finished(std::size_t index) {
  const std::lock_guard<std::mutex> lock(mutex_);
  running_.erase(index);
  ++done_;
  stale_ = true;
  bar_.finish();
}

void BatchProgress::clear() {
  const std::lock_guard<std::mutex> lock(mutex_);
  bar_.finish();
}

}  // namespace ncpath::cli
