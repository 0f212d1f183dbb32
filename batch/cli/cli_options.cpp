#include "batch/cli/cli_options.hpp"

namespace ncpath::cli {

void add_common(CLI::App* app, Common& c) {
  app->add_option("--mesh", c.mesh, "Part mesh: STL (binary or ASCII) or OFF")->required();
  app->add_option("--tool", c.tool, "Cutter: ball:D, flat:D or bull:D:r (mm)")
      ->capture_default_str();
  app->add_option("--out", c.out, "HDF5 file to write (see docs/hdf5-schema.md)")
      ->capture_default_str();
  app->add_option("--name", c.name, "Job name inside the HDF5 file (default: the operation)");
  app->add_option("--threads", c.threads, "Worker threads, 0 = all cores")->capture_default_str();
  app->add_option(
      "--fit-xy", c.fit_xy,
      "Scale the mesh uniformly about the origin so its longest xy side is this many mm");
  app->add_option("--scale", c.scale, "Uniform scale factor (applied with --fit-xy)")
      ->capture_default_str();
  app->add_option("--translate", c.translate, "Translation x y z in mm, after scaling")
      ->expected(3);
  app->add_flag("-q,--quiet", c.quiet, "No progress bar");
}

void add_gcode(CLI::App* app, GcodeCli& g) {
  app->add_option("--gcode", g.path, "Also write the paths as G-code to this file (docs/gcode.md)");
  app->add_option("--dialect", g.dialect, "G-code dialect")
      ->check(CLI::IsMember({"linuxcnc", "grbl"}))
      ->capture_default_str();
  app->add_option("--feed", g.params.feed, "Cutting feed (mm/min)")->capture_default_str();
  app->add_option("--plunge-feed", g.params.plunge_feed, "Plunge feed (mm/min)")
      ->capture_default_str();
  app->add_option("--spindle", g.params.spindle_rpm, "Spindle speed (rev/min)")
      ->capture_default_str();
  app->add_option("--safe-z", g.safe_z,
                  "Safe height for rapid moves (mm); default: 5 above the part's top (meshes) "
                  "or 5 (pockets)");
  app->add_option("--verify", g.verify,
                  "Check the paths against the input (docs/cli.md): every move (full), every "
                  "8th move (sample) or none (off)")
      ->check(CLI::IsMember({"off", "sample", "full"}))
      ->capture_default_str();
  app->add_option("--preview", g.preview,
                  "Also draw the job (the part from above and its paths) into this .png or .svg");
}

void apply_gcode(const GcodeCli& g, jobs::JobSpec& j) {
  j.preview = g.preview;
  if (std::string e = jobs::parse_verify_mode(g.verify, j.verify); !e.empty() && j.error.empty()) {
    j.error = "--verify " + e;
    j.error_status = "invalid_parameter";
  }
  if (g.path.empty()) return;
  j.gcode = g.path;
  j.gcode_params = g.params;
  j.gcode_safe_z = g.safe_z;
  if (std::string e = jobs::parse_dialect(g.dialect, j.gcode_params.dialect);
      !e.empty() && j.error.empty()) {
    j.error = "--dialect: " + e;
    j.error_status = "invalid_parameter";
  }
}

jobs::JobSpec job_from(const Common& c, jobs::Operation op) {
  jobs::JobSpec j;
  j.operation = op;
  j.name = c.name.empty() ? jobs::operation_name(op) : c.name;
  j.input = c.mesh;
  j.tool_text = c.tool;
  if (std::string e = jobs::parse_tool(c.tool, j.tool); !e.empty()) {
    j.error = "--tool: " + e;
    j.error_status = "invalid_parameter";
  }
  j.transform.scale = c.scale;
  j.transform.fit_xy_mm = c.fit_xy;
  if (c.translate.size() == 3)
    j.transform.translate = Vec3(c.translate[0], c.translate[1], c.translate[2]);
  if (std::string e = validate(j.transform); !e.empty() && j.error.empty()) {
    j.error = "--" + e;
    j.error_status = "invalid_parameter";
  }
  return j;
}

void add_mesh_job(const Common& c, const GcodeCli& g, jobs::JobSpec j,
                  const std::string& param_error, jobs::BatchSpec& batch, bool& quiet) {
  if (!param_error.empty() && j.error.empty()) {
    // The key at the start of the message, as the option is spelled: floor_z -> --floor-z.
    std::string e = param_error;
    for (std::size_t i = 0; i < e.size() && e[i] != ' '; ++i)
      if (e[i] == '_') e[i] = '-';
    j.error = "--" + e;
    j.error_status = "invalid_parameter";
  }
  apply_gcode(g, j);
  batch.output = c.out;
  batch.threads = c.threads;
  quiet = c.quiet;
  batch.jobs.push_back(std::move(j));
}

}  // namespace ncpath::cli
