#pragma once
// The input half of the profile operations (offset, pocket, pocket3d): read a pocket profile (DXF
// or TOML), chain and nest it into regions, and record the input statistics. One function, so both
// operations accept the same files and report the same problems.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <variant>
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

// Adds `text` to the job's input_warning statistic ("; "-separated: one statistic per name).
inline void add_input_warning(std::vector<out::StatValue>& stats, const std::string& text) {
  for (out::StatValue& s : stats)
    if (s.name == kInputWarningStat) {
      if (std::string* v = std::get_if<std::string>(&s.value)) *v += "; " + text;
      return;
    }
  stats.push_back({std::string(kInputWarningStat), text, ""});
}

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

// "region 2 (boundary: CIRCLE 2F)": a region of `in` named by the entities the user drew.
std::string region_label(const ProfileInput& in, std::size_t region);

// Runs `plan` (a pocket planner, called with a list of regions) on the regions of `in` the
// tool fits in: a region for which it throws RegionTooSmall is left out and the plan made
// again without it. Appends the statistic regions_left_out and, when it is not 0, an
// input_warning naming them by their entities ("the tool does not fit in region 2
// (boundary: CIRCLE 2F): left out"). nullopt when the tool fits in no region.
template <class Plan>
auto plan_regions_that_fit(const ProfileInput& in, Plan&& plan,
                           std::vector<out::StatValue>& stats)
    -> std::optional<decltype(plan(in.regions))> {
  std::vector<Region> regions = in.regions;
  std::vector<std::size_t> original(regions.size());
  for (std::size_t r = 0; r < original.size(); ++r) original[r] = r;
  std::string left_out;
  std::optional<decltype(plan(in.regions))> out;
  while (!regions.empty() && !out) {
    try {
      out.emplace(plan(regions));
    } catch (const RegionTooSmall& e) {
      left_out += (left_out.empty() ? "" : ", ") + region_label(in, original.at(e.region));
      regions.erase(regions.begin() + std::ptrdiff_t(e.region));
      original.erase(original.begin() + std::ptrdiff_t(e.region));
    }
  }
  const std::int64_t n = std::int64_t(in.regions.size() - regions.size());
  stats.push_back({"regions_left_out", n, ""});
  if (n > 0) add_input_warning(stats, "the tool does not fit in " + left_out + ": left out");
  return out;
}

}  // namespace ncpath::jobs
