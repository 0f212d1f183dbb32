#include "engine/pencil.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "engine/drop_index.hpp"
#include "engine/mesh_distance.hpp"
#include "engine/parallel.hpp"
#include "engine/pencil_crease.hpp"
#include "engine/scan.hpp"
#include "engine/surface_check.hpp"
#include "engine/zlevel.hpp"
#include "kernels/cleanup/pencil.hpp"
#include "kernels/mesh/closest_point.hpp"
#include "kernels/scan/envelope.hpp"
#include <functional>
#include <map>

namespace ncpath {

std::string validate(const PencilParams& p) {
  std::ostringstream os;
  auto positive = [&](const char* key, double v) {
    if (os.tellp() == 0 && !(std::isfinite(v) && v > 0))
      os << key << " must be a positive number of mm, got " << v;
  };
  positive("interval", p.interval);
  positive("tolerance", p.tolerance);
  if (os.tellp() == 0 && !(std::isfinite(p.step_down) && p.step_down >= 0))
    os << "step_down must be >= 0 mm (0 = no z-levels), got " << p.step_down;
  if (os.tellp() == 0 && !(std::isfinite(p.min_angle_deg) && p.min_angle_deg > 0 &&
                           p.min_angle_deg < 180))
    os << "min_angle must be between 0 and 180 degrees, got " << p.min_angle_deg;
  if (os.tellp() == 0 && !(std::isfinite(p.merge_distance) && p.merge_distance >= 0))
    os << "merge_distance must be >= 0 mm (0 = twice the interval), got " << p.merge_distance;
  if (os.tellp() == 0 && !(std::isfinite(p.min_length) && p.min_length >= 0))
    os << "min_length must be >= 0 mm, got " << p.min_length;
  if (os.tellp() == 0 && !(std::isfinite(p.margin) && p.margin >= 0))
    os << "margin must be >= 0 mm, got " << p.margin;
  if (os.tellp() == 0 && p.floor_z && !std::isfinite(*p.floor_z))
    os << "floor_z must be a finite number of mm";
  if (os.tellp() == 0 && !std::isfinite(p.stock))
    os << "stock must be a finite number of mm, got " << p.stock;
  return os.str();
}

namespace {

Vec3 tangent_of(const PencilCandidate& c) { return crease_tangent(c.b1, c.b2); }

// Appends the refined points strictly between A and B (A and B excluded).
// Refined when the chord's error bound exceeds tol or its middle is below the CL surface.
template <class Deficit>
void refine(const ScanElements& se, const PencilCandidate& a, const PencilCandidate& b,
            double tol, double min_angle, double floor_z, int depth, const Deficit& deficit,
            std::vector<PencilCandidate>& out, std::uint64_t& added) {
  // Chords shorter than twice the tolerance are within it of any crease between their ends:
  // only a dip below the surface by more than half the tolerance still refines them, to
  // depth 8 (1/256 of the chord; near a kink of the crease at a wall's top). Smaller dips
  // (a crease curving sideways into a wall) are lifted by the check below.
  if (a.family == 2 || depth >= 16) return;
  const bool loose = (b.p - a.p).norm() >= 2 * tol &&
                     chord_error(a.p, tangent_of(a), b.p, tangent_of(b)) > tol;
  if (!loose && (depth >= 8 || deficit(0.5 * (a.p + b.p)) <= 0.5 * tol)) return;
  PencilCandidate c;
  if (!crease_between(se, a, b, min_angle, floor_z, c)) return;
  ++added;
  refine(se, a, c, tol, min_angle, floor_z, depth + 1, deficit, out, added);
  out.push_back(c);
  refine(se, c, b, tol, min_angle, floor_z, depth + 1, deficit, out, added);
}

double polyline_length(const std::vector<Vec3>& p) {
  double s = 0;
  for (std::size_t i = 1; i < p.size(); ++i) s += (p[i] - p[i - 1]).norm();
  return s;
}

struct ZLevelCandidates {
  std::vector<PencilCandidate> cand;
  std::vector<std::array<ElementRef, 2>> refs;  // the two touched elements
};

// The sharp-concave junctions of the z-levels (none without a step-down) as candidates of
// family 2, layer = level index below the part's top `top`.
ZLevelCandidates zlevel_candidates(const TriangleMesh& mesh, const Cutter& cutter,
                                   const PencilParams& p, double top, RunControl& control,
                                   PencilStats& st) {
  ZLevelCandidates z;
  if (!(p.step_down > 0)) return z;
  Stopwatch clock;
  ZLevelOpParams zp;
  zp.step_down = p.step_down;
  zp.tolerance = p.tolerance;
  zp.condition = false;  // run_pencil conditioned the mesh
  const ZLevelOpStats zs = run_zlevel(
      mesh, cutter, zp,
      [&](const ZLevelChunk& ch) {
        for (const ZLevelJunctionRecord& j : ch.junctions) {
          if (j.kind != std::uint8_t(JunctionKind::kSharpConcave)) continue;
          PencilCandidate c;
          c.p = Vec3(j.position[0], j.position[1], j.position[2]);
          c.b1 = Vec3(j.b1[0], j.b1[1], j.b1[2]);
          c.b2 = Vec3(j.b2[0], j.b2[1], j.b2[2]);
          c.family = 2;
          c.layer = std::uint32_t(std::lround((top - c.p.z()) / p.step_down) - 1);
          z.cand.push_back(c);
          z.refs.push_back({j.element1, j.element2});
        }
      },
      control);
  st.levels = zs.levels;
  st.zlevel_open_chains = zs.open_chains;
  st.zlevel_s = clock.seconds();
  return z;
}

}  // namespace

// The stages for the ball as given (validated by run_pencil), tool tip = centre - radius z
// (p.stock is not used: run_pencil below grows the ball by it).
static PencilResult run_pencil_exact(const TriangleMesh& mesh, const Cutter& cutter,
                                     const PencilParams& p, RunControl& control) {
  PencilResult res;
  PencilStats& st = res.stats;
  const double min_angle = p.min_angle_deg * std::numbers::pi / 180;
  const Aabb3 box = bounding_box(mesh);
  const double floor_z = p.floor_z.value_or(box.lo.z());
  // Candidates from z-levels first (appended after the drive planes' below): their elements
  // are freed before the drive planes' are built, so the two never take memory at once.
  ZLevelCandidates z = zlevel_candidates(mesh, cutter, p, box.hi.z(), control, st);
  const ScanElements se = build_scan_elements(mesh, cutter.radius);
  st.elements_s = se.build_s;

  // 1. Candidates from both drive-plane families.
  std::vector<PencilCandidate> cand;
  std::vector<std::array<ElementRef, 2>> cand_refs;  // the two touched elements
  std::array<double, 4> rect{};                       // the scanned rectangle
  {
    Stopwatch clock;
    ScanParams sp;
    sp.families = ScanFamilies::kBoth;
    sp.interval = p.interval;
    sp.tolerance = p.tolerance;
    sp.margin = p.margin;
    sp.floor_z = floor_z;
    std::vector<ScanJunctionRecord> js;
    const ScanStats ss = run_scan(
        se, cutter, sp,
        [&](const ScanChunk& ch) {
          // The floor is not the part: its junctions are not creases.
          for (const ScanJunctionRecord& j : ch.junctions)
            if (j.kind == std::uint8_t(JunctionKind::kSharpConcave) && j.element1.kind != 3 &&
                j.element2.kind != 3)
              js.push_back(j);
        },
        control);
    st.planes = ss.planes;
    rect = ss.rect;
    for (const ScanJunctionRecord& j : js) {
      PencilCandidate c;
      c.p = Vec3(j.position[0], j.position[1], j.position[2]);
      c.b1 = Vec3(j.b1[0], j.b1[1], j.b1[2]);
      c.b2 = Vec3(j.b2[0], j.b2[1], j.b2[2]);
      const bool x_line = std::uint64_t(j.path) < ss.planes_x;
      c.family = x_line ? 0 : 1;
      c.layer = std::uint32_t(x_line ? j.path : j.path - std::int64_t(ss.planes_x));
      cand.push_back(c);
      cand_refs.push_back({j.element1, j.element2});
    }
    st.scan_s = clock.seconds();
  }
  cand.insert(cand.end(), z.cand.begin(), z.cand.end());
  cand_refs.insert(cand_refs.end(), z.refs.begin(), z.refs.end());
  st.candidates = cand.size();

  // 2. Pencil points (both contacts within the tolerance of the part) and the family that
  // traces each.
  Stopwatch index_clock0;
  const MeshDistance distance(mesh);
  st.index_s = index_clock0.seconds();
  Stopwatch link_clock;
  std::vector<std::uint8_t> touches(cand.size(), 0);
  par::for_each(cand.size(), 256, [&](std::size_t i) {
    const PencilCandidate& c = cand[i];
    if (bicontact_angle(c.b1, c.b2) < min_angle) return;
    const Vec3 centre = c.p + Vec3(0, 0, cutter.radius);
    auto on_part = [&](const Vec3& b) {
      return distance.closest(centre - cutter.radius * b, p.tolerance).distance <= p.tolerance;
    };
    touches[i] = on_part(c.b1) && on_part(c.b2);
  });
  const bool scanned[3] = {true, true, p.step_down > 0};
  std::array<std::vector<PencilCandidate>, 3> kept;
  std::array<std::vector<std::array<ElementRef, 2>>, 3> kept_refs;
  for (std::size_t i = 0; i < cand.size(); ++i) {
    const PencilCandidate& c = cand[i];
    const double angle = bicontact_angle(c.b1, c.b2);
    if (angle < min_angle) continue;
    if (!touches[i]) {
      ++st.contactless_points;
      continue;
    }
    const bool keep = pencil_keep(c, scanned);
    res.points.push_back({c.p, c.b1, c.b2, angle, c.family, std::uint8_t(keep)});
    if (keep) {
      kept[c.family].push_back(c);
      kept_refs[c.family].push_back(cand_refs[i]);
    }
  }
  st.pencil_points = res.points.size();

  // 3. Chains per family.
  struct Chain {
    std::vector<PencilCandidate> pts;
    std::vector<std::array<ElementRef, 2>> refs;
  };
  std::vector<Chain> chains;
  for (int f = 0; f < 3; ++f) {
    st.kept_points += kept[f].size();
    PencilLinkParams lp;
    const double spacing = f == 2 ? p.step_down : p.interval;
    lp.max_gap = 1.5 * spacing + 0.1;
    lp.min_cos = kCreaseMinCos;
    for (const auto& ids : link_layers(kept[f], lp)) {
      Chain c;
      for (std::uint32_t i : ids) {
        c.pts.push_back(kept[f][i]);
        c.refs.push_back(kept_refs[f][i]);
      }
      chains.push_back(std::move(c));
    }
  }
  st.chains = chains.size();
  // Drive-plane chains reach to where their crease ends between layers.
  par::for_each(chains.size(), 1, [&](std::size_t k) {
    Chain& ch = chains[k];
    if (ch.pts.empty() || ch.pts[0].family == 2) return;
    PencilCandidate e;
    const int f = ch.pts[0].family;
    const double v_min = f == 0 ? rect[1] : rect[0], v_max = f == 0 ? rect[3] : rect[2];
    if (crease_end(se, ch.pts.back(), 1, p.interval, v_min, v_max, min_angle, floor_z, e)) {
      ch.pts.push_back(e);
      ch.refs.push_back(ch.refs.back());
    }
    if (crease_end(se, ch.pts.front(), -1, p.interval, v_min, v_max, min_angle, floor_z, e)) {
      ch.pts.insert(ch.pts.begin(), e);
      ch.refs.insert(ch.refs.begin(), ch.refs.front());
    }
  });
  st.link_s = link_clock.seconds();
  if (control.cancel.load()) throw Cancelled{};

  // The point drop-cutter (Embree, exact in double): checks refined points and chords.
  Stopwatch index_clock;
  const DropIndex index(mesh, cutter);
  st.index_s += index_clock.seconds();
  auto deficit_at = [&](const Vec3& q) { return surface_deficit(index, floor_z, q); };
  const PartProbe part{index, distance, cutter.radius, floor_z, bounding_box(mesh).hi.z()};
  auto closest = [&](const ElementRef& e) -> std::function<Vec3(const Vec3&)> {
    const auto& V = mesh.vertices;
    if (e.kind == 0) {
      const auto& f = mesh.facets[std::size_t(e.a)];
      return [&V, f](const Vec3& q) {
        Vec3 c;
        point_triangle_closest(q, V[f[0]], V[f[1]], V[f[2]], c);
        return c;
      };
    }
    if (e.kind == 1) {
      const Vec3 a = V[std::size_t(e.a)], b = V[std::size_t(e.b)];
      return [a, b](const Vec3& q) {
        Vec3 c;
        point_segment_closest(q, a, b, c);
        return c;
      };
    }
    const Vec3 v = V[std::size_t(e.a)];
    return [v](const Vec3&) { return v; };
  };
  // Z-level chains: the crease point of A's two elements at the middle height, kept when it
  // lies on the CL surface (the crease may have moved to other elements in between).
  const double R = cutter.radius;
  using Pair = std::array<ElementRef, 2>;
  std::function<void(const PencilCandidate&, const Pair&, const PencilCandidate&, const Pair&,
                     int, std::vector<PencilCandidate>&, std::uint64_t&)>
      refine_z = [&](const PencilCandidate& a, const Pair& ea, const PencilCandidate& b,
                     const Pair& eb, int depth, std::vector<PencilCandidate>& out,
                     std::uint64_t& added) {
        if (depth >= 16) return;
        const bool loose = (b.p - a.p).norm() >= 2 * p.tolerance &&
                           chord_error(a.p, tangent_of(a), b.p, tangent_of(b)) > p.tolerance;
        if (!loose && (depth >= 8 || deficit_at(0.5 * (a.p + b.p)) <= 0.5 * p.tolerance)) return;
        const double zm = 0.5 * (a.p.z() + b.p.z());
        const Vec2 guess = 0.5 * (a.p.head<2>() + b.p.head<2>());
        // The crease of a's elements, else of b's (a crease may pass from one pair to another
        // between them, e.g. from two walls to their rim edges).
        for (const Pair* e : {&ea, &eb}) {
          const Pair& el = *e;
          if (el[0].kind > 2 || el[1].kind > 2) continue;
          Vec2 xy;
          if (!crease_at_height(closest(el[0]), closest(el[1]), guess, zm + R, R,
                                (b.p - a.p).norm(), xy))
            continue;
          const Vec3 q(xy.x(), xy.y(), zm);
          // On the CL surface: the drop-cutter reaches it there (upper semicontinuous: at a
          // wall's foot it reports the wall's top) and the point is not inside the part.
          const double top = std::max(floor_z, index.query(q.x(), q.y()).tip_z);
          if (top < zm - tol::kSweepSlack || !reachable(part, q)) continue;
          const Vec3 centre = q + Vec3(0, 0, R);
          PencilCandidate c = a;
          c.p = q;
          c.b1 = (centre - closest(el[0])(centre)).normalized();
          c.b2 = (centre - closest(el[1])(centre)).normalized();
          ++added;
          refine_z(a, ea, c, el, depth + 1, out, added);
          out.push_back(c);
          refine_z(c, el, b, eb, depth + 1, out, added);
          return;
        }
        // Under an overhang or along walls (z-level junctions of shadowed elements) the
        // contacts are on walls below the elements: the crease follows a's tangent, straight
        // (vertical between two walls). Kept when that point is on the CL surface.
        for (const PencilCandidate* e : {&a, &b}) {
          const Vec3 t = tangent_of(*e);
          if (!(std::abs(t.z()) > 0.5)) continue;
          const Vec3 q = e->p + t * ((zm - e->p.z()) / t.z());
          const double top = std::max(floor_z, index.query(q.x(), q.y()).tip_z);
          if ((q - e->p).norm() > (b.p - a.p).norm() || top < zm - tol::kSweepSlack ||
              !reachable(part, q))
            continue;
          PencilCandidate c = *e;
          c.p = q;
          ++added;
          refine_z(a, ea, c, e == &a ? ea : eb, depth + 1, out, added);
          out.push_back(c);
          refine_z(c, e == &a ? ea : eb, b, eb, depth + 1, out, added);
          return;
        }
      };

  // Join chain ends (the same crease traced by different families meets end to end), on
  // the candidates themselves so that the joins are refined like the rest.
  struct Node {
    PencilCandidate c;
    std::array<ElementRef, 2> refs;
  };
  std::vector<Node> nodes;
  std::vector<std::vector<Vec3>> polys;
  for (const Chain& ch : chains) {
    std::vector<Vec3> poly;
    for (std::size_t i = 0; i < ch.pts.size(); ++i) {
      // The node's index rides in the polyline as its position; recovered below.
      poly.push_back(ch.pts[i].p);
      nodes.push_back({ch.pts[i], ch.refs[i]});
    }
    polys.push_back(std::move(poly));
  }
  std::map<std::array<double, 3>, std::uint32_t> node_at;
  for (std::uint32_t i = 0; i < nodes.size(); ++i)
    node_at.emplace(std::array<double, 3>{nodes[i].c.p.x(), nodes[i].c.p.y(), nodes[i].c.p.z()}, i);
  const double merge = p.merge_distance > 0 ? p.merge_distance : 2 * p.interval;
  const std::vector<std::vector<Vec3>> joined = merge_paths(std::move(polys), merge, 0.5, 0);

  // Refinement: exact crease points where a chord's error bound exceeds the tolerance or the
  // chord dips below the CL surface. Drive-plane pairs by the exact envelope of an
  // intermediate plane; pairs involving a z-level point by the crease of the lower point's
  // two elements at the middle height.
  Stopwatch refine_clock;
  std::vector<std::vector<Vec3>> pieces(joined.size());
  std::vector<std::vector<std::array<Vec3, 2>>> normals(joined.size());
  std::vector<std::uint64_t> added(joined.size(), 0);
  par::for_each(joined.size(), 1, [&](std::size_t k) {
    std::vector<PencilCandidate> full;
    const Node* prev = nullptr;
    for (const Vec3& q : joined[k]) {
      const Node& n = nodes[node_at.at({q.x(), q.y(), q.z()})];
      if (prev) {
        const Node& lo = prev->c.p.z() <= n.c.p.z() ? *prev : n;
        if (prev->c.family == 2 || n.c.family == 2) {
          std::vector<PencilCandidate> mid;
          const Node& hi = &lo == prev ? n : *prev;
          refine_z(lo.c, lo.refs, hi.c, hi.refs, 0, mid, added[k]);
          if (&lo != prev) std::reverse(mid.begin(), mid.end());
          full.insert(full.end(), mid.begin(), mid.end());
        } else {
          PencilCandidate a = prev->c;
          PencilCandidate b = n.c;
          if (a.family != b.family) b.family = a.family;  // refine on a's planes
          refine(se, a, b, p.tolerance, min_angle, floor_z, 0, deficit_at, full, added[k]);
        }
      }
      full.push_back(n.c);
      prev = &n;
    }
    for (const PencilCandidate& c : full) {
      pieces[k].push_back(c.p);
      normals[k].push_back({c.b1, c.b2});
    }
  });
  for (std::uint64_t a : added) st.refined_points += a;
  st.refine_s = refine_clock.seconds();
  {
    std::size_t w = 0;
    for (std::size_t k = 0; k < pieces.size(); ++k) {
      if (pieces[k].size() < 2 || polyline_length(pieces[k]) < std::max(p.min_length, 1e-9))
        continue;
      if (w != k) {
        pieces[w] = std::move(pieces[k]);
        normals[w] = std::move(normals[k]);
      }
      ++w;
    }
    pieces.resize(w);
    normals.resize(w);
  }

  // 4. Never below the CL surface: the ball swept along every chord (exact), a chord that
  // touches lifted. A chord that would need more than `leave` has left the crease (a link
  // between two creases the refinement could not bridge): the piece is split there instead
  // of lifted, so that pencil paths stay on creases.
  Stopwatch check_clock;
  const double spacing = std::max(0.02, 0.1 * p.interval);
  const double leave = std::max(10 * p.tolerance, 0.05);
  std::vector<std::vector<std::vector<Vec3>>> split(pieces.size());
  std::vector<std::vector<std::vector<std::array<Vec3, 2>>>> split_b(pieces.size());
  std::vector<std::uint64_t> lifted(pieces.size(), 0), splits(pieces.size(), 0);
  par::for_each(pieces.size(), 1, [&](std::size_t k) {
    std::vector<Vec3> cur = pieces[k];
    const auto& cur_b = normals[k];
    std::vector<bool> touching;
    lifted[k] += lift_swept(distance, index, floor_z, R, leave, spacing, cur, 24, &touching);
    std::size_t from = 0;
    for (std::size_t i = 0; i <= touching.size(); ++i) {
      if (i < touching.size() && !touching[i]) continue;
      // Piece [from, i]; a chord still touching is never cut.
      if (i > from) {
        std::vector<Vec3> part(cur.begin() + from, cur.begin() + i + 1);
        if (polyline_length(part) >= std::max(p.min_length, 1e-9)) {
          split[k].push_back(std::move(part));
          split_b[k].emplace_back(cur_b.begin() + from, cur_b.begin() + i + 1);
        }
      }
      if (i < touching.size()) ++splits[k];
      from = i + 1;
    }
  });
  pieces.clear();
  normals.clear();
  for (std::size_t k = 0; k < split.size(); ++k) {
    st.lifted_points += lifted[k];
    st.split_chords += splits[k];
    for (std::size_t m = 0; m < split[k].size(); ++m) {
      pieces.push_back(std::move(split[k][m]));
      normals.push_back(std::move(split_b[k][m]));
    }
  }
  st.check_s = check_clock.seconds();

  // 5. Order and orient. With a cut direction, pieces with a material side are turned to
  // cut that way first and keep it; the ordering orients the others.
  std::vector<std::uint8_t> fixed;
  if (p.direction != CutDirection::kAny) {
    fixed.assign(pieces.size(), 0);
    for (std::size_t k = 0; k < pieces.size(); ++k) {
      const int side = cut_side(cut_side_score(pieces[k], normals[k]));
      if (side == 0) {
        ++st.neutral_paths;
        continue;
      }
      fixed[k] = 1;
      if (reverse_for(p.direction, side)) {
        std::reverse(pieces[k].begin(), pieces[k].end());
        std::reverse(normals[k].begin(), normals[k].end());
      }
    }
  }
  for (const OrderedPath& o : order_paths(pieces, fixed)) {
    std::vector<Vec3> path = pieces[o.index];
    std::vector<std::array<Vec3, 2>> b = normals[o.index];
    if (o.reversed) {
      std::reverse(path.begin(), path.end());
      std::reverse(b.begin(), b.end());
    }
    if (!res.paths.empty()) st.air_length += (path.front() - res.paths.back().back()).norm();
    st.traced_length += polyline_length(path);
    res.paths.push_back(std::move(path));
    res.path_normals.push_back(std::move(b));
  }
  st.paths = res.paths.size();
  return res;
}

std::string validate_stock(double stock, double radius) {
  std::ostringstream os;
  if (!std::isfinite(stock))
    os << "stock must be a finite number of mm, got " << stock;
  else if (!(stock > -radius))
    os << "stock must be greater than minus the ball radius (-" << radius
       << " mm): the ball's centre runs R + stock from the part, got " << stock;
  return os.str();
}

// Stock s: the stages for the ball of radius R + s (the same centres), tips raised by s. The
// mesh is conditioned first (condition_for_slicing) and s grown by its largest vertex move,
// so the tool keeps s from the part as given.
PencilResult run_pencil(const TriangleMesh& mesh, const Cutter& cutter, const PencilParams& p,
                        RunControl& control, const ConditionedMesh* conditioned) {
  if (std::string e = validate(cutter); !e.empty()) throw std::invalid_argument("tool: " + e);
  if (cutter.type != CutterType::kBall)
    throw std::invalid_argument("tool: pencil-cut needs a ball-end mill");
  if (std::string e = validate(p); !e.empty()) throw std::invalid_argument(e);
  if (std::string e = validate_stock(p.stock, cutter.radius); !e.empty())
    throw std::invalid_argument(e);
  Stopwatch clock;
  ConditionedMesh own;
  if (!conditioned) own = condition_for_slicing(mesh);
  const ConditionedMesh& cond = conditioned ? *conditioned : own;
  const double condition_s = clock.seconds();
  const double stock = p.stock + cond.stats.max_move;
  Cutter grown = cutter;
  grown.radius = cutter.radius + stock;
  grown.corner_radius = grown.radius;
  PencilParams exact = p;
  exact.stock = 0;
  PencilResult res = run_pencil_exact(cond.mesh, grown, exact, control);
  res.stats.condition = cond.stats;
  res.stats.elements_s += condition_s;
  if (stock == 0) return res;
  const Vec3 up(0, 0, stock);
  for (auto& path : res.paths)
    for (Vec3& q : path) q += up;
  for (PencilPoint& pt : res.points) pt.position += up;
  return res;
}

ClChunk pencil_chunk(const PencilResult& r) {
  ClChunk ch;
  for (std::size_t i = 0; i < r.paths.size(); ++i) {
    const auto& path = r.paths[i];
    if (i > 0) {
      ch.xyz.insert(ch.xyz.end(), {path[0].x(), path[0].y(), path[0].z()});
      ch.contact.push_back(std::uint8_t(ContactKind::kEdge));
      ch.path_sizes.push_back(1);
      ch.path_kinds.push_back(std::uint8_t(PathKind::kRapid));
    }
    for (const Vec3& q : path) ch.xyz.insert(ch.xyz.end(), {q.x(), q.y(), q.z()});
    ch.contact.insert(ch.contact.end(), path.size(), std::uint8_t(ContactKind::kEdge));
    ch.path_sizes.push_back(std::uint32_t(path.size()));
    ch.path_kinds.push_back(std::uint8_t(PathKind::kCut));
  }
  return ch;
}

}  // namespace ncpath
