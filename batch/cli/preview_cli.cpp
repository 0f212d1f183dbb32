#include "batch/cli/preview_cli.hpp"

#include <cstdio>
#include <exception>

#include "batch/output/cl_reader.hpp"
#include "batch/preview/preview.hpp"
#include "batch/preview/report.hpp"

namespace ncpath::cli {

CLI::App* add_preview_command(CLI::App& app, PictureCli& p) {
  CLI::App* cmd = app.add_subcommand(
      "preview", "Draw a job of a CL file: the part from above and its paths (docs/cli.md)");
  cmd->add_option("file", p.in, "HDF5 file written by ncpath")->required();
  cmd->add_option("--job", p.job, "The job to draw (needed when the file has several)");
  cmd->add_option("-o,--out", p.out, "Picture to write: .png or .svg")->required();
  cmd->add_option("--width", p.width, "Width in pixels")->capture_default_str();
  cmd->add_option("--height", p.height, "Height in pixels")->capture_default_str();
  return cmd;
}

CLI::App* add_report_command(CLI::App& app, PictureCli& r) {
  CLI::App* cmd = app.add_subcommand(
      "report", "Write one self-contained HTML page of a CL file's jobs (docs/cli.md)");
  cmd->add_option("file", r.in, "HDF5 file written by ncpath")->required();
  cmd->add_option("-o,--out", r.out, "HTML page to write")->required();
  return cmd;
}

int run_preview_command(const PictureCli& p) {
  try {
    std::string job = p.job;
    if (job.empty()) {
      const std::vector<out::StoredJob> jobs = out::read_jobs(p.in);
      if (jobs.size() != 1) {
        std::string names;
        for (const out::StoredJob& j : jobs) names += (names.empty() ? "" : ", ") + j.name;
        std::fprintf(stderr, "ncpath: %s has %zu jobs: name one with --job (%s)\n", p.in.c_str(),
                     jobs.size(), names.c_str());
        return 2;
      }
      job = jobs[0].name;
    }
    preview::write_preview(p.in, job, p.out, preview::Options{p.width, p.height});
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ncpath: %s\n", e.what());
    return 2;
  }
  return 0;
}

int run_report_command(const PictureCli& r) {
  try {
    const std::size_t n = preview::write_report(r.in, r.out);
    std::printf("ncpath: report of %zu job(s) -> %s\n", n, r.out.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ncpath: %s\n", e.what());
    return 2;
  }
  return 0;
}

bool write_batch_pictures(const jobs::BatchSpec& batch) {
  bool ok = true;
  for (const jobs::JobSpec& j : batch.jobs) {
    if (j.preview.empty()) continue;
    try {
      preview::write_preview(batch.output, j.name, j.preview);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "ncpath: preview of %s: %s\n", j.name.c_str(), e.what());
      ok = false;
    }
  }
  if (batch.report.empty()) return ok;
  try {
    preview::write_report(batch.output, batch.report);
    std::printf("ncpath: report -> %s\n", batch.report.string().c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ncpath: report: %s\n", e.what());
    ok = false;
  }
  return ok;
}

}  // namespace ncpath::cli
