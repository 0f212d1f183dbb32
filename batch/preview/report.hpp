#pragma once
// `ncpath report out.h5 -o report.html` (docs/cli.md, "Previews and the batch report"): one
// self-contained HTML page for a CL file, readable with no network: CSS inline, pictures
// inline as PNG data. A table of the jobs, failed ones first (in batch order among
// themselves) with their messages, then the ok ones: a thumbnail linking to the job's full
// picture further down, status, operation, input, tool, points, path lengths by kind, time
// and the verifier's figures. Errors: std::runtime_error (unreadable CL file, unwritable
// page).
#include <cstddef>
#include <filesystem>

#include "batch/preview/preview.hpp"

namespace ncpath::preview {

struct ReportOptions {
  Options full{1000, 750};  // each job's picture
  Options thumb{320, 240};  // its thumbnail in the table
};

// Writes the page; returns the number of jobs in it.
std::size_t write_report(const std::filesystem::path& cl_file, const std::filesystem::path& html,
                         const ReportOptions& options = {});

}  // namespace ncpath::preview
