#pragma once
// Test helpers: run the ncpath program built next to the tests and read what it wrote.
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <sys/wait.h>

namespace ncpath::test {

struct CmdResult {
  int exit_code;
  std::string output;  // stdout and stderr together
};

inline CmdResult ncpath(const std::string& args) {
  const std::string cmd = std::string(NCPATH_BINARY_DIR) + "/batch/ncpath " + args + " 2>&1";
  CmdResult r{-1, ""};
  FILE* p = popen(cmd.c_str(), "r");
  std::array<char, 4096> buf;
  while (p && fgets(buf.data(), buf.size(), p)) r.output += buf.data();
  const int status = p ? pclose(p) : -1;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

}  // namespace ncpath::test
