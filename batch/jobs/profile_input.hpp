#pragma once
// The input half of the profile operations (offset, pocket): read a pocket profile (DXF or
// TOML), chain and nest it into regions, and record the input statistics. One function, so
// both operations accept the same files and report the same problems.
#include <filesystem>
#include <string>
#include <vector>

#include "batch/output/cl_writer.hpp"
#include "kernels/pocket/profile.hpp"

namespace ncpath::jobs {

struct ProfileInput {
  std::vector<Region> regions;        // as chain_and_nest made them; never empty
  std::vector<SourceEntity> sources;  // the regions' Seg2::source indexes this table
};

// Reads `path` (.dxf or .toml, by extension) and chains it with `join_tolerance` (mm).
// Appends profile_curves, zero_length_dropped, warnings, largest_gap_closed (mm), regions and
// read_s (s) to stats. Throws io::ReadError for unreadable or malformed profiles and for
// profiles that do not chain into closed, non-crossing loops (the message names the entity
// and the point).
ProfileInput read_profile_regions(const std::filesystem::path& path, double join_tolerance,
                                  std::vector<out::StatValue>& stats);

// The input entities that drew the boundary of regions[region], for messages: "LWPOLYLINE 2F",
// "LINE 30, LINE 31, LINE 32 and 1 more"; "" when the curves carry no source.
std::string boundary_entities(const ProfileInput& in, std::size_t region);

}  // namespace ncpath::jobs
