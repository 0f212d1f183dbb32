#pragma once
// `ncpath preview out.h5 [--job NAME] -o picture.png|svg` and `ncpath report out.h5 -o
// report.html` (batch/preview/preview.hpp, report.hpp; docs/cli.md), and the pictures a batch
// asks for when it ends (jobs' `preview`, the batch's `report`).
#include <CLI/CLI.hpp>

#include <string>

#include "batch/jobs/job_spec.hpp"

namespace ncpath::cli {

struct PictureCli {
  std::string in, job, out;
  int width = 1200, height = 900;
};

CLI::App* add_preview_command(CLI::App& app, PictureCli& p);
CLI::App* add_report_command(CLI::App& app, PictureCli& r);

// 0: written; 2: the file, the job or the picture could not be read or written (message on
// stderr; a file of several jobs needs --job).
int run_preview_command(const PictureCli& p);
int run_report_command(const PictureCli& r);

// After a batch has written its file: each job's `preview` picture and the batch's `report`
// page, when asked for. Problems are printed (the batch's results stand); false when any.
bool write_batch_pictures(const jobs::BatchSpec& batch);

}  // namespace ncpath::cli
