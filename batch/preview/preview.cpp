#include "batch/preview/preview.hpp"

#include <cairo-svg.h>
#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <variant>

#include "batch/jobs/job_verify.hpp"
#include "batch/output/cl_reader.hpp"
#include "batch/preview/preview_part.hpp"
#include "engine/verify_report.hpp"
#include "kernels/geom/tolerance.hpp"

namespace ncpath::preview {

Rgb cut_colour(double t) {
  // Blue (low) through teal and green to yellow (high): readable over the grey part.
  t = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0);
  return {0.15 + 0.8 * t * t, 0.25 + 0.6 * t, 0.75 - 0.6 * t};
}

namespace {

constexpr int kRampBins = 32;          // colours of the cutting paths' height ramp
constexpr double kMinSegmentPx = 0.5;  // shorter moves are merged into the next one
constexpr double kMarginPx = 20;       // around the drawing
constexpr double kTitlePx = 64;        // above it
constexpr double kFooterPx = 56;       // below it: scale bar and legend

// What the picture says of the job besides the part.
struct JobData {
  out::StoredJob job;
  std::vector<out::StatValue> stats;
  std::vector<VerifyViolation> worst;
};

JobData read_job(const std::filesystem::path& file, const std::string& name) {
  JobData d;
  bool found = false;
  for (out::StoredJob& j : out::read_jobs(file))
    if (j.name == name) {
      d.job = std::move(j);
      found = true;
    }
  if (!found) throw std::runtime_error(file.string() + ": no job named '" + name + "'");
  d.stats = out::read_stats(file, name);
  if (auto w = out::read_float64_array(file, name, "verify/worst"))
    d.worst = jobs::violations_from_rows(w->data);
  return d;
}

// First pass over the paths: their box, and into the picture's figures their counts,
// lengths and the range of the cutting heights.
struct PathSummary {
  Part box;  // only the box fields
  bool any_cut = false;
};

bool has_cl(const std::filesystem::path& file, const std::string& job) {
  try {
    out::PathReader r(file, job);
    return true;
  } catch (const std::exception&) {
    return false;  // a job that failed before writing paths
  }
}

PathSummary summarize(const std::filesystem::path& file, const std::string& job, Picture& pic) {
  PathSummary s;
  if (!has_cl(file, job)) return s;
  out::read_paths(file, job, [&](const ClChunk& c) {
    std::size_t i = 0;
    for (std::size_t k = 0; k < c.path_sizes.size(); ++k) {
      const auto kind = static_cast<PathKind>(c.path_kinds[k]);
      double& len = kind == PathKind::kCut           ? pic.cut_mm
                    : kind == PathKind::kLinkAtDepth ? pic.link_mm
                                                     : pic.rapid_mm;
      for (std::size_t e = i + c.path_sizes[k]; i < e; ++i) {
        const Vec3 p = c.point(i);
        if (i + 1 < e && std::isfinite(p.z()) && std::isfinite(c.point(i + 1).z()))
          len += (c.point(i + 1) - p).norm();  // a probe's point that touched nothing: no z
        if (s.box.empty) s.box.x_lo = s.box.x_hi = p.x(), s.box.y_lo = s.box.y_hi = p.y();
        s.box.empty = false;
        s.box.x_lo = std::min(s.box.x_lo, p.x());
        s.box.x_hi = std::max(s.box.x_hi, p.x());
        s.box.y_lo = std::min(s.box.y_lo, p.y());
        s.box.y_hi = std::max(s.box.y_hi, p.y());
        if (kind != PathKind::kCut || !std::isfinite(p.z())) continue;
        pic.z_lo = s.any_cut ? std::min(pic.z_lo, p.z()) : p.z();
        pic.z_hi = s.any_cut ? std::max(pic.z_hi, p.z()) : p.z();
        s.any_cut = true;
      }
    }
    pic.points += c.point_count();
    pic.paths += c.path_sizes.size();
  });
  return s;
}

// The frame that fits the part and the paths into the drawing area of a w x h picture.
Frame fit(const Part& part, const PathSummary& paths, int w, int h) {
  double x_lo = 0, y_lo = 0, x_hi = 1, y_hi = 1;
  bool first = true;
  for (const Part* b : {&part, &paths.box}) {
    if (b->empty) continue;
    x_lo = first ? b->x_lo : std::min(x_lo, b->x_lo);
    y_lo = first ? b->y_lo : std::min(y_lo, b->y_lo);
    x_hi = first ? b->x_hi : std::max(x_hi, b->x_hi);
    y_hi = first ? b->y_hi : std::max(y_hi, b->y_hi);
    first = false;
  }
  const double aw = w - 2 * kMarginPx, ah = h - kTitlePx - kFooterPx;
  const double dx = std::max(tol::kPreviewMinExtent, x_hi - x_lo),
               dy = std::max(tol::kPreviewMinExtent, y_hi - y_lo);
  Frame f;
  f.scale = std::min(aw / dx, ah / dy);
  f.x0 = x_lo;
  f.y1 = y_hi;
  f.left = kMarginPx + (aw - dx * f.scale) / 2;
  f.top = kTitlePx + (ah - dy * f.scale) / 2;
  return f;
}

void set(cairo_t* cr, const Rgb& c, double alpha = 1) {
  cairo_set_source_rgba(cr, c.r, c.g, c.b, alpha);
}

void draw_mesh(cairo_t* cr, const TriangleMesh& mesh, const Frame& frame, int w, int h) {
  const std::vector<Rgb> map = height_map(mesh, frame, w, h);
  cairo_surface_t* img = cairo_image_surface_create(CAIRO_FORMAT_RGB24, w, h);
  cairo_surface_flush(img);
  unsigned char* data = cairo_image_surface_get_data(img);
  const int stride = cairo_image_surface_get_stride(img);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const Rgb& c = map[static_cast<std::size_t>(y) * w + x];
      auto* px = reinterpret_cast<std::uint32_t*>(data + static_cast<std::size_t>(y) * stride) + x;
      *px = (static_cast<std::uint32_t>(c.r * 255) << 16) |
            (static_cast<std::uint32_t>(c.g * 255) << 8) | static_cast<std::uint32_t>(c.b * 255);
    }
  cairo_surface_mark_dirty(img);
  cairo_set_source_surface(cr, img, 0, 0);
  cairo_paint(cr);
  cairo_surface_destroy(img);
}

void draw_loops(cairo_t* cr, const Part& part, const Frame& frame) {
  cairo_new_path(cr);
  for (const auto& loop : part.loops) {
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const Vec2 p = frame.pixel(loop[i].x(), loop[i].y());
      i == 0 ? cairo_move_to(cr, p.x(), p.y()) : cairo_line_to(cr, p.x(), p.y());
    }
    cairo_close_path(cr);
  }
  cairo_set_fill_rule(cr, CAIRO_FILL_RULE_EVEN_ODD);
  set(cr, {0.93, 0.88, 0.78});
  cairo_fill_preserve(cr);
  set(cr, {0.35, 0.25, 0.15});
  cairo_set_line_width(cr, 1.5);
  cairo_stroke(cr);
}

// The paths, merged into a few strokes: the cutting ones by colour bin, links, rapids.
void draw_paths(cairo_t* cr, const std::filesystem::path& file, const std::string& job,
                const Frame& frame, const Picture& s) {
  if (s.points == 0) return;
  std::vector<std::vector<float>> cut(kRampBins);
  std::vector<float> link, rapid;
  const double z_span = std::max(tol::kPreviewMinZSpan, s.z_hi - s.z_lo);
  // The stroke a move of `kind` between heights za and zb goes into.
  auto strokes_of = [&](PathKind kind, double za, double zb) -> std::vector<float>& {
    if (kind == PathKind::kLinkAtDepth) return link;
    if (kind != PathKind::kCut) return rapid;
    const double t = std::max(0.0, ((za + zb) / 2 - s.z_lo) / z_span);  // NaN z: 0
    return cut[std::min<std::size_t>(kRampBins - 1, static_cast<std::size_t>(t * kRampBins))];
  };
  out::read_paths(file, job, [&](const ClChunk& c) {
    std::size_t i = 0;
    for (std::size_t k = 0; k < c.path_sizes.size(); ++k) {
      const std::size_t e = i + c.path_sizes[k];
      if (e == i) continue;  // an empty path
      const auto kind = static_cast<PathKind>(c.path_kinds[k]);
      Vec2 p = frame.pixel(c.xyz[3 * i], c.xyz[3 * i + 1]);
      double zp = c.xyz[3 * i + 2];
      for (++i; i < e; ++i) {
        const Vec2 q = frame.pixel(c.xyz[3 * i], c.xyz[3 * i + 1]);
        if ((q - p).norm() < kMinSegmentPx && i + 1 < e) continue;
        const double zq = c.xyz[3 * i + 2];
        std::vector<float>& to = strokes_of(kind, zp, zq);
        to.insert(to.end(), {float(p.x()), float(p.y()), float(q.x()), float(q.y())});
        p = q;
        zp = zq;
      }
    }
  });
  auto stroke = [&](const std::vector<float>& segs, const Rgb& colour, double width) {
    if (segs.empty()) return;
    cairo_new_path(cr);
    for (std::size_t k = 0; k + 3 < segs.size(); k += 4) {
      cairo_move_to(cr, segs[k], segs[k + 1]);
      cairo_line_to(cr, segs[k + 2], segs[k + 3]);
    }
    set(cr, colour);
    cairo_set_line_width(cr, width);
    cairo_stroke(cr);
  };
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  for (int b = 0; b < kRampBins; ++b) stroke(cut[b], cut_colour((b + 0.5) / kRampBins), 1.0);
  stroke(link, kLinkColour, 1.0);
  const double dash[] = {5, 3};
  cairo_set_dash(cr, dash, 2, 0);
  stroke(rapid, kRapidColour, 1.0);
  cairo_set_dash(cr, nullptr, 0, 0);
}

void text(cairo_t* cr, double x, double y, const std::string& s, double size, bool bold = false) {
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL,
                         bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size);
  cairo_move_to(cr, x, y);
  cairo_show_text(cr, s.c_str());
}

void draw_worst(cairo_t* cr, const std::vector<VerifyViolation>& worst, const Frame& frame) {
  for (const VerifyViolation& v : worst) {
    const Vec3 m = (v.from + v.to) / 2;
    const Vec2 p = frame.pixel(m.x(), m.y());
    cairo_new_path(cr);
    cairo_arc(cr, p.x(), p.y(), 10, 0, 2 * M_PI);
    set(cr, kRapidColour);
    cairo_set_line_width(cr, 2);
    cairo_stroke(cr);
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.3g mm %s", v.amount, violation_name(v.kind));
    text(cr, p.x() + 13, p.y() - 6, buf, 12, true);
  }
}

// `s` shortened (at a character boundary) and ended with "..." to fit `px` pixels in the
// current font.
std::string fit_text(cairo_t* cr, std::string s, double px) {
  cairo_text_extents_t e;
  cairo_text_extents(cr, s.c_str(), &e);
  while (e.x_advance > px && s.size() > 3) {
    std::size_t n = s.size() * 9 / 10;
    while (n > 0 && (static_cast<unsigned char>(s[n]) & 0xC0) == 0x80) --n;  // UTF-8 follower
    s = s.substr(0, n) + "...";
    cairo_text_extents(cr, s.c_str(), &e);
  }
  return s;
}

std::string stat_text(const std::vector<out::StatValue>& stats, const char* name,
                      const char* format) {
  for (const out::StatValue& s : stats)
    if (s.name == name) {
      char buf[64];
      if (const auto* d = std::get_if<double>(&s.value))
        std::snprintf(buf, sizeof buf, format, *d);
      else if (const auto* i = std::get_if<std::int64_t>(&s.value))
        std::snprintf(buf, sizeof buf, format, static_cast<double>(*i));
      else
        return "";
      return buf;
    }
  return "";
}

void draw_title(cairo_t* cr, const JobData& d, const Picture& s, const Part& part, int w) {
  const bool ok = d.job.status == "ok";
  set(cr, {0.1, 0.1, 0.1});
  text(cr, kMarginPx, 24, d.job.name + "  ·  " + d.job.operation + "  ·  ", 18, true);
  cairo_text_extents_t ext;
  cairo_text_extents(cr, (d.job.name + "  ·  " + d.job.operation + "  ·  ").c_str(), &ext);
  set(cr, ok ? Rgb{0.1, 0.55, 0.2} : kRapidColour);
  text(cr, kMarginPx + ext.x_advance, 24, d.job.status, 18, true);
  char line[256];
  std::snprintf(line, sizeof line,
                "%llu points in %llu paths  ·  cut %.0f mm, links %.0f mm, rapids %.0f mm",
                static_cast<unsigned long long>(s.points), static_cast<unsigned long long>(s.paths),
                s.cut_mm, s.link_mm, s.rapid_mm);
  std::string second = line;
  if (auto t = stat_text(d.stats, "total_s", "%.2f s"); !t.empty()) second += "  ·  " + t;
  if (auto g = stat_text(d.stats, "verify_max_gouge", "%.3g mm"); !g.empty())
    second += "  ·  verifier: deepest gouge " + g;
  set(cr, {0.2, 0.2, 0.2});
  text(cr, kMarginPx, 44, second, 13);
  std::string third = d.job.message;
  if (!part.problem.empty())
    third += (third.empty() ? "" : "  ·  ") + ("part not drawn: " + part.problem);
  cairo_set_font_size(cr, 12);
  third = fit_text(cr, third, w - 2 * kMarginPx);
  set(cr, ok ? Rgb{0.4, 0.4, 0.4} : kRapidColour);
  text(cr, kMarginPx, 60, third, 12);
}

// A round length (1, 2 or 5 times a power of ten) about a quarter of the drawing's width.
double nice_length(double mm) {
  const double p = std::pow(10.0, std::floor(std::log10(mm)));
  for (double m : {5.0, 2.0, 1.0})
    if (m * p <= mm) return m * p;
  return p;
}

void draw_scale_bar(cairo_t* cr, const Frame& frame, int w, int h) {
  const double mm = nice_length((w - 2 * kMarginPx) / 4 / frame.scale);
  const double x = kMarginPx, y = h - 22, len = mm * frame.scale;
  set(cr, {0.1, 0.1, 0.1});
  cairo_set_line_width(cr, 2);
  cairo_new_path(cr);
  cairo_move_to(cr, x, y - 6);
  cairo_line_to(cr, x, y);
  cairo_line_to(cr, x + len, y);
  cairo_line_to(cr, x + len, y - 6);
  cairo_stroke(cr);
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g mm", mm);
  text(cr, x, y + 16, buf, 12);
}

// The legend, right-aligned (about 530 pixels), clear of the scale bar on its left.
void draw_legend(cairo_t* cr, const Picture& s, bool worst, int w, int h) {
  double x = std::max(kMarginPx + (w - 2 * kMarginPx) / 4 + 40, w - kMarginPx - 530);
  const double y = h - 30;
  for (int k = 0; k < 40; ++k) {
    set(cr, cut_colour(k / 39.0));
    cairo_rectangle(cr, x + 2 * k, y - 8, 2, 10);
    cairo_fill(cr);
  }
  char buf[96];
  std::snprintf(buf, sizeof buf, "cut, z %.1f to %.1f mm", s.z_lo, s.z_hi);
  set(cr, {0.1, 0.1, 0.1});
  text(cr, x + 86, y + 1, buf, 12);
  x += 240;
  auto line_item = [&](const Rgb& c, bool dashed, const char* label) {
    const double dash[] = {5, 3};
    cairo_set_dash(cr, dash, dashed ? 2 : 0, 0);
    set(cr, c);
    cairo_set_line_width(cr, 2);
    cairo_new_path(cr);
    cairo_move_to(cr, x, y - 3);
    cairo_line_to(cr, x + 24, y - 3);
    cairo_stroke(cr);
    cairo_set_dash(cr, nullptr, 0, 0);
    set(cr, {0.1, 0.1, 0.1});
    text(cr, x + 30, y + 1, label, 12);
    x += 80;
  };
  line_item(kLinkColour, false, "link");
  line_item(kRapidColour, true, "rapid");
  if (!worst) return;
  set(cr, kRapidColour);
  cairo_new_path(cr);
  cairo_arc(cr, x + 8, y - 3, 7, 0, 2 * M_PI);
  cairo_stroke(cr);
  set(cr, {0.1, 0.1, 0.1});
  text(cr, x + 22, y + 1, "verifier's worst", 12);
}

void check(cairo_status_t st, const char* what) {
  if (st != CAIRO_STATUS_SUCCESS)
    throw std::runtime_error(std::string("preview: ") + what + ": " + cairo_status_to_string(st));
}

// Draws the whole picture on `surface` (w x h).
Picture draw(cairo_surface_t* surface, const std::filesystem::path& file, const std::string& job,
             int w, int h) {
  const JobData d = read_job(file, job);
  Part part;
  try {
    part = load_part(jobs::stored_job_spec(d.job.operation, d.job.input_path, d.job.tool_json,
                                           d.job.params_json));
  } catch (const std::exception& e) {  // a job whose spec was invalid: its paths alone
    part.problem = e.what();
  }
  Picture pic;
  const PathSummary s = summarize(file, job, pic);
  pic.frame = fit(part, s, w, h);
  cairo_t* cr = cairo_create(surface);
  std::unique_ptr<cairo_t, void (*)(cairo_t*)> own(cr, cairo_destroy);
  set(cr, kBackground);
  cairo_paint(cr);
  if (!part.mesh.facets.empty()) draw_mesh(cr, part.mesh, pic.frame, w, h);
  if (!part.loops.empty()) draw_loops(cr, part, pic.frame);
  draw_paths(cr, file, job, pic.frame, pic);
  draw_worst(cr, d.worst, pic.frame);
  set(cr, kBackground, 0.85);
  cairo_rectangle(cr, 0, 0, w, kTitlePx);
  cairo_rectangle(cr, 0, h - kFooterPx, w, kFooterPx);
  cairo_fill(cr);
  draw_title(cr, d, pic, part, w);
  draw_scale_bar(cr, pic.frame, w, h);
  draw_legend(cr, pic, !d.worst.empty(), w, h);
  check(cairo_status(cr), "drawing");
  return pic;
}

void check_size(const Options& o) {
  if (o.width < 200 || o.height < 150 || o.width > 20000 || o.height > 20000)
    throw std::invalid_argument("preview size must be 200 x 150 to 20000 x 20000 pixels");
}

cairo_status_t append(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

}  // namespace

Picture preview_png(const std::filesystem::path& cl_file, const std::string& job,
                    const Options& o) {
  check_size(o);
  cairo_surface_t* s = cairo_image_surface_create(CAIRO_FORMAT_RGB24, o.width, o.height);
  std::unique_ptr<cairo_surface_t, void (*)(cairo_surface_t*)> own(s, cairo_surface_destroy);
  check(cairo_surface_status(s), "image surface");
  Picture pic = draw(s, cl_file, job, o.width, o.height);
  check(cairo_surface_write_to_png_stream(s, append, &pic.png), "PNG");
  return pic;
}

Picture write_preview(const std::filesystem::path& cl_file, const std::string& job,
                      const std::filesystem::path& out, const Options& o) {
  check_size(o);
  const std::string ext = out.extension().string();
  if (ext == ".png") {
    Picture pic = preview_png(cl_file, job, o);
    std::FILE* f = std::fopen(out.c_str(), "wb");
    if (!f) throw std::runtime_error(out.string() + ": cannot write");
    const bool ok = std::fwrite(pic.png.data(), 1, pic.png.size(), f) == pic.png.size();
    if (std::fclose(f) != 0 || !ok) throw std::runtime_error(out.string() + ": cannot write");
    pic.png.clear();
    return pic;
  }
  if (ext != ".svg")
    throw std::invalid_argument(out.string() + ": a preview is a .png or an .svg file");
  cairo_surface_t* s = cairo_svg_surface_create(out.c_str(), o.width, o.height);
  std::unique_ptr<cairo_surface_t, void (*)(cairo_surface_t*)> own(s, cairo_surface_destroy);
  check(cairo_surface_status(s), ("SVG surface " + out.string()).c_str());
  const Picture pic = draw(s, cl_file, job, o.width, o.height);
  cairo_surface_finish(s);
  check(cairo_surface_status(s), ("writing " + out.string()).c_str());
  return pic;
}

}  // namespace ncpath::preview
