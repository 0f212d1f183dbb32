#pragma once
// The random pockets of random_pockets.hpp as the DXF entity soups users bring.
//
// region_to_dxf(regions, shuffle_seed): an ASCII DXF (R2000 group codes, HEADER + ENTITIES) of
// LINE, ARC (some with extrusion -Z), CIRCLE and SPLINE entities in shuffled order, some
// reversed, numbers with 17 significant digits, which batch/io/dxf_reader.* reads back to the
// same geometry (ARC end points to ~1e-15 relative, everything else bitwise).
// With units (DxfUnits: an $INSUNITS code and its size in mm, stated by the caller) every
// coordinate is written in those units, so that the reader's mm are the regions' again.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "tests/support/random_pockets.hpp"

namespace ncpath::test {

namespace random_pocket_detail {

inline std::string dxf_num(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}
inline void dxf_pair(std::string& out, int code, const std::string& value) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "%3d", code);
  out.append(buf).append("\n").append(value).append("\n");
}
inline double degrees_of(const Vec2& v) {
  double a = std::atan2(v.y(), v.x()) * 180 / std::numbers::pi;
  if (a < 0) a += 360;
  return a;
}

// The entity text without its "0 TYPE" and handle (added after shuffling).
struct DxfEntity {
  std::string type;
  std::string body;
};

inline DxfEntity dxf_line(const Vec2& a, const Vec2& b) {
  DxfEntity e{"LINE", ""};
  dxf_pair(e.body, 100, "AcDbLine");
  dxf_pair(e.body, 10, dxf_num(a.x()));
  dxf_pair(e.body, 20, dxf_num(a.y()));
  dxf_pair(e.body, 30, "0.0");
  dxf_pair(e.body, 11, dxf_num(b.x()));
  dxf_pair(e.body, 21, dxf_num(b.y()));
  dxf_pair(e.body, 31, "0.0");
  return e;
}

// mirrored: written in the object coordinates of extrusion (0, 0, -1), x mirrored.
inline DxfEntity dxf_arc(const Seg2& s, bool mirrored) {
  Vec2 a = s.a, b = s.b, c = s.c;
  bool ccw = s.kind == SegKind::kArcCcw;
  if (mirrored) {
    a.x() = -a.x(), b.x() = -b.x(), c.x() = -c.x();
    ccw = !ccw;
  }
  if (!ccw) std::swap(a, b);  // DXF arcs run counter-clockwise in their object coordinates
  DxfEntity e{"ARC", ""};
  dxf_pair(e.body, 100, "AcDbCircle");
  dxf_pair(e.body, 10, dxf_num(c.x()));
  dxf_pair(e.body, 20, dxf_num(c.y()));
  dxf_pair(e.body, 30, "0.0");
  dxf_pair(e.body, 40, dxf_num(s.r));
  if (mirrored) {
    dxf_pair(e.body, 210, "0.0");
    dxf_pair(e.body, 220, "0.0");
    dxf_pair(e.body, 230, "-1.0");
  }
  dxf_pair(e.body, 100, "AcDbArc");
  dxf_pair(e.body, 50, dxf_num(degrees_of(a - c)));
  dxf_pair(e.body, 51, dxf_num(degrees_of(b - c)));
  return e;
}

inline DxfEntity dxf_circle(const Vec2& c, double r) {
  DxfEntity e{"CIRCLE", ""};
  dxf_pair(e.body, 100, "AcDbCircle");
  dxf_pair(e.body, 10, dxf_num(c.x()));
  dxf_pair(e.body, 20, dxf_num(c.y()));
  dxf_pair(e.body, 30, "0.0");
  dxf_pair(e.body, 40, dxf_num(r));
  return e;
}

inline DxfEntity dxf_spline(const Nurbs2& n) {
  const bool rational =
      std::any_of(n.weights.begin(), n.weights.end(), [](double w) { return w != 1; });
  const bool closed = n.ctrl.front() == n.ctrl.back();
  DxfEntity e{"SPLINE", ""};
  dxf_pair(e.body, 100, "AcDbSpline");
  dxf_pair(e.body, 210, "0.0");
  dxf_pair(e.body, 220, "0.0");
  dxf_pair(e.body, 230, "1.0");
  dxf_pair(e.body, 70, std::to_string(8 + (rational ? 4 : 0) + (closed ? 1 : 0)));
  dxf_pair(e.body, 71, std::to_string(n.degree));
  dxf_pair(e.body, 72, std::to_string(n.knots.size()));
  dxf_pair(e.body, 73, std::to_string(n.ctrl.size()));
  dxf_pair(e.body, 74, "0");
  dxf_pair(e.body, 42, "0.0000001");
  dxf_pair(e.body, 43, "0.0000001");
  for (double k : n.knots) dxf_pair(e.body, 40, dxf_num(k));
  for (std::size_t i = 0; i < n.ctrl.size(); ++i) {
    dxf_pair(e.body, 10, dxf_num(n.ctrl[i].x()));
    dxf_pair(e.body, 20, dxf_num(n.ctrl[i].y()));
    dxf_pair(e.body, 30, "0.0");
    if (rational) dxf_pair(e.body, 41, dxf_num(n.weights[i]));
  }
  return e;
}

// A loop of exactly two arcs about one centre (a circle as the generator and the reader make
// it), which a CIRCLE entity reproduces curve for curve.
inline bool is_two_arc_circle(const Profile& p) {
  if (p.curves.size() != 2) return false;
  const Seg2& s = p.curves[0].seg;
  const Seg2& t = p.curves[1].seg;
  return p.curves[0].nurbs < 0 && p.curves[1].nurbs < 0 && s.is_arc() && s.kind == t.kind &&
         s.c == t.c && std::abs(s.r - t.r) <= 1e-12 * s.r;
}

// The regions with every coordinate and radius multiplied by k.
inline std::vector<Region> scaled_regions(std::vector<Region> regions, double k) {
  auto scale = [k](Profile& p) {
    for (ProfileCurve& c : p.curves) {
      c.seg.a *= k, c.seg.b *= k, c.seg.c *= k;
      c.seg.r *= k;
    }
    for (Nurbs2& n : p.nurbs)
      for (Vec2& q : n.ctrl) q *= k;
  };
  for (Region& r : regions) {
    scale(r.boundary);
    for (Profile& isl : r.islands) scale(isl);
  }
  return regions;
}

}  // namespace random_pocket_detail

// The drawing's units as its HEADER declares them: $INSUNITS code and the unit in mm.
struct DxfUnits {
  int insunits = 4;  // mm
  double mm_per_unit = 1;
};

// The regions as an ASCII DXF entity soup (see the top of this file); shuffle_seed decides
// the entity order, which entities are reversed, which arcs use extrusion -Z and whether
// two-arc circles become CIRCLE entities.
inline std::string region_to_dxf(const std::vector<Region>& mm_regions,
                                 std::uint64_t shuffle_seed, const DxfUnits& units = {}) {
  namespace d = random_pocket_detail;
  const std::vector<Region> regions =
      units.mm_per_unit == 1 ? mm_regions : d::scaled_regions(mm_regions, 1 / units.mm_per_unit);
  d::Rng rng(shuffle_seed);
  std::vector<d::DxfEntity> ents;
  auto add_profile = [&](const Profile& p) {
    if (d::is_two_arc_circle(p) && rng.chance(0.5)) {
      ents.push_back(d::dxf_circle(p.curves[0].seg.c, p.curves[0].seg.r));
      return;
    }
    for (const ProfileCurve& pc : p.curves) {
      const bool flip = rng.chance(0.5);
      if (pc.nurbs >= 0) {
        const Nurbs2& n = p.nurbs[pc.nurbs];
        ents.push_back(d::dxf_spline(flip ? nurbs_reversed(n) : n));
      } else if (pc.seg.is_arc()) {
        ents.push_back(d::dxf_arc(pc.seg, rng.chance(0.3)));
      } else {
        ents.push_back(flip ? d::dxf_line(pc.seg.b, pc.seg.a) : d::dxf_line(pc.seg.a, pc.seg.b));
      }
    }
  };
  for (const Region& r : regions) {
    add_profile(r.boundary);
    for (const Profile& isl : r.islands) add_profile(isl);
  }
  rng.shuffle(ents);
  std::string out;
  d::dxf_pair(out, 0, "SECTION");
  d::dxf_pair(out, 2, "HEADER");
  d::dxf_pair(out, 9, "$ACADVER");
  d::dxf_pair(out, 1, "AC1015");
  d::dxf_pair(out, 9, "$INSUNITS");
  d::dxf_pair(out, 70, std::to_string(units.insunits));
  d::dxf_pair(out, 0, "ENDSEC");
  d::dxf_pair(out, 0, "SECTION");
  d::dxf_pair(out, 2, "ENTITIES");
  unsigned handle = 0x100;
  for (const d::DxfEntity& e : ents) {
    char h[16];
    std::snprintf(h, sizeof h, "%X", handle++);
    d::dxf_pair(out, 0, e.type);
    d::dxf_pair(out, 5, h);
    d::dxf_pair(out, 100, "AcDbEntity");
    d::dxf_pair(out, 8, "POCKET");
    out += e.body;
  }
  d::dxf_pair(out, 0, "ENDSEC");
  d::dxf_pair(out, 0, "EOF");
  return out;
}

}  // namespace ncpath::test
