#include "batch/io/profile_toml.hpp"

#include <toml++/toml.h>
#include <fstream>
#include <initializer_list>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "batch/io/reader_support.hpp"
#include "batch/io/toml_support.hpp"
#include "kernels/curves/nurbs.hpp"
#include "kernels/curves/segment.hpp"
#include "kernels/geom/tolerance.hpp"

namespace ncpath::io {
namespace {

// Builds the soup; every error names the item ("loop 0 segment 3: arc") and the TOML line.
class Parser : detail::TomlChecks {
 public:
  explicit Parser(std::filesystem::path path) : TomlChecks(std::move(path)) {}

  // job_units: the job's units, which override the file's `units` key.
  ProfileSoup run(const toml::table& root, const std::optional<LengthUnit>& job_units) {
    for (const auto& [key, node] : root) {
      const std::string k(key.str());
      if (k == "units") {
        const std::optional<LengthUnit> u = unit_by_name(node.value_or(std::string()));
        if (!u) fail(node, "units", "must be one of " + unit_names());
        soup_.units = *u;
        soup_.units_from = kUnitsFromFile;
      } else if (k != "loop" && k != "circle" && k != "polyline") {
        fail(node, k, "unknown key (expected [[loop]], [[circle]], [[polyline]] or units)");
      }
    }
    // Loops first, then circles, then polylines (the table does not keep the file's order).
    for (const std::string k : {"loop", "circle", "polyline"}) {
      const toml::node* node = root.get(k);
      if (!node) continue;
      const toml::array* items = node->as_array();
      if (!items || !items->is_array_of_tables())
        fail(*node, k, "must be an array of tables: write [[" + k + "]]");
      for (std::size_t i = 0; i < items->size(); ++i) {
        const toml::table& t = *items->get(i)->as_table();
        const std::string what = k + " " + std::to_string(i);
        if (k == "loop") read_loop(t, what);
        if (k == "circle") read_circle(t, what);
        if (k == "polyline") read_polyline(t, what);
      }
    }
    if (soup_.curves.empty())
      throw ReadError(path_, "", "no profile curves (add [[loop]], [[circle]] or [[polyline]])");
    if (job_units) {
      soup_.units = *job_units;
      soup_.units_from = kUnitsFromJob;
    }
    scale_to_mm(soup_);
    return std::move(soup_);
  }

 private:
  double number(const toml::node& n, const std::string& what, std::string_view key) {
    std::optional<double> v = n.is_number() ? n.value<double>() : std::nullopt;
    if (!v || !std::isfinite(*v))
      fail(n, what, "'" + std::string(key) + "' must be a finite number");
    return *v;
  }
  // [x, y], or [x, y, bulge] when bulge is non-null.
  Vec2 point(const toml::node& n, const std::string& what, std::string_view key,
             double* bulge = nullptr) {
    const toml::array* a = n.as_array();
    const std::size_t max = bulge ? 3 : 2;
    if (!a || a->size() < 2 || a->size() > max) {
      // Built by appending: GCC 12 warns (-Wrestrict, a false positive) on the + chain.
      std::string msg = "'";
      msg.append(key).append("' must be ").append(bulge ? "[x, y] or [x, y, bulge]" : "[x, y]");
      fail(n, what, msg);
    }
    if (bulge) *bulge = a->size() == 3 ? number(*a->get(2), what, key) : 0.0;
    return {number(*a->get(0), what, key), number(*a->get(1), what, key)};
  }
  std::vector<Vec2> points(const toml::node& n, const std::string& what, std::string_view key) {
    const toml::array* a = n.as_array();
    if (!a) fail(n, what, "'" + std::string(key) + "' must be an array of [x, y]");
    std::vector<Vec2> out;
    for (const toml::node& p : *a) out.push_back(point(p, what, key));
    return out;
  }

  std::uint32_t source(const std::string& handle, const std::string& type) {
    soup_.sources.push_back({handle, type});
    return static_cast<std::uint32_t>(soup_.sources.size() - 1);
  }
  void add(const Seg2& s) {
    if (length(s) < tol::kProfileZeroLength) {
      ++soup_.zero_length_dropped;
      soup_.sources.pop_back();  // sources are added just before their curve
      return;
    }
    soup_.curves.push_back({s, -1});
  }

  // One loop segment, before its start is known: kind, explicit start (if any), end.
  struct Piece {
    const toml::node* node;
    const toml::table* body;  // arc / nurbs table
    std::string kind;         // "line", "line_to", "arc", "nurbs"
    std::optional<Vec2> from;
    Vec2 to;
    Nurbs2 nurbs;
  };

  void read_loop(const toml::table& t, const std::string& what) {
    check_keys(t, what, {"segments"});
    const toml::array* segs = need(t, "segments", what).as_array();
    if (!segs || segs->empty()) fail(t, what, "'segments' must be a non-empty array");
    std::vector<Piece> pieces;
    for (std::size_t i = 0; i < segs->size(); ++i) {
      const std::string w = what + " segment " + std::to_string(i);
      const toml::table* seg = segs->get(i)->as_table();
      if (!seg || seg->size() != 1)
        fail(
            *segs->get(i), w,
            "must be one of { line = ... }, { line_to = ... }, { arc = {...} }, { nurbs = {...} }");
      // The iterator owns the key/value proxy that operator* refers to: keep it alive.
      const auto first = seg->begin();
      const auto& [key, body] = *first;
      Piece p{segs->get(i), body.as_table(), std::string(key.str()), std::nullopt, {}, {}};
      if (p.kind == "line") {
        std::vector<Vec2> ab = points(body, w + ": line", "line");
        if (ab.size() != 2) fail(body, w + ": line", "'line' must be [[x0, y0], [x1, y1]]");
        p.from = ab[0], p.to = ab[1];
      } else if (p.kind == "line_to") {
        p.to = point(body, w + ": line_to", "line_to");
      } else if (p.kind == "arc" && p.body) {
        check_keys(*p.body, w + ": arc", {"from", "to", "center", "centre", "dir", "bulge"});
        if (const toml::node* f = p.body->get("from")) p.from = point(*f, w + ": arc", "from");
        p.to = point(need(*p.body, "to", w + ": arc"), w + ": arc", "to");
      } else if (p.kind == "nurbs" && p.body) {
        p.nurbs = read_nurbs(*p.body, w + ": nurbs");
        p.from = p.nurbs.ctrl.front(), p.to = p.nurbs.ctrl.back();
      } else {
        fail(body, w,
             "unknown segment '" + p.kind +
                 "' (expected line, line_to, arc = {...}, nurbs = {...})");
      }
      pieces.push_back(std::move(p));
    }
    // A segment without its own start begins where the previous one ended; the first where
    // the last ended, which closes the loop.
    for (std::size_t i = 0; i < pieces.size(); ++i) {
      Piece& p = pieces[i];
      const Vec2 a = p.from ? *p.from : pieces[(i + pieces.size() - 1) % pieces.size()].to;
      const std::string w = what + " segment " + std::to_string(i);
      const std::uint32_t src = source("in " + w, p.kind == "line_to" ? "line" : p.kind);
      if (p.kind == "line" || p.kind == "line_to") add(make_line(a, p.to, src));
      if (p.kind == "arc") add(read_arc(*p.body, a, p.to, w + ": arc", src));
      if (p.kind == "nurbs") add_nurbs(std::move(p.nurbs), src);
    }
  }

  Seg2 read_arc(const toml::table& t, const Vec2& a, const Vec2& b, const std::string& w,
                std::uint32_t src) {
    const toml::node* c = t.get("center") ? t.get("center") : t.get("centre");
    const toml::node* bulge = t.get("bulge");
    if ((c != nullptr) == (bulge != nullptr)) fail(t, w, "give either center (with dir) or bulge");
    if (bulge) {
      if (t.get("dir"))
        fail(*t.get("dir"), w, "'dir' goes with center; a bulge's sign is its direction");
      return make_bulge_segment(a, b, number(*bulge, w, "bulge"), src);
    }
    std::string dir = "ccw";
    if (const toml::node* d = t.get("dir")) {
      dir = d->value<std::string>().value_or("");
      if (dir != "ccw" && dir != "cw") fail(*d, w, "'dir' must be \"ccw\" or \"cw\"");
    }
    const Vec2 centre = point(*c, w, "center");
    const double ra = (a - centre).norm(), rb = (b - centre).norm();
    if (std::abs(ra - rb) > tol::kProfileJoin * std::max(1.0, ra))
      fail(*c, w,
           "start and end are not equally far from the center (" + std::to_string(ra) + " vs " +
               std::to_string(rb) + " mm)");
    if ((a - b).norm() < tol::kProfileZeroLength && ra >= tol::kProfileZeroLength)
      fail(t, w, "start and end coincide: a full circle is a [[circle]]");
    return make_arc(a, b, centre, dir == "ccw", src);
  }

  Nurbs2 read_nurbs(const toml::table& t, const std::string& w) {
    check_keys(t, w, {"degree", "ctrl", "weights", "knots"});
    Nurbs2 n;
    const toml::node& deg = need(t, "degree", w);
    if (!deg.is_integer() || *deg.value<std::int64_t>() < 1 || *deg.value<std::int64_t>() > 30)
      fail(deg, w, "'degree' must be an integer from 1 to 30");
    n.degree = static_cast<int>(*deg.value<std::int64_t>());
    n.ctrl = points(need(t, "ctrl", w), w, "ctrl");
    if (static_cast<int>(n.ctrl.size()) < n.degree + 1)
      fail(t, w, "needs at least degree + 1 = " + std::to_string(n.degree + 1) + " control points");
    auto numbers = [&](std::string_view key) {
      std::vector<double> v;
      const toml::node& node = need(t, key, w);
      if (!node.as_array()) fail(node, w, "'" + std::string(key) + "' must be an array of numbers");
      for (const toml::node& x : *node.as_array()) v.push_back(number(x, w, key));
      return v;
    };
    n.weights = t.get("weights") ? numbers("weights") : std::vector<double>(n.ctrl.size(), 1.0);
    if (t.get("knots")) {
      n.knots = numbers("knots");
    } else {
      n.knots = clamped_uniform_knots(n.ctrl.size(), n.degree);
    }
    const std::string why = validate(n);
    if (!why.empty()) fail(t, w, why);
    return n;
  }
  void add_nurbs(Nurbs2 n, std::uint32_t src) {
    ProfileCurve pc;
    pc.seg = make_line(n.ctrl.front(), n.ctrl.back(), src);
    pc.nurbs = static_cast<std::int32_t>(soup_.nurbs.size());
    soup_.nurbs.push_back(std::move(n));
    soup_.curves.push_back(pc);
  }

  void read_circle(const toml::table& t, const std::string& what) {
    check_keys(t, what, {"center", "centre", "radius"});
    const toml::node* cn = t.get("center") ? t.get("center") : t.get("centre");
    if (!cn) fail(t, what, "missing key 'center'");
    const Vec2 c = point(*cn, what, "center");
    const double r = number(need(t, "radius", what), what, "radius");
    if (r < 0) fail(*t.get("radius"), what, "'radius' must not be negative");
    if (r < tol::kProfileZeroLength) return void(++soup_.zero_length_dropped);
    const std::uint32_t src = source(what.substr(7), "circle");  // "circle 1"
    soup_.curves.push_back({make_arc(c + Vec2(r, 0), c - Vec2(r, 0), c, true, src), -1});
    soup_.curves.push_back({make_arc(c - Vec2(r, 0), c + Vec2(r, 0), c, true, src), -1});
  }

  void read_polyline(const toml::table& t, const std::string& what) {
    check_keys(t, what, {"points", "closed"});
    const toml::node& pn = need(t, "points", what);
    const toml::array* arr = pn.as_array();
    if (!arr || arr->size() < 2) fail(pn, what, "'points' must list at least 2 points");
    std::vector<Vec2> pts;
    std::vector<double> bulges;
    for (const toml::node& p : *arr) {
      double b = 0;
      pts.push_back(point(p, what, "points", &b));
      bulges.push_back(b);
    }
    bool closed = false;
    if (const toml::node* c = t.get("closed")) {
      if (!c->is_boolean()) fail(*c, what, "'closed' must be true or false");
      closed = *c->value<bool>();
    }
    const std::size_t spans = closed ? pts.size() : pts.size() - 1;
    for (std::size_t i = 0; i < spans; ++i) {
      const std::uint32_t src =
          source(what.substr(9) + " segment " + std::to_string(i), "polyline");
      add(make_bulge_segment(pts[i], pts[(i + 1) % pts.size()], bulges[i], src));
    }
  }

  ProfileSoup soup_;
};

}  // namespace

ProfileSoup parse_profile_toml(std::string_view text, const std::filesystem::path& path,
                               const std::optional<LengthUnit>& units) {
  toml::table root;
  try {
    root = toml::parse(text, path.string());
  } catch (const toml::parse_error& e) {
    throw ReadError(path, "line " + std::to_string(e.source().begin.line),
                    "TOML syntax: " + std::string(e.description()));
  }
  return Parser(path).run(root, units);
}

ProfileSoup read_profile_toml(const std::filesystem::path& path,
                              const std::optional<LengthUnit>& units) {
  return parse_profile_toml(detail::read_file_bytes(path), path, units);
}

}  // namespace ncpath::io
