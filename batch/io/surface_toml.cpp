#include "batch/io/surface_toml.hpp"

#include <toml++/toml.h>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <initializer_list>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "batch/io/reader_support.hpp"
#include "batch/io/toml_support.hpp"
#include "kernels/curves/nurbs.hpp"  // clamped_uniform_knots

namespace ncpath::io {
namespace {

// Concatenation by appending: GCC 12 warns (-Wrestrict, a false positive) on chains that start
// with a literal and a temporary, as profile_toml.cpp notes.
std::string cat(std::initializer_list<std::string_view> parts) {
  std::string s;
  for (std::string_view p : parts) s.append(p);
  return s;
}

std::string count_of(std::size_t n, const char* one, const char* many) {
  return cat({std::to_string(n), " ", n == 1 ? one : many});
}

// Builds the surface; every error names the table ("nurbs_surface"), the key and the TOML line.
// The small helpers mirror those of profile_toml.cpp, whose messages these follow.
class SurfaceParser : detail::TomlChecks {
 public:
  explicit SurfaceParser(std::filesystem::path path) : TomlChecks(std::move(path)) {}

  NurbsSurface run(const toml::table& root) {
    const toml::node* native = nullptr;
    const toml::node* grid = nullptr;
    for (const auto& [key, node] : root) {
      const std::string k(key.str());
      if (k == "units") {
        if (node.value<std::string>() != "mm") fail(node, "units", "only \"mm\" is supported");
      } else if (k == "nurbs_surface") {
        native = &node;
      } else if (k == "bezier_grid") {
        grid = &node;
      } else {
        fail(node, k, "unknown key (expected [nurbs_surface], [bezier_grid] or units)");
      }
    }
    if (native && grid) {
      const bool grid_later = grid->source().begin.line >= native->source().begin.line;
      fail(grid_later ? *grid : *native, grid_later ? "bezier_grid" : "nurbs_surface",
           "give exactly one of [nurbs_surface] and [bezier_grid]");
    }
    if (!native && !grid)
      throw ReadError(path_, "", "no surface (add [nurbs_surface] or [bezier_grid])");

    const toml::node& node = native ? *native : *grid;
    const std::string what = native ? "nurbs_surface" : "bezier_grid";
    const toml::table* t = node.as_table();
    if (!t) fail(node, what, cat({"must be a table: write [", what, "]"}));
    NurbsSurface s = native ? read_native(*t, what) : read_grid(*t, what);

    // Checks on the whole surface come from the kernel, so the reader and the pocket job agree
    // on what is usable; they point at the table.
    const std::string why = validate(s);
    if (!why.empty()) fail(*t, what, why);
    const std::string fold = check_height_field(s);
    if (!fold.empty())
      fail(*t, what,
           fold.starts_with("not a height field") ? fold : cat({"not a height field: ", fold}));
    return s;
  }

 private:
  int integer(const toml::table& t, std::string_view key, const std::string& what, int lo, int hi) {
    const toml::node& n = need(t, key, what);
    const std::optional<std::int64_t> v = n.is_integer() ? n.value<std::int64_t>() : std::nullopt;
    if (!v || *v < lo || *v > hi)
      fail(n, what,
           cat({"'", key, "' must be an integer from ", std::to_string(lo), " to ",
                std::to_string(hi)}));
    return static_cast<int>(*v);
  }
  std::vector<double> numbers(const toml::node& n, const std::string& what, std::string_view key) {
    const std::string msg = cat({"'", key, "' must be an array of finite numbers"});
    const toml::array* a = n.as_array();
    if (!a) fail(n, what, msg);
    std::vector<double> out;
    for (const toml::node& x : *a) {
      const std::optional<double> v = x.is_number() ? x.value<double>() : std::nullopt;
      if (!v || !std::isfinite(*v)) fail(x, what, msg);
      out.push_back(*v);
    }
    return out;
  }
  // [[x, y, z], ...]: each point exactly three finite numbers.
  std::vector<Vec3> points(const toml::node& n, const std::string& what) {
    const toml::array* a = n.as_array();
    if (!a) fail(n, what, "'ctrl' must be an array of [x, y, z]");
    std::vector<Vec3> out;
    for (std::size_t i = 0; i < a->size(); ++i) {
      const toml::node& p = *a->get(i);
      const toml::array* xyz = p.as_array();
      Vec3 q = Vec3::Zero();
      bool ok = xyz && xyz->size() == 3;
      for (int k = 0; ok && k < 3; ++k) {
        const toml::node& c = *xyz->get(k);
        const std::optional<double> v = c.is_number() ? c.value<double>() : std::nullopt;
        ok = v && std::isfinite(*v);
        if (ok) q[k] = *v;
      }
      if (!ok)
        fail(p, what,
             cat({"'ctrl' point ", std::to_string(i), " must be [x, y, z] (finite numbers)"}));
      out.push_back(q);
    }
    return out;
  }

  NurbsSurface read_native(const toml::table& t, const std::string& w) {
    check_keys(t, w, {"degree_u", "degree_v", "nu", "nv", "ctrl", "weights", "knots_u", "knots_v"});
    NurbsSurface s;
    s.degree_u = integer(t, "degree_u", w, 1, kMaxDegree);
    s.degree_v = integer(t, "degree_v", w, 1, kMaxDegree);
    s.nu = integer(t, "nu", w, 1, kMaxCount);
    s.nv = integer(t, "nv", w, 1, kMaxCount);
    // clamped_uniform_knots needs n > p, and so does any clamped knot vector.
    auto enough = [&](int n, int p, const char* n_key, const char* p_key) {
      if (n < p + 1)
        fail(*t.get(n_key), w,
             cat({n_key, " = ", std::to_string(n), " is too few control points for ", p_key, " = ",
                  std::to_string(p), " (needs at least ", std::to_string(p + 1), ")"}));
    };
    enough(s.nu, s.degree_u, "nu", "degree_u");
    enough(s.nv, s.degree_v, "nv", "degree_v");
    const std::size_t count = static_cast<std::size_t>(s.nu) * static_cast<std::size_t>(s.nv);
    const toml::node& ctrl = need(t, "ctrl", w);
    s.ctrl = points(ctrl, w);
    if (s.ctrl.size() != count)
      fail(ctrl, w,
           cat({"ctrl has ", count_of(s.ctrl.size(), "point", "points"),
                ", nu * nv = ", std::to_string(count)}));
    if (const toml::node* wn = t.get("weights")) {
      s.weights = numbers(*wn, w, "weights");
      if (s.weights.size() != count)
        fail(*wn, w,
             cat({"weights has ", count_of(s.weights.size(), "value", "values"),
                  ", nu * nv = ", std::to_string(count)}));
    } else {
      s.weights.assign(count, 1.0);
    }
    s.knots_u = knots(t, "knots_u", "nu + degree_u + 1", s.nu, s.degree_u, w);
    s.knots_v = knots(t, "knots_v", "nv + degree_v + 1", s.nv, s.degree_v, w);
    return s;
  }
  std::vector<double> knots(const toml::table& t, std::string_view key, const char* rule, int n,
                            int p, const std::string& w) {
    const toml::node* kn = t.get(key);
    if (!kn) return clamped_uniform_knots(static_cast<std::size_t>(n), p);
    std::vector<double> k = numbers(*kn, w, key);
    const std::size_t want = static_cast<std::size_t>(n) + static_cast<std::size_t>(p) + 1;
    if (k.size() != want)
      fail(*kn, w,
           cat({key, " has ", count_of(k.size(), "knot", "knots"), ", ", rule, " = ",
                std::to_string(want)}));
    return k;
  }

  NurbsSurface read_grid(const toml::table& t, const std::string& w) {
    check_keys(t, w, {"patches_u", "patches_v", "ctrl"});
    const int pu = integer(t, "patches_u", w, 1, kMaxCount);
    const int pv = integer(t, "patches_v", w, 1, kMaxCount);
    const std::size_t count =
        (3 * static_cast<std::size_t>(pu) + 1) * (3 * static_cast<std::size_t>(pv) + 1);
    const toml::node& ctrl = need(t, "ctrl", w);
    const std::vector<Vec3> pts = points(ctrl, w);
    if (pts.size() != count)
      fail(ctrl, w,
           cat({"ctrl has ", count_of(pts.size(), "point", "points"),
                ", (3 * patches_u + 1) * (3 * patches_v + 1) = ", std::to_string(count)}));
    try {
      return bezier_grid_surface(pu, pv, pts);
    } catch (const std::invalid_argument& e) {  // the count is checked above; kept as a guard
      fail(t, w, e.what());
    }
  }

  // Bounds that keep sizes in int and allocations sane; the control net must be listed anyway.
  static constexpr int kMaxDegree = 30;
  static constexpr int kMaxCount = 1'000'000;
};

}  // namespace

NurbsSurface parse_surface_toml(std::string_view text, const std::filesystem::path& path) {
  toml::table root;
  try {
    root = toml::parse(text, path.string());
  } catch (const toml::parse_error& e) {
    throw ReadError(path, cat({"line ", std::to_string(e.source().begin.line)}),
                    cat({"TOML syntax: ", e.description()}));
  }
  return SurfaceParser(path).run(root);
}

NurbsSurface read_surface_toml(const std::filesystem::path& path) {
  return parse_surface_toml(detail::read_file_bytes(path), path);
}

}  // namespace ncpath::io
