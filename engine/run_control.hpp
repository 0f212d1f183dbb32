#pragma once
// Progress and cancellation, checked by the engine once per chunk of work (never inside a
// kernel), plus the small measuring tools every stage uses.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>

namespace ncpath {

struct RunControl {
  // Called from the thread that drives the operation (never concurrently) with the units
  // done so far and the total (e.g. scan lines).
  std::function<void(std::uint64_t done, std::uint64_t total)> progress;
  std::atomic<bool> cancel{false};  // set from anywhere; the run stops at the next chunk
};

// Thrown by an operation that saw RunControl::cancel.
struct Cancelled {};

class Stopwatch {
 public:
  Stopwatch() : t0_(std::chrono::steady_clock::now()) {}
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
  }

 private:
  std::chrono::steady_clock::time_point t0_;
};

// Peak resident set size of this process so far, bytes (VmHWM).
std::uint64_t peak_rss_bytes();

}  // namespace ncpath
