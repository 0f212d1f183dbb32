#pragma once
// Job specifications: what to run, on which input, with which tool and parameters. Built
// from a TOML batch file (`ncpath run jobs.toml`) or from the command line; both end in the
// same JobSpec, so a job behaves the same whichever way it was given.
//
// Batch file (all lengths in mm; relative paths are relative to the TOML file):
//
//   output  = "out/demo.h5"      # required unless given with --out
//   threads = 0                  # 0 = all cores
//   concurrent_jobs = 0          # jobs at the same time at most; 0 = as many as threads
//   memory_limit = "16G"         # budget for jobs at the same time; default 3/4 of free
//   report  = "out/demo.html"    # optional: an HTML page of the results (docs/cli.md)
//   [[job]]
//   name      = "bunny-ball5"     # unique; default "job<N>"
//   operation = "raster"          # "raster", "scan", "zlevel", "pencil", "fillet", "drop",
//                                 # "offset", "pocket" or "pocket3d"
//   input     = "../datasets/cache/meshes/bunny00.off"
//   surface   = "bottom.toml"     # pocket3d only: the bottom surface
//   units     = "inch"            # offset, pocket, pocket3d: the drawing's units (default:
//                                 # what the drawing declares, else mm with a warning)
//   tool      = "ball:5"          # ball:D, flat:D, bull:D:r (diameter, corner radius)
//   transform = { fit_xy = 200, scale = 1, translate = [0, 0, 0] }
//   params    = { interval = 0.5, step = 0.1 }     # see docs/cli.md for every key
//   preview   = "bunny.png"       # optional: a picture of the job (.png or .svg)
//   gcode     = { path = "bunny.ngc", dialect = "linuxcnc", feed = 800, plunge_feed = 200,
//                 spindle_rpm = 12000, safe_z = 5, arc_tolerance = 0.005 }   # optional
//
// A job whose keys or values are wrong is still a job: it carries the error (status
// "invalid_parameter" and a message naming the key) and the batch records it and goes on.
#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "batch/io/length_units.hpp"
#include "batch/output/gcode_writer.hpp"
#include "engine/fillet.hpp"
#include "engine/pencil.hpp"
#include "engine/pocket_path.hpp"
#include "engine/raster.hpp"
#include "engine/scan.hpp"
#include "engine/zlevel.hpp"
#include "kernels/cutters/cutter.hpp"
#include "kernels/mesh/mesh_transform.hpp"

namespace ncpath::jobs {

enum class Operation : std::uint8_t {
  kRaster,
  kDrop,
  kOffset,
  kPocket,
  kPocket3d,
  kScan,
  kZLevel,
  kPencil,
  kFillet
};

// The offset operation (pocket offset loops, unlinked; PocketParams for tool paths).
struct OffsetParams {
  double stepover = 0;           // mm; from "stepover = 2.4" or "stepover = \"40%\"" (of D)
  double stock = 0;              // mm left on walls and islands
  double depth = 0;              // mm below z = 0 at which the loops are written as paths
  double tolerance = 0.01;       // mm: NURBS to arcs, and arcs to polylines for the paths
  double join_tolerance = 1e-6;  // mm: profile end points closer than this are joined
};

// The pocket operation (linked pocket tool paths, engine/pocket_path.hpp). The stock top is
// z = 0; the floor z = -depth.
struct PocketParams {
  double stepover = 0;           // mm; 0 until parsed: "stepover" absent means 50% of D
  double stock = 0;              // mm left on walls and islands
  double depth = 0;              // mm below the top, > 0 (required)
  double stepdown = 0;           // mm per depth pass; 0 = one pass at full depth
  double tolerance = 0.01;       // mm: NURBS to arcs, and arcs to polylines for the paths
  double join_tolerance = 1e-6;  // mm: profile end points closer than this are joined
  CutOrder order = CutOrder::kOutward;
  Milling milling = Milling::kClimb;
  double helix_radius = 0;  // mm; 0 = half the tool radius
  double ramp_angle = 3;    // degrees, helix and ramp descent, in (0, 90)
  double clearance = 1;     // mm above the top where feed moves start
};

// The pocket3d operation: a pocket with a sculptured bottom (a NURBS surface from
// JobSpec::surface) cut with a ball-end mill (engine/pocket3d.hpp). The stock top is z = 0.
struct Pocket3dJobParams {
  double scallop = 0;            // cusp height h left between passes, mm, in (0, R) (required)
  double eps = 0.01;             // plan tolerance of the straight moves, mm
  double delta = 0.01;           // surface tolerance of the straight moves, mm
  double stock = 0;              // mm left on walls and islands
  double tolerance = 0;          // mm: profile NURBS to arcs; 0 until parsed: default below
  double join_tolerance = 1e-6;  // mm: profile end points closer than this are joined
  CutOrder order = CutOrder::kOutward;
  Milling milling = Milling::kClimb;
  double clearance = 1;     // mm above the top where feed moves start
  double min_interval = 0;  // smallest plan path interval, mm; 0 = R / 100
};

// Profile tolerance of a pocket3d job when none is given: well inside the plan tolerance eps,
// so that arcs standing in for the profile's NURBS curves use little of it.
// How much of a job's CL data the verifier checks (batch/jobs/job_verify.hpp): every move
// (full, the default), every 8th move (sample) or nothing (off).
enum class VerifyMode : std::uint8_t { kOff, kSample, kFull };
// "" when text is off, sample or full (then out is set), else a message.
std::string parse_verify_mode(const std::string& text, VerifyMode& out);

inline double default_pocket3d_tolerance(double eps) { return std::min(0.01, eps / 4); }

// Stepover of a pocket job when none is given: this fraction of the tool diameter.
inline constexpr double kDefaultPocketStepoverFraction = 0.5;
// Safe height of rapids when none is given: this many mm above the part's top (meshes) or
// above z = 0 (profile jobs, whose stock top is z = 0).
inline constexpr double kDefaultSafeAboveTop = 5;

struct JobSpec {
  std::string name;
  Operation operation = Operation::kRaster;
  std::filesystem::path input;    // mesh: STL or OFF
  std::filesystem::path points;   // drop: CSV of "x,y" lines (blank line = new path)
  std::filesystem::path surface;  // pocket3d: the bottom surface (TOML, docs/profile-format.md)
  // Profile jobs: the drawing's units (key `units`, --units), overriding what the drawing
  // declares; nullopt: the drawing's (batch/io/dxf_reader.hpp).
  std::optional<io::LengthUnit> units;
  MeshTransform transform;
  std::string tool_text;  // as the user wrote it, e.g. "ball:5"
  Cutter tool;
  RasterParams raster;
  ScanParams scan;        // the scan operation (curve-based drive-plane scanning, ball only)
  ZLevelOpParams zlevel;  // the zlevel operation (z-level contours, ball only)
  PencilParams pencil;    // the pencil operation (pencil-cut of concave creases, ball only)
  // The fillet operation (fillet-cut clean-up after a larger reference ball, ball only):
  // reference_diameter from `fillet_reference`, the reference ball as written ("ball:10").
  FilletParams fillet;
  std::string fillet_reference;
  OffsetParams offset;
  PocketParams pocket;
  Pocket3dJobParams pocket3d;
  std::filesystem::path gcode;  // also write the job's paths as G-code here (empty: no)
  out::GcodeParams gcode_params;
  // Safe height for rapids, mm. Unset: 5 mm above the part's top for mesh jobs (z = 0 for
  // pockets). A given height below a mesh's top is rejected. Pocket jobs also use it for
  // their rapid paths in the HDF5 file, with or without G-code.
  std::optional<double> gcode_safe_z;
  VerifyMode verify = VerifyMode::kFull;  // key `verify` (job, or the batch's default)
  std::filesystem::path preview;          // key `preview`: draw the job here when the batch ends
  std::string error;         // non-empty: the spec is invalid; status + message below
  std::string error_status;  // "invalid_parameter"
};

struct BatchSpec {
  std::filesystem::path output;
  std::filesystem::path report;  // key `report`: the batch's HTML page, written at its end
  int threads = 0;
  int concurrent_jobs = 0;         // 0 = as many as threads (batch_schedule.hpp)
  std::uint64_t memory_limit = 0;  // bytes; 0 = default_memory_limit()
  VerifyMode verify = VerifyMode::kFull;  // default of the jobs that do not set `verify`
  std::vector<JobSpec> jobs;
  int mpi_rank = -1;  // >= 0 (ncpath-mpi): every job's statistic `mpi_rank`, where it ran
};

// "inch" -> out (io::unit_by_name). Returns an error message to follow the key's name, or "".
std::string parse_units(const std::string& text, std::optional<io::LengthUnit>& out);

// "ball:5" -> ball_cutter(5). Returns an error message naming the problem, or "".
std::string parse_tool(const std::string& text, Cutter& out);

// Parses a batch file. Throws std::runtime_error for a file that cannot be read or is not
// valid TOML (message with file:line:column). Per-job problems land in JobSpec::error.
BatchSpec parse_batch_file(const std::filesystem::path& path);
BatchSpec parse_batch_text(std::string_view text, const std::filesystem::path& base_dir,
                           const std::string& source_name);

// "raster", "drop", "offset", "pocket", "pocket3d", "scan", "zlevel", "pencil", "fillet"
const char* operation_name(Operation op);
// The operation operation_name gives `name`; false for any other name.
bool operation_by_name(const std::string& name, Operation& out);

// "x", "y", "both" -> families; error message to follow the key's name, or "".
// (In raster_scan_params.cpp.)
std::string parse_families(const std::string& text, ScanFamilies& out);
const char* families_name(ScanFamilies families);  // "x", "y", "both"

// The choice of a zlevel job between a list of levels and a step-down: exactly one of them
// given (has_*: the key or option is present), and usable. "" or the problem, naming the keys
// as spelled by the caller (levels_key "'params.levels'" or "--levels", step_key likewise).
// The other parameters are checked by validate(ZLevelOpParams). (In mesh_op_params.cpp.)
std::string check_zlevel_choice(bool has_levels, bool has_step_down, const ZLevelOpParams& params,
                                const std::string& levels_key, const std::string& step_key);

// The reference ball of a fillet job, from its spec as written ("ball:10"): sets
// params.reference_diameter. "" or the problem, to follow the key's name ("must be a ball-end
// mill ..."): a spec parse_tool refuses, a cutter that is not a ball, or, when the job's tool
// is a ball, a reference not larger than it. (In mesh_op_params.cpp.)
std::string parse_fillet_reference(const std::string& text, const Cutter& tool,
                                   FilletParams& params);
// The spacing keys of a fillet job: a scallop height given (has_scallop) next to a stepover
// > 0 would not be used, so it is refused. "" or the problem, naming the keys as spelled by the
// caller ("'params.stepover'" or "--stepover"). (In mesh_op_params.cpp.)
std::string check_fillet_spacing(bool has_scallop, const FilletParams& params,
                                 const std::string& stepover_key, const std::string& scallop_key);
// validate(FilletParams) with the pencil keys' messages as the other keys' ("interval must be
// ...", not "pencil: interval must be ..."): a job's keys are one flat table; then, when the
// tool is a ball (another shape is the engine's to refuse, at run time), the stock against
// its radius (validate_stock). "" when usable. (In mesh_op_params.cpp.)
std::string validate_fillet(const FilletParams& params, const Cutter& tool);
// validate(PencilParams), then the stock against the tool's radius when it is a ball. ""
// when usable. (In mesh_op_params.cpp.)
std::string validate_pencil(const PencilParams& params, const Cutter& tool);
// "any" / "climb" / "conventional" -> the cut direction of pencil and fillet jobs; "" or an
// error to follow the key's name ("must be \"any\", \"climb\" or \"conventional\", got
// \"up\""). (In mesh_op_params.cpp.)
std::string parse_direction(const std::string& text, CutDirection& out);

// The profile operations' keys, from parse_stepover to milling_name: in
// profile_op_params.cpp.
// "2.4" -> 2.4 mm; "40%" -> 40 % of the tool diameter. Error message or "".
std::string parse_stepover(const std::string& text, const Cutter& tool, double& out_mm);
// "" when usable, else a message naming the key.
std::string validate(const OffsetParams& params);
// "" when usable, else a message naming the key. tool: stepover may not exceed its diameter.
std::string validate(const PocketParams& params, const Cutter& tool);
// "" when usable, else a message naming the key; the tool must be a ball (its radius is R).
std::string validate(const Pocket3dJobParams& params, const Cutter& tool);
// "outward" / "inward" and "climb" / "conventional"; "" or an error to follow the key's name
// ("must be \"outward\" or \"inward\", got \"up\"").
std::string parse_order(const std::string& text, CutOrder& out);
std::string parse_milling(const std::string& text, Milling& out);
const char* order_name(CutOrder order);     // "outward" / "inward"
const char* milling_name(Milling milling);  // "climb" / "conventional"
// "linuxcnc" / "grbl" -> dialect; error message or "".
std::string parse_dialect(const std::string& text, out::GcodeDialect& out);

// The parameters of a job as JSON text, defaults included (HDF5 `params` attribute).
// (This and tool_json in job_spec_json.cpp.)
std::string params_json(const JobSpec& job);
// The tool as JSON text: {"type":..., "diameter_mm":..., "corner_radius_mm":...}.
std::string tool_json(const Cutter& tool);

}  // namespace ncpath::jobs
