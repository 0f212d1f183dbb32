// Regions of offset elements at one z level and their candidate boundary curves
// (kernels/scan/zlevel.hpp, zlevel_detail.hpp).
#include <algorithm>
#include <cmath>
#include <numbers>

#include "kernels/geom/tolerance.hpp"
#include "kernels/scan/zlevel_detail.hpp"

namespace ncpath::zlevel_detail {

namespace {

constexpr double kPi = std::numbers::pi;

void box_add(double* box, const Vec2& p) {
  box[0] = std::min(box[0], p.x());
  box[1] = std::min(box[1], p.y());
  box[2] = std::max(box[2], p.x());
  box[3] = std::max(box[3], p.y());
}

void box_reset(double* box) {
  box[0] = box[1] = INFINITY;
  box[2] = box[3] = -INFINITY;
}

Vec2 xy(const Vec3& p) { return Vec2(p.x(), p.y()); }

std::uint32_t vertex_element(const OffsetElements& el, std::uint32_t point) {
  const auto it = std::lower_bound(el.vertex_source.begin(), el.vertex_source.end(), point);
  if (it == el.vertex_source.end() || *it != point) return kNone;
  return el.vertex_id(std::size_t(it - el.vertex_source.begin()));
}

std::uint32_t edge_element(const OffsetElements& el, std::uint32_t p, std::uint32_t q) {
  const std::array<std::uint32_t, 2> key{std::min(p, q), std::max(p, q)};
  const auto it = std::lower_bound(el.edge_vertices.begin(), el.edge_vertices.end(), key);
  if (it == el.edge_vertices.end() || *it != key) return kNone;
  return el.edge_id(std::size_t(it - el.edge_vertices.begin()));
}

// x-gradient of the offset plane's height over the projected offset triangle, from its three
// vertex heights (the same numbers that place the clip points).
Vec2 facet_gradient(const std::array<Vec3, 3>& t) {
  const Vec2 e1 = xy(t[1]) - xy(t[0]), e2 = xy(t[2]) - xy(t[0]);
  const double d1 = t[1].z() - t[0].z(), d2 = t[2].z() - t[0].z();
  const double det = cross2(e1, e2);
  return Vec2(d1 * e2.y() - d2 * e1.y(), e1.x() * d2 - e2.x() * d1) / det;
}

// Clip point on the side from t[i] to t[j] where the height crosses zc, computed from the
// lower end so that both facets' and all callers' arithmetic agree.
Vec2 clip_point(const Vec3& p, const Vec3& q, double zc) {
  const Vec3& lo = p.z() < q.z() ? p : q;
  const Vec3& hi = p.z() < q.z() ? q : p;
  const double lam = (zc - lo.z()) / (hi.z() - lo.z());
  return xy(lo) + lam * (xy(hi) - xy(lo));
}

bool build_facet(const OffsetElements& el, std::uint32_t f, const Level& lv, Region& g) {
  if (el.facet_vertical[f]) return false;
  const auto t = el.offset_tri(f);
  const double zc = lv.zc;
  if (std::max({t[0].z(), t[1].z(), t[2].z()}) < zc) return false;
  const Vec2 p[3] = {xy(t[0]), xy(t[1]), xy(t[2])};
  const double area2 = cross2(p[1] - p[0], p[2] - p[0]);
  if (!(area2 != 0)) return false;
  const double o = area2 > 0 ? 1.0 : -1.0;
  g.kind = RegionKind::kFacet;
  g.element = f;
  g.index = f;
  g.nhp = 0;
  for (int k = 0; k < 3; ++k) {
    const Vec2 d = p[(k + 1) % 3] - p[k];
    const double len = d.norm();
    if (!(len > 0)) return false;
    HalfPlane h;
    h.n = o * Vec2(d.y(), -d.x()) / len;
    h.c = h.n.dot(p[k]);
    g.hp[g.nhp++] = h;
  }
  box_reset(g.box);
  Vec2 poly[4];
  int np = 0;
  for (int k = 0; k < 3; ++k) {
    const Vec3 &a = t[k], &b = t[(k + 1) % 3];
    if (a.z() >= zc) poly[np++] = p[k];
    if ((a.z() >= zc) != (b.z() >= zc)) poly[np++] = clip_point(a, b, zc);
  }
  if (np < 3) return false;
  double parea = 0;
  for (int k = 0; k < np; ++k) parea += cross2(poly[k] - poly[0], poly[(k + 1) % np] - poly[0]);
  if (!(parea != 0)) return false;
  for (int k = 0; k < np; ++k) box_add(g.box, poly[k]);
  if (std::min({t[0].z(), t[1].z(), t[2].z()}) < zc) {
    const Vec2 grad = facet_gradient(t);
    const double gl = grad.norm();
    if (gl > 0) {
      HalfPlane h;
      h.n = -grad / gl;
      h.c = h.n.dot(p[0]) + (t[0].z() - zc) / gl;
      g.hp[g.nhp++] = h;
    }
  }
  return true;
}

bool build_edge(const OffsetElements& el, std::uint32_t e, const Level& lv, Region& g) {
  if (el.edge_reachable.size() == el.edge_count() && !el.edge_reachable[e]) return false;
  const auto& ev = el.edge_vertices[e];
  Vec3 A = el.points[ev[0]], B = el.points[ev[1]];
  if (B.z() < A.z()) std::swap(A, B);
  const Vec3 d = B - A;
  const double dxy2 = d.x() * d.x() + d.y() * d.y(), dd = d.squaredNorm();
  if (!(std::sqrt(dxy2) >= tol::kVerticalEdge * std::sqrt(dd)) || !(dxy2 > 0)) return false;
  const double R = lv.R;
  // The envelope of the discs exists where (1 + k^2) h^2 < R^2; h is smallest at B. Otherwise
  // every disc lies inside B's disc (the vertex region).
  const double hB = std::max(0.0, lv.zc - B.z());
  if (!(hB * hB * dd < R * R * dxy2)) return false;
  g.kind = RegionKind::kEdge;
  g.element = el.edge_id(e);
  g.index = e;
  g.a = A;
  g.d = d;
  g.dd = dd;
  g.dxy2 = dxy2;
  // Box: the part of AB within R below zc, widened by R.
  const double t0 = d.z() > 0 ? std::clamp((lv.zc - R - A.z()) / d.z(), 0.0, 1.0) : 0.0;
  box_reset(g.box);
  box_add(g.box, xy(A + t0 * d));
  box_add(g.box, xy(B));
  g.box[0] -= R;
  g.box[1] -= R;
  g.box[2] += R;
  g.box[3] += R;
  return true;
}

bool build_vertex(const OffsetElements& el, std::uint32_t v, const Level& lv, Region& g) {
  if (el.vertex_reachable.size() == el.vertex_count() && !el.vertex_reachable[v]) return false;
  const Vec3& p = el.points[el.vertex_source[v]];
  const double h = std::max(0.0, lv.zc - p.z());
  if (!(h < lv.R)) return false;
  g.kind = RegionKind::kVertex;
  g.element = el.vertex_id(v);
  g.index = v;
  g.c = xy(p);
  g.r = std::sqrt((lv.R - h) * (lv.R + h));
  g.vz = p.z();
  g.box[0] = g.c.x() - g.r;
  g.box[1] = g.c.y() - g.r;
  g.box[2] = g.c.x() + g.r;
  g.box[3] = g.c.y() + g.r;
  return true;
}

// x-interval of the stadium of radius rad around segment p0 p1, on the line at height y.
bool stadium_row(const Vec2& p0, const Vec2& p1, double rad, double y, double& x0, double& x1) {
  double lo = INFINITY, hi = -INFINITY;
  for (const Vec2* p : {&p0, &p1}) {
    const double dy = y - p->y();
    if (std::abs(dy) < rad) {
      const double w = std::sqrt((rad - dy) * (rad + dy));
      lo = std::min(lo, p->x() - w);
      hi = std::max(hi, p->x() + w);
    }
  }
  const Vec2 dv = p1 - p0;
  const double len = dv.norm();
  if (len > 0) {
    const Vec2 u = dv / len, v = perp(u);
    // 0 <= (X - p0).u <= len and |(X - p0).v| <= rad, X = (x, y): linear in x.
    double blo = -INFINITY, bhi = INFINITY;
    auto clamp_lin = [&](double coef, double off, double m0, double m1) {
      if (coef == 0) {
        if (off < m0 || off > m1) blo = INFINITY;
        return;
      }
      double a = (m0 - off) / coef, b = (m1 - off) / coef;
      if (a > b) std::swap(a, b);
      blo = std::max(blo, a);
      bhi = std::min(bhi, b);
    };
    clamp_lin(u.x(), (y - p0.y()) * u.y() - p0.x() * u.x(), 0, len);
    clamp_lin(v.x(), (y - p0.y()) * v.y() - p0.x() * v.x(), -rad, rad);
    if (blo <= bhi) {
      lo = std::min(lo, blo);
      hi = std::max(hi, bhi);
    }
  }
  x0 = lo;
  x1 = hi;
  return lo < hi;
}

Curve line_curve(const Region& g, std::uint32_t gi, const Vec2& a, const Vec2& b, bool shadow) {
  Curve c;
  c.kind = CurveKind::kLine;
  c.shadow = shadow;
  c.region = gi;
  c.element = g.element;
  c.a = a;
  c.b = b;
  c.len = (b - a).norm();
  c.dir = (b - a) / c.len;
  finish_box(c);
  return c;
}

void facet_curves(const OffsetElements& el, const Region& g, std::uint32_t gi, const Level& lv,
                  std::vector<Curve>& curves, std::vector<Joint>& joints) {
  const auto t = el.offset_tri(g.index);
  const auto& fv = el.facet_vertices[g.index];
  const double zc = lv.zc;
  const Vec2 p[3] = {xy(t[0]), xy(t[1]), xy(t[2])};
  const bool ccw = cross2(p[1] - p[0], p[2] - p[0]) > 0;
  if (std::min({t[0].z(), t[1].z(), t[2].z()}) >= zc) {
    // Whole triangle: a side whose offset lies exactly at zc bounds U where nothing else does
    // (a horizontal facet at the level: a floor).
    for (int k = 0; k < 3; ++k) {
      const int j = (k + 1) % 3;
      if (t[k].z() == zc && t[j].z() == zc)
        curves.push_back(ccw ? line_curve(g, gi, p[k], p[j], false)
                             : line_curve(g, gi, p[j], p[k], false));
    }
    return;
  }
  Vec2 q[2];
  int side[2];
  int nq = 0;
  for (int k = 0; k < 3 && nq < 2; ++k) {
    const Vec3 &a = t[k], &b = t[(k + 1) % 3];
    if ((a.z() >= zc) != (b.z() >= zc)) {
      side[nq] = k;
      q[nq++] = clip_point(a, b, zc);
    }
  }
  if (nq < 2 || q[0] == q[1]) return;
  const Vec2 grad = facet_gradient(t);
  if (cross2(q[1] - q[0], grad) < 0) {
    std::swap(q[0], q[1]);
    std::swap(side[0], side[1]);
  }
  curves.push_back(line_curve(g, gi, q[0], q[1], false));
  for (int m = 0; m < 2; ++m) {
    const std::uint32_t v0 = fv[side[m]], v1 = fv[(side[m] + 1) % 3];
    Joint j;
    j.p = q[m];
    j.target = edge_element(el, v0, v1);
    j.alt[0] = vertex_element(el, v0);
    j.alt[1] = vertex_element(el, v1);
    joints.push_back(j);
  }
}

// Ellipse arc(s) of the capsule side (see edge_curves) from angle ts to te (te > ts), split
// into sweeps of at most pi / 2; first and last points pa, pb exactly.
void ellipse_arcs(const Region& g, std::uint32_t gi, const Level& lv, double k, const Vec2& u,
                  double ts, double te, const Vec2& pa, const Vec2& pb,
                  std::vector<Curve>& curves) {
  const double R = lv.R, q = std::sqrt(1 + k * k);
  const double a1 = R * q / k;
  const Vec2 v = perp(u);
  const Vec2 centre = xy(g.a) + ((lv.zc - g.a.z()) / k) * u;
  const double sweep = te - ts;
  const int n = std::max(1, int(std::ceil(sweep / (kPi / 2) - tol::kCountSlack)));
  Vec2 prev = pa;
  for (int j = 0; j < n; ++j) {
    const double tj = ts + sweep * j / n;
    Curve c;
    c.kind = CurveKind::kEllipse;
    c.region = gi;
    c.element = g.element;
    c.a = prev;
    c.len = sweep / n;
    c.e1 = a1 * std::cos(tj) * u + R * std::sin(tj) * v;
    c.e2 = -a1 * std::sin(tj) * u + R * std::cos(tj) * v;
    c.centre = centre;
    c.r1 = a1;
    c.r2 = R;
    c.axis = u;
    c.t0 = tj;
    c.ax_p = g.a;
    c.ax_d = g.d / std::sqrt(g.dd);
    c.b = j + 1 == n ? pb : curve_point(c, c.len);
    // The sweep from the end point itself: te - ts loses digits when the arc is short.
    if (j + 1 == n) c.len = curve_param(c, pb);
    prev = c.b;
    finish_box(c);
    curves.push_back(c);
  }
}

// Sides of a capsule (edge region), counter-clockwise: the +v side from B towards A, around
// A (end disc: the vertex's curve, or the ellipse's tip), the -v side from A to B. Frame:
// A the lower end, s the horizontal abscissa along u, h(s) = max(0, zc - z(s)); the envelope
// of the discs touches the disc at s at A + (s - k h) u +- w v, w^2 = R^2 - (1 + k^2) h^2:
// straight where h = 0 (the edge above the level: shadow), an arc of the ellipse
// (cylinder section) where h > 0.
void edge_curves(const OffsetElements& el, const Region& g, std::uint32_t gi, const Level& lv,
                 std::vector<Curve>& curves, std::vector<Joint>& joints) {
  const double R = lv.R, L = std::sqrt(g.dxy2);
  const Vec2 A = xy(g.a), u = Vec2(g.d.x(), g.d.y()) / L, v = perp(u);
  const double k = g.d.z() / L, H = lv.zc - g.a.z();
  const auto& ev = el.edge_vertices[g.index];
  const Vec3& P0 = el.points[ev[0]];
  // Vertex elements at A (lower) and B.
  const bool a_is_0 = P0.z() == g.a.z() && P0.x() == g.a.x() && P0.y() == g.a.y();
  const std::uint32_t va = vertex_element(el, a_is_0 ? ev[0] : ev[1]);
  const std::uint32_t vb = vertex_element(el, a_is_0 ? ev[1] : ev[0]);
  auto joint = [&](const Vec2& p, std::uint32_t vtx) {
    Joint j;
    j.p = p;
    j.target = vtx;
    joints.push_back(j);
  };
  if (k < tol::kZLevelFlatSlope) {
    const double h = std::max(0.0, H - 0.5 * g.d.z());
    if (!(h < R)) return;
    const double w = h == 0 ? R : std::sqrt((R - h) * (R + h));
    const Vec2 pa_p = A + w * v, pb_p = A + L * u + w * v;
    const Vec2 pa_m = A - w * v, pb_m = A + L * u - w * v;
    curves.push_back(line_curve(g, gi, pb_p, pa_p, h == 0));
    curves.push_back(line_curve(g, gi, pa_m, pb_m, h == 0));
    joint(pb_p, vb);
    joint(pa_p, va);
    joint(pa_m, va);
    joint(pb_m, vb);
    return;
  }
  const double q = std::sqrt(1 + k * k);
  auto hh = [&](double s) { return std::max(0.0, H - k * s); };
  auto ww = [&](double h) { return h == 0 ? R : std::sqrt(std::max(0.0, R * R - q * q * h * h)); };
  auto point = [&](double s, double side) {
    const double h = hh(s);
    return Vec2(A + (s - k * h) * u + side * ww(h) * v);
  };
  auto angle = [&](double s, double side) {
    const double h = hh(s);
    return std::atan2(side * ww(h), -h * q);
  };
  const double s_lo = std::max(0.0, (H - R / q) / k);
  if (!(s_lo < L)) return;
  const double s_c = std::clamp(H / k, s_lo, L);
  const bool tip = s_lo > 0;
  const Vec2 pb_p = point(L, 1), pb_m = point(L, -1);
  const Vec2 pc_p = point(s_c, 1), pc_m = point(s_c, -1);
  if (s_c < L) curves.push_back(line_curve(g, gi, pb_p, pc_p, true));
  // Arcs of a very flat edge within tol::kZLevelFlatArc of their chord are chords: the
  // envelope's curvature is k^2 R^2 / ((1 + k^2) w^3), largest at the lowest point.
  bool chord = false;
  if (!tip && s_lo < s_c) {
    const double w0 = ww(hh(0));
    chord = w0 > 0 && k * k * R * R * s_c * s_c < 8 * tol::kZLevelFlatArc * w0 * w0 * w0;
  }
  if (chord) {
    const Vec2 pa_p = point(0, 1), pa_m = point(0, -1);
    curves.push_back(line_curve(g, gi, pc_p, pa_p, false));
    curves.push_back(line_curve(g, gi, pa_m, pc_m, false));
  } else if (s_lo < s_c) {
    if (tip) {
      ellipse_arcs(g, gi, lv, k, u, angle(s_c, 1), angle(s_c, -1) + 2 * kPi, pc_p, pc_m, curves);
    } else {
      const Vec2 pa_p = point(0, 1), pa_m = point(0, -1);
      ellipse_arcs(g, gi, lv, k, u, angle(s_c, 1), angle(0, 1), pc_p, pa_p, curves);
      ellipse_arcs(g, gi, lv, k, u, angle(0, -1), angle(s_c, -1), pa_m, pc_m, curves);
    }
  }
  if (s_c < L) curves.push_back(line_curve(g, gi, pc_m, pb_m, true));
  joint(pb_p, vb);
  joint(pb_m, vb);
  if (!tip) {
    joint(point(0, 1), va);
    joint(point(0, -1), va);
  }
}

void vertex_curves(const Region& g, std::uint32_t gi, const Level& lv, std::vector<Curve>& curves) {
  const double r = g.r;
  const Vec2 q[4] = {Vec2(r, 0), Vec2(0, r), Vec2(-r, 0), Vec2(0, -r)};
  for (int j = 0; j < 4; ++j) {
    Curve c;
    c.kind = CurveKind::kCircle;
    c.shadow = g.vz >= lv.zc;
    c.region = gi;
    c.element = g.element;
    c.a = g.c + q[j];
    c.b = g.c + q[(j + 1) % 4];
    c.len = kPi / 2;
    c.e1 = q[j];
    c.e2 = perp(q[j]);
    c.centre = g.c;
    c.r1 = c.r2 = r;
    c.t0 = j * (kPi / 2);
    finish_box(c);
    curves.push_back(c);
  }
}

}  // namespace

bool build_region(const OffsetElements& el, std::uint32_t id, const Level& lv, Region& out) {
  const auto nf = std::uint32_t(el.facet_count()), ne = std::uint32_t(el.edge_count());
  if (id < nf) return build_facet(el, id, lv, out);
  if (id < nf + ne) return build_edge(el, id - nf, lv, out);
  return build_vertex(el, id - nf - ne, lv, out);
}

double region_phi(const Region& g, const Vec2& x, const Level& lv, Vec2* outward, double* contact) {
  switch (g.kind) {
    case RegionKind::kFacet: {
      int best = 0;
      double phi = -INFINITY;
      for (int i = 0; i < g.nhp; ++i) {
        const double s = g.hp[i].n.dot(x) - g.hp[i].c;
        if (s > phi) {
          phi = s;
          best = i;
        }
      }
      if (outward) *outward = g.hp[best].n;
      return phi;
    }
    case RegionKind::kVertex: {
      const Vec2 w = x - g.c;
      if (outward) *outward = w;
      return w.norm() - g.r;
    }
    case RegionKind::kEdge: {
      // g(t) = |W - t D|^2 + max(0, H - t dz)^2 is convex: its minimum over [0, 1] is at the
      // stationary point of the part where it lies, clamped, or at the joint t = H / dz.
      const Vec2 W(x.x() - g.a.x(), x.y() - g.a.y()), D(g.d.x(), g.d.y());
      const double H = lv.zc - g.a.z(), dz = g.d.z(), wd = W.dot(D);
      auto gt = [&](double t) {
        const double h = std::max(0.0, H - t * dz);
        return (W - t * D).squaredNorm() + h * h;
      };
      double tb = std::clamp((wd + H * dz) / g.dd, 0.0, 1.0), best = gt(tb);
      for (double t :
           {std::clamp(wd / g.dxy2, 0.0, 1.0), dz > 0 ? std::clamp(H / dz, 0.0, 1.0) : 0.0}) {
        const double v = gt(t);
        if (v < best) {
          best = v;
          tb = t;
        }
      }
      if (outward) *outward = W - tb * D;
      if (contact) *contact = tb;
      return (best - lv.R * lv.R) / (2 * lv.R);
    }
  }
  return INFINITY;
}

bool region_row(const Region& g, double y, double margin, const Level& lv, double& x0, double& x1) {
  switch (g.kind) {
    case RegionKind::kFacet: {
      double lo = -INFINITY, hi = INFINITY;
      for (int i = 0; i < g.nhp; ++i) {
        const HalfPlane& h = g.hp[i];
        const double rhs = h.c - margin - h.n.y() * y;  // n.x x <= rhs
        if (h.n.x() > 0)
          hi = std::min(hi, rhs / h.n.x());
        else if (h.n.x() < 0)
          lo = std::max(lo, rhs / h.n.x());
        else if (rhs < 0)
          return false;
      }
      x0 = lo;
      x1 = hi;
      return lo < hi;
    }
    case RegionKind::kVertex: {
      const double rr = g.r - margin, dy = y - g.c.y();
      if (!(std::abs(dy) < rr)) return false;
      const double w = std::sqrt((rr - dy) * (rr + dy));
      x0 = g.c.x() - w;
      x1 = g.c.x() + w;
      return true;
    }
    case RegionKind::kEdge: {
      // Inner subset: the stadium of radius R around the part of AB at or above zc.
      const Vec3 B = g.a + g.d;
      if (B.z() < lv.zc) return false;
      const double t = g.d.z() > 0 ? std::clamp((lv.zc - g.a.z()) / g.d.z(), 0.0, 1.0)
                                   : (g.a.z() >= lv.zc ? 0.0 : 1.0);
      const Vec3 P = g.a + t * g.d;
      return stadium_row(xy(P), xy(B), lv.R - margin, y, x0, x1);
    }
  }
  return false;
}

void region_curves(const OffsetElements& el, const Region& g, std::uint32_t gi, const Level& lv,
                   std::vector<Curve>& curves, std::vector<Joint>& joints) {
  switch (g.kind) {
    case RegionKind::kFacet:
      facet_curves(el, g, gi, lv, curves, joints);
      break;
    case RegionKind::kEdge:
      edge_curves(el, g, gi, lv, curves, joints);
      break;
    case RegionKind::kVertex:
      vertex_curves(g, gi, lv, curves);
      break;
  }
}

}  // namespace ncpath::zlevel_detail
