#include "batch/output/gcode_writer.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ncpath::out {

namespace {

// Largest |coordinate| accepted, mm: keeps quantised values far inside int64 at 6 decimals.
constexpr double kMaxCoordinate = 1e9;
constexpr std::size_t kFlushBytes = std::size_t{1} << 16;

// Printable ASCII without parentheses (which would end or nest a comment), at most 60 chars.
std::string comment_safe(const std::string& s) {
  std::string out;
  for (const char ch : s.substr(0, 60)) {
    const bool ok = ch >= ' ' && ch <= '~' && ch != '(' && ch != ')';
    out += ok ? ch : '_';
  }
  return out;
}

std::string path_msg(const std::filesystem::path& p) { return "'" + p.string() + "'"; }

}  // namespace

GcodeWriter::GcodeWriter(const std::filesystem::path& path, const GcodeParams& params)
    : path_(path), params_(params) {
  const GcodeParams& p = params_;
  if (p.decimals < 3 || p.decimals > 6) {
    throw std::invalid_argument("G-code decimals must be 3..6, got " + std::to_string(p.decimals));
  }
  for (int i = 0; i < p.decimals; ++i) scale_ *= 10;
  // Rounding budget: emitted end points move by up to sqrt(3)/2 units, arc centres by
  // sqrt(2)/2, and the controller's radius (start to centre) by sqrt(2): every point of an
  // emitted move lies within about 2.2 units of the fitted move. 3 units are reserved.
  const double rounding = 3.0 / static_cast<double>(scale_);
  if (!(p.arc_tolerance > rounding) || !std::isfinite(p.arc_tolerance)) {
    throw std::invalid_argument("G-code arc_tolerance must exceed the rounding budget " +
                                std::to_string(rounding) + " mm (raise decimals)");
  }
  const bool finite = std::isfinite(p.safe_z) && std::isfinite(p.feed) &&
                      std::isfinite(p.plunge_feed) && std::isfinite(p.spindle_rpm);
  if (!finite || std::abs(p.safe_z) > kMaxCoordinate || !(p.feed > 0) || !(p.plunge_feed > 0) ||
      !(p.spindle_rpm > 0)) {
    throw std::invalid_argument(
        "G-code params: safe_z must be finite, feed, plunge_feed and spindle_rpm positive");
  }
  fit_.tol = p.arc_tolerance - rounding;

  file_.open(path, std::ios::binary | std::ios::trunc);
  if (!file_) throw std::runtime_error("cannot create G-code file " + path_msg(path));

  const bool grbl = p.dialect == GcodeDialect::kGrbl;
  const Q safe = quant(p.safe_z);
  line(grbl ? "(ncpath G-code, dialect grbl: Grbl 0.9 / 1.1)"
            : "(ncpath G-code, dialect linuxcnc: LinuxCNC RS274NGC)");
  line("(job: " + comment_safe(p.job_name) + ")");
  line("(units mm, absolute, XY plane; safe Z " + num(safe) + "; arc tolerance " +
       num(quant(p.arc_tolerance)) + " mm)");
  line("(feed " + trimmed(p.feed) + " mm/min; plunge feed " + trimmed(p.plunge_feed) +
       " mm/min; spindle " + trimmed(p.spindle_rpm) + " rpm)");
  if (grbl) {
    // Only words every Grbl since 0.8 accepts; G40 (1.1) and G49 (0.9h) are Grbl's power-up
    // state anyway (no cutter compensation, no tool table).
    line("G21 G90 G17 G94");
  } else {
    line("G21 G90 G17");
    line("G40 G49 G80 G94");
  }
  // Retract before the spindle starts: the tool may sit low when the program begins.
  line(std::string("G0 Z").append(num(safe)));  // append: GCC 12 -Wrestrict false positive
  ++stats_.rapids;
  cur_[2] = safe;
  line(std::string("S").append(trimmed(p.spindle_rpm)).append(" M3"));
}

GcodeWriter::~GcodeWriter() {
  if (finished_) return;
  try {
    line("(incomplete: ncpath stopped before the end of the job; no program end)");
    flush();
  } catch (...) {
  }
}

GcodeWriter::Q GcodeWriter::quant(double v) const {
  return static_cast<Q>(std::llround(v * static_cast<double>(scale_)));
}

std::string GcodeWriter::num(Q q) const {
  // Integer arithmetic on the quantised value: exact, no exponent, and 0 is never "-0".
  std::string s = q < 0 ? "-" : "";
  const std::uint64_t a = q < 0 ? -static_cast<std::uint64_t>(q) : static_cast<std::uint64_t>(q);
  const auto sc = static_cast<std::uint64_t>(scale_);
  s += std::to_string(a / sc);
  std::string frac = std::to_string(a % sc);
  s += '.';
  s.append(static_cast<std::size_t>(params_.decimals) - frac.size(), '0');
  s += frac;
  return s;
}

std::string GcodeWriter::trimmed(double v) const {
  // F and S words without trailing zeros (F800, F812.5): fixed decimals are for coordinates.
  std::string s = num(quant(v));
  while (s.back() == '0') s.pop_back();
  if (s.back() == '.') s.pop_back();
  return s;
}

void GcodeWriter::line(const std::string& text) {
  buf_ += text;
  buf_ += '\n';
  if (buf_.size() >= kFlushBytes) flush();
}

void GcodeWriter::flush() {
  file_.write(buf_.data(), static_cast<std::streamsize>(buf_.size()));
  buf_.clear();
  if (!file_) throw std::runtime_error("error writing G-code file " + path_msg(path_));
}

void GcodeWriter::set_feed(double feed, std::string& text) {
  if (feed == cur_feed_) return;
  text += " F" + trimmed(feed);
  cur_feed_ = feed;
}

void GcodeWriter::rapid_xy(Q x, Q y) {
  if (xy_known_ && x == cur_[0] && y == cur_[1]) return;
  line("G0 X" + num(x) + " Y" + num(y));
  cur_[0] = x;
  cur_[1] = y;
  xy_known_ = true;
  ++stats_.rapids;
}

void GcodeWriter::rapid_z(Q z) {
  if (z == cur_[2]) return;
  line("G0 Z" + num(z));
  cur_[2] = z;
  ++stats_.rapids;
}

void GcodeWriter::feed_to(const Q t[3], double feed) {
  if (xy_known_ && t[0] == cur_[0] && t[1] == cur_[1] && t[2] == cur_[2]) return;
  std::string text = "G1";
  if (!xy_known_ || t[0] != cur_[0]) text += " X" + num(t[0]);
  if (!xy_known_ || t[1] != cur_[1]) text += " Y" + num(t[1]);
  if (t[2] != cur_[2]) text += " Z" + num(t[2]);
  set_feed(feed, text);
  line(text);
  std::copy(t, t + 3, cur_);
  xy_known_ = true;
  ++stats_.lines;
}

void GcodeWriter::enter(const double* p) {
  const Q t[3] = {quant(p[0]), quant(p[1]), quant(p[2])};
  if (xy_known_) {
    const double s = static_cast<double>(scale_);
    const Vec3 cur(static_cast<double>(cur_[0]) / s, static_cast<double>(cur_[1]) / s,
                   static_cast<double>(cur_[2]) / s);
    if ((cur - Vec3(p[0], p[1], p[2])).norm() <= params_.arc_tolerance) {
      feed_to(t, params_.feed);  // continues where the tool is
      return;
    }
  }
  const Q safe = quant(params_.safe_z);
  if (cur_[2] < safe) {
    rapid_z(safe);
    ++stats_.retractions;
  }
  rapid_xy(t[0], t[1]);
  if (t[2] >= safe) {
    rapid_z(t[2]);
    return;
  }
  rapid_z(safe);  // down from a higher clearance at rapid speed, then plunge at plunge_feed
  feed_to(t, params_.plunge_feed);
  ++stats_.plunges;
}

void GcodeWriter::emit_path(std::span<const double> xyz) {
  const std::size_t n = xyz.size() / 3;
  std::size_t a = 0;
  while (a < n) {
    // A run of points with finite z; points without z split the path.
    while (a < n && !std::isfinite(xyz[3 * a + 2])) ++a;
    std::size_t b = a;
    while (b < n && std::isfinite(xyz[3 * b + 2])) ++b;
    if (a == b) break;
    enter(&xyz[3 * a]);
    moves_.clear();
    fit_arcs(xyz.subspan(3 * a, 3 * (b - a)), fit_, moves_);
    for (const FitMove& mv : moves_) {
      const Q t[3] = {quant(mv.end.x()), quant(mv.end.y()), quant(mv.end.z())};
      // An arc whose end rounds onto its start would be read as a full circle: its chord is
      // below the resolution, so the line is within the rounding budget.
      if (mv.kind == SegKind::kLine || (t[0] == cur_[0] && t[1] == cur_[1])) {
        feed_to(t, params_.feed);
        continue;
      }
      std::string text = mv.kind == SegKind::kArcCw ? "G2" : "G3";
      text += " X" + num(t[0]) + " Y" + num(t[1]);
      if (t[2] != cur_[2]) text += " Z" + num(t[2]);
      // Centre relative to the start as emitted, so that the controller's start radius and
      // end radius differ only by rounding.
      text +=
          " I" + num(quant(mv.centre.x()) - cur_[0]) + " J" + num(quant(mv.centre.y()) - cur_[1]);
      set_feed(params_.feed, text);
      line(text);
      std::copy(t, t + 3, cur_);
      ++stats_.arcs;
    }
    a = b;
  }
}

void GcodeWriter::emit_rapid(std::span<const double> xyz) {
  const std::size_t n = xyz.size() / 3;
  if (n == 0) return;
  const Q safe = quant(params_.safe_z);
  // Travel height: safe_z, or higher if the rapid's own points are higher.
  Q travel = safe;
  for (std::size_t k = 0; k < n; ++k) {
    if (std::isfinite(xyz[3 * k + 2])) travel = std::max(travel, quant(xyz[3 * k + 2]));
  }
  if (cur_[2] < travel) {
    if (cur_[2] < safe) ++stats_.retractions;
    rapid_z(travel);
  }
  for (std::size_t k = 0; k < n; ++k) rapid_xy(quant(xyz[3 * k]), quant(xyz[3 * k + 1]));
  const double z_end = xyz[3 * n - 1];
  if (!std::isfinite(z_end)) return;
  const Q t[3] = {cur_[0], cur_[1], quant(z_end)};
  if (t[2] >= safe) {
    rapid_z(t[2]);
    return;
  }
  rapid_z(safe);
  feed_to(t, params_.plunge_feed);
  ++stats_.plunges;
}

void GcodeWriter::append(const ClChunk& chunk) {
  if (finished_) throw std::logic_error("GcodeWriter::append after finish()");
  if (chunk.path_kinds.size() != chunk.path_sizes.size()) {
    throw std::invalid_argument("ClChunk: path_kinds and path_sizes differ in length");
  }
  std::size_t total = 0;
  for (std::size_t i = 0; i < chunk.path_sizes.size(); ++i) {
    total += chunk.path_sizes[i];
    if (chunk.path_kinds[i] > static_cast<std::uint8_t>(PathKind::kRapid)) {
      throw std::invalid_argument("ClChunk: unknown path kind " +
                                  std::to_string(chunk.path_kinds[i]) + " of path " +
                                  std::to_string(i));
    }
  }
  if (chunk.xyz.size() != 3 * total) {
    throw std::invalid_argument("ClChunk: xyz has " + std::to_string(chunk.xyz.size()) +
                                " values, path_sizes need " + std::to_string(3 * total));
  }
  for (std::size_t k = 0; k < chunk.xyz.size(); ++k) {
    const double v = chunk.xyz[k];
    // x and y must be finite; z may be NaN (no contact), never infinite or huge.
    const bool ok = k % 3 == 2 ? (std::isnan(v) || std::abs(v) <= kMaxCoordinate)
                               : std::abs(v) <= kMaxCoordinate;
    if (!ok) {
      throw std::invalid_argument("ClChunk: point " + std::to_string(k / 3) +
                                  " has a non-finite or out-of-range coordinate");
    }
  }

  const std::span<const double> all(chunk.xyz);
  std::size_t offset = 0;
  for (std::size_t i = 0; i < chunk.path_sizes.size(); ++i) {
    const std::span<const double> pts = all.subspan(3 * offset, 3 * chunk.path_sizes[i]);
    offset += chunk.path_sizes[i];
    if (static_cast<PathKind>(chunk.path_kinds[i]) == PathKind::kRapid) {
      emit_rapid(pts);
    } else {
      emit_path(pts);
    }
    ++stats_.paths;
  }
  flush();
}

void GcodeWriter::finish() {
  if (finished_) throw std::logic_error("GcodeWriter::finish called twice");
  finished_ = true;  // no "incomplete" trailer even if the postamble fails to write
  const Q safe = quant(params_.safe_z);
  if (cur_[2] < safe) rapid_z(safe);
  line("M5");
  line("M2");
  flush();
  file_.close();
  if (!file_) throw std::runtime_error("error closing G-code file " + path_msg(path_));
}

}  // namespace ncpath::out
