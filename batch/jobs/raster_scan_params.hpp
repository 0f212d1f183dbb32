#pragma once
// Parameters of the raster and scan operations in batch files: reading the `params` table.
// The checks are validate(RasterParams) and validate(ScanParams) (engine/raster.hpp,
// engine/scan.hpp); parse_families and families_name are declared in job_spec.hpp.
// Internal to the batch library (job_spec.cpp); the keys are listed in docs/cli.md.
#include "batch/jobs/toml_keys.hpp"
#include "engine/raster.hpp"
#include "engine/scan.hpp"

namespace ncpath::jobs {

// raster: direction ("x" or "y"), interval, step, margin, rect, adaptive_tolerance, min_step,
// floor_z, chunk_lines, strip_height, bin_width. The first problem lands in k.error, named by
// its key.
void parse_raster_params(Keys& k, RasterParams& p);
// scan: families ("x", "y" or "both"), interval, tolerance, margin, rect, floor_z,
// chunk_planes.
void parse_scan_params(Keys& k, ScanParams& p);

}  // namespace ncpath::jobs
