// Previews and the batch report (batch/preview/preview.hpp, report.hpp), checked on their
// pixels: the paths are drawn where the HDF5 file says, in the colour of their kind and
// height; the part is drawn under them (a pocket's islands left out); the report holds every
// job, failed ones first, and opens in headless Chromium with its pictures.
#include <gtest/gtest.h>

#include <cairo.h>

#include <cmath>
#include <fstream>
#include <memory>
#include <regex>
#include <string>

#include "batch/io/stl_writer.hpp"
#include "batch/jobs/job_runner.hpp"
#include "batch/jobs/job_verify.hpp"
#include "batch/output/cl_reader.hpp"
#include "batch/preview/preview.hpp"
#include "batch/preview/report.hpp"
#include "tests/batch/cli_run.hpp"
#include "tests/batch/output/h5_read.hpp"
#include "tests/support/meshes.hpp"

namespace ncpath::preview {
namespace {

namespace h5 = out::test;

// A decoded picture: the pixel at (x, y) as RGB in [0, 1].
class Pixels {
 public:
  explicit Pixels(const std::string& png) : pos_(0), png_(png) {
    s_ = cairo_image_surface_create_from_png_stream(read, this);
    EXPECT_EQ(cairo_surface_status(s_), CAIRO_STATUS_SUCCESS);
    cairo_surface_flush(s_);
  }
  ~Pixels() { cairo_surface_destroy(s_); }
  Pixels(const Pixels&) = delete;
  Pixels& operator=(const Pixels&) = delete;
  int width() const { return cairo_image_surface_get_width(s_); }
  int height() const { return cairo_image_surface_get_height(s_); }
  Rgb at(int x, int y) const {
    const unsigned char* row = cairo_image_surface_get_data(s_) +
                               static_cast<std::size_t>(y) * cairo_image_surface_get_stride(s_);
    const std::uint32_t v = reinterpret_cast<const std::uint32_t*>(row)[x];
    return {((v >> 16) & 255) / 255.0, ((v >> 8) & 255) / 255.0, (v & 255) / 255.0};
  }
  // The pixel of the 3 x 3 around p closest to `want`: its distance to it.
  double nearest(const Vec2& p, const Rgb& want) const {
    double best = 1e9;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
        best = std::min(best, distance(at(int(p.x()) + dx, int(p.y()) + dy), want));
    return best;
  }
  static double distance(const Rgb& a, const Rgb& b) {
    return std::sqrt((a.r - b.r) * (a.r - b.r) + (a.g - b.g) * (a.g - b.g) +
                     (a.b - b.b) * (a.b - b.b));
  }

 private:
  static cairo_status_t read(void* self, unsigned char* data, unsigned int n) {
    auto* p = static_cast<Pixels*>(self);
    if (p->pos_ + n > p->png_.size()) return CAIRO_STATUS_READ_ERROR;
    std::copy_n(p->png_.data() + p->pos_, n, data);
    p->pos_ += n;
    return CAIRO_STATUS_SUCCESS;
  }
  std::size_t pos_;
  const std::string& png_;
  cairo_surface_t* s_;
};

jobs::JobOutcome run_job(const jobs::JobSpec& job, const std::filesystem::path& out) {
  jobs::BatchSpec b;
  b.output = out;
  b.threads = 1;
  b.jobs = {job};
  return jobs::run_batch(b, jobs::BatchObserver{}).at(0);
}

// A sparse raster (lines 4 mm apart) over a dome of radius 12 on a plate.
jobs::JobSpec dome_raster(const std::filesystem::path& dir) {
  io::write_binary_stl(dir / "dome.stl", test::height_field(48, 40, [](double x, double y) {
                         const double r2 = (x - 20) * (x - 20) + (y - 20) * (y - 20);
                         return r2 < 144 ? std::sqrt(144 - r2) : 0.0;
                       }));
  jobs::JobSpec job;
  job.name = "dome";
  job.input = dir / "dome.stl";
  EXPECT_EQ(jobs::parse_tool("ball:2", job.tool), "");
  job.raster.interval = 4;
  job.raster.step = 0.2;
  return job;
}

// Where the file has a cutting point, the picture has its height's colour (the pixel nearest
// to it at least half-way from the part's colour under it to the path's: lines are one pixel
// wide and anti-aliased); half-way between two lines there is the part, not a path.
TEST(Preview, CuttingPathsAreDrawnWhereTheFileSaysInTheirHeightsColour) {
  const auto dir = h5::out_dir("preview_raster");
  ASSERT_EQ(run_job(dome_raster(dir), dir / "r.h5").status, "ok");
  const Picture pic = preview_png(dir / "r.h5", "dome", Options{800, 600});
  const Pixels px(pic.png);
  ASSERT_EQ(px.width(), 800);
  ASSERT_EQ(px.height(), 600);
  ASSERT_GT(pic.z_hi - pic.z_lo, 10);
  int checked = 0, drawn = 0;
  out::read_paths(dir / "r.h5", "dome", [&](const ClChunk& c) {
    std::size_t start = 0;
    for (std::size_t k = 0; k < c.path_sizes.size(); start += c.path_sizes[k++]) {
      if (c.path_kinds[k] != static_cast<std::uint8_t>(PathKind::kCut)) continue;
      for (std::size_t i = start; i < start + c.path_sizes[k]; i += 7) {
        const Vec3 p = c.point(i);
        if (p.x() < 1 || p.x() > 39) continue;  // the part's edge: no part beside the line
        const Rgb want = cut_colour((p.z() - pic.z_lo) / (pic.z_hi - pic.z_lo));
        // The part under the line: 2 mm across it (half-way to the next line), inwards.
        const double y_part = p.y() + (p.y() < 20 ? 2 : -2);
        const Vec2 q = pic.frame.pixel(p.x(), p.y()), under = pic.frame.pixel(p.x(), y_part);
        const Rgb part = px.at(int(under.x()), int(under.y()));
        EXPECT_GT(Pixels::distance(part, kBackground), 0.05) << "no part at " << p.transpose();
        ++checked;
        drawn += px.nearest(q, want) <= 0.5 * Pixels::distance(part, want) + 0.06;
      }
    }
  });
  EXPECT_GT(checked, 300);
  EXPECT_GE(drawn, checked * 98 / 100) << drawn << " of " << checked;
}

// The plate pocket (datasets/pockets/plate.toml: an island of radius 12 at (45, 50)) with a
// flat 8 mm end mill, no stock: the island's centre is left blank, the pocket's floor next to
// the island is filled, and the first loop around the island, a circle of radius 12 + 4, is
// drawn in the colour of its depth.
TEST(Preview, APocketShowsItsIslandsAndItsLoops) {
  const auto dir = h5::out_dir("preview_pocket");
  jobs::JobSpec job;
  job.name = "plate";
  job.operation = jobs::Operation::kPocket;
  job.input = std::filesystem::path(NCPATH_SOURCE_DIR) / "datasets/pockets/plate.toml";
  ASSERT_EQ(jobs::parse_tool("flat:8", job.tool), "");
  job.pocket.stepover = 3.2;
  job.pocket.depth = 10;
  job.pocket.stepdown = 10;
  ASSERT_EQ(run_job(job, dir / "p.h5").status, "ok");
  const Picture pic = preview_png(dir / "p.h5", "plate", Options{1200, 900});
  const Pixels px(pic.png);
  auto pixel = [&](double x, double y) { return pic.frame.pixel(x, y); };
  const Vec2 centre = pixel(45, 50);
  EXPECT_LT(Pixels::distance(px.at(int(centre.x()), int(centre.y())), kBackground), 0.02);
  const Rgb floor{0.93, 0.88, 0.78};
  const Rgb want = cut_colour((-10 - pic.z_lo) / (pic.z_hi - pic.z_lo));
  int drawn = 0;
  for (int k = 0; k < 24; ++k) {
    const double a = 2 * M_PI * k / 24;
    const Vec2 f = pixel(45 + 14 * std::cos(a), 50 + 14 * std::sin(a));
    EXPECT_LT(Pixels::distance(px.at(int(f.x()), int(f.y())), floor), 0.05) << "angle " << a;
    drawn += px.nearest(pixel(45 + 16 * std::cos(a), 50 + 16 * std::sin(a)), want) <=
             0.5 * Pixels::distance(floor, want) + 0.06;
  }
  EXPECT_EQ(drawn, 24);
}

// A job whose verifier found gouges (written here as the verifier writes them): each of its
// worst moves is circled in red, 10 pixels around the move's middle; the picture says why
// the part is missing (the job's attributes name no tool).
TEST(Preview, TheVerifiersWorstMovesAreCircled) {
  const auto dir = h5::out_dir("preview_worst");
  {
    out::ClFile f(dir / "g.h5", "test");
    out::ClJob cl = f.begin_job("g", out::JobInfo{"raster", "none.stl", "", "{}", "{}"});
    ClChunk c;
    for (int i = 0; i <= 100; ++i) {
      c.xyz.insert(c.xyz.end(), {double(i), 0.0, 0.0, double(i), 50.0, 0.0});  // x = i, up
      c.contact.insert(c.contact.end(), {out::kContactFacet, out::kContactFacet});
      c.path_sizes.push_back(2);
      c.path_kinds.push_back(static_cast<std::uint8_t>(PathKind::kCut));
    }
    c.path_sizes.push_back(0);  // an empty path, last: nothing to draw, nothing to read past
    c.path_kinds.push_back(static_cast<std::uint8_t>(PathKind::kCut));
    cl.append_paths(c.xyz, c.contact, c.path_sizes, c.path_kinds);
    VerifyReport r;
    r.add({7, 3, Vec3(20, 10, 0), Vec3(20, 20, 0), 0.5, ViolationKind::kMesh});
    r.add({9, 4, Vec3(70, 30, 0), Vec3(70, 40, 0), 0.2, ViolationKind::kMesh});
    jobs::write_verify_worst(cl, r);
    cl.set_status("failed_verification", "failed verification: move 7 ...");
    cl.close();
    f.close();
  }
  const Picture pic = preview_png(dir / "g.h5", "g", Options{800, 600});
  const Pixels px(pic.png);
  for (const Vec2& mid : {Vec2(20, 15), Vec2(70, 35)}) {
    const Vec2 m = pic.frame.pixel(mid.x(), mid.y());
    int red = 0;
    for (int k = 0; k < 36; ++k) {
      const double a = 2 * M_PI * k / 36;
      red += px.nearest(m + 10 * Vec2(std::cos(a), std::sin(a)), kRapidColour) < 0.25;
    }
    EXPECT_GE(red, 30) << "circle at " << mid.transpose();
    // Inside the circle, away from its ring and the paths: not red.
    EXPECT_GT(Pixels::distance(px.at(int(m.x()) + 4, int(m.y()) + 4), kRapidColour), 0.5);
  }
}

TEST(Preview, SvgHasTheSameDrawingAsVectors) {
  const auto dir = h5::out_dir("preview_svg");
  ASSERT_EQ(run_job(dome_raster(dir), dir / "r.h5").status, "ok");
  const Picture pic = write_preview(dir / "r.h5", "dome", dir / "dome.svg", Options{640, 480});
  const std::string svg = test::slurp(dir / "dome.svg");
  EXPECT_NE(svg.find("<svg"), std::string::npos);
  EXPECT_NE(svg.find("width=\"640\""), std::string::npos);
  EXPECT_NE(svg.find("<path"), std::string::npos);   // the strokes, as vectors
  EXPECT_NE(svg.find("<image"), std::string::npos);  // the part's height map
  EXPECT_GT(pic.points, 1000u);
  EXPECT_THROW(write_preview(dir / "r.h5", "dome", dir / "dome.jpg"), std::invalid_argument);
  EXPECT_THROW(write_preview(dir / "r.h5", "none", dir / "none.png"), std::runtime_error);
}

// A batch of three jobs, the second failing: the page lists the failed one first, with its
// message, then the others; every row has its thumbnail and a link to the full picture.
// Headless Chromium loads it with no console message, the DOM it builds has the three rows,
// and its screenshot shows the pictures (not a blank page).
TEST(Report, OpensInChromiumWithEveryJobFailedFirst) {
  const auto dir = h5::out_dir("report");
  jobs::BatchSpec b;
  b.output = dir / "b.h5";
  b.threads = 1;
  b.jobs = {dome_raster(dir), dome_raster(dir), dome_raster(dir)};
  b.jobs[1].name = "broken";
  b.jobs[1].input = dir / "missing.stl";
  b.jobs[2].name = "dome2";
  b.jobs[2].raster.interval = 2;
  const auto outcomes = jobs::run_batch(b, jobs::BatchObserver{});
  ASSERT_EQ(outcomes[1].status, "invalid_input");
  EXPECT_EQ(write_report(b.output, dir / "r.html"), 3u);
  const std::string html = test::slurp(dir / "r.html");
  const auto row = [&](const std::string& name) { return html.find("<td>" + name + "</td>"); };
  ASSERT_NE(row("broken"), std::string::npos);
  EXPECT_LT(row("broken"), row("dome"));
  EXPECT_LT(row("dome"), row("dome2"));
  EXPECT_NE(html.find("missing.stl"), std::string::npos);  // the failed job's message
  std::size_t images = 0;
  for (std::size_t p = 0; (p = html.find("src=\"data:image/png;base64,", p)) != std::string::npos;
       ++p)
    ++images;
  EXPECT_EQ(images, 6u);  // a thumbnail and a full picture per job
  for (const char* id : {"full-0", "full-1", "full-2"}) {
    EXPECT_NE(html.find(std::string("href=\"#") + id), std::string::npos);
    EXPECT_NE(html.find(std::string("id=\"") + id), std::string::npos);
  }

  const std::string chromium =
      "timeout 120 chromium --headless --no-sandbox --disable-gpu "
      "--user-data-dir=" +
      (dir / "profile").string() + " --enable-logging=stderr --v=0 --window-size=1200,900 ";
  const std::string url = "file://" + (dir / "r.html").string();
  const test::CmdResult dom = test::run_command(chromium + "--dump-dom " + url);
  ASSERT_EQ(dom.exit_code, 0) << "chromium (scripts/install-deps.sh installs it): " << dom.output;
  EXPECT_EQ(dom.output.find("CONSOLE"), std::string::npos) << dom.output;
  const std::regex tr("<tr class=\"(ok|failed)\"");
  EXPECT_EQ(std::distance(std::sregex_iterator(dom.output.begin(), dom.output.end(), tr),
                          std::sregex_iterator()),
            3);
  const test::CmdResult shot =
      test::run_command(chromium + "--screenshot=" + (dir / "shot.png").string() + " " + url);
  ASSERT_EQ(shot.exit_code, 0) << shot.output;
  const std::string png = test::slurp(dir / "shot.png");
  const Pixels px(png);
  ASSERT_EQ(px.width(), 1200);
  // The first thumbnail's area (its row, the picture column) holds the part: many colours.
  int coloured = 0;
  for (int y = 100; y < 400; y += 3)
    for (int x = 20; x < 200; x += 3) {
      const Rgb c = px.at(x, y);
      coloured += std::abs(c.r - c.b) > 0.1 || std::abs(c.g - c.b) > 0.1;
    }
  EXPECT_GT(coloured, 200);
}

// The command line: `--preview` on a command draws its job; `ncpath preview` draws a job of
// a file and needs --job when the file has several; `ncpath run --report` writes the page.
TEST(PreviewCli, CommandsWriteTheirPicturesAndNameProblems) {
  const auto dir = h5::out_dir("preview_cli");
  io::write_binary_stl(dir / "p.stl", test::hemisphere(10, 6, 16));
  const std::string mesh = (dir / "p.stl").string();
  const test::CmdResult r =
      test::ncpath("raster --mesh " + mesh + " --tool ball:2 --interval 2 -q --out " +
                   (dir / "a.h5").string() + " --preview " + (dir / "a.png").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_GT(std::filesystem::file_size(dir / "a.png"), 1000u);
  const std::string a = (dir / "a.h5").string();
  EXPECT_EQ(test::ncpath("preview " + a + " -o " + (dir / "b.svg").string()).exit_code, 0);
  const test::CmdResult bad = test::ncpath("preview " + a + " -o " + (dir / "b.gif").string());
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.output.find(".png or an .svg"), std::string::npos) << bad.output;
  std::ofstream(dir / "b.toml") << "output = \"b.h5\"\nreport = \"b.html\"\n"
                                << "[[job]]\nname = \"x\"\ninput = \"p.stl\"\ntool = \"ball:3\"\n"
                                << "[[job]]\nname = \"y\"\ninput = \"p.stl\"\ntool = \"ball:9\"\n"
                                << "preview = \"y.svg\"\n";
  const test::CmdResult run = test::ncpath("run " + (dir / "b.toml").string() + " -q");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(test::slurp(dir / "b.html").find("<td>y</td>"), std::string::npos);
  EXPECT_NE(test::slurp(dir / "y.svg").find("<svg"), std::string::npos);
  const test::CmdResult two =
      test::ncpath("preview " + (dir / "b.h5").string() + " -o " + (dir / "c.png").string());
  EXPECT_EQ(two.exit_code, 2);
  EXPECT_NE(two.output.find("name one with --job (x, y)"), std::string::npos) << two.output;
}

}  // namespace
}  // namespace ncpath::preview
