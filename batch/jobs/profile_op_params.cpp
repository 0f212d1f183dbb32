// The profile operations' parameters (offset, pocket, pocket3d): reading a job's `params`
// table, checking the values (validate), and the text forms the command line shares:
// stepover ("2.4" mm or "40%" of the tool diameter), order ("outward" / "inward") and milling
// ("climb" / "conventional").
#include "batch/jobs/profile_op_params.hpp"

#include <charconv>
#include <cmath>
#include <sstream>

namespace ncpath::jobs {

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

namespace {

// stepover: a number (mm) or a string percentage of the tool diameter. False when absent.
bool parse_stepover_key(Keys& k, const Cutter& tool, double& out) {
  if (!k.is_string("stepover")) return k.number("stepover", out);
  std::string text;
  if (k.string("stepover", text))
    if (std::string e = parse_stepover(text, tool, out); !e.empty()) k.fail("stepover", e);
  return true;
}

// order and milling of the linked pocket operations.
void parse_order_milling(Keys& k, CutOrder& order, Milling& milling) {
  std::string text;
  if (k.string("order", text))
    if (std::string e = parse_order(text, order); !e.empty()) k.fail("order", e);
  if (k.string("milling", text))
    if (std::string e = parse_milling(text, milling); !e.empty()) k.fail("milling", e);
}

}  // namespace

void parse_offset_params(Keys& k, JobSpec& job) {
  OffsetParams& p = job.offset;
  if (!parse_stepover_key(k, job.tool, p.stepover))
    k.fail("stepover", "is required (mm, or a percentage of the tool diameter like \"40%\")");
  k.number("stock", p.stock);
  k.number("depth", p.depth);
  k.number("tolerance", p.tolerance);
  k.number("join_tolerance", p.join_tolerance);
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

}  // namespace ncpath::jobs
