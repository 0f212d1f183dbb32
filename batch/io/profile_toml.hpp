#pragma once
// The native profile format: a small TOML file of loops, circles and polylines, meant to be
// written by hand or by scripts. Documented with examples in docs/profile-format.md.
//
//   [[loop]]                          # closed by construction; any direction
//   segments = [
//     { line = [[0, 0], [100, 0]] },  # explicit start and end
//     { arc = { to = [100, 50], center = [100, 25], dir = "ccw" } },
//     { line_to = [0, 50] },          # starts where the previous segment ended
//     { arc = { to = [0, 0], bulge = 0.4142 } },
//   ]
//   [[circle]]
//   center = [50, 25]
//   radius = 5
//   [[polyline]]
//   points = [[0, 0], [10, 0, 1.0], [10, 10]]   # [x, y] or [x, y, bulge]
//   closed = true
//
// Millimetres unless the file says otherwise: a top-level `units = "inch"` (any name of
// length_units.hpp unit_by_name); the job's units override it. Errors are ReadError "<file>: line N: loop 0 segment 3: arc: <problem>".
#include <filesystem>
#include <optional>
#include <string_view>

#include "batch/io/profile_soup.hpp"
#include "batch/io/read_error.hpp"

namespace ncpath::io {

// Reads the file; ReadError when it cannot be read or is not a valid profile file. `units`:
// the job's, which override the file's.
ProfileSoup read_profile_toml(const std::filesystem::path& path,
                              const std::optional<LengthUnit>& units = std::nullopt);

// The same from text in memory; `path` only names the source in messages.
ProfileSoup parse_profile_toml(std::string_view text, const std::filesystem::path& path,
                               const std::optional<LengthUnit>& units = std::nullopt);

}  // namespace ncpath::io
