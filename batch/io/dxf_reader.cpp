#include "batch/io/dxf_reader.hpp"

#include <dl_creationadapter.h>
#include <dl_dxf.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <optional>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "kernels/curves/nurbs.hpp"
#include "kernels/curves/segment.hpp"
#include "kernels/geom/tolerance.hpp"

namespace ncpath::io {
namespace {

// What we know about one DXF object from its raw group codes. dxflib's own bookkeeping is
// not enough: it parses the handle (hexadecimal) as a decimal int ("2F" -> 2), keeps SPLINE
// and LWPOLYLINE counts from the previous entity when a count code is missing, and never
// reports entities it does not know. processCodeValuePair sees every pair before dxflib acts
// on it, and dxflib emits an entity when the next "0" arrives, so the object being emitted is
// the one snapshot at that "0".
struct RawObject {
  std::string type;
  std::string handle;
  std::uint64_t line = 0;  // line of the "0" group code
  bool in_entities = false;
  int n10 = 0, n11 = 0, n40 = 0, n41 = 0;  // occurrences of these group codes
  int flags70 = 0;
};

const std::set<std::string> kCurveTypes = {"LINE",       "ARC",      "CIRCLE", "ELLIPSE",
                                           "LWPOLYLINE", "POLYLINE", "SPLINE"};
const std::set<std::string> kQuietTypes = {"VERTEX", "SEQEND", "ENDSEC", "EOF"};

struct Vertex {
  Vec2 p;
  double bulge;
};

class Collector : public DL_CreationAdapter {
 public:
  ProfileSoup soup;
  std::optional<std::pair<std::uint64_t, std::string>> error;  // first fatal problem

  // job_units: the job's units, which override the drawing's header.
  explicit Collector(const std::optional<LengthUnit>& job_units) : job_units_(job_units) {}

  void processCodeValuePair(unsigned int code, const std::string& value) override {
    line_ += 2;
    const std::uint64_t code_line = line_ - 1;
    if (code == 0) {
      finish_object();
      emitting_ = current_;
      current_ = RawObject{value, "", code_line, section_ == "ENTITIES"};
      if (value == "ENDSEC") section_.clear();
      expect_section_name_ = value == "SECTION";
      return;
    }
    if (code == 2 && expect_section_name_) section_ = value, expect_section_name_ = false;
    if (section_ == "HEADER") header_pair(code, value, code_line);
    if (code == 5) current_.handle = value;
    if (code == 10) ++current_.n10;
    if (code == 11) ++current_.n11;
    if (code == 40) ++current_.n40;
    if (code == 41) ++current_.n41;
    if (code == 70) current_.flags70 = std::atoi(value.c_str());
  }

  void addLine(const DL_LineData& d) override {
    if (!usable()) return;
    const Vec2 a = mm(d.x1, d.y1), b = mm(d.x2, d.y2);
    add_seg(make_line(a, b), (b - a).norm());
  }

  void addArc(const DL_ArcData& d) override {
    if (!usable()) return;
    const double a1 = d.angle1 * std::numbers::pi / 180;
    double a2 = d.angle2 * std::numbers::pi / 180;
    while (a2 <= a1) a2 += 2 * std::numbers::pi;  // DXF arcs run counter-clockwise (in OCS)
    const Vec2 c = mm(d.cx, d.cy);
    const double r = scale_ * d.radius;
    const Vec2 pa = c + r * Vec2(std::cos(a1), std::sin(a1));
    const Vec2 pb = c + r * Vec2(std::cos(a2), std::sin(a2));
    if (r * (a2 - a1) < tol::kProfileZeroLength) return drop();
    if ((pb - pa).norm() < tol::kProfileZeroLength) return add_circle(c, r);
    add_seg(make_arc(ocs(pa), ocs(pb), ocs(c), sx_ > 0), 1);
  }

  void addCircle(const DL_CircleData& d) override {
    if (!usable()) return;
    const double r = scale_ * d.radius;
    if (r < tol::kProfileZeroLength) return drop();
    add_circle(mm(d.cx, d.cy), r);
  }

  void addEllipse(const DL_EllipseData& d) override {
    if (!usable()) return;
    const Vec2 c = mm(d.cx, d.cy), m = mm(d.mx, d.my);
    if (m.norm() * std::min(d.ratio, 1.0) < tol::kProfileZeroLength) return drop();
    double t1 = d.angle1, t2 = d.angle2;
    while (t2 <= t1) t2 += 2 * std::numbers::pi;
    // Centre and axis are world coordinates; the parameter runs counter-clockwise about the
    // extrusion direction, so about -Z it is the +Z ellipse from -t2 to -t1, reversed.
    Nurbs2 n = sx_ > 0 ? nurbs_ellipse(c, m, d.ratio, t1, t2)
                       : nurbs_reversed(nurbs_ellipse(c, m, d.ratio, -t2, -t1));
    add_nurbs(std::move(n));
  }

  void addPolyline(const DL_PolylineData& d) override {
    poly_.reset();
    if (!usable()) return;
    if (d.flags & (16 | 64)) {
      warn("a polygon mesh, not a profile curve");
      return;
    }
    poly_.emplace();
    poly_closed_ = (d.flags & 1) != 0;
    poly_source_ = add_source();
  }

  void addVertex(const DL_VertexData& d) override {
    if (!poly_) return;
    // A VERTEX object's own flags: 16 = spline frame control point, not on the curve.
    if (emitting_.type == "VERTEX" && (emitting_.flags70 & 16)) return;
    poly_->push_back({ocs(mm(d.x, d.y)), sx_ * d.bulge});
  }

  void endEntity() override {
    if (poly_) finish_polyline();
    if (spline_) finish_spline();
  }
  void endSequence() override { endEntity(); }

  void addSpline(const DL_SplineData& d) override {
    spline_.reset();
    if (!usable()) return;
    spline_.emplace();
    spline_->degree = static_cast<int>(d.degree);
    spline_decl_ = {static_cast<int>(d.nKnots), static_cast<int>(d.nControl),
                    static_cast<int>(d.nFit)};
  }
  void addControlPoint(const DL_ControlPointData& d) override {
    if (!spline_) return;
    spline_->ctrl.push_back(mm(d.x, d.y));
    spline_->weights.push_back(d.w);
  }
  void addKnot(const DL_KnotData& d) override {
    if (spline_) spline_->knots.push_back(d.k);
  }

  void finish() {
    finish_object();
    resolve_units();
  }

 private:
  // True when the entity being emitted is a top-level entity whose plane we can read.
  bool usable() {
    if (!emitting_.in_entities || error) return false;
    resolve_units();
    if (error) return false;
    const double* n = getExtrusion()->getDirection();
    if (std::abs(n[0]) >= tol::kDxfExtrusionAxis || std::abs(n[1]) >= tol::kDxfExtrusionAxis ||
        n[2] == 0) {
      warn("not in the xy plane (extrusion direction is not +Z or -Z)");
      return false;
    }
    sx_ = n[2] > 0 ? 1 : -1;
    return true;
  }
  // A point of the file in mm (its coordinates times the drawing's unit).
  Vec2 mm(double x, double y) const { return scale_ * Vec2(x, y); }
  // Object coordinates of a -Z extrusion are mirrored in x (DXF arbitrary axis algorithm).
  Vec2 ocs(const Vec2& p) const { return {sx_ * p.x(), p.y()}; }

  std::string name() const { return emitting_.type + " " + handle(); }
  std::string handle() const {
    return emitting_.handle.empty() ? "(line " + std::to_string(emitting_.line) + ")"
                                    : emitting_.handle;
  }
  void warn(const std::string& why) { soup.warnings.push_back("skipped " + name() + ": " + why); }
  void fail(const std::string& problem) {
    if (!error) error.emplace(emitting_.line, problem);
  }
  void drop() { ++soup.zero_length_dropped; }

  std::uint32_t add_source() {
    soup.sources.push_back({handle(), emitting_.type});
    return static_cast<std::uint32_t>(soup.sources.size() - 1);
  }
  void add_seg(Seg2 s, double length) {
    if (length < tol::kProfileZeroLength) return drop();
    s.source = add_source();
    soup.curves.push_back({s, -1});
  }
  void add_circle(const Vec2& c_ocs, double r) {
    const Vec2 c = ocs(c_ocs), p0 = ocs(c_ocs + Vec2(r, 0)), p1 = ocs(c_ocs - Vec2(r, 0));
    const std::uint32_t src = add_source();
    soup.curves.push_back({make_arc(p0, p1, c, sx_ > 0, src), -1});
    soup.curves.push_back({make_arc(p1, p0, c, sx_ > 0, src), -1});
  }
  void add_nurbs(Nurbs2 n) {
    const std::string why = validate(n);
    if (!why.empty()) return fail(name() + ": " + why);
    double extent = 0;
    for (const Vec2& p : n.ctrl) extent = std::max(extent, (p - n.ctrl[0]).norm());
    if (extent < tol::kProfileZeroLength) return drop();
    ProfileCurve pc;
    pc.seg = make_line(n.ctrl.front(), n.ctrl.back(), add_source());
    pc.nurbs = static_cast<std::int32_t>(soup.nurbs.size());
    soup.nurbs.push_back(std::move(n));
    soup.curves.push_back(pc);
  }

  void finish_polyline() {
    std::vector<Vertex> v = std::move(*poly_);
    poly_.reset();
    const std::size_t m = v.size();
    const std::size_t spans = m < 2 ? 0 : (poly_closed_ ? m : m - 1);
    if (spans == 0) drop();
    for (std::size_t i = 0; i < spans; ++i) {
      const Vertex& a = v[i];
      const Vertex& b = v[(i + 1) % m];
      if ((b.p - a.p).norm() < tol::kProfileZeroLength) {
        drop();
        continue;
      }
      soup.curves.push_back({make_bulge_segment(a.p, b.p, a.bulge, poly_source_), -1});
    }
  }

  void finish_spline() {
    Nurbs2 n = std::move(*spline_);
    spline_.reset();
    const auto [nk, nc, nf] = spline_decl_;
    if (nc == 0 && nf > 0)
      return fail(name() + " has only fit points; ncpath needs control points");
    if (nc == 0) return fail(name() + " has no control points");
    // dxflib fills missing entries with zeros; compare with what the file really lists.
    if (emitting_.n10 != nc)
      return fail(name() + " declares " + std::to_string(nc) +
                  " control points (code 73) but lists " + std::to_string(emitting_.n10));
    if (emitting_.n40 != nk)
      return fail(name() + " declares " + std::to_string(nk) + " knots (code 72) but lists " +
                  std::to_string(emitting_.n40));
    if (emitting_.n41 != 0 && emitting_.n41 != nc)
      return fail(name() + " lists " + std::to_string(emitting_.n41) + " weights for " +
                  std::to_string(nc) + " control points");
    add_nurbs(std::move(n));
  }

  // Called when an object is complete (its successor's "0" arrived): warn about entities of
  // the ENTITIES section that are no profile curves.
  void finish_object() {
    const RawObject& o = current_;
    if (o.in_entities && !kCurveTypes.count(o.type) && !kQuietTypes.count(o.type)) {
      const std::string h = o.handle.empty() ? "(line " + std::to_string(o.line) + ")" : o.handle;
      soup.warnings.push_back("skipped " + o.type + " " + h + ": not a profile curve");
    }
  }

  // The HEADER's unit variables: "9 $INSUNITS" then "70 <code>" (likewise $MEASUREMENT).
  void header_pair(unsigned int code, const std::string& value, std::uint64_t line) {
    if (code == 9) {
      header_var_ = value;
      return;
    }
    if (code != 70 || (header_var_ != "$INSUNITS" && header_var_ != "$MEASUREMENT")) return;
    if (units_resolved_ && !error)
      error.emplace(line, header_var_ + " comes after the entities (ncpath reads the HEADER "
                                        "section first; save the drawing again)");
    auto& var = header_var_ == "$INSUNITS" ? insunits_ : measurement_;
    var = {std::atoi(value.c_str()), line};
  }

  // The drawing's units, once, before its first entity: the job's, else $INSUNITS, else
  // $MEASUREMENT (0 imperial: inches; 1 metric: mm), else mm with a warning.
  void resolve_units() {
    if (units_resolved_) return;
    units_resolved_ = true;
    if (job_units_) {
      set_units(*job_units_, kUnitsFromJob);
    } else if (insunits_ && insunits_->first != 0) {
      const std::optional<LengthUnit> u = unit_by_insunits(insunits_->first);
      if (!u) {
        error.emplace(insunits_->second,
                      "$INSUNITS " + std::to_string(insunits_->first) +
                          " is not a unit code of the DXF reference (0 to 24); give the job's "
                          "units (units = \"mm\", --units mm)");
        return;
      }
      set_units(*u, kUnitsFromInsunits);
    } else if (measurement_ && (measurement_->first == 0 || measurement_->first == 1)) {
      const bool imperial = measurement_->first == 0;
      set_units(*unit_by_name(imperial ? "inch" : "mm"), kUnitsFromMeasurement);
      soup.units_warning = std::string("the drawing gives no $INSUNITS; read in ") +
                           (imperial ? "inches" : "mm") + " from $MEASUREMENT = " +
                           std::to_string(measurement_->first) +
                           "; give the job's units (units = \"...\", --units) if that is wrong";
    } else {
      soup.units_warning =
          "the drawing declares no units ($INSUNITS, $MEASUREMENT); read as mm; give the job's "
          "units (units = \"inch\", --units inch) if that is wrong";
    }
  }
  void set_units(const LengthUnit& u, const char* from) {
    soup.units = u;
    soup.units_from = from;
    scale_ = u.mm_per_unit;
  }

  std::optional<LengthUnit> job_units_;
  std::string header_var_;
  std::optional<std::pair<int, std::uint64_t>> insunits_, measurement_;  // value, line
  bool units_resolved_ = false;
  double scale_ = 1;  // mm per drawing unit
  std::uint64_t line_ = 0;
  std::string section_;
  bool expect_section_name_ = false;
  RawObject current_, emitting_;
  double sx_ = 1;
  std::optional<std::vector<Vertex>> poly_;
  bool poly_closed_ = false;
  std::uint32_t poly_source_ = kNoSource;
  std::optional<Nurbs2> spline_;
  std::tuple<int, int, int> spline_decl_;
};

}  // namespace

ProfileSoup read_dxf(const std::filesystem::path& path, const std::optional<LengthUnit>& units) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw ReadError(path, "", "is a directory");
  std::ifstream probe(path, std::ios::binary);
  if (!probe) throw ReadError(path, "", "cannot open");
  char head[22] = {};
  probe.read(head, sizeof head);
  if (probe.gcount() == 0) throw ReadError(path, "", "empty file");
  if (std::string(head, probe.gcount()).starts_with("AutoCAD Binary DXF"))
    throw ReadError(path, "", "binary DXF is not supported; save the drawing as ASCII DXF");
  probe.close();

  Collector collector(units);
  DL_Dxf dxf;
  if (!dxf.in(path.string(), &collector)) throw ReadError(path, "", "cannot open");
  collector.finish();
  if (collector.error)
    throw ReadError(path, "line " + std::to_string(collector.error->first),
                    collector.error->second);
  ProfileSoup soup = std::move(collector.soup);
  if (soup.curves.empty()) {
    std::string problem =
        "no usable profile entity (LINE, ARC, CIRCLE, ELLIPSE, LWPOLYLINE, POLYLINE, SPLINE) in "
        "the ENTITIES section";
    if (soup.zero_length_dropped > 0)
      problem += "; " + std::to_string(soup.zero_length_dropped) + " zero-length dropped";
    if (!soup.warnings.empty()) problem += "; " + std::to_string(soup.warnings.size()) + " skipped";
    throw ReadError(path, "", problem);
  }
  return soup;
}

}  // namespace ncpath::io
