// Batch files: the TOML document (output, threads, [[job]]) and each job table's own keys
// (name, operation, input, surface, tool, transform, gcode). A job's `params` table goes to
// its operation's parser and check (raster_scan_params, mesh_op_params, profile_op_params;
// drop's one key, points, is read here). Also the text forms of the job-level keys the
// command line shares: operation name, tool ("ball:5") and G-code dialect.
#include "batch/jobs/job_spec.hpp"

#include <charconv>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include <toml++/toml.h>

#include "batch/jobs/batch_schedule.hpp"
#include "batch/jobs/mesh_op_params.hpp"
#include "batch/jobs/profile_op_params.hpp"
#include "batch/jobs/raster_scan_params.hpp"
#include "batch/jobs/toml_keys.hpp"

namespace ncpath::jobs {

std::string parse_units(const std::string& text, std::optional<io::LengthUnit>& out) {
  out = io::unit_by_name(text);
  if (out) return "";
  return "must be one of " + io::unit_names() + ", got \"" + text + "\"";
}

std::string parse_verify_mode(const std::string& text, VerifyMode& out) {
  if (text == "off")
    out = VerifyMode::kOff;
  else if (text == "sample")
    out = VerifyMode::kSample;
  else if (text == "full")
    out = VerifyMode::kFull;
  else
    return "must be \"off\", \"sample\" or \"full\" (got \"" + text + "\")";
  return "";
}

const char* operation_name(Operation op) {
  switch (op) {
    case Operation::kRaster:
      return "raster";
    case Operation::kDrop:
      return "drop";
    case Operation::kOffset:
      return "offset";
    case Operation::kPocket:
      return "pocket";
    case Operation::kPocket3d:
      return "pocket3d";
    case Operation::kScan:
      return "scan";
    case Operation::kZLevel:
      return "zlevel";
    case Operation::kPencil:
      return "pencil";
    case Operation::kFillet:
      return "fillet";
  }
  return "?";
}

std::string parse_dialect(const std::string& text, out::GcodeDialect& out) {
  if (text == "linuxcnc") {
    out = out::GcodeDialect::kLinuxCnc;
  } else if (text == "grbl") {
    out = out::GcodeDialect::kGrbl;
  } else {
    return "G-code dialect must be \"linuxcnc\" or \"grbl\", got \"" + text + "\"";
  }
  return "";
}

std::string parse_tool(const std::string& text, Cutter& out) {
  std::vector<std::string> parts;
  std::stringstream ss(text);
  for (std::string p; std::getline(ss, p, ':');) parts.push_back(p);
  auto num = [&](std::size_t i, double& v) {
    const std::string& s = parts[i];
    auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    return ec == std::errc() && ptr == s.data() + s.size();
  };
  const std::string usage = " (expected ball:D, flat:D or bull:D:r, in mm)";
  if (parts.empty()) return "tool is empty" + usage;
  double d = 0, r = 0;
  const std::string& type = parts[0];
  if (type == "ball" || type == "flat") {
    if (parts.size() != 2 || !num(1, d)) return "tool '" + text + "' is malformed" + usage;
    out = type == "ball" ? ball_cutter(d) : flat_cutter(d);
  } else if (type == "bull" || type == "bullnose") {
    if (parts.size() != 3 || !num(1, d) || !num(2, r))
      return "tool '" + text + "' is malformed" + usage;
    out = bull_nose_cutter(d, r);
  } else {
    return "tool type '" + type + "' is unknown" + usage;
  }
  if (std::string e = validate(out); !e.empty()) return "tool '" + text + "': " + e;
  return "";
}

bool operation_by_name(const std::string& name, Operation& out) {
  for (Operation op : {Operation::kRaster, Operation::kDrop, Operation::kOffset, Operation::kPocket,
                       Operation::kPocket3d, Operation::kScan, Operation::kZLevel,
                       Operation::kPencil, Operation::kFillet})
    if (name == operation_name(op)) {
      out = op;
      return true;
    }
  return false;
}

namespace {

// The job-level key `units`: a profile job's drawing units; refused on mesh jobs.
void parse_units_key(Keys& k, bool profile_op, JobSpec& job) {
  std::string units;
  if (!k.string("units", units)) return;
  if (!profile_op)
    k.fail("units", "applies to profile drawings (offset, pocket, pocket3d); scale a mesh "
                    "with transform.scale");
  else if (std::string e = parse_units(units, job.units); !e.empty())
    k.fail("units", e);
}

JobSpec parse_job(const toml::table& t, std::size_t index, const std::filesystem::path& base) {
  JobSpec job;
  job.name = "job" + std::to_string(index + 1);
  Keys k(t, "");
  k.string("name", job.name);
  std::string op = "raster";
  k.string("operation", op);
  std::string verify;
  if (k.string("verify", verify))
    if (std::string e = parse_verify_mode(verify, job.verify); !e.empty()) k.fail("verify", e);
  std::string preview;
  if (k.string("preview", preview)) job.preview = (base / preview).lexically_normal();
  if (!operation_by_name(op, job.operation))
    k.fail("operation",
           "must be \"raster\", \"scan\", \"zlevel\", \"pencil\", \"fillet\", \"drop\", "
           "\"offset\", \"pocket\" or \"pocket3d\", got \"" +
               op + "\"");
  const bool profile_op = job.operation == Operation::kOffset ||
                          job.operation == Operation::kPocket ||
                          job.operation == Operation::kPocket3d;
  std::string input;
  if (k.string("input", input))
    job.input = (base / input).lexically_normal();
  else
    k.fail("input", profile_op ? "is required (a profile: DXF or TOML)"
                               : "is required (a mesh file: STL or OFF)");
  parse_units_key(k, profile_op, job);
  if (job.operation == Operation::kPocket3d) {
    std::string surface;
    if (k.string("surface", surface))
      job.surface = (base / surface).lexically_normal();
    else
      k.fail("surface", "is required for a pocket3d job (the bottom surface: TOML)");
  }
  if (k.string("tool", job.tool_text)) {
    if (std::string e = parse_tool(job.tool_text, job.tool); !e.empty() && k.error.empty())
      k.error = e;  // already names the tool
  } else {
    k.fail("tool", "is required (e.g. \"ball:5\")");
  }
  job.pocket.stepover = kDefaultPocketStepoverFraction * 2 * job.tool.radius;
  if (const toml::table* tt = k.table("transform")) {
    Keys tk(*tt, "transform.");
    tk.number("scale", job.transform.scale);
    double fit;
    if (tk.number("fit_xy", fit)) job.transform.fit_xy_mm = fit;
    double tr[3];
    if (tk.numbers("translate", 3, tr)) job.transform.translate = Vec3(tr[0], tr[1], tr[2]);
    tk.finish();
    if (tk.error.empty())
      if (std::string e = validate(job.transform); !e.empty()) tk.fail("", e);
    if (!tk.error.empty()) k.fail("transform", ": " + tk.error);
  }
  if (const toml::table* pt = k.table("params")) {
    Keys pk(*pt, "params.");
    if (job.operation == Operation::kRaster) {
      parse_raster_params(pk, job.raster);
    } else if (job.operation == Operation::kScan) {
      parse_scan_params(pk, job.scan);
    } else if (job.operation == Operation::kZLevel) {
      parse_zlevel_params(pk, job.zlevel);
    } else if (job.operation == Operation::kPencil) {
      parse_pencil_params(pk, job.pencil);
    } else if (job.operation == Operation::kFillet) {
      parse_fillet_params(pk, job.tool, job.fillet, job.fillet_reference);
    } else if (job.operation == Operation::kOffset) {
      parse_offset_params(pk, job);
    } else if (job.operation == Operation::kPocket) {
      parse_pocket_params(pk, job);
    } else if (job.operation == Operation::kPocket3d) {
      parse_pocket3d_params(pk, job);
    } else {
      std::string pts;
      if (pk.string("points", pts)) job.points = (base / pts).lexically_normal();
    }
    pk.finish();
    if (pk.error.empty() && job.operation == Operation::kRaster)
      if (std::string e = validate(job.raster); !e.empty()) pk.fail("", e);
    if (pk.error.empty() && job.operation == Operation::kScan)
      if (std::string e = validate(job.scan); !e.empty()) pk.fail("", e);
    if (pk.error.empty() && job.operation == Operation::kZLevel)
      if (std::string e = validate(job.zlevel); !e.empty()) pk.fail("", e);
    if (pk.error.empty() && job.operation == Operation::kPencil)
      if (std::string e = validate_pencil(job.pencil, job.tool); !e.empty()) pk.fail("", e);
    if (pk.error.empty() && job.operation == Operation::kFillet)
      if (std::string e = validate_fillet(job.fillet, job.tool); !e.empty()) pk.fail("", e);
    if (pk.error.empty() && job.operation == Operation::kOffset)
      if (std::string e = validate(job.offset); !e.empty()) pk.fail("", e);
    if (pk.error.empty() && job.operation == Operation::kPocket)
      if (std::string e = validate(job.pocket, job.tool); !e.empty()) pk.fail("", e);
    if (pk.error.empty() && job.operation == Operation::kPocket3d)
      if (std::string e = validate(job.pocket3d, job.tool); !e.empty()) pk.fail("", e);
    if (!pk.error.empty()) k.error = k.error.empty() ? pk.error : k.error;
  }
  if (const toml::table* gt = k.table("gcode")) {
    Keys gk(*gt, "gcode.");
    std::string path, dialect;
    if (gk.string("path", path))
      job.gcode = (base / path).lexically_normal();
    else
      gk.fail("path", "is required (the .ngc file to write)");
    if (gk.string("dialect", dialect))
      if (std::string e = parse_dialect(dialect, job.gcode_params.dialect); !e.empty())
        gk.fail("dialect", e);
    gk.number("feed", job.gcode_params.feed);
    gk.number("plunge_feed", job.gcode_params.plunge_feed);
    gk.number("spindle_rpm", job.gcode_params.spindle_rpm);
    double safe_z;
    if (gk.number("safe_z", safe_z)) job.gcode_safe_z = safe_z;
    gk.number("arc_tolerance", job.gcode_params.arc_tolerance);
    gk.finish();
    if (!gk.error.empty() && k.error.empty()) k.error = gk.error;
  }
  if (job.operation == Operation::kOffset && !(job.offset.stepover > 0) && k.error.empty())
    k.fail("params.stepover", "is required for an offset job (mm, or a percentage like \"40%\")");
  if (job.operation == Operation::kPocket && !(job.pocket.depth > 0) && k.error.empty())
    k.fail("params.depth", "is required for a pocket job (mm below the top, > 0)");
  if (job.operation == Operation::kPocket3d && !(job.pocket3d.scallop > 0) && k.error.empty())
    k.fail("params.scallop", "is required for a pocket3d job (cusp height between passes, mm)");
  if (job.operation == Operation::kZLevel && k.error.empty())  // no `params` table at all
    if (job.zlevel.levels.empty() && !(job.zlevel.step_down > 0))
      k.error =
          check_zlevel_choice(false, false, job.zlevel, "'params.levels'", "'params.step_down'");
  if (job.operation == Operation::kFillet && job.fillet_reference.empty() && k.error.empty())
    k.fail("params.reference",
           "is required for a fillet job (the finishing ball, larger than the tool, e.g. "
           "\"ball:10\")");
  if (job.operation == Operation::kDrop && job.points.empty())
    k.fail("params.points", "is required for a drop job (CSV of x,y lines)");
  k.finish();
  if (!k.error.empty()) {
    job.error = k.error;
    job.error_status = "invalid_parameter";
  }
  return job;
}

}  // namespace

BatchSpec parse_batch_text(std::string_view text, const std::filesystem::path& base_dir,
                           const std::string& source_name) {
  toml::table root;
  try {
    root = toml::parse(text, source_name);
  } catch (const toml::parse_error& e) {
    std::ostringstream os;
    os << source_name << ":" << e.source().begin.line << ":" << e.source().begin.column << ": "
       << e.description();
    throw std::runtime_error(os.str());
  }
  BatchSpec b;
  Keys k(root, "");
  std::string out;
  if (k.string("output", out)) b.output = (base_dir / out).lexically_normal();
  std::string report;
  if (k.string("report", report)) b.report = (base_dir / report).lexically_normal();
  // A whole number >= 0 into out, or the key named.
  auto count = [&k](const char* key, int& out) {
    double v;
    if (!k.number(key, v)) return;
    if (v >= 0 && v <= 1e6 && v == static_cast<int>(v))
      out = static_cast<int>(v);
    else
      k.fail(key, "must be a whole number >= 0");
  };
  count("threads", b.threads);
  count("concurrent_jobs", b.concurrent_jobs);
  std::string memory_limit;
  if (k.string("memory_limit", memory_limit))
    if (std::string e = parse_byte_size(memory_limit, b.memory_limit); !e.empty())
      k.fail("memory_limit", e);
  std::string verify;
  if (k.string("verify", verify))
    if (std::string e = parse_verify_mode(verify, b.verify); !e.empty()) k.fail("verify", e);
  const toml::node* jobs = root.get("job");
  const std::string error = k.error;  // of the batch's own keys
  k.table("job");  // marks the key as known; its type is checked below
  k.error = error;
  k.finish();
  if (!k.error.empty()) throw std::runtime_error(source_name + ": " + k.error);
  const toml::array* arr = jobs ? jobs->as_array() : nullptr;
  if (!arr || arr->empty())
    throw std::runtime_error(source_name + ": no [[job]] tables: nothing to run");
  std::set<std::string> names;
  std::map<std::filesystem::path, std::string> gcode_of;  // G-code file -> its job
  for (std::size_t i = 0; i < arr->size(); ++i) {
    const toml::table* t = (*arr)[i].as_table();
    if (!t)
      throw std::runtime_error(source_name + ": job " + std::to_string(i + 1) + " is not a table");
    JobSpec job = parse_job(*t, i, base_dir);
    if (!t->contains("verify")) job.verify = b.verify;
    if (!names.insert(job.name).second) {
      job.error = "job name '" + job.name + "' is used twice";
      job.error_status = "invalid_parameter";
      job.name += "#";
      job.name += std::to_string(i + 1);
    }
    // Jobs may run at the same time: two of them must not write one G-code file.
    if (!job.gcode.empty() && job.error.empty()) {
      const auto [at, fresh] = gcode_of.try_emplace(job.gcode.lexically_normal(), job.name);
      if (!fresh) {
        job.error = "gcode.path '" + job.gcode.string() + "' is also job '" + at->second +
                    "''s: each job needs a G-code file of its own";
        job.error_status = "invalid_parameter";
      }
    }
    b.jobs.push_back(std::move(job));
  }
  return b;
}

BatchSpec parse_batch_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path.string() + ": cannot open the batch file");
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_batch_text(ss.str(), path.parent_path(), path.string());
}

}  // namespace ncpath::jobs
