#include "engine/fillet.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "engine/drop_index.hpp"
#include "engine/mesh_distance.hpp"
#include "engine/parallel.hpp"
#include "engine/surface_check.hpp"
#include "kernels/cleanup/pencil.hpp"

namespace ncpath {

namespace {
constexpr double kNoLiftLimit = std::numeric_limits<double>::infinity();
}  // namespace

std::string validate(const FilletParams& p) {
  std::ostringstream os;
  if (!(std::isfinite(p.reference_diameter) && p.reference_diameter > 0))
    os << "reference_diameter must be a positive number of mm, got " << p.reference_diameter;
  else if (!(std::isfinite(p.stepover) && p.stepover >= 0))
    os << "stepover must be >= 0 mm (0 = from the scallop height), got " << p.stepover;
  else if (p.stepover == 0 && !(std::isfinite(p.scallop) && p.scallop > 0))
    os << "scallop must be a positive number of mm when stepover is 0, got " << p.scallop;
  else if (p.max_passes < 1)
    os << "max_passes must be >= 1";
  else if (!std::isfinite(p.stock))
    os << "stock must be a finite number of mm, got " << p.stock;
  else if (p.pencil.stock != 0)
    os << "pencil.stock must be 0: the fillet's own stock applies to both balls, got "
       << p.pencil.stock;
  else if (p.pencil.direction != CutDirection::kAny)
    os << "pencil.direction must be any: the fillet's own direction orients the passes";
  else if (std::string e = validate(p.pencil); !e.empty())
    os << "pencil: " << e;
  return os.str();
}

namespace {

// b1 turned toward b2 by angle th about t = b1 x b2 / |b1 x b2| (t is perpendicular to b1).
Vec3 turn(const Vec3& b1, const Vec3& t, double th) {
  return b1 * std::cos(th) + t.cross(b1) * std::sin(th);
}

struct PathOut {
  std::vector<std::vector<Vec3>> polys;
  std::vector<PathKind> kinds;
  std::uint64_t passes = 0, points = 0, rays = 0, misses = 0, unreachable = 0, lifted = 0;
  std::uint64_t neutral = 0;
  double length = 0;
};

}  // namespace

FilletResult run_fillet(const TriangleMesh& mesh, const Cutter& cutter, const FilletParams& p,
                        RunControl& control, const ConditionedMesh* conditioned) {
  if (std::string e = validate(cutter); !e.empty()) throw std::invalid_argument("tool: " + e);
  if (cutter.type != CutterType::kBall)
    throw std::invalid_argument("tool: fillet-cut needs a ball-end mill");
  if (std::string e = validate(p); !e.empty()) throw std::invalid_argument(e);
  const double r = cutter.radius, R_ref = 0.5 * p.reference_diameter;
  if (!(r < R_ref))
    throw std::invalid_argument("reference_diameter (" + std::to_string(p.reference_diameter) +
                                " mm) must be larger than the clean-up tool's diameter (" +
                                std::to_string(2 * r) + " mm)");
  if (std::string e = validate_stock(p.stock, r); !e.empty()) throw std::invalid_argument(e);
  // Stock s: the tips of the grown clean-up ball (radius rc) are computed and checked, then
  // raised by s; the reference run grows its ball itself (its tips are centre - R_ref z).
  const double s = p.stock, rc = r + s;
  Cutter grown = cutter;
  grown.radius = grown.corner_radius = rc;
  FilletResult res;
  FilletStats& st = res.stats;

  Stopwatch pencil_clock;
  PencilParams pencil = p.pencil;
  pencil.stock = s;
  const PencilResult ref =
      run_pencil(mesh, ball_cutter(p.reference_diameter), pencil, control, conditioned);
  st.pencil = ref.stats;
  st.pencil_s = pencil_clock.seconds();
  if (control.cancel.load()) throw Cancelled{};

  Stopwatch rays_clock;
  const MeshDistance distance(mesh);
  const DropIndex index(mesh, grown);
  const double floor_z = p.pencil.floor_z.value_or(bounding_box(mesh).lo.z());
  const PartProbe part{index, distance, rc, floor_z, bounding_box(mesh).hi.z()};
  const double step =
      p.stepover > 0 ? p.stepover : 2 * std::sqrt(std::max(0.0, 2 * r * p.scallop - p.scallop * p.scallop));
  const double spacing = std::max(0.02, 0.1 * p.pencil.interval);

  std::vector<PathOut> outs(ref.paths.size());
  par::for_each(ref.paths.size(), 1, [&](std::size_t k) {
    PathOut& out = outs[k];
    const auto& pts = ref.paths[k];
    // b1, b2 ordered so that b1 x b2 points along the path: pass j then stays on one side.
    std::vector<std::array<Vec3, 2>> nrm = ref.path_normals[k];
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const Vec3 along = pts[std::min(i + 1, pts.size() - 1)] - pts[i > 0 ? i - 1 : 0];
      if (nrm[i][0].cross(nrm[i][1]).dot(along) < 0) std::swap(nrm[i][0], nrm[i][1]);
    }
    // Ball centre of the small ball on the ray from the reference centre along -v.
    auto hit = [&](const Vec3& P, const Vec3& v, Vec3& tip) {
      ++out.rays;
      const std::optional<double> d = distance.march(P, -v, rc, 2 * (R_ref + s));
      if (!d) {
        ++out.misses;
        return false;
      }
      tip = P - *d * v - Vec3(0, 0, rc);
      if (!reachable(part, tip)) {
        ++out.unreachable;
        return false;
      }
      return true;
    };
    // Passes: from the step-over (arc length of the centres at the widest point); with a
    // scallop height, doubled until the cusp between neighbouring passes is within it at
    // every 8th point of the path: the cusp tip is where the two balls' spheres meet on the
    // part's side, and the material left there is its exact distance to the mesh (less the
    // stock: the height above the stock surface).
    double widest = 0;
    std::size_t widest_i = 0;
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const Vec3 P = pts[i] + Vec3(0, 0, R_ref);
      const Vec3 &b1 = nrm[i][0], &b2 = nrm[i][1];
      const double beta = bicontact_angle(b1, b2);
      const Vec3 t = crease_tangent(b1, b2);
      if (t.isZero()) continue;
      Vec3 prev = Vec3::Zero();
      double len = 0;
      bool have = false;
      for (int j = 0; j <= 16; ++j) {
        Vec3 tip;
        if (!hit(P, turn(b1, t, beta * j / 16), tip)) continue;
        if (have) len += (tip - prev).norm();
        prev = tip;
        have = true;
      }
      if (len > widest) {
        widest = len;
        widest_i = i;
      }
    }
    auto n = std::uint32_t(std::clamp(std::ceil(widest / step), 1.0, double(p.max_passes)));
    auto worst_cusp = [&](std::uint32_t m) -> double {
      double worst = 0;
      for (std::size_t i = widest_i % 8; i < pts.size(); i += 8) {
        const Vec3 P = pts[i] + Vec3(0, 0, R_ref);
        const Vec3 &b1 = nrm[i][0], &b2 = nrm[i][1];
        const double beta = bicontact_angle(b1, b2);
        const Vec3 t = crease_tangent(b1, b2);
        if (t.isZero()) continue;
        Vec3 a, b;
        for (std::uint32_t j = 0; j < m; ++j) {
          const Vec3 vm = turn(b1, t, beta * (j + 0.5) / m);
          if (!hit(P, turn(b1, t, beta * j / m), a) || !hit(P, turn(b1, t, beta * (j + 1) / m), b))
            continue;
          const Vec3 ca = a + Vec3(0, 0, rc), cb = b + Vec3(0, 0, rc), mid = 0.5 * (ca + cb);
          const Vec3 ab = cb - ca;
          const double half = 0.5 * ab.norm();
          if (!(half < r)) return double(INFINITY);  // the balls do not even overlap
          Vec3 d = -vm - ab * (-vm).dot(ab) / ab.squaredNorm();
          if (!(d.norm() > 0)) continue;
          const Vec3 x = mid + d.normalized() * std::sqrt(r * r - half * half);
          worst = std::max(worst, distance.closest(x, 2 * (R_ref + s)).distance - s);
        }
      }
      return worst;
    };
    if (p.stepover == 0)
      while (n < p.max_passes && worst_cusp(n) > p.scallop) n = std::min(p.max_passes, 2 * n);
    std::vector<std::vector<Vec3>> passes(n + 1);
    std::vector<std::vector<std::size_t>> from(n + 1);  // the pencil path point of each
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const Vec3 P = pts[i] + Vec3(0, 0, R_ref);
      const Vec3 &b1 = nrm[i][0], &b2 = nrm[i][1];
      const double beta = bicontact_angle(b1, b2);
      const Vec3 t = crease_tangent(b1, b2);
      if (t.isZero()) continue;
      for (std::uint32_t j = 0; j <= n; ++j) {
        Vec3 tip;
        if (hit(P, turn(b1, t, beta * j / n), tip)) {
          passes[j].push_back(tip);
          from[j].push_back(i);
        }
      }
    }
    // Zig-zag, linked at depth; or one-way, each pass turned to cut in the direction by the
    // material side of the reference crease, joined by rapids.
    const bool one_way = p.direction != CutDirection::kAny;
    std::vector<std::array<Vec3, 2>> side_nrm;
    for (std::uint32_t j = 0; j <= n; ++j) {
      auto& pass = passes[j];
      if (pass.size() < 2) continue;
      bool reverse = j % 2 == 1;
      if (one_way) {
        side_nrm.clear();
        for (std::size_t i : from[j]) side_nrm.push_back(ref.path_normals[k][i]);
        const int side = cut_side(cut_side_score(pass, side_nrm));
        if (side == 0) ++out.neutral;
        reverse = reverse_for(p.direction, side);
      }
      if (reverse) std::reverse(pass.begin(), pass.end());
      // The ball swept along every chord (exact; a touching chord is lifted by its sampled
      // deficits, then doubling until clear: never cut).
      out.lifted += lift_swept(distance, index, floor_z, rc, kNoLiftLimit, spacing, pass, 48);
      if (!out.polys.empty() && one_way) {
        out.polys.push_back({pass.front()});
        out.kinds.push_back(PathKind::kRapid);
      } else if (!out.polys.empty()) {
        std::vector<Vec3> link = {out.polys.back().back(), pass.front()};
        out.lifted += lift_swept(distance, index, floor_z, rc, kNoLiftLimit, spacing, link, 48);
        out.polys.push_back(std::move(link));
        out.kinds.push_back(PathKind::kLinkAtDepth);
      }
      for (std::size_t i = 1; i < pass.size(); ++i) out.length += (pass[i] - pass[i - 1]).norm();
      out.points += pass.size();
      ++out.passes;
      out.polys.push_back(std::move(pass));
      out.kinds.push_back(PathKind::kCut);
    }
    // From the grown ball's tips to the tool's.
    if (s != 0)
      for (auto& poly : out.polys)
        for (Vec3& q : poly) q.z() += s;
  });
  st.rays_s = rays_clock.seconds();
  for (PathOut& o : outs) {
    st.passes += o.passes;
    st.points += o.points;
    st.rays += o.rays;
    st.misses += o.misses;
    st.unreachable += o.unreachable;
    st.lifted_points += o.lifted;
    st.neutral_passes += o.neutral;
    st.cut_length += o.length;
    if (o.polys.empty()) continue;
    if (!res.paths.empty()) {
      res.paths.push_back({o.polys.front().front()});
      res.kinds.push_back(PathKind::kRapid);
    }
    for (std::size_t i = 0; i < o.polys.size(); ++i) {
      res.paths.push_back(std::move(o.polys[i]));
      res.kinds.push_back(o.kinds[i]);
    }
  }
  return res;
}

ClChunk fillet_chunk(const FilletResult& r) {
  ClChunk ch;
  for (std::size_t i = 0; i < r.paths.size(); ++i) {
    for (const Vec3& q : r.paths[i]) ch.xyz.insert(ch.xyz.end(), {q.x(), q.y(), q.z()});
    ch.contact.insert(ch.contact.end(), r.paths[i].size(), std::uint8_t(ContactKind::kEdge));
    ch.path_sizes.push_back(std::uint32_t(r.paths[i].size()));
    ch.path_kinds.push_back(std::uint8_t(r.kinds[i]));
  }
  return ch;
}

}  // namespace ncpath
