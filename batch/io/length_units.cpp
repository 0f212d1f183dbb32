#include "batch/io/length_units.hpp"

#include <algorithm>
#include <array>
#include <cctype>

namespace ncpath::io {

namespace {

struct NamedUnit {
  const char* name;  // canonical first, then its other spellings
  double mm;
  std::array<const char*, 3> aliases;
};

// Sizes by definition: inch 25.4 mm; US survey foot 1200/3937 m.
constexpr double kSurveyFootMm = 1200.0 / 3937.0 * 1000.0;
const NamedUnit kUnits[] = {
    {"mm", 1, {"millimeter", "millimetre", nullptr}},
    {"cm", 10, {"centimeter", "centimetre", nullptr}},
    {"dm", 100, {"decimeter", "decimetre", nullptr}},
    {"m", 1000, {"meter", "metre", nullptr}},
    {"km", 1e6, {"kilometer", "kilometre", nullptr}},
    {"micron", 1e-3, {"um", "\xC2\xB5m", "micrometer"}},
    {"nm", 1e-6, {"nanometer", "nanometre", nullptr}},
    {"inch", 25.4, {"in", "inches", nullptr}},
    {"foot", 304.8, {"ft", "feet", nullptr}},
    {"yard", 914.4, {"yd", "yards", nullptr}},
    {"mile", 1609344, {"mi", "miles", nullptr}},
    {"mil", 0.0254, {"thou", nullptr, nullptr}},
    {"microinch", 25.4e-6, {nullptr, nullptr, nullptr}},
    {"us_survey_foot", kSurveyFootMm, {nullptr, nullptr, nullptr}},
    {"us_survey_inch", kSurveyFootMm / 12, {nullptr, nullptr, nullptr}},
    {"us_survey_yard", 3 * kSurveyFootMm, {nullptr, nullptr, nullptr}},
    {"us_survey_mile", 5280 * kSurveyFootMm, {nullptr, nullptr, nullptr}},
    {"angstrom", 1e-7, {nullptr, nullptr, nullptr}},
    {"decameter", 1e4, {nullptr, nullptr, nullptr}},
    {"hectometer", 1e5, {nullptr, nullptr, nullptr}},
    {"gigameter", 1e12, {nullptr, nullptr, nullptr}},
    {"astronomical_unit", 1.495978707e14, {"au", nullptr, nullptr}},
    {"light_year", 9.4607304725808e18, {nullptr, nullptr, nullptr}},
    {"parsec", 3.0856775814913673e19, {nullptr, nullptr, nullptr}},
};

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

}  // namespace

std::optional<LengthUnit> unit_by_name(const std::string& name) {
  const std::string n = lower(name);
  for (const NamedUnit& u : kUnits) {
    bool match = n == u.name;
    for (const char* a : u.aliases) match = match || (a && n == a);
    if (match) return LengthUnit{u.name, u.mm};
  }
  return std::nullopt;
}

std::string unit_names() {
  std::string out;
  for (const NamedUnit& u : kUnits) out += (out.empty() ? "" : ", ") + std::string(u.name);
  return out;
}

std::optional<LengthUnit> unit_by_insunits(int code) {
  // AutoCAD's $INSUNITS table (DXF reference, HEADER section): code -> unit; 0 is unitless.
  static const std::array<const char*, 25> kCodes = {
      nullptr,  "inch",      "foot",       "mile",      "mm",
      "cm",     "m",         "km",         "microinch", "mil",
      "yard",   "angstrom",  "nm",         "micron",    "dm",
      "decameter", "hectometer", "gigameter", "astronomical_unit", "light_year",
      "parsec", "us_survey_foot", "us_survey_inch", "us_survey_yard", "us_survey_mile"};
  if (code <= 0 || code >= int(kCodes.size())) return std::nullopt;
  return unit_by_name(kCodes[std::size_t(code)]);
}

}  // namespace ncpath::io
