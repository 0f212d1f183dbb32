#include "batch/cli/verify_cli.hpp"

#include <cmath>
#include <cstdio>
#include <exception>
#include <memory>

#include "batch/io/mesh_reader.hpp"
#include "batch/jobs/job_verify.hpp"
#include "batch/output/cl_reader.hpp"
#include "engine/parallel.hpp"

namespace ncpath::cli {

namespace {

using jobs::Operation;

std::unique_ptr<jobs::JobVerifier> verifier_for(const jobs::JobSpec& spec) {
  if (spec.operation == Operation::kOffset || spec.operation == Operation::kPocket ||
      spec.operation == Operation::kPocket3d)
    return jobs::profile_verifier(spec);
  io::MeshReadResult in = io::read_mesh(spec.input);
  const TransformOutcome tr = apply_transform(spec.transform, in.mesh);
  if (!tr.ok()) throw std::invalid_argument("transform." + tr.error);
  auto index = std::make_shared<const MeshVerifier>(in.mesh);
  return jobs::mesh_verifier(spec, [index] { return index; });
}

// Checks one stored job; prints its line. Returns true when it is clean.
bool verify_one(const std::string& file, const out::StoredJob& job) {
  jobs::JobSpec spec =
      jobs::stored_job_spec(job.operation, job.input_path, job.tool_json, job.params_json);
  spec.verify = jobs::VerifyMode::kFull;
  if (spec.operation == Operation::kDrop) {
    std::printf("%s: %s: not verified (a probe: its points are answers, not moves)\n",
                job.name.c_str(), job.operation.c_str());
    return true;
  }
  std::unique_ptr<jobs::JobVerifier> v = verifier_for(spec);
  out::read_paths(file, job.name, [&](const ClChunk& c) { v->feed(c); });
  std::vector<out::StatValue> stats;
  const VerifyReport& r = v->finish(stats);
  std::printf("%s: %s, %llu moves, max gouge %.3g mm", job.name.c_str(), job.operation.c_str(),
              static_cast<unsigned long long>(r.moves), r.max_gouge);
  if (std::isfinite(r.min_clearance)) std::printf(", min clearance %.3g mm", r.min_clearance);
  for (const out::StatValue& s : stats)
    if (s.name == "verify_max_scallop")
      std::printf(", max scallop %.3g mm", std::get<double>(s.value));
  const std::string failure = jobs::verification_failure(r);
  std::printf("%s%s\n", failure.empty() ? ": ok" : ": ", failure.c_str());
  return failure.empty();
}

}  // namespace

CLI::App* add_verify_command(CLI::App& app, VerifyCli& v) {
  CLI::App* cmd = app.add_subcommand(
      "verify", "Re-check the paths of a CL file against each job's input (docs/cli.md)");
  cmd->add_option("--in", v.in, "HDF5 file written by ncpath")->required();
  cmd->add_option("--job", v.job, "Only this job (default: every job)");
  cmd->add_option("--threads", v.threads, "Worker threads, 0 = all cores")->capture_default_str();
  return cmd;
}

int run_verify_command(const VerifyCli& v) {
  par::ThreadLimit limit(v.threads);
  std::vector<out::StoredJob> stored;
  try {
    stored = out::read_jobs(v.in);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ncpath: %s\n", e.what());
    return 2;
  }
  int code = 0;
  bool found = false;
  for (const out::StoredJob& job : stored) {
    if (!v.job.empty() && job.name != v.job) continue;
    found = true;
    if (job.status != "ok" && job.status != "failed_verification") {
      std::printf("%s: %s: skipped (status %s)\n", job.name.c_str(), job.operation.c_str(),
                  job.status.c_str());
      continue;
    }
    try {
      if (!verify_one(v.in, job)) code = std::max(code, 1);
    } catch (const std::exception& e) {
      std::printf("%s: cannot verify: %s\n", job.name.c_str(), e.what());
      code = 2;
    }
  }
  if (!found) {
    std::fprintf(stderr, "ncpath: %s: no job named '%s'\n", v.in.c_str(), v.job.c_str());
    return 2;
  }
  return code;
}

}  // namespace ncpath::cli
