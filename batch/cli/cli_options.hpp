#pragma once
// Options and helpers the mesh commands of the ncpath CLI share (raster, scan, zlevel, pencil,
// fillet, drop): the mesh, tool, output and transform options, the G-code options, and turning
// them into the JobSpec a batch file would give.
#include <CLI/CLI.hpp>

#include <optional>
#include <string>
#include <vector>

#include "batch/jobs/job_spec.hpp"

namespace ncpath::cli {

struct Common {
  std::string mesh, tool = "ball:5", out = "ncpath-out.h5", name;
  int threads = 0;
  bool quiet = false;
  std::optional<double> fit_xy;
  double scale = 1;
  std::vector<double> translate;
};

// --mesh, --tool, --out, --name, --threads, --fit-xy, --scale, --translate, --quiet.
void add_common(CLI::App* app, Common& c);

struct GcodeCli {
  std::string path, dialect = "linuxcnc";
  out::GcodeParams params;
  std::optional<double> safe_z;
  std::string verify = "full";  // --verify: off, sample or full (every command has it)
  std::string preview;          // --preview: a picture of the job (every command has it)
};

// --gcode, --dialect, --feed, --plunge-feed, --spindle, --safe-z, and --verify and --preview.
void add_gcode(CLI::App* app, GcodeCli& g);
void apply_gcode(const GcodeCli& g, jobs::JobSpec& j);

// The job of a mesh command with the common options; a bad tool or transform is its error.
jobs::JobSpec job_from(const Common& c, jobs::Operation op);

// Adds the job of a mesh command (raster, scan, zlevel, pencil, fillet, drop) to the batch:
// `param_error` (the first problem of its parameters, "" when none, starting with the key's
// name as in a batch file: "min_angle must be ...") is reported as the option ("--min-angle
// must be ...") unless the tool or transform is bad.
void add_mesh_job(const Common& c, const GcodeCli& g, jobs::JobSpec j,
                  const std::string& param_error, jobs::BatchSpec& batch, bool& quiet);

}  // namespace ncpath::cli
