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

// Runs a shell command line, stdout and stderr together.
inline CmdResult run_command(const std::string& command) {
  const std::string cmd = command + " 2>&1";
  CmdResult r{-1, ""};
  FILE* p = popen(cmd.c_str(), "r");
  std::array<char, 4096> buf;
  while (p && fgets(buf.data(), buf.size(), p)) r.output += buf.data();
  const int status = p ? pclose(p) : -1;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

inline CmdResult ncpath(const std::string& args) {
  return run_command(std::string(NCPATH_BINARY_DIR) + "/batch/ncpath " + args);
}

// Writes dir/batch.toml: seven jobs of five operations on dir/part.stl (one job names a
// missing file: it fails) and the plate pocket, output "x.h5".
inline void write_seven_job_batch(const std::filesystem::path& dir) {
  const std::string plate =
      (std::filesystem::path(NCPATH_SOURCE_DIR) / "datasets/pockets/plate.toml").string();
  std::ofstream(dir / "batch.toml")
      << "output = \"x.h5\"\nthreads = 2\n"
      << "[[job]]\nname = \"raster\"\ninput = \"part.stl\"\ntool = \"ball:4\"\n"
      << "params = { interval = 0.25, step = 0.05 }\n"
      << "[[job]]\nname = \"zlevel\"\noperation = \"zlevel\"\ninput = \"part.stl\"\n"
      << "tool = \"ball:4\"\nparams = { step_down = 0.5 }\n"
      << "[[job]]\nname = \"missing\"\ninput = \"none.stl\"\ntool = \"ball:4\"\n"
      << "[[job]]\nname = \"scan\"\noperation = \"scan\"\ninput = \"part.stl\"\n"
      << "tool = \"ball:5\"\ntransform = { scale = 1.5 }\nparams = { interval = 1 }\n"
      << "[[job]]\nname = \"pocket\"\noperation = \"pocket\"\ninput = \"" << plate
      << "\"\ntool = \"flat:8\"\nparams = { stepover = \"40%\", depth = 10, stepdown = 2.5 }\n"
      << "[[job]]\nname = \"pencil\"\noperation = \"pencil\"\ninput = \"part.stl\"\n"
      << "tool = \"ball:6\"\nparams = { interval = 0.5 }\n"
      << "[[job]]\nname = \"raster2\"\ninput = \"part.stl\"\ntool = \"flat:3\"\n"
      << "transform = { scale = 1.5 }\nparams = { interval = 0.5, step = 0.25 }\n";
}

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

}  // namespace ncpath::test
