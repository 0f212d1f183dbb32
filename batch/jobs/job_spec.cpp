#include "batch/jobs/job_spec.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

#include <toml++/toml.h>
#include <nlohmann/json.hpp>

#include "batch/jobs/mesh_op_params.hpp"
#include "batch/jobs/toml_keys.hpp"

namespace ncpath::jobs {

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

std::string parse_families(const std::string& text, ScanFamilies& out) {
  if (text == "x")
    out = ScanFamilies::kX;
  else if (text == "y")
    out = ScanFamilies::kY;
  else if (text == "both")
    out = ScanFamilies::kBoth;
  else
    return "must be \"x\", \"y\" or \"both\", got \"" + text + "\"";
  return "";
}

const char* families_name(ScanFamilies families) {
  switch (families) {
    case ScanFamilies::kX:
      return "x";
    case ScanFamilies::kY:
      return "y";
    case ScanFamilies::kBoth:
      return "both";
  }
  return "?";
}

std::string parse_stepover(const std::string& text, const Cutter& tool, double& out) {
  std::string t = text;
  const bool percent = !t.empty() && t.back() == '%';
  if (percent) t.pop_back();
  double v = 0;
  auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
  if (t.empty() || ec != std::errc() || ptr != t.data() + t.size())
    return "stepover '" + text + "' is not a number of mm or a percentage like \"40%\"";
  out = percent ? v / 100 * 2 * tool.radius : v;
  return "";
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

std::string validate(const OffsetParams& p) {
  std::ostringstream os;
  if (!(std::isfinite(p.stepover) && p.stepover > 0))
    os << "stepover must be a positive number of mm, got " << p.stepover;
  else if (!(std::isfinite(p.stock) && p.stock >= 0))
    os << "stock must be >= 0 mm, got " << p.stock;
  else if (!std::isfinite(p.depth))
    os << "depth must be a number of mm";
  else if (!(std::isfinite(p.tolerance) && p.tolerance > 0))
    os << "tolerance must be a positive number of mm, got " << p.tolerance;
  else if (!(std::isfinite(p.join_tolerance) && p.join_tolerance > 0))
    os << "join_tolerance must be a positive number of mm, got " << p.join_tolerance;
  return os.str();
}

namespace {

bool non_negative(double v) { return std::isfinite(v) && v >= 0; }

// The keys the linked pocket operations (pocket, pocket3d) share; "" or the first problem.
std::string validate_pocket_common(double stock, double tolerance, double join_tolerance,
                                   double clearance) {
  std::ostringstream os;
  if (!non_negative(stock))
    os << "stock must be >= 0 mm, got " << stock;
  else if (!(std::isfinite(tolerance) && tolerance > 0))
    os << "tolerance must be a positive number of mm, got " << tolerance;
  else if (!(std::isfinite(join_tolerance) && join_tolerance > 0))
    os << "join_tolerance must be a positive number of mm, got " << join_tolerance;
  else if (!non_negative(clearance))
    os << "clearance must be >= 0 mm, got " << clearance;
  return os.str();
}

}  // namespace

std::string validate(const PocketParams& p, const Cutter& tool) {
  std::ostringstream os;
  if (!(std::isfinite(p.stepover) && p.stepover > 0))
    os << "stepover must be a positive number of mm, got " << p.stepover;
  else if (p.stepover > 2 * tool.radius)
    os << "stepover " << p.stepover << " mm is larger than the tool diameter " << 2 * tool.radius
       << " mm: material would be left between the loops (at most 100%)";
  else if (!(std::isfinite(p.depth) && p.depth > 0))
    os << "depth must be a positive number of mm below the top, got " << p.depth;
  else if (!non_negative(p.stepdown))
    os << "stepdown must be >= 0 mm (0 = one pass at full depth), got " << p.stepdown;
  else if (std::string e =
               validate_pocket_common(p.stock, p.tolerance, p.join_tolerance, p.clearance);
           !e.empty())
    return e;
  else if (!non_negative(p.helix_radius))
    os << "helix_radius must be >= 0 mm (0 = half the tool radius), got " << p.helix_radius;
  else if (!(std::isfinite(p.ramp_angle) && p.ramp_angle > 0 && p.ramp_angle < 90))
    os << "ramp_angle must be in (0, 90) degrees, got " << p.ramp_angle;
  return os.str();
}

std::string validate(const Pocket3dJobParams& p, const Cutter& tool) {
  std::ostringstream os;
  if (tool.type != CutterType::kBall)
    os << "pocket3d needs a ball-end mill (ball:D): the path is planned for a ball of radius "
          "D/2 touching the sculptured bottom; got a "
       << cutter_type_name(tool.type) << " cutter";
  else if (!(std::isfinite(p.scallop) && p.scallop > 0 && p.scallop < tool.radius))
    os << "scallop must be a cusp height in mm between 0 and the ball radius " << tool.radius
       << " mm, got " << p.scallop;
  else if (!(std::isfinite(p.eps) && p.eps > 0))
    os << "eps (plan tolerance) must be a positive number of mm, got " << p.eps;
  else if (!(std::isfinite(p.delta) && p.delta > 0))
    os << "delta (surface tolerance) must be a positive number of mm, got " << p.delta;
  else if (std::string e =
               validate_pocket_common(p.stock, p.tolerance, p.join_tolerance, p.clearance);
           !e.empty())
    return e;
  else if (!non_negative(p.min_interval))
    os << "min_interval must be >= 0 mm (0 = a hundredth of the ball radius), got "
       << p.min_interval;
  return os.str();
}

const char* order_name(CutOrder order) {
  return order == CutOrder::kOutward ? "outward" : "inward";
}

const char* milling_name(Milling milling) {
  return milling == Milling::kClimb ? "climb" : "conventional";
}

std::string parse_order(const std::string& text, CutOrder& out) {
  if (text == "outward")
    out = CutOrder::kOutward;
  else if (text == "inward")
    out = CutOrder::kInward;
  else
    return "must be \"outward\" or \"inward\", got \"" + text + "\"";
  return "";
}

std::string parse_milling(const std::string& text, Milling& out) {
  if (text == "climb")
    out = Milling::kClimb;
  else if (text == "conventional")
    out = Milling::kConventional;
  else
    return "must be \"climb\" or \"conventional\", got \"" + text + "\"";
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

namespace {

void parse_raster_params(Keys& k, RasterParams& p) {
  std::string dir;
  if (k.string("direction", dir)) {
    if (dir == "x")
      p.direction = ScanDirection::kX;
    else if (dir == "y")
      p.direction = ScanDirection::kY;
    else
      k.fail("direction", "must be \"x\" or \"y\", got \"" + dir + "\"");
  }
  k.number("interval", p.interval);
  k.number("step", p.step);
  k.number("margin", p.margin);
  double rect[4];
  if (k.numbers("rect", 4, rect))
    p.rect = std::array<double, 4>{rect[0], rect[1], rect[2], rect[3]};
  k.number("adaptive_tolerance", p.adaptive_tolerance);
  k.number("min_step", p.min_step);
  double floor_z;
  if (k.number("floor_z", floor_z)) p.floor_z = floor_z;
  k.whole_number("chunk_lines", p.chunk_lines);
  k.number("strip_height", p.strip_height);
  k.number("bin_width", p.bin_width);
}

void parse_scan_params(Keys& k, ScanParams& p) {
  std::string families;
  if (k.string("families", families))
    if (std::string e = parse_families(families, p.families); !e.empty()) k.fail("families", e);
  k.number("interval", p.interval);
  k.number("tolerance", p.tolerance);
  k.number("margin", p.margin);
  double rect[4];
  if (k.numbers("rect", 4, rect))
    p.rect = std::array<double, 4>{rect[0], rect[1], rect[2], rect[3]};
  double floor_z;
  if (k.number("floor_z", floor_z)) p.floor_z = floor_z;
  k.whole_number("chunk_planes", p.chunk_planes);
}

// stepover: a number (mm) or a string percentage of the tool diameter. False when absent.
bool parse_stepover_key(Keys& k, const Cutter& tool, double& out) {
  if (!k.is_string("stepover")) return k.number("stepover", out);
  std::string text;
  if (k.string("stepover", text))
    if (std::string e = parse_stepover(text, tool, out); !e.empty()) k.fail("stepover", e);
  return true;
}

void parse_offset_params(Keys& k, JobSpec& job) {
  OffsetParams& p = job.offset;
  if (!parse_stepover_key(k, job.tool, p.stepover))
    k.fail("stepover", "is required (mm, or a percentage of the tool diameter like \"40%\")");
  k.number("stock", p.stock);
  k.number("depth", p.depth);
  k.number("tolerance", p.tolerance);
  k.number("join_tolerance", p.join_tolerance);
}

// order and milling of the linked pocket operations.
void parse_order_milling(Keys& k, CutOrder& order, Milling& milling) {
  std::string text;
  if (k.string("order", text))
    if (std::string e = parse_order(text, order); !e.empty()) k.fail("order", e);
  if (k.string("milling", text))
    if (std::string e = parse_milling(text, milling); !e.empty()) k.fail("milling", e);
}

void parse_pocket_params(Keys& k, JobSpec& job) {
  PocketParams& p = job.pocket;
  parse_stepover_key(k, job.tool, p.stepover);  // absent: the default set by parse_job
  k.number("stock", p.stock);
  if (!k.number("depth", p.depth) && k.error.empty())
    k.fail("depth", "is required for a pocket job (mm below the top, > 0)");
  k.number("stepdown", p.stepdown);
  k.number("tolerance", p.tolerance);
  k.number("join_tolerance", p.join_tolerance);
  parse_order_milling(k, p.order, p.milling);
  k.number("helix_radius", p.helix_radius);
  k.number("ramp_angle", p.ramp_angle);
  k.number("clearance", p.clearance);
}

void parse_pocket3d_params(Keys& k, JobSpec& job) {
  Pocket3dJobParams& p = job.pocket3d;
  if (!k.number("scallop", p.scallop) && k.error.empty())
    k.fail("scallop", "is required for a pocket3d job (cusp height between passes, mm)");
  k.number("eps", p.eps);
  k.number("delta", p.delta);
  k.number("stock", p.stock);
  if (!k.number("tolerance", p.tolerance)) p.tolerance = default_pocket3d_tolerance(p.eps);
  k.number("join_tolerance", p.join_tolerance);
  parse_order_milling(k, p.order, p.milling);
  k.number("clearance", p.clearance);
  k.number("min_interval", p.min_interval);
}

JobSpec parse_job(const toml::table& t, std::size_t index, const std::filesystem::path& base) {
  JobSpec job;
  job.name = "job" + std::to_string(index + 1);
  Keys k(t, "");
  k.string("name", job.name);
  std::string op = "raster";
  k.string("operation", op);
  if (op == "raster")
    job.operation = Operation::kRaster;
  else if (op == "drop")
    job.operation = Operation::kDrop;
  else if (op == "offset")
    job.operation = Operation::kOffset;
  else if (op == "pocket")
    job.operation = Operation::kPocket;
  else if (op == "pocket3d")
    job.operation = Operation::kPocket3d;
  else if (op == "scan")
    job.operation = Operation::kScan;
  else if (op == "zlevel")
    job.operation = Operation::kZLevel;
  else if (op == "pencil")
    job.operation = Operation::kPencil;
  else if (op == "fillet")
    job.operation = Operation::kFillet;
  else
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
  double threads;
  if (k.number("threads", threads)) {
    if (threads >= 0 && threads == static_cast<int>(threads))
      b.threads = static_cast<int>(threads);
    else
      k.fail("threads", "must be a whole number >= 0");
  }
  const toml::node* jobs = root.get("job");
  k.table("job");  // marks the key as known; its type is checked below
  k.error.clear();
  k.finish();
  if (!k.error.empty()) throw std::runtime_error(source_name + ": " + k.error);
  const toml::array* arr = jobs ? jobs->as_array() : nullptr;
  if (!arr || arr->empty())
    throw std::runtime_error(source_name + ": no [[job]] tables: nothing to run");
  std::set<std::string> names;
  for (std::size_t i = 0; i < arr->size(); ++i) {
    const toml::table* t = (*arr)[i].as_table();
    if (!t)
      throw std::runtime_error(source_name + ": job " + std::to_string(i + 1) + " is not a table");
    JobSpec job = parse_job(*t, i, base_dir);
    if (!names.insert(job.name).second) {
      job.error = "job name '" + job.name + "' is used twice";
      job.error_status = "invalid_parameter";
      job.name += "#" + std::to_string(i + 1);
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

std::string tool_json(const Cutter& c) {
  nlohmann::ordered_json j;
  j["type"] = cutter_type_name(c.type);
  j["diameter_mm"] = 2 * c.radius;
  j["corner_radius_mm"] = c.corner_radius;
  return j.dump();
}

std::string params_json(const JobSpec& job) {
  nlohmann::ordered_json j;
  j["operation"] = operation_name(job.operation);
  nlohmann::ordered_json t;
  t["scale"] = job.transform.scale;
  t["translate"] = {job.transform.translate.x(), job.transform.translate.y(),
                    job.transform.translate.z()};
  t["fit_xy"] = job.transform.fit_xy_mm ? nlohmann::ordered_json(*job.transform.fit_xy_mm)
                                        : nlohmann::ordered_json(nullptr);
  j["transform"] = t;
  if (job.operation == Operation::kRaster) {
    const RasterParams& p = job.raster;
    j["direction"] = p.direction == ScanDirection::kX ? "x" : "y";
    j["interval"] = p.interval;
    j["step"] = p.step;
    j["margin"] = p.margin;
    j["rect"] = p.rect ? nlohmann::ordered_json(*p.rect) : nlohmann::ordered_json(nullptr);
    j["adaptive_tolerance"] = p.adaptive_tolerance;
    j["min_step"] = p.min_step;
    j["floor_z"] = p.floor_z ? nlohmann::ordered_json(*p.floor_z) : nlohmann::ordered_json(nullptr);
    j["chunk_lines"] = p.chunk_lines;
    j["strip_height"] = p.strip_height;
    j["bin_width"] = p.bin_width;
  } else if (job.operation == Operation::kScan) {
    const ScanParams& p = job.scan;
    j["families"] = families_name(p.families);
    j["interval"] = p.interval;
    j["tolerance"] = p.tolerance;
    j["margin"] = p.margin;
    j["rect"] = p.rect ? nlohmann::ordered_json(*p.rect) : nlohmann::ordered_json(nullptr);
    j["floor_z"] = p.floor_z ? nlohmann::ordered_json(*p.floor_z) : nlohmann::ordered_json(nullptr);
    j["chunk_planes"] = p.chunk_planes;
  } else if (job.operation == Operation::kZLevel) {
    zlevel_params_json(job.zlevel, j);
  } else if (job.operation == Operation::kPencil) {
    pencil_params_json(job.pencil, j);
  } else if (job.operation == Operation::kFillet) {
    fillet_params_json(job.fillet, job.fillet_reference, j);
  } else if (job.operation == Operation::kOffset) {
    j["stepover"] = job.offset.stepover;
    j["stock"] = job.offset.stock;
    j["depth"] = job.offset.depth;
    j["tolerance"] = job.offset.tolerance;
    j["join_tolerance"] = job.offset.join_tolerance;
  } else if (job.operation == Operation::kPocket) {
    const PocketParams& p = job.pocket;
    j["stepover"] = p.stepover;
    j["stock"] = p.stock;
    j["depth"] = p.depth;
    j["stepdown"] = p.stepdown;
    j["tolerance"] = p.tolerance;
    j["join_tolerance"] = p.join_tolerance;
    j["order"] = order_name(p.order);
    j["milling"] = milling_name(p.milling);
    j["helix_radius"] = p.helix_radius;
    j["ramp_angle"] = p.ramp_angle;
    j["clearance"] = p.clearance;
    j["safe_z"] = job.gcode_safe_z.value_or(kDefaultSafeAboveTop);
  } else if (job.operation == Operation::kPocket3d) {
    const Pocket3dJobParams& p = job.pocket3d;
    j["surface"] = job.surface.string();
    j["scallop"] = p.scallop;
    j["eps"] = p.eps;
    j["delta"] = p.delta;
    j["stock"] = p.stock;
    j["tolerance"] = p.tolerance;
    j["join_tolerance"] = p.join_tolerance;
    j["order"] = order_name(p.order);
    j["milling"] = milling_name(p.milling);
    j["clearance"] = p.clearance;
    j["min_interval"] = p.min_interval;
    j["safe_z"] = job.gcode_safe_z.value_or(kDefaultSafeAboveTop);
  } else {
    j["points"] = job.points.string();
  }
  return j.dump();
}

}  // namespace ncpath::jobs
