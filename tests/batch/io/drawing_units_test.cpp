// Drawing units (batch/io/length_units.hpp): a profile read in the units its file declares
// (DXF $INSUNITS, else $MEASUREMENT; TOML `units`), or the job's, and always delivered in mm.
// The expected sizes are the definitions (an inch is 25.4 mm, a US survey foot 1200/3937 m),
// written here rather than taken from the reader's table.
#include <gtest/gtest.h>

#include <optional>
#include <string>

#include "batch/io/dxf_reader.hpp"
#include "batch/io/length_units.hpp"
#include "batch/io/profile_toml.hpp"
#include "tests/batch/io/dxf_test_util.hpp"

namespace ncpath::io {
namespace {

using test::pairs;
using test::write_temp;

// A 4 x 2 rectangle (LWPOLYLINE) and a circle of radius 0.5 at (1, 1), in drawing units,
// after a HEADER with the given variables ("$INSUNITS" -> "1", ...), in that order.
std::string drawing(std::initializer_list<std::pair<std::string, std::string>> header) {
  std::string h = pairs({"0", "SECTION", "2", "HEADER", "9", "$ACADVER", "1", "AC1015"});
  for (const auto& [var, value] : header) h += pairs({"9", var, "70", value});
  h += pairs({"0", "ENDSEC"});
  const std::string ents =
      pairs({"0", "SECTION", "2", "ENTITIES", "0", "LWPOLYLINE", "5", "2A", "8", "0", "90", "4",
             "70", "1", "10", "0", "20", "0", "10", "4", "20", "0", "10", "4", "20", "2", "10",
             "0", "20", "2", "0", "CIRCLE", "5", "2B", "8", "0", "10", "1", "20", "1", "30", "0",
             "40", "0.5", "0", "ENDSEC", "0", "EOF"});
  return h + ents;
}

// A file name of the running test's own: ctest runs the tests of this binary in parallel
// processes, which share write_temp's folder.
std::string own_name(const std::string& what) {
  return std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" + what;
}

// The rectangle's far corner and the circle's radius as read, mm.
struct Read {
  ProfileSoup soup;
  Vec2 corner;
  double radius;
};
Read read(const std::string& text, const std::optional<LengthUnit>& job = std::nullopt) {
  Read r{read_dxf(write_temp(own_name("units.dxf"), text), job), {}, 0};
  for (const ProfileCurve& c : r.soup.curves) {
    if (c.seg.is_arc()) r.radius = c.seg.r;
    if (!c.seg.is_arc() && c.seg.a.x() > r.corner.x()) r.corner = c.seg.a;
    if (!c.seg.is_arc() && c.seg.a.y() > r.corner.y()) r.corner = c.seg.a;
  }
  return r;
}

std::string read_error_of(const std::string& text) {
  try {
    read_dxf(write_temp(own_name("units_bad.dxf"), text));
  } catch (const ReadError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(DrawingUnits, InsunitsScaleEveryCoordinateAndRadius) {
  struct Case {
    const char* code;
    const char* name;
    double mm;
  };
  for (const Case& c : {Case{"1", "inch", 25.4}, Case{"2", "foot", 304.8}, Case{"4", "mm", 1},
                        Case{"5", "cm", 10}, Case{"6", "m", 1000}, Case{"9", "mil", 0.0254},
                        Case{"13", "micron", 1e-3},
                        Case{"21", "us_survey_foot", 1200.0 / 3937 * 1000}}) {
    const Read r = read(drawing({{"$INSUNITS", c.code}}));
    EXPECT_EQ(r.soup.units.name, c.name) << c.code;
    EXPECT_EQ(r.soup.units_from, kUnitsFromInsunits);
    EXPECT_TRUE(r.soup.units_warning.empty());
    EXPECT_NEAR(r.corner.x(), 4 * c.mm, 1e-12 * c.mm) << c.name;
    EXPECT_NEAR(r.corner.y(), 2 * c.mm, 1e-12 * c.mm) << c.name;
    EXPECT_NEAR(r.radius, 0.5 * c.mm, 1e-12 * c.mm) << c.name;
  }
}

// The drawing: a 4 x 2 in rectangle is 101.6 x 50.8 mm.
TEST(DrawingUnits, InchRectangleIs101Point6By50Point8Mm) {
  const Read r = read(drawing({{"$INSUNITS", "1"}, {"$MEASUREMENT", "1"}}));
  EXPECT_DOUBLE_EQ(r.corner.x(), 101.6);
  EXPECT_DOUBLE_EQ(r.corner.y(), 50.8);
}

TEST(DrawingUnits, MeasurementDecidesOnlyWithoutInsunitsAndWarns) {
  const Read imperial = read(drawing({{"$MEASUREMENT", "0"}}));
  EXPECT_EQ(imperial.soup.units.name, "inch");
  EXPECT_EQ(imperial.soup.units_from, kUnitsFromMeasurement);
  EXPECT_NE(imperial.soup.units_warning.find("$MEASUREMENT = 0"), std::string::npos);
  EXPECT_DOUBLE_EQ(imperial.corner.x(), 101.6);
  // $INSUNITS 0 is "unitless": $MEASUREMENT decides.
  const Read metric = read(drawing({{"$INSUNITS", "0"}, {"$MEASUREMENT", "1"}}));
  EXPECT_EQ(metric.soup.units.name, "mm");
  EXPECT_EQ(metric.soup.units_from, kUnitsFromMeasurement);
  EXPECT_DOUBLE_EQ(metric.corner.x(), 4);
  const Read declared = read(drawing({{"$MEASUREMENT", "0"}, {"$INSUNITS", "4"}}));
  EXPECT_EQ(declared.soup.units.name, "mm");
  EXPECT_TRUE(declared.soup.units_warning.empty());
}

TEST(DrawingUnits, NoUnitsIsMmWithAWarning) {
  for (const std::string& text :
       {drawing({}), test::dxf_entities(pairs({"0", "CIRCLE", "8", "0", "10", "0", "20", "0",
                                               "30", "0", "40", "3"}))}) {
    const Read r = read(text);
    EXPECT_EQ(r.soup.units.name, "mm");
    EXPECT_EQ(r.soup.units_from, kUnitsFromDefault);
    EXPECT_NE(r.soup.units_warning.find("declares no units"), std::string::npos);
  }
}

TEST(DrawingUnits, TheJobsUnitsOverrideTheDrawing) {
  const Read as_mm = read(drawing({{"$INSUNITS", "1"}}), unit_by_name("mm"));
  EXPECT_EQ(as_mm.soup.units_from, kUnitsFromJob);
  EXPECT_DOUBLE_EQ(as_mm.corner.x(), 4);
  const Read as_cm = read(drawing({}), unit_by_name("cm"));
  EXPECT_DOUBLE_EQ(as_cm.corner.x(), 40);
  EXPECT_DOUBLE_EQ(as_cm.radius, 5);
  EXPECT_TRUE(as_cm.soup.units_warning.empty());
  // An unknown code does not matter when the job says what the units are.
  EXPECT_DOUBLE_EQ(read(drawing({{"$INSUNITS", "99"}}), unit_by_name("in")).corner.x(), 101.6);
}

TEST(DrawingUnits, BadCodesAndLateHeadersAreErrorsWithTheirLine) {
  const std::string bad = read_error_of(drawing({{"$INSUNITS", "99"}}));
  EXPECT_NE(bad.find("units_bad.dxf: line 11: $INSUNITS 99 is not a unit code"), std::string::npos)
      << bad;
  // A HEADER after the ENTITIES (not valid DXF): the entities would have been read in
  // the wrong units, so it is refused.
  const std::string late =
      pairs({"0", "SECTION", "2", "ENTITIES", "0", "CIRCLE", "8", "0", "10", "0", "20", "0", "30",
             "0", "40", "3", "0", "ENDSEC", "0", "SECTION", "2", "HEADER", "9", "$INSUNITS", "70",
             "1", "0", "ENDSEC", "0", "EOF"});
  EXPECT_NE(read_error_of(late).find("line 25: $INSUNITS comes after the entities"),
            std::string::npos)
      << read_error_of(late);
}

TEST(DrawingUnits, NamesAreCaseInsensitiveAndUnknownNamesRefused) {
  EXPECT_DOUBLE_EQ(unit_by_name("IN")->mm_per_unit, 25.4);
  EXPECT_DOUBLE_EQ(unit_by_name("Feet")->mm_per_unit, 304.8);
  EXPECT_DOUBLE_EQ(unit_by_name("um")->mm_per_unit, 1e-3);
  EXPECT_EQ(unit_by_name("inch")->name, "inch");
  EXPECT_FALSE(unit_by_name("furlong"));
  EXPECT_FALSE(unit_by_name(""));
  EXPECT_EQ(unit_by_insunits(11)->mm_per_unit, 1e-7);  // angstrom
  EXPECT_EQ(unit_by_insunits(20)->name, "parsec");
  EXPECT_FALSE(unit_by_insunits(0));
  EXPECT_FALSE(unit_by_insunits(25));
  EXPECT_FALSE(unit_by_insunits(-1));
}

TEST(DrawingUnits, TomlUnitsKeyAndTheJobsOverride) {
  const std::string text = "units = \"inch\"\n[[circle]]\ncenter = [1, 1]\nradius = 0.5\n";
  const ProfileSoup in = parse_profile_toml(text, "p.toml");
  EXPECT_EQ(in.units_from, kUnitsFromFile);
  ASSERT_EQ(in.curves.size(), 2u);
  EXPECT_DOUBLE_EQ(in.curves[0].seg.r, 12.7);
  EXPECT_DOUBLE_EQ(in.curves[0].seg.c.x(), 25.4);
  const ProfileSoup mm = parse_profile_toml(text, "p.toml", unit_by_name("mm"));
  EXPECT_EQ(mm.units_from, kUnitsFromJob);
  EXPECT_DOUBLE_EQ(mm.curves[0].seg.r, 0.5);
  const ProfileSoup plain = parse_profile_toml("[[circle]]\ncenter = [1, 1]\nradius = 0.5\n",
                                               "p.toml");
  EXPECT_EQ(plain.units_from, kUnitsFromDefault);
  EXPECT_TRUE(plain.units_warning.empty());  // the format's unit is mm
  try {
    parse_profile_toml("units = \"furlong\"\n[[circle]]\ncenter = [1, 1]\nradius = 0.5\n",
                       "p.toml");
    ADD_FAILURE() << "no error";
  } catch (const ReadError& e) {
    EXPECT_NE(std::string(e.what()).find("p.toml: line 1: units: must be one of mm, cm"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace ncpath::io
