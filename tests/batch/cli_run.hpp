#pragma once
// Test helpers: run the ncpath program built next to the tests and read what it wrote.
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <sys/wait.h>

#include <gtest/gtest.h>

#include "batch/io/stl_writer.hpp"
#include "tests/batch/output/h5_read.hpp"
#include "tests/support/meshes.hpp"

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

// A clean output folder for the running test, `prefix` + its name, holding part.stl: a wavy
// height field over 40 x 40 mm.
inline std::filesystem::path part_dir(const std::string& prefix) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const auto dir = out::test::out_dir(prefix + (info ? info->name() : "none"));
  const TriangleMesh m = height_field(
      20, 40, [](double x, double y) { return 2 + std::sin(x / 5) * std::cos(y / 4); });
  io::write_binary_stl(dir / "part.stl", m);
  return dir;
}

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

}  // namespace ncpath::test
