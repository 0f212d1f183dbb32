#include "batch/jobs/mesh_op_params.hpp"

#include <cmath>
#include <sstream>

#include "batch/jobs/job_spec.hpp"

namespace ncpath::jobs {

std::string check_zlevel_choice(bool has_levels, bool has_step_down, const ZLevelOpParams& p,
                                const std::string& levels_key, const std::string& step_key) {
  const std::string what = " (" + levels_key + ": tool-tip heights, mm; " + step_key +
                           ": mm between levels, down from the part's top)";
  std::ostringstream os;
  if (has_levels && has_step_down)
    os << levels_key << " and " << step_key << " are both given: give one of them" << what;
  else if (!has_levels && !has_step_down)
    os << levels_key << " or " << step_key << " is required for a zlevel job" << what;
  else if (has_levels && p.levels.empty())
    os << levels_key << " must hold at least one tool-tip height (mm)";
  else if (has_step_down && !(std::isfinite(p.step_down) && p.step_down > 0))
    os << step_key << " must be a positive number of mm, got " << p.step_down;
  return os.str();
}

void parse_zlevel_params(Keys& k, ZLevelOpParams& p) {
  const bool has_levels = k.has("levels"), has_step_down = k.has("step_down");
  k.number_list("levels", p.levels);
  k.number("step_down", p.step_down);
  k.number("tolerance", p.tolerance);
  k.whole_number("chunk_levels", p.chunk_levels);
  if (k.error.empty())
    k.error =
        check_zlevel_choice(has_levels, has_step_down, p, "'params.levels'", "'params.step_down'");
}

namespace {

// The keys that say how pencil paths are found: a pencil job's, and a fillet job's for its
// reference run.
void parse_pencil_search(Keys& k, PencilParams& p) {
  k.number("interval", p.interval);
  k.number("step_down", p.step_down);
  k.number("min_angle", p.min_angle_deg);
  k.number("tolerance", p.tolerance);
  k.number("merge_distance", p.merge_distance);
  k.number("min_length", p.min_length);
  k.number("margin", p.margin);
  double floor_z;
  if (k.number("floor_z", floor_z)) p.floor_z = floor_z;
}

// stock and direction: a pencil job's, or a fillet job's own.
void parse_stock_direction(Keys& k, double& stock, CutDirection& direction) {
  k.number("stock", stock);
  std::string text;
  if (k.string("direction", text))
    if (std::string e = parse_direction(text, direction); !e.empty()) k.fail("direction", e);
}

void pencil_search_json(const PencilParams& p, nlohmann::ordered_json& j) {
  j["interval"] = p.interval;
  j["step_down"] = p.step_down;
  j["min_angle"] = p.min_angle_deg;
  j["tolerance"] = p.tolerance;
  j["merge_distance"] = p.merge_distance;
  j["min_length"] = p.min_length;
  j["margin"] = p.margin;
  j["floor_z"] = p.floor_z ? nlohmann::ordered_json(*p.floor_z) : nlohmann::ordered_json(nullptr);
}

}  // namespace

std::string parse_direction(const std::string& text, CutDirection& out) {
  if (parse_cut_direction(text, out)) return "";
  return "must be \"any\", \"climb\" or \"conventional\", got \"" + text + "\"";
}

void parse_pencil_params(Keys& k, PencilParams& p) {
  parse_pencil_search(k, p);
  parse_stock_direction(k, p.stock, p.direction);
}

std::string parse_fillet_reference(const std::string& text, const Cutter& tool, FilletParams& p) {
  Cutter ref;
  if (std::string e = parse_tool(text, ref); !e.empty()) return "is not a usable ball: " + e;
  std::ostringstream os;
  if (ref.type != CutterType::kBall)
    os << "must be a ball-end mill (ball:D, the finishing ball whose pencil paths are "
          "followed), got '"
       << text << "'";
  else if (tool.type == CutterType::kBall && !(ref.radius > tool.radius))
    os << "must be a larger ball than the tool (" << 2 * tool.radius << " mm), got '" << text
       << "' (" << 2 * ref.radius << " mm): the tool cleans up what the reference ball left";
  else
    p.reference_diameter = 2 * ref.radius;
  return os.str();
}

std::string check_fillet_spacing(bool has_scallop, const FilletParams& p,
                                 const std::string& stepover_key, const std::string& scallop_key) {
  if (has_scallop && p.stepover > 0)
    return scallop_key + " is not used when " + stepover_key +
           " is given (> 0): give one of them (" + stepover_key + ": mm between passes; " +
           scallop_key + ": cusp height between passes, mm, with " + stepover_key + " 0)";
  return "";
}

std::string validate_fillet(const FilletParams& p, const Cutter& tool) {
  std::string e = validate(p);
  const std::string nested = "pencil: ";
  if (e.rfind(nested, 0) == 0) e.erase(0, nested.size());
  if (e.empty() && tool.type == CutterType::kBall) e = validate_stock(p.stock, tool.radius);
  return e;
}

std::string validate_pencil(const PencilParams& p, const Cutter& tool) {
  std::string e = validate(p);
  if (e.empty() && tool.type == CutterType::kBall) e = validate_stock(p.stock, tool.radius);
  return e;
}

void parse_fillet_params(Keys& k, const Cutter& tool, FilletParams& p,
                         std::string& reference_text) {
  // Absent: refused by parse_job, which also sees a job without `params`.
  if (k.string("reference", reference_text))
    if (std::string e = parse_fillet_reference(reference_text, tool, p); !e.empty())
      k.fail("reference", e);
  k.number("stepover", p.stepover);
  const bool has_scallop = k.number("scallop", p.scallop);
  k.whole_number("max_passes", p.max_passes);
  parse_pencil_search(k, p.pencil);
  parse_stock_direction(k, p.stock, p.direction);
  if (k.error.empty())
    k.error = check_fillet_spacing(has_scallop, p, "'params.stepover'", "'params.scallop'");
}

void zlevel_params_json(const ZLevelOpParams& p, nlohmann::ordered_json& j) {
  // The one of levels and step_down that is used; the other null.
  const bool stepped = p.step_down > 0;
  j["levels"] = stepped ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(p.levels);
  j["step_down"] = stepped ? nlohmann::ordered_json(p.step_down) : nlohmann::ordered_json(nullptr);
  j["tolerance"] = p.tolerance;
  j["chunk_levels"] = p.chunk_levels;
}

void pencil_params_json(const PencilParams& p, nlohmann::ordered_json& j) {
  pencil_search_json(p, j);
  j["stock"] = p.stock;
  j["direction"] = cut_direction_name(p.direction);
}

void fillet_params_json(const FilletParams& p, const std::string& reference_text,
                        nlohmann::ordered_json& j) {
  j["reference"] = reference_text;
  j["reference_diameter"] = p.reference_diameter;
  j["stepover"] = p.stepover;
  j["scallop"] = p.scallop;
  j["max_passes"] = p.max_passes;
  pencil_search_json(p.pencil, j);
  j["stock"] = p.stock;
  j["direction"] = cut_direction_name(p.direction);
}

}  // namespace ncpath::jobs
