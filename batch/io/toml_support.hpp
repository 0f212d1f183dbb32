#pragma once
// Internal to batch/io's TOML readers (profile_toml.cpp, surface_toml.cpp): errors that name
// the file, the line and the table, and the key checks both formats share. Includes toml++:
// keep it out of headers that others include.
#include <toml++/toml.h>

#include <filesystem>
#include <initializer_list>
#include <string>
#include <string_view>

#include "batch/io/read_error.hpp"

namespace ncpath::io::detail {

class TomlChecks {
 public:
  explicit TomlChecks(std::filesystem::path path) : path_(std::move(path)) {}

  // "<file>: line N: <what>: <msg>".
  [[noreturn]] void fail(const toml::node& at, const std::string& what,
                         const std::string& msg) const {
    throw ReadError(path_, "line " + std::to_string(at.source().begin.line), what + ": " + msg);
  }
  // Every key of t must be one of `allowed`; else "unknown key 'k' (expected a, b, c)".
  void check_keys(const toml::table& t, const std::string& what,
                  std::initializer_list<std::string_view> allowed) const {
    for (const auto& [key, node] : t) {
      bool ok = false;
      std::string list;
      for (std::string_view a : allowed) {
        ok = ok || key.str() == a;
        list += (list.empty() ? "" : ", ") + std::string(a);
      }
      if (!ok)
        fail(node, what, "unknown key '" + std::string(key.str()) + "' (expected " + list + ")");
    }
  }
  // The node at `key`; else "missing key 'k'".
  const toml::node& need(const toml::table& t, std::string_view key,
                         const std::string& what) const {
    const toml::node* n = t.get(key);
    if (!n) fail(t, what, "missing key '" + std::string(key) + "'");
    return *n;
  }
  const std::filesystem::path& path() const { return path_; }

 protected:
  std::filesystem::path path_;
};

}  // namespace ncpath::io::detail
