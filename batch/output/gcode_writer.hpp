#pragma once
// Writer of G-code programs for LinuxCNC (RS274NGC) and Grbl from streamed CL data. The
// program is the same path as the CL data (and the HDF5 file written from it) to the chordal
// tolerance `arc_tolerance`; the exact preamble, postamble and rules are in docs/gcode.md.
//
//   out::GcodeWriter w("part.ngc", {.dialect = out::GcodeDialect::kLinuxCnc, .job_name = "a"});
//   w.append(chunk);   // as often as needed, paths in cutting order
//   w.finish();        // postamble; the program is complete only after this
//
// Paths: kCut and kLinkAtDepth paths are cut at `feed` with G1/G2/G3 (lines and arcs fitted
// within the tolerance by kernels/curves/arc_fit); kRapid paths are travelled with G0 at safe
// height (retract, move, plunge at `plunge_feed`). Whenever a path does not start where the
// tool is (farther than arc_tolerance), the writer retracts to safe_z, moves over with G0 and
// plunges. Points with a non-finite z (the tool touched nothing there) split a path: the tool
// retracts over them.
//
// Errors: std::invalid_argument for bad parameters or chunks (nothing of the chunk is
// written); std::runtime_error naming the path when the file cannot be created or written.
// Not thread-safe; one writer per file.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <span>
#include <string>
#include <vector>

#include "engine/cl_chunk.hpp"
#include "kernels/curves/arc_fit.hpp"

namespace ncpath::out {

enum class GcodeDialect { kLinuxCnc, kGrbl };

struct GcodeParams {
  GcodeDialect dialect = GcodeDialect::kLinuxCnc;
  double safe_z = 5;             // mm, travel height for G0 moves (absolute, work coordinates)
  double feed = 800;             // mm/min, cutting and linking moves
  double plunge_feed = 200;      // mm/min, plunges from safe height to the path
  double spindle_rpm = 12000;    // rev/min, S word (M3: clockwise)
  double arc_tolerance = 0.005;  // mm, emitted path vs CL points (fitting + rounding), > 0
  int decimals = 4;              // digits after the point of coordinates, 3..6
  std::string job_name;          // written in the header comment (sanitised)
};

// What the writer emitted so far.
struct GcodeStats {
  std::int64_t paths = 0;        // paths appended (any kind)
  std::int64_t lines = 0;        // G1 moves (cutting, linking and plunges)
  std::int64_t arcs = 0;         // G2/G3 moves
  std::int64_t rapids = 0;       // G0 moves
  std::int64_t retractions = 0;  // climbs from below safe_z to safe height between paths
  std::int64_t plunges = 0;      // descents from safe height onto a path
};

class GcodeWriter {
 public:
  // Creates/truncates `path` and writes the preamble. Throws std::invalid_argument for bad
  // params, std::runtime_error naming the path when the file cannot be created.
  GcodeWriter(const std::filesystem::path& path, const GcodeParams& params);
  // Without finish(), the file ends with a comment saying it is incomplete and has no program
  // end (LinuxCNC refuses to run it); errors are swallowed.
  ~GcodeWriter();
  GcodeWriter(const GcodeWriter&) = delete;
  GcodeWriter& operator=(const GcodeWriter&) = delete;

  // Appends whole paths (chunk.xyz: 3 doubles per point, mm; path_sizes and path_kinds one per
  // path). Checked first: sizes consistent, kinds known, x and y finite.
  void append(const ClChunk& chunk);
  // Writes the postamble and closes the file; std::runtime_error if anything failed. Further
  // append() or finish() calls throw std::logic_error.
  void finish();

  const GcodeStats& stats() const { return stats_; }
  const GcodeParams& params() const { return params_; }

 private:
  using Q = std::int64_t;  // coordinate in units of 10^-decimals mm

  Q quant(double v) const;
  std::string num(Q q) const;           // fixed decimals, never "-0" or an exponent
  std::string trimmed(double v) const;  // num() without trailing zeros, for F and S
  void line(const std::string& text);
  void emit_path(std::span<const double> xyz);
  void emit_rapid(std::span<const double> xyz);
  void enter(const double* p);  // go to point p (3 doubles) from wherever the tool is
  void rapid_xy(Q x, Q y);
  void rapid_z(Q z);
  void feed_to(const Q t[3], double feed);
  void set_feed(double feed, std::string& text);
  void flush();

  std::filesystem::path path_;
  GcodeParams params_;
  ArcFitParams fit_;
  Q scale_ = 1;  // 10^decimals
  std::ofstream file_;
  std::string buf_;
  bool finished_ = false;
  bool xy_known_ = false;  // false until the first XY move
  Q cur_[3] = {0, 0, 0};   // emitted position (quantised), z always known after the preamble
  double cur_feed_ = -1;   // modal F, -1: none yet
  GcodeStats stats_;
  std::vector<FitMove> moves_;  // scratch, reused
};

}  // namespace ncpath::out
