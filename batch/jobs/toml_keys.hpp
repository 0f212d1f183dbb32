#pragma once
// Reading the keys of one TOML table of a batch file (a job, its `params`, `transform` or
// `gcode`): each read remembers its key, so that what is left over is reported as unknown,
// and the first problem is kept as a message naming the key ("'params.interval' must be a
// number"). Internal to the batch library: job_spec.cpp and the parsers of operations'
// parameters (mesh_op_params.cpp, profile_op_params.cpp, raster_scan_params.cpp).
#include <cstddef>
#include <cstdint>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <toml++/toml.h>

namespace ncpath::jobs {

class Keys {
 public:
  Keys(const toml::table& t, std::string prefix) : t_(t), prefix_(std::move(prefix)) {}

  bool number(const char* key, double& out) {
    const toml::node* n = take(key);
    if (!n) return false;
    if (auto v = n->value<double>()) {
      out = *v;
      return true;
    }
    fail(key, "must be a number");
    return false;
  }
  bool string(const char* key, std::string& out) {
    const toml::node* n = take(key);
    if (!n) return false;
    if (auto v = n->value<std::string>()) {
      out = *v;
      return true;
    }
    fail(key, "must be a string");
    return false;
  }
  bool numbers(const char* key, std::size_t count, double* out) {
    const toml::node* n = take(key);
    if (!n) return false;
    const toml::array* a = n->as_array();
    if (!a || a->size() != count) {
      fail(key, "must be an array of " + std::to_string(count) + " numbers");
      return false;
    }
    for (std::size_t i = 0; i < count; ++i) {
      auto v = (*a)[i].value<double>();
      if (!v) {
        fail(key, "must be an array of " + std::to_string(count) + " numbers");
        return false;
      }
      out[i] = *v;
    }
    return true;
  }
  // A count (chunk sizes, passes): a whole number from 1 to 1e6. False when absent or refused.
  bool whole_number(const char* key, std::uint32_t& out) {
    double v;
    if (!number(key, v)) return false;
    if (v >= 1 && v <= 1e6 && v == static_cast<std::uint32_t>(v)) {
      out = static_cast<std::uint32_t>(v);
      return true;
    }
    fail(key, "must be a whole number >= 1");
    return false;
  }
  // An array of any length (possibly empty) of numbers.
  bool number_list(const char* key, std::vector<double>& out) {
    const toml::node* n = take(key);
    if (!n) return false;
    const toml::array* a = n->as_array();
    std::vector<double> v;
    for (std::size_t i = 0; a && i < a->size(); ++i) {
      auto x = (*a)[i].value<double>();
      if (!x) break;
      v.push_back(*x);
    }
    if (!a || v.size() != a->size()) {
      fail(key, "must be an array of numbers");
      return false;
    }
    out = std::move(v);
    return true;
  }
  bool is_string(const char* key) const {
    const toml::node* n = t_.get(key);
    return n && n->is_string();
  }
  bool has(const char* key) const { return t_.get(key) != nullptr; }
  const toml::table* table(const char* key) {
    const toml::node* n = take(key);
    if (!n) return nullptr;
    if (const toml::table* t = n->as_table()) return t;
    fail(key, "must be a table");
    return nullptr;
  }
  void fail(const std::string& key, const std::string& what) {
    if (error.empty()) error = "'" + prefix_ + key + "' " + what;
  }
  // Call once every known key was read.
  void finish() {
    for (const auto& [k, v] : t_)
      if (!used_.count(std::string(k.str()))) fail(std::string(k.str()), "is not a known key");
  }
  std::string error;

 private:
  const toml::node* take(const char* key) {
    used_.insert(key);
    return t_.get(key);
  }
  const toml::table& t_;
  std::string prefix_;
  std::set<std::string> used_;
};

}  // namespace ncpath::jobs
