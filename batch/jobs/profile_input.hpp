#pragma once
// The input half of the profile operations (offset, pocket, pocket3d): read a pocket profile (DXF
// or TOML), chain and nest it into regions, and record the input statistics. One function, so both
// operations accept the same files and report the same problems.
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "batch/io/length_units.hpp"
#include "batch/output/cl_writer.hpp"
#include "engine/pocket_path.hpp"  // RegionTooSmall
#include "kernels/pocket/profile.hpp"

namespace ncpath::jobs {

struct ProfileInput {
  std::vector<Region> regions;        // as chain_and_nest made them; never empty
  std::vector<SourceEntity> sources;  // the regions' Seg2::source indexes this table
};

// The statistic (a string) an ok job's message repeats: what the reading had to guess.
inline constexpr const char* kInputWarningStat = "input_warning";

// Reads `path` (.dxf or .toml, by extension) in the job's `units` (nullopt: the drawing's, see
// io::read_dxf) and chains it with `join_tolerance` (mm). Appends units (its name, e.g.
// "inch"), units_from (job, $INSUNITS, $MEASUREMENT, file or default), mm_per_unit,
// input_warning (when the units were a guess), profile_curves, zero_length_dropped, warnings, largest_gap_closed (mm), regions and
// read_s (s) to stats. Throws io::ReadError for unreadable or malformed profiles and for
// profiles that do not chain into closed, non-crossing loops (the message names the entity
// and the point).
ProfileInput read_profile_regions(const std::filesystem::path& path, double join_tolerance,
                                  const std::optional<io::LengthUnit>& units,
                                  std::vector<out::StatValue>& stats);

// The input entities that drew the boundary of regions[region], for messages: "LWPOLYLINE 2F",
// "LINE 30, LINE 31, LINE 32 and 1 more"; "" when the curves carry no source.
std::string boundary_entities(const ProfileInput& in, std::size_t region);

// Runs `plan` (a pocket planner over in.regions) and returns what it returns. The user drew
// entities, not regions: a RegionTooSmall it throws becomes std::invalid_argument with the
// planner's message and the entities of that region's boundary ("... (boundary: CIRCLE 2F)").
template <class Plan>
auto plan_naming_entities(const ProfileInput& in, Plan&& plan) -> decltype(plan()) {
  try {
    return plan();
  } catch (const RegionTooSmall& e) {
    const std::string names = boundary_entities(in, e.region);
    throw std::invalid_argument(names.empty()
                                    ? std::string(e.what())
                                    : e.what() + std::string(" (boundary: ") + names + ")");
  }
}

}  // namespace ncpath::jobs
