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
  double chunk;
  if (k.number("chunk_levels", chunk)) {
    if (chunk >= 1 && chunk <= 1e6 && chunk == static_cast<std::uint32_t>(chunk))
      p.chunk_levels = static_cast<std::uint32_t>(chunk);
    else
      k.fail("chunk_levels", "must be a whole number >= 1");
  }
  if (k.error.empty())
    k.error =
        check_zlevel_choice(has_levels, has_step_down, p, "'params.levels'", "'params.step_down'");
}

void parse_pencil_params(Keys& k, PencilParams& p) {
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

void zlevel_params_json(const ZLevelOpParams& p, nlohmann::ordered_json& j) {
  // The one of levels and step_down that is used; the other null.
  const bool stepped = p.step_down > 0;
  j["levels"] = stepped ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(p.levels);
  j["step_down"] = stepped ? nlohmann::ordered_json(p.step_down) : nlohmann::ordered_json(nullptr);
  j["tolerance"] = p.tolerance;
  j["chunk_levels"] = p.chunk_levels;
}

void pencil_params_json(const PencilParams& p, nlohmann::ordered_json& j) {
  j["interval"] = p.interval;
  j["step_down"] = p.step_down;
  j["min_angle"] = p.min_angle_deg;
  j["tolerance"] = p.tolerance;
  j["merge_distance"] = p.merge_distance;
  j["min_length"] = p.min_length;
  j["margin"] = p.margin;
  j["floor_z"] = p.floor_z ? nlohmann::ordered_json(*p.floor_z) : nlohmann::ordered_json(nullptr);
}

}  // namespace ncpath::jobs
