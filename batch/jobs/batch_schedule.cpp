#include "batch/jobs/batch_schedule.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "batch/io/mesh_reader.hpp"

namespace ncpath::jobs {

namespace {

constexpr std::uint64_t kMiB = 1024 * 1024;
// What any job holds besides its mesh: the output writer's chunks, the tool, small inputs.
constexpr std::uint64_t kJobBaseBytes = 64 * kMiB;

// Peak bytes per facet of the mesh, by operation: peak RSS over facets on bunny00
// Loop-subdivided twice (1,206,528 facets, binary STL, ball 5, fit to 200 mm, verify on;
// docs/performance.md "Memory per facet"), rounded up with a quarter spare. Scan and the
// z-level family grow with the number of planes and levels too; these are at the measured
// intervals (scan and pencil 0.5 mm, z-levels 1 mm step-down).
std::uint64_t bytes_per_facet(Operation op) {
  switch (op) {
    // clang-format off
    case Operation::kRaster: return 900;
    case Operation::kDrop: return 900;
    case Operation::kScan: return 1500;
    case Operation::kZLevel: return 2000;
    case Operation::kPencil: return 1250;
    case Operation::kFillet: return 1250;
    default: return 0;
    // clang-format on
  }
}

}  // namespace

std::uint64_t estimate_job_bytes(const JobSpec& job) {
  const std::uint64_t per_facet = job.error.empty() ? bytes_per_facet(job.operation) : 0;
  if (per_facet == 0) return kJobBaseBytes;
  const std::uint64_t facets = io::facet_count_hint(job.input);  // a header may say anything
  const std::uint64_t most = std::numeric_limits<std::uint64_t>::max() / 2;
  return facets > most / per_facet ? most : kJobBaseBytes + per_facet * facets;
}

std::uint64_t default_memory_limit() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  std::uint64_t kib = 0;
  std::string unit;
  while (in >> key >> kib >> unit)
    if (key == "MemAvailable:") return kib * 1024 / 4 * 3;
  return 4096 * kMiB;
}

std::string parse_byte_size(const std::string& text, std::uint64_t& bytes) {
  std::istringstream in(text);
  double value = 0;
  std::string suffix;
  if (!(in >> value) || !std::isfinite(value) || value <= 0)
    return "'" + text + "' is not a size like 8G, 512M or 2048";
  in >> suffix;
  std::transform(suffix.begin(), suffix.end(), suffix.begin(),
                 [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  const std::string units = "KMGT";
  double scale = 1;
  std::string rest = suffix;
  if (!rest.empty() && units.find(rest[0]) != std::string::npos) {
    scale = std::pow(1024.0, static_cast<double>(units.find(rest[0]) + 1));
    rest.erase(0, 1);
  }
  std::string extra;
  const bool known = rest.empty() || rest == "B" || (scale > 1 && rest == "IB");
  if (!known || in >> extra)
    return "'" + text + "' has an unknown unit (use K, M, G or T, binary multiples)";
  if (value * scale < 1 || value * scale > 1e19) return "'" + text + "' is out of range";
  bytes = static_cast<std::uint64_t>(value * scale);
  return "";
}

Admission::Admission(std::vector<std::uint64_t> estimates, std::uint64_t limit, std::size_t slots)
    : estimates_(std::move(estimates)),
      limit_(limit),
      slots_(std::max<std::size_t>(slots, 1)),
      running_flag_(estimates_.size(), false) {}

std::vector<std::size_t> Admission::start_ready() {
  std::vector<std::size_t> ready;
  while (next_ < estimates_.size() &&
         (running_ == 0 || (running_ < slots_ && estimates_[next_] <= limit_ &&
                            in_use_ <= limit_ - estimates_[next_]))) {
    running_flag_[next_] = true;
    in_use_ += estimates_[next_];
    ++running_;
    ready.push_back(next_++);
  }
  return ready;
}

void Admission::finished(std::size_t job) {
  if (job >= estimates_.size() || !running_flag_[job])
    throw std::logic_error("Admission::finished: job " + std::to_string(job) + " is not running");
  running_flag_[job] = false;
  in_use_ -= estimates_[job];
  --running_;
}

}  // namespace ncpath::jobs
