#pragma once
// `ncpath verify --in out.h5 [--job NAME]`: re-checks the paths stored in a CL file against
// each job's input (read again from the paths in the job's attributes), as the verifier in
// every job does (batch/jobs/job_verify.hpp). Prints one line per job.
#include <CLI/CLI.hpp>

#include <string>

namespace ncpath::cli {

struct VerifyCli {
  std::string in, job;
  int threads = 0;
};

CLI::App* add_verify_command(CLI::App& app, VerifyCli& v);

// 0: every checked job is clean; 1: some job gouges; 2: the file or a job cannot be read.
int run_verify_command(const VerifyCli& v);

}  // namespace ncpath::cli
