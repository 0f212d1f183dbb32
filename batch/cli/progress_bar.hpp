#pragma once
// A one-line progress bar on stderr, redrawn at most every 100 ms, with the time left in the
// current stage. Silent unless stderr is a terminal and the user did not ask for --quiet.
#include <chrono>
#include <cstdint>
#include <string>

namespace ncpath::cli {

class ProgressBar {
 public:
  explicit ProgressBar(bool enabled);
  void start(const std::string& label);
  void update(std::uint64_t done, std::uint64_t total);
  void finish();  // clears the line

 private:
  bool enabled_;
  std::string label_;
  std::chrono::steady_clock::time_point last_{};
  std::chrono::steady_clock::time_point started_{};
};

// "ETA 1m05s" for a stage `elapsed_s` into it with `done` of `total` units done (the rest at
// the same pace); "" before the first unit or at the end.
std::string eta_text(double elapsed_s, std::uint64_t done, std::uint64_t total);

// True when stderr is a terminal.
bool stderr_is_terminal();

}  // namespace ncpath::cli
