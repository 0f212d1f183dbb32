#include "engine/pencil.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <numbers>
#include <stdexcept>
#include <tuple>

#include "engine/concave_zone.hpp"
#include "engine/drop_index.hpp"
#include "engine/mesh_distance.hpp"
#include "engine/parallel.hpp"
#include "engine/pencil_crease.hpp"
#include "engine/pencil_outline.hpp"
#include "engine/scan.hpp"
#include "engine/surface_check.hpp"
#include "engine/zlevel.hpp"
#include "kernels/cleanup/pencil.hpp"
#include "kernels/scan/envelope.hpp"

namespace ncpath {

namespace {

struct Candidates {
  std::vector<PencilCandidate> cand;
  std::vector<ElementPair> refs;
};

// Candidates sorted by layer, position, contact vectors and elements.
void canonical_order(Candidates& c) {
  std::vector<std::uint32_t> order(c.cand.size());
  std::iota(order.begin(), order.end(), 0u);
  auto key = [&](std::uint32_t i) {
    const PencilCandidate& a = c.cand[i];
    const ElementPair& r = c.refs[i];
    return std::make_tuple(a.layer, a.p.x(), a.p.y(), a.p.z(), a.b1.x(), a.b1.y(), a.b1.z(),
                           a.b2.x(), a.b2.y(), a.b2.z(), r[0].kind, r[0].a, r[0].b, r[1].kind,
                           r[1].a, r[1].b);
  };
  std::stable_sort(order.begin(), order.end(),
                   [&](std::uint32_t x, std::uint32_t y) { return key(x) < key(y); });
  Candidates sorted;
  for (std::uint32_t i : order) {
    sorted.cand.push_back(c.cand[i]);
    sorted.refs.push_back(c.refs[i]);
  }
  c = std::move(sorted);
}

// The sharp-concave junctions of the z-levels (none without a step-down) as candidates of
// family 2, layer = level index below the part's top `top`, in a canonical order (level,
// position, elements): the same whether or not the z-levels sliced the concave zone only.
Candidates zlevel_candidates(const TriangleMesh& mesh, const Cutter& cutter, const PencilParams& p,
                             double top, const ConcaveZone* zone, RunControl& control,
                             PencilStats& st) {
  Candidates z;
  // An empty zone (a convex part) holds no bi-contact: nothing to slice.
  if (!(p.step_down > 0) || (zone && zone->kept.facet.empty())) return z;
  Stopwatch clock;
  ZLevelOpParams zp;
  zp.step_down = p.step_down;
  zp.tolerance = p.tolerance;
  zp.condition = false;  // run_pencil conditioned the mesh
  zp.zone = zone;
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
  canonical_order(z);
  st.levels = zs.levels;
  st.zlevel_open_chains = zs.open_chains;
  st.zlevel_s = clock.seconds();
  return z;
}

// The part sliced to the concave zone (engine/concave_zone.hpp) by the drive planes of the
// whole part (its rectangle).
struct ZoneSlice {
  const ConcaveZone& zone;
  std::array<double, 4> rect;
};

// A junction's element on the sliced part as the whole mesh's.
ElementRef whole_mesh_ref(const ElementRef& r, const ZoneSlice* slice) {
  return slice ? slice->zone.kept.in_mesh(r) : r;
}

// The sharp-concave junctions of both drive-plane families (not the floor's: its junctions
// are not creases) as candidates of family 0 (x planes) and 1 (y planes), layer = plane
// index; `rect` is the scanned rectangle.
Candidates drive_plane_candidates(const ScanElements& se, const Cutter& cutter,
                                  const PencilParams& p, double floor_z, const ZoneSlice* slice,
                                  RunControl& control, PencilStats& st,
                                  std::array<double, 4>& rect) {
  Candidates out;
  Stopwatch clock;
  ScanParams sp;
  sp.families = ScanFamilies::kBoth;
  sp.interval = p.interval;
  sp.tolerance = p.tolerance;
  sp.margin = pencil_reach(p, cutter.radius);
  sp.floor_z = floor_z;
  if (slice) sp.rect = slice->rect;
  std::vector<ScanJunctionRecord> js;
  const ScanStats ss = run_scan(
      se, cutter, sp,
      [&](const ScanChunk& ch) {
        // The floor is not the part: its junctions are not creases.
        for (const ScanJunctionRecord& j : ch.junctions)
          if (j.kind == std::uint8_t(JunctionKind::kSharpConcave) && j.element1.kind != 3 &&
              j.element2.kind != 3 &&
              (!slice || slice->zone.holds(Vec3(j.position[0], j.position[1],
                                                j.position[2] + cutter.radius))))
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
    out.cand.push_back(c);
    out.refs.push_back({whole_mesh_ref(j.element1, slice), whole_mesh_ref(j.element2, slice)});
  }
  canonical_order(out);
  st.scan_s = clock.seconds();
  return out;
}

// Per family (x planes, y planes, z-levels): the points it traces and their elements.
struct Kept {
  std::array<std::vector<PencilCandidate>, 3> pts;
  std::array<std::vector<ElementPair>, 3> refs;
};

// Pencil points: the candidates whose bi-contact angle reaches min_angle, whose two contacts
// lie within the tolerance of the part and whose ball does not hang over the part's outline
// (res.points), and the family that traces each.
Kept pencil_points(const Candidates& all, const MeshDistance& distance, const Cutter& cutter,
                   const PencilParams& p, double min_angle, const HangingTest& hang,
                   PencilResult& res) {
  PencilStats& st = res.stats;
  const std::vector<PencilCandidate>& cand = all.cand;
  std::vector<std::uint8_t> touches(cand.size(), 0), hangs(cand.size(), 0);
  par::for_each(cand.size(), 256, [&](std::size_t i) {
    const PencilCandidate& c = cand[i];
    if (bicontact_angle(c.b1, c.b2) < min_angle) return;
    const Vec3 centre = c.p + Vec3(0, 0, cutter.radius);
    auto on_part = [&](const Vec3& b) {
      return distance.closest(centre - cutter.radius * b, p.tolerance).distance <= p.tolerance;
    };
    touches[i] = on_part(c.b1) && on_part(c.b2);
    hangs[i] = touches[i] && hang.hanging(c.p, c.b1, c.b2, all.refs[i]);
  });
  const bool scanned[3] = {true, true, p.step_down > 0};
  Kept kept;
  for (std::size_t i = 0; i < cand.size(); ++i) {
    const PencilCandidate& c = cand[i];
    const double angle = bicontact_angle(c.b1, c.b2);
    if (angle < min_angle) continue;
    if (!touches[i]) {
      ++st.contactless_points;
      continue;
    }
    if (hangs[i]) {
      ++st.hanging_points;
      continue;
    }
    const bool keep = pencil_keep(c, scanned);
    res.points.push_back({c.p, c.b1, c.b2, angle, c.family, std::uint8_t(keep)});
    if (keep) {
      kept.pts[c.family].push_back(c);
      kept.refs[c.family].push_back(all.refs[i]);
    }
  }
  st.pencil_points = res.points.size();
  return kept;
}

struct Chain {
  std::vector<PencilCandidate> pts;
  std::vector<ElementPair> refs;
};

// Chains per family; drive-plane chains reach to where their crease ends between layers (or
// where the ball starts to hang over the outline).
std::vector<Chain> trace_chains(const Kept& kept, const ScanElements& se, const PencilParams& p,
                                const std::array<double, 4>& rect, const HangingTest& hang,
                                double min_angle, double floor_z, PencilStats& st) {
  std::vector<Chain> chains;
  for (int f = 0; f < 3; ++f) {
    st.kept_points += kept.pts[f].size();
    PencilLinkParams lp;
    const double spacing = f == 2 ? p.step_down : p.interval;
    lp.max_gap = 1.5 * spacing + 0.1;
    lp.min_cos = kCreaseMinCos;
    for (const auto& ids : link_layers(kept.pts[f], lp)) {
      Chain c;
      for (std::uint32_t i : ids) {
        c.pts.push_back(kept.pts[f][i]);
        c.refs.push_back(kept.refs[f][i]);
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
    const CreaseFilter keep = hang.filter();
    ElementPair r;
    if (crease_end(se, ch.pts.back(), 1, p.interval, v_min, v_max, keep, min_angle, floor_z, e,
                   r)) {
      ch.pts.push_back(e);
      ch.refs.push_back(r);
    }
    if (crease_end(se, ch.pts.front(), -1, p.interval, v_min, v_max, keep, min_angle, floor_z, e,
                   r)) {
      ch.pts.insert(ch.pts.begin(), e);
      ch.refs.insert(ch.refs.begin(), r);
    }
  });
  return chains;
}

struct Pieces {
  std::vector<std::vector<Vec3>> paths;
  std::vector<std::vector<std::array<Vec3, 2>>> normals;
};

// The chains' points with their elements, and the chains joined into polylines of their
// positions (a point's position finds it again: node_at).
struct Joined {
  struct Node {
    PencilCandidate c;
    ElementPair refs;
  };
  std::vector<Node> nodes;
  std::map<std::array<double, 3>, std::uint32_t> node_at;
  std::vector<std::vector<Vec3>> polylines;
};

// Chain ends joined (the same crease traced by different families meets end to end), on the
// candidates themselves so that the joins are refined like the rest.
Joined join_chains(const std::vector<Chain>& chains, const PencilParams& p) {
  Joined j;
  std::vector<std::vector<Vec3>> polys;
  for (const Chain& ch : chains) {
    std::vector<Vec3> poly;
    for (std::size_t i = 0; i < ch.pts.size(); ++i) {
      poly.push_back(ch.pts[i].p);
      j.nodes.push_back({ch.pts[i], ch.refs[i]});
    }
    polys.push_back(std::move(poly));
  }
  for (std::uint32_t i = 0; i < j.nodes.size(); ++i) {
    const Vec3& q = j.nodes[i].c.p;
    j.node_at.emplace(std::array<double, 3>{q.x(), q.y(), q.z()}, i);
  }
  const double merge = p.merge_distance > 0 ? p.merge_distance : 2 * p.interval;
  j.polylines = merge_paths(std::move(polys), merge, 0.5, 0);
  return j;
}

// The joined chains refined: exact crease points where a chord's error bound exceeds the
// tolerance or the chord dips below the CL surface. Drive-plane pairs by the exact envelope
// of an intermediate plane; pairs involving a z-level point by the crease of the lower
// point's two elements at the middle height. Pieces shorter than min_length are dropped.
Pieces refine_joined(const Joined& joined, const ScanElements& se,
                     const ZLevelCreaseRefine& refine_z, const PencilParams& p, double min_angle,
                     PencilStats& st) {
  using Node = Joined::Node;
  const std::vector<Node>& nodes = joined.nodes;
  const double floor_z = refine_z.floor_z;
  Stopwatch refine_clock;
  const std::size_t count = joined.polylines.size();
  std::vector<std::vector<Vec3>> pieces(count);
  std::vector<std::vector<std::array<Vec3, 2>>> normals(count);
  std::vector<std::uint64_t> added(count, 0);
  par::for_each(count, 1, [&](std::size_t k) {
    std::vector<PencilCandidate> full;
    const Node* prev = nullptr;
    for (const Vec3& q : joined.polylines[k]) {
      const Node& n = nodes[joined.node_at.at({q.x(), q.y(), q.z()})];
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
          refine_on_planes(se, refine_z.index, a, b, p.tolerance, min_angle, floor_z, 0, full,
                           added[k]);
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
      const double shortest = std::max(p.min_length, tol::kPencilMinPiece);
      if (pieces[k].size() < 2 || polyline_length(pieces[k]) < shortest) continue;
      if (w != k) {
        pieces[w] = std::move(pieces[k]);
        normals[w] = std::move(normals[k]);
      }
      ++w;
    }
    pieces.resize(w);
    normals.resize(w);
  }

  return {std::move(pieces), std::move(normals)};
}

// A crease traced twice (by both drive-plane families past a turn of 45 degrees) kept once,
// and its pieces joined: pieces split where they turn back, points within twice the
// tolerance of a longer piece, along it, dropped (uncovered_runs), and pieces whose ends meet
// within the merge distance joined (a piece whose ends meet closed), each point keeping its
// contact vectors.
void drop_retraced(Pieces& pc, const PencilParams& p) {
  auto key = [](const Vec3& q) { return std::array<double, 3>{q.x(), q.y(), q.z()}; };
  std::map<std::array<double, 3>, std::array<Vec3, 2>> normal_at;
  for (std::size_t k = 0; k < pc.paths.size(); ++k)
    for (std::size_t i = 0; i < pc.paths[k].size(); ++i)
      normal_at.emplace(key(pc.paths[k][i]), pc.normals[k][i]);
  std::vector<std::vector<Vec3>> split, runs;
  for (const PathRun& r : cusp_runs(pc.paths))
    split.emplace_back(pc.paths[r.path].begin() + r.from, pc.paths[r.path].begin() + r.to + 1);
  for (const PathRun& r : uncovered_runs(split, 2 * p.tolerance, kCreaseMinCos))
    runs.emplace_back(split[r.path].begin() + r.from, split[r.path].begin() + r.to + 1);
  const double merge = p.merge_distance > 0 ? p.merge_distance : 2 * p.interval;
  pc.paths = merge_paths(std::move(runs), merge, 0.5, 0);
  close_loops(pc.paths, merge, 0.5);
  pc.normals.assign(pc.paths.size(), {});
  for (std::size_t k = 0; k < pc.paths.size(); ++k)
    for (const Vec3& q : pc.paths[k]) pc.normals[k].push_back(normal_at.at(key(q)));
}

// Never below the CL surface: the ball swept along every chord (exact), a chord that touches
// lifted away from both contacts (a chord of a crease curving around a vertical edge at a
// floor cuts into the edge sideways, which no vertical lift clears). A chord that would need
// more than `leave` has left the crease (a link between two creases the refinement could not
// bridge), and one with an end the ball cannot reach from above: the piece is split there
// instead, so that pencil paths stay on creases and every point is a CL point.
void check_pieces(Pieces& pc, const PartProbe& part, const PencilParams& p, PencilStats& st) {
  const double R = part.radius, floor_z = part.floor_z;
  std::vector<std::vector<Vec3>>& pieces = pc.paths;
  std::vector<std::vector<std::array<Vec3, 2>>>& normals = pc.normals;
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
    const std::vector<Vec3> away = away_from_contacts(cur_b);
    lifted[k] += lift_swept(part.distance, part.index, floor_z, R, leave, spacing, cur, 24,
                            &touching, &away);
    // Every point a ball can reach from above (its shank free): the chord guard's vertical
    // moves and the verifier assume it of every CL point.
    std::vector<bool> reached(cur.size());
    for (std::size_t i = 0; i < cur.size(); ++i) reached[i] = reachable(part, cur[i]);
    for (std::size_t i = 0; i < touching.size(); ++i)
      if (!reached[i] || !reached[i + 1]) touching[i] = true;
    std::size_t from = 0;
    for (std::size_t i = 0; i <= touching.size(); ++i) {
      if (i < touching.size() && !touching[i]) continue;
      // Piece [from, i]; a chord still touching is never cut.
      if (i > from) {
        std::vector<Vec3> part(cur.begin() + from, cur.begin() + i + 1);
        if (polyline_length(part) >= std::max(p.min_length, tol::kPencilMinPiece)) {
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

}

// Order and orient. With a cut direction, pieces with a material side are turned to cut that
// way first and keep it; the ordering orients the others.
void order_pieces(Pieces& pc, const PencilParams& p, PencilResult& res) {
  PencilStats& st = res.stats;
  std::vector<std::vector<Vec3>>& pieces = pc.paths;
  std::vector<std::vector<std::array<Vec3, 2>>>& normals = pc.normals;
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
  // The concave zone: where the part can hold a pencil bi-contact. When it is narrow, the
  // z-levels and the drive planes slice only its kept facets.
  const ConcaveZone zone =
      concave_zone(mesh, cutter.radius, min_angle, p.tolerance, p.zone_max_share);
  st.zone_s = zone.build_s;
  const bool sliced = !zone.wide;
  st.sliced_facets = zone.keep_facets;
  // Candidates from z-levels first (appended after the drive planes' below): their elements
  // are freed before the drive planes' are built, so the two never take memory at once.
  const Candidates z = zlevel_candidates(mesh, cutter, p, box.hi.z(), sliced ? &zone : nullptr,
                                         control, st);
  std::array<double, 4> rect{};  // the scanned rectangle
  Candidates cand;
  if (sliced) {
    const double m = pencil_reach(p, cutter.radius);
    rect = {box.lo.x() - m, box.lo.y() - m, box.hi.x() + m, box.hi.y() + m};
    if (!zone.kept.facet.empty()) {  // an empty zone (a convex part) holds no bi-contact
      const ScanElements part = build_scan_elements(zone.kept.mesh, cutter.radius);
      st.elements_s += part.build_s;
      const ZoneSlice slice{zone, rect};
      cand = drive_plane_candidates(part, cutter, p, floor_z, &slice, control, st, rect);
    }
  }
  // The whole part's elements: the tracing and the refinement follow creases to their ends.
  const ScanElements se = build_scan_elements(mesh, cutter.radius);
  st.elements_s += se.build_s;
  if (!sliced) cand = drive_plane_candidates(se, cutter, p, floor_z, nullptr, control, st, rect);
  cand.cand.insert(cand.cand.end(), z.cand.begin(), z.cand.end());
  cand.refs.insert(cand.refs.end(), z.refs.begin(), z.refs.end());
  st.candidates = cand.cand.size();

  Stopwatch index_clock0;
  const MeshDistance distance(mesh);
  st.index_s = index_clock0.seconds();
  Stopwatch link_clock;
  const HangingTest hang(mesh, distance, min_angle, cand.refs);
  const Kept kept = pencil_points(cand, distance, cutter, p, min_angle, hang, res);
  const std::vector<Chain> chains = trace_chains(kept, se, p, rect, hang, min_angle, floor_z, st);
  st.link_s = link_clock.seconds();
  if (control.cancel.load()) throw Cancelled{};

  // The point drop-cutter (Embree, exact in double): checks refined points and chords.
  Stopwatch index_clock;
  const DropIndex index(mesh, cutter);
  st.index_s += index_clock.seconds();
  const PartProbe part{index, distance, cutter.radius, floor_z, box.hi.z()};
  const ZLevelCreaseRefine refine_z{mesh, index, part, p.tolerance, cutter.radius, floor_z};
  Pieces pieces = refine_joined(join_chains(chains, p), se, refine_z, p, min_angle, st);
  drop_retraced(pieces, p);
  check_pieces(pieces, part, p, st);
  order_pieces(pieces, p, res);
  return res;
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
