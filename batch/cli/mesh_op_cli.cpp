#include "batch/cli/mesh_op_cli.hpp"

#include <string>

namespace ncpath::cli {

namespace {

// The ball-only mesh commands: the common options, G-code, and the tool described as a ball.
CLI::App* add_ball_command(CLI::App& app, const char* name, const char* description, Common& common,
                           GcodeCli& gcode) {
  CLI::App* cmd = app.add_subcommand(name, description);
  add_common(cmd, common);
  add_gcode(cmd, gcode);
  cmd->get_option("--tool")->description("Ball-end mill ball:D (mm); flat and bull are refused");
  return cmd;
}

// The options of a pencil run: the pencil command's, and the fillet command's for the pencil
// run of its reference ball.
void add_pencil_options(CLI::App* c, PencilParams& params, std::optional<double>& floor_z) {
  c->add_option("--interval", params.interval,
                "Distance between the drive planes that find the creases, both families (mm)")
      ->capture_default_str();
  c->add_option("--step-down", params.step_down,
                "Distance between the z-levels that find near-vertical creases (mm), 0 = none")
      ->capture_default_str();
  c->add_option("--min-angle", params.min_angle_deg,
                "Smallest bi-contact angle of a crease (degrees, between 0 and 180)")
      ->capture_default_str();
  c->add_option("--tolerance", params.tolerance,
                "Chord error bound of the traced paths and the gouge check (mm)")
      ->capture_default_str();
  c->add_option("--merge-distance", params.merge_distance,
                "Join pieces whose ends are closer than this (mm), 0 = twice the interval")
      ->capture_default_str();
  c->add_option("--min-length", params.min_length, "Drop pieces shorter than this (mm)")
      ->capture_default_str();
  c->add_option("--margin", params.margin, "Grow the part's xy box by this on every side (mm)")
      ->capture_default_str();
  c->add_option("--floor-z", floor_z,
                "Height where the tool touches nothing (mm); default: the part's lowest z");
}

// --stock and --direction: the pencil command's, and the fillet command's own.
void add_stock_direction(CLI::App* c, double& stock, std::string& direction, const char* stock_what,
                         const char* any_what) {
  c->add_option("--stock", stock,
                std::string("Material left on the part (mm), > -D/2: ") + stock_what +
                    " this far from it everywhere")
      ->capture_default_str();
  c->add_option("--direction", direction,
                std::string("Cut direction, spindle clockwise (M3): climb (the material on the "
                            "right of travel), conventional (on the left), or any (") +
                    any_what + ")")
      ->check(CLI::IsMember({"any", "climb", "conventional"}))
      ->capture_default_str();
}

// The job's direction from --direction, then its parameters' first problem: "" or the
// problem, starting with the key's name.
std::string direction_then(const std::string& text, CutDirection& out, const std::string& rest) {
  if (std::string e = jobs::parse_direction(text, out); !e.empty()) return "direction " + e;
  return rest;
}

}  // namespace

ZLevelCommand::ZLevelCommand(CLI::App& app) {
  cmd_ = add_ball_command(
      app, "zlevel",
      "Z-level contours with a ball-end mill: exact closed contours (lines, circular and "
      "elliptic arcs), junctions and bi-contact vectors at each level",
      common_, gcode_);
  levels_opt_ = cmd_->add_option("--levels", params_.levels,
                                 "Tool-tip heights of the contours (mm), comma-separated: "
                                 "10,20.5; give these or --step-down")
                    ->delimiter(',');
  step_opt_ = cmd_->add_option(
      "--step-down", params_.step_down,
      "Distance between levels (mm), from the part's top down while above its lowest point; "
      "give this or --levels");
  cmd_->add_option("--tolerance", params_.tolerance,
                   "Chordal tolerance of the arcs' polylines (mm); they never cut into the region")
      ->capture_default_str();
}

void ZLevelCommand::add_job(jobs::BatchSpec& batch, bool& quiet) const {
  jobs::JobSpec j = job_from(common_, jobs::Operation::kZLevel);
  j.zlevel = params_;
  // Exactly one of --levels and --step-down; checked here so that the job is recorded with
  // status invalid_parameter, like the same job in a batch file.
  const std::string e = jobs::check_zlevel_choice(levels_opt_->count() > 0, step_opt_->count() > 0,
                                                  params_, "--levels", "--step-down");
  if (!e.empty() && j.error.empty()) {
    j.error = e;
    j.error_status = "invalid_parameter";
  }
  add_mesh_job(common_, gcode_, std::move(j), validate(params_), batch, quiet);
}

PencilCommand::PencilCommand(CLI::App& app) {
  cmd_ = add_ball_command(
      app, "pencil",
      "Pencil-cut clean-up of concave creases with a ball-end mill: one path along each crease "
      "where the ball touches two surfaces at once",
      common_, gcode_);
  add_pencil_options(cmd_, params_, floor_z_);
  add_stock_direction(cmd_, params_.stock, direction_, "the ball keeps",
                      "oriented for short moves between the paths");
}

void PencilCommand::add_job(jobs::BatchSpec& batch, bool& quiet) const {
  jobs::JobSpec j = job_from(common_, jobs::Operation::kPencil);
  j.pencil = params_;
  j.pencil.floor_z = floor_z_;
  const std::string e =
      direction_then(direction_, j.pencil.direction, jobs::validate_pencil(j.pencil, j.tool));
  add_mesh_job(common_, gcode_, std::move(j), e, batch, quiet);
}

FilletCommand::FilletCommand(CLI::App& app) {
  cmd_ = add_ball_command(
      app, "fillet",
      "Fillet-cut clean-up with a ball-end mill smaller than the finishing (reference) ball: "
      "passes along the reference ball's pencil paths across the fillets it could not reach",
      common_, gcode_);
  cmd_->get_option("--tool")->description(
      "Clean-up ball-end mill ball:d (mm), smaller than --reference; flat and "
      "bull are refused");
  cmd_->add_option("--reference", reference_,
                   "The finishing ball whose creases are cleaned up: ball:D (mm), larger than "
                   "--tool")
      ->required();
  cmd_->add_option("--stepover", params_.stepover,
                   "Distance between neighbouring passes (mm), 0 = from --scallop")
      ->capture_default_str();
  scallop_opt_ = cmd_->add_option("--scallop", params_.scallop,
                                  "Cusp height left between passes (mm), when --stepover is 0")
                     ->capture_default_str();
  cmd_->add_option("--max-passes", params_.max_passes, "Most passes per pencil path")
      ->capture_default_str();
  add_stock_direction(cmd_, params_.stock, direction_, "both balls (tool and reference) keep",
                      "zig-zag passes linked at depth; climb and conventional cut one-way "
                      "passes joined by rapids");
  add_pencil_options(cmd_, params_.pencil, floor_z_);
}

void FilletCommand::add_job(jobs::BatchSpec& batch, bool& quiet) const {
  jobs::JobSpec j = job_from(common_, jobs::Operation::kFillet);
  j.fillet = params_;
  j.fillet.pencil.floor_z = floor_z_;
  j.fillet_reference = reference_;
  // The reference ball, then the spacing options; checked here so that the job is recorded
  // with status invalid_parameter, like the same job in a batch file.
  std::string e = jobs::parse_fillet_reference(reference_, j.tool, j.fillet);
  if (!e.empty())
    e = "--reference " + e;
  else
    e = jobs::check_fillet_spacing(scallop_opt_->count() > 0, j.fillet, "--stepover", "--scallop");
  if (!e.empty() && j.error.empty()) {
    j.error = e;
    j.error_status = "invalid_parameter";
  }
  const std::string v =
      direction_then(direction_, j.fillet.direction, jobs::validate_fillet(j.fillet, j.tool));
  add_mesh_job(common_, gcode_, std::move(j), v, batch, quiet);
}

}  // namespace ncpath::cli
