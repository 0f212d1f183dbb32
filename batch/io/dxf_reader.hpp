#pragma once
// DXF input of pocket profiles (ASCII DXF, R12 to current; read with dxflib).
//
// Read from the ENTITIES section (entities inside BLOCKS are only reachable through INSERT,
// which is not expanded):
//   LINE, ARC, CIRCLE (two half arcs), LWPOLYLINE and POLYLINE (bulges, closed flag),
//   SPLINE (degree, knots, control points, weights), ELLIPSE (exact rational NURBS).
// Coordinates are projected onto the xy plane (z dropped) and converted to mm.
// Units: the job's when given (`units`), else the header's $INSUNITS (inches, feet, cm, m,
// microns, ... : the DXF reference's table, length_units.hpp), else $MEASUREMENT (0: inches,
// 1: mm; a guess, with soup.units_warning), else mm with soup.units_warning. An $INSUNITS
// code outside the table is an error, and so is a unit variable after the entities. Entities whose extrusion
// direction is -Z (mirrored OCS, common in CAM exports) are mapped to world coordinates;
// other extrusion directions are skipped with a warning.
// Every other entity (TEXT, MTEXT, INSERT, HATCH, DIMENSION, POINT, 3DFACE, ...) is skipped
// with a warning naming its type and handle; POLYLINE meshes likewise. Entities (or polyline
// spans) shorter than tol::kProfileZeroLength are dropped and counted.
//
// Errors (ReadError, "<file>: line N: <problem>", N = line of the entity's "0" group code):
// unreadable or binary file, a SPLINE with only fit points ("SPLINE 2F has only fit points;
// ncpath needs control points") or whose counts, knots or weights are invalid, and a file
// with no usable entity at all.
#include <filesystem>
#include <optional>

#include "batch/io/profile_soup.hpp"
#include "batch/io/read_error.hpp"

namespace ncpath::io {

using DxfContent = ProfileSoup;

// Curves in file order. A source's handle is the DXF handle (group code 5, e.g. "2F"), or
// "(line N)" when the entity has none (R12 files without handles). `units`: the job's units,
// which override the drawing's.
ProfileSoup read_dxf(const std::filesystem::path& path,
                     const std::optional<LengthUnit>& units = std::nullopt);

}  // namespace ncpath::io
