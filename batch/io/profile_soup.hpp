#pragma once
// What the profile readers (DXF: dxf_reader.hpp, native TOML: profile_toml.hpp) deliver: the
// drawing's curves as an unordered soup, in the file's order and directions, ready for
// chain_and_nest (kernels/pocket/chain.hpp), which chains and nests them into regions.
#include <cstdint>
#include <string>
#include <vector>

#include "batch/io/length_units.hpp"
#include "kernels/pocket/profile.hpp"

namespace ncpath::io {

struct ProfileSoup {
  // Lines and arcs, and NURBS curves (curve.nurbs indexes `nurbs`; seg.a / seg.b are then
  // its end points). curve.seg.source indexes `sources`. mm, xy plane.
  std::vector<ProfileCurve> curves;
  std::vector<Nurbs2> nurbs;
  // One per input entity that produced curves (a polyline or circle gives several curves
  // with the same source); messages name an entity as "<type> <handle>". DXF: type "LINE",
  // handle "2F" or, without handles, "(line 12)" (the line of its "0" group code). TOML:
  // "arc in loop 0 segment 3", "circle 1", "polyline 2 segment 0".
  std::vector<SourceEntity> sources;
  // Entities (or polyline spans) shorter than tol::kProfileZeroLength, dropped.
  std::uint64_t zero_length_dropped = 0;
  // Entities that were skipped, one line each, e.g. "skipped TEXT 3A: not a profile curve".
  std::vector<std::string> warnings;
  // The drawing's units (every coordinate above is already in mm) and where they came from
  // (length_units.hpp: kUnitsFromJob, kUnitsFromInsunits, ...).
  LengthUnit units{"mm", 1};
  std::string units_from = kUnitsFromDefault;
  // Non-empty when the units were a guess the user should check (a drawing that declares
  // none is read as mm), for the job's message.
  std::string units_warning;
};

// Multiplies every coordinate (and radius) of the soup by soup.units.mm_per_unit, for a reader
// that read the file in its own units.
inline void scale_to_mm(ProfileSoup& soup) {
  const double k = soup.units.mm_per_unit;
  if (k == 1) return;
  for (ProfileCurve& c : soup.curves) {
    c.seg.a *= k;
    c.seg.b *= k;
    c.seg.c *= k;
    c.seg.r *= k;
  }
  for (Nurbs2& n : soup.nurbs)
    for (Vec2& p : n.ctrl) p *= k;
}

}  // namespace ncpath::io
