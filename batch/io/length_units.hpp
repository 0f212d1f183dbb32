#pragma once
// Length units of a drawing: the names a job may give (`units = "inch"`, `--units inch`) and
// the DXF header's unit codes ($INSUNITS, $MEASUREMENT), each with its size in mm. ncpath
// works in mm: a profile reader multiplies every coordinate by mm_per_unit.
#include <optional>
#include <string>

namespace ncpath::io {

struct LengthUnit {
  std::string name;        // canonical: "mm", "inch", "foot", "micron", ...
  double mm_per_unit = 1;  // exact by definition (an inch is 25.4 mm)
};

// A unit by the name a user writes: mm, cm, dm, m, km, um (or micron, µm), nm, in (or inch),
// ft (or foot), yd (or yard), mi (or mile), mil, microinch, us_survey_foot, us_survey_inch,
// us_survey_yard, us_survey_mile, and the rest of the DXF table (angstrom, decameter,
// hectometer, gigameter, astronomical_unit, light_year, parsec). Case-insensitive; nullopt
// for other names.
std::optional<LengthUnit> unit_by_name(const std::string& name);

// The names unit_by_name accepts, for messages: "mm, cm, dm, m, ...".
std::string unit_names();

// A DXF $INSUNITS code (AutoCAD's table: 1 inch, 2 foot, 4 mm, 5 cm, 6 m, ... 24 US survey
// mile). nullopt for 0 (unitless) and for codes outside the table.
std::optional<LengthUnit> unit_by_insunits(int code);

// Where the units a profile was read in came from (statistic `units_from`).
inline constexpr const char* kUnitsFromJob = "job";              // units = / --units
inline constexpr const char* kUnitsFromInsunits = "$INSUNITS";   // the DXF header
inline constexpr const char* kUnitsFromMeasurement = "$MEASUREMENT";
inline constexpr const char* kUnitsFromFile = "file";            // a TOML profile's units key
inline constexpr const char* kUnitsFromDefault = "default";      // nothing said: mm

}  // namespace ncpath::io
