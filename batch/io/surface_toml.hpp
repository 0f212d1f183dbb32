#pragma once
// Bottom surfaces of sculptured pockets (issue 7) in TOML, written by hand or by scripts.
// Documented with examples in docs/profile-format.md ("Bottom surfaces"). Exactly one of:
//
//   units = "mm"                 # optional; only "mm"
//   [nurbs_surface]              # native: any degree, rational, clamped knots
//   degree_u = 3
//   degree_v = 3
//   nu = 4                       # control points along u
//   nv = 4                       # control points along v
//   ctrl = [[x, y, z], ...]      # nu * nv points, row-major by u: ctrl[i * nv + j]
//   weights = [...]              # optional: all 1
//   knots_u = [...]              # optional: clamped uniform on [0, 1]
//   knots_v = [...]              # optional: clamped uniform on [0, 1]
//
//   [bezier_grid]                # bicubic Bezier patches sharing edges
//   patches_u = 2
//   patches_v = 3
//   ctrl = [[x, y, z], ...]      # (3 * patches_u + 1) * (3 * patches_v + 1), row-major by u
//
// The result has passed validate() and check_height_field() (kernels/surface/
// nurbs_surface.hpp). Whether the pocket lies over the surface depends on the profile too and
// is checked where both are known. Millimetres. Errors are ReadError
// "<file>: line N: nurbs_surface: ctrl has 15 points, nu * nv = 16".
#include <filesystem>
#include <string_view>

#include "batch/io/read_error.hpp"
#include "kernels/surface/nurbs_surface.hpp"

namespace ncpath::io {

// Reads the file; ReadError when it cannot be read or is not a valid, usable bottom surface.
NurbsSurface read_surface_toml(const std::filesystem::path& path);

// The same from text in memory; `path` only names the source in messages.
NurbsSurface parse_surface_toml(std::string_view text, const std::filesystem::path& path);

}  // namespace ncpath::io
