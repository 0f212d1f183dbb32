#pragma once
// A one-line progress bar on stderr, redrawn at most every 100 ms. Silent unless stderr is
// a terminal and the user did not ask for --quiet.
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
};

// True when stderr is a terminal.
bool stderr_is_terminal();

}  // namespace ncpath::cli
