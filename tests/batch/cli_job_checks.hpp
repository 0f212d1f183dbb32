#pragma once
// Test helpers of the mesh operation command tests (scan, zlevel, pencil, fillet): the checks
// each of them makes of a run of the ncpath program and of the job it recorded (status ok,
// one and two threads writing the same bytes, the problems a user can make named on the
// command line and in a batch file), so that each test states only what is its own.
#include <gtest/gtest.h>

#include <filesystem>
#include <initializer_list>
#include <stdexcept>
#include <string>
#include <vector>

#include "tests/batch/cli_run.hpp"
#include "tests/batch/output/h5_read.hpp"

namespace ncpath::cli_checks {

namespace h5 = out::test;

// Job `job` of file f: `operation` (unless empty), each of `params` in its params text, and
// status ok (else its message: a fatal failure, so wrap the call in ASSERT_NO_FATAL_FAILURE
// where the test cannot go on without the job).
inline void expect_job_ok(hid_t f, const std::string& job, const std::string& operation,
                          std::initializer_list<const char*> params = {}) {
  h5::Id g(H5Gopen2(f, ("/jobs/" + job).c_str(), H5P_DEFAULT));
  if (!operation.empty()) {
    EXPECT_EQ(h5::attr_str(g, "operation"), operation);
  }
  const std::string text = h5::attr_str(g, "params");
  for (const char* p : params) EXPECT_NE(text.find(p), std::string::npos) << p << " in " << text;
  ASSERT_EQ(h5::attr_str(g, "status"), "ok") << h5::attr_str(g, "message");
}

// The G-code file at `path` contains each of `words`.
inline void expect_gcode_has(const std::filesystem::path& path,
                             std::initializer_list<const char*> words) {
  const std::string g = test::slurp(path);
  for (const char* w : words) EXPECT_NE(g.find(w), std::string::npos) << w << " in " << path;
}

// The raw bytes of a dataset, read in its own (native) type.
inline std::vector<unsigned char> raw(hid_t f, const std::string& path) {
  h5::Id ds(H5Dopen2(f, path.c_str(), H5P_DEFAULT), "open " + path);
  h5::Id file_type(H5Dget_type(ds));
  h5::Id type(H5Tget_native_type(file_type, H5T_DIR_ASCEND));
  h5::Id space(H5Dget_space(ds));
  std::vector<unsigned char> out(H5Sget_simple_extent_npoints(space) * H5Tget_size(type));
  if (!out.empty() && H5Dread(ds, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) < 0)
    throw std::runtime_error("read " + path);
  return out;
}

// Dataset `path` is not empty in file a and has the same bytes in file b.
inline void expect_same_dataset(hid_t a, hid_t b, const std::string& path) {
  const std::vector<unsigned char> x = raw(a, path);
  EXPECT_GT(x.size(), 0u) << path;
  EXPECT_TRUE(x == raw(b, path)) << path;
}

// Runs the batch file dir/jobs.toml with 1 and with 2 threads, into dir/t1.h5 and dir/t2.h5;
// a fatal failure when a run does not exit with 0 (wrap the call in ASSERT_NO_FATAL_FAILURE).
inline void run_with_one_and_two_threads(const std::filesystem::path& dir) {
  for (const char* t : {"1", "2"}) {
    const test::CmdResult r =
        test::ncpath("run " + (dir / "jobs.toml").string() + " --quiet --threads " + t + " --out " +
                     (dir / (std::string("t") + t + ".h5")).string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
}

// `command args --quiet --out dir/bad.h5` exits with 1 naming invalid_parameter and
// `expected`; the file records the job (named for the command) with that status and a
// message that contains `expected`.
inline void expect_failure(const std::filesystem::path& dir, const std::string& command,
                           const std::string& args, const std::string& expected) {
  const std::string out = (dir / "bad.h5").string();
  const test::CmdResult r = test::ncpath(command + " " + args + " --quiet --out " + out);
  EXPECT_EQ(r.exit_code, 1) << args << "\n" << r.output;
  EXPECT_NE(r.output.find("invalid_parameter"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(expected), std::string::npos) << expected << " in: " << r.output;
  h5::Id f = h5::open_read(out);
  h5::Id job(H5Gopen2(f, ("/jobs/" + command).c_str(), H5P_DEFAULT));
  EXPECT_EQ(h5::attr_str(job, "status"), "invalid_parameter");
  EXPECT_NE(h5::attr_str(job, "message").find(expected), std::string::npos)
      << h5::attr_str(job, "message");
}

// The command line refused before anything runs (by CLI11), naming `option`.
inline void expect_refused(const std::string& args, const std::string& option) {
  const test::CmdResult r = test::ncpath(args);
  EXPECT_NE(r.exit_code, 0) << args;
  EXPECT_NE(r.output.find(option), std::string::npos) << r.output;
}

// A job of a batch file that must fail, and words of its message.
struct BadJob {
  const char* name;
  const char* message;
};

// Runs the batch file dir/jobs.toml, whose output is dir/batch.h5: exit code 1 and `summary`
// ("N job(s), G ok, B failed") in the output; each of `bad` recorded with status
// invalid_parameter and its message, each of `good` with status ok.
inline void expect_bad_jobs_named(const std::filesystem::path& dir, const std::string& summary,
                                  std::initializer_list<BadJob> bad,
                                  std::initializer_list<const char*> good) {
  const test::CmdResult b = test::ncpath("run " + (dir / "jobs.toml").string() + " --quiet");
  EXPECT_EQ(b.exit_code, 1) << b.output;
  EXPECT_NE(b.output.find(summary), std::string::npos) << b.output;
  h5::Id f = h5::open_read(dir / "batch.h5");
  for (const auto& [name, message] : bad) {
    h5::Id job(H5Gopen2(f, (std::string("/jobs/") + name).c_str(), H5P_DEFAULT));
    EXPECT_EQ(h5::attr_str(job, "status"), "invalid_parameter") << name;
    EXPECT_NE(h5::attr_str(job, "message").find(message), std::string::npos)
        << name << ": " << h5::attr_str(job, "message");
  }
  for (const char* name : good) {
    h5::Id job(H5Gopen2(f, (std::string("/jobs/") + name).c_str(), H5P_DEFAULT));
    EXPECT_EQ(h5::attr_str(job, "status"), "ok") << name << ": " << h5::attr_str(job, "message");
  }
}

}  // namespace ncpath::cli_checks
