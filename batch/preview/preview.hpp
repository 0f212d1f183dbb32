#pragma once
// Pictures of a job stored in a CL file (docs/cli.md, "Previews and the batch report"):
// the part seen from above and the job's paths over it, drawn with cairo as PNG or SVG.
//
//   - The part: a mesh job's mesh (read again from the job's input, with its transform) as a
//     shaded height map: each pixel the highest facet over it, lit from the upper left and
//     tinted by height; a profile job's pockets filled, islands cut out, outlines drawn.
//   - The paths, from /jobs/<job>/cl: cutting paths coloured by the height of their points
//     (a ramp from the lowest to the highest), links at depth in orange, rapids dashed red.
//   - The verifier's worst locations (verify/worst) circled in red with their depth.
//   - A title (job, operation, status), a line of key figures (points, path lengths, time,
//     the verifier's deepest gouge), a legend and a scale bar in mm.
//
// The picture maps world x, y (mm) to pixels by one uniform scale (Frame), x to the right
// and y up, the part and the paths fitted with a margin.
// Errors: std::runtime_error (unreadable file, no such job, cairo failure: the message says
// which); std::invalid_argument for a bad size or an unknown file extension.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "kernels/geom/vec.hpp"

namespace ncpath::preview {

struct Options {
  int width = 1200, height = 900;  // pixels (SVG: points)
};

// World (mm) to picture (pixels): px = left + (x - x0) * scale, py = top + (y1 - y) * scale.
struct Frame {
  double scale = 1, x0 = 0, y1 = 0, left = 0, top = 0;
  Vec2 pixel(double x, double y) const { return {left + (x - x0) * scale, top + (y1 - y) * scale}; }
};

// What a picture shows, besides the pixels: its frame, the colours of the path kinds, and the
// lengths of the job's paths by kind (mm), for the report.
struct Picture {
  Frame frame;
  std::uint64_t points = 0, paths = 0;
  double cut_mm = 0, link_mm = 0, rapid_mm = 0;
  double z_lo = 0, z_hi = 0;  // range of the cutting points' heights (the colour ramp)
  std::string png;            // the PNG bytes, when asked for in memory
};

// RGB in [0, 1] of each kind of drawing, and of the cutting ramp at t in [0, 1].
struct Rgb {
  double r, g, b;
};
inline constexpr Rgb kLinkColour{0.95, 0.55, 0.1};
inline constexpr Rgb kRapidColour{0.85, 0.1, 0.1};
inline constexpr Rgb kBackground{1, 1, 1};
Rgb cut_colour(double t);

// Draws job `job` of `cl_file` into `out`: PNG or SVG by its extension (.png, .svg).
Picture write_preview(const std::filesystem::path& cl_file, const std::string& job,
                      const std::filesystem::path& out, const Options& options = {});

// The same picture as PNG bytes in memory (Picture::png).
Picture preview_png(const std::filesystem::path& cl_file, const std::string& job,
                    const Options& options = {});

}  // namespace ncpath::preview
