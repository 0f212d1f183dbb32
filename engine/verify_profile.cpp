#include "engine/verify_profile.hpp"

#include <algorithm>
#include <cmath>

#include "engine/parallel.hpp"

namespace ncpath {

namespace {

// What one move gives: its clearance to the walls (inf when above the top or out of reach)
// and its worst violation (amount 0: none).
struct MoveResult {
  double clearance = std::numeric_limits<double>::infinity();
  double rapid_clearance = std::numeric_limits<double>::infinity();
  double amount = 0;
  ViolationKind kind = ViolationKind::kWall;
};

// The tool's widest radius at or below the top when its tip is `depth` mm below it.
double radius_below_top(const Cutter& c, double depth) {
  const double r = c.corner_radius, a = c.radius - r;
  if (depth >= r) return c.radius;
  return a + std::sqrt(std::max(0.0, r * r - (r - depth) * (r - depth)));
}

MoveResult check_move(const WallSet& walls, const Vec3& p, const Vec3& q, PathKind kind,
                      const ProfileVerifyParams& prm) {
  MoveResult m;
  const double zmin = std::min(p.z(), q.z());
  const auto violate = [&](double amount, ViolationKind k) {
    if (amount > prm.gouge_tolerance && amount > m.amount) {
      m.amount = amount;
      m.kind = k;
    }
  };
  // Rapids travel above the limit; a vertical one (a retract or the approach to the feed
  // height) may start or end lower, inside the pocket, and is checked like a feed move.
  if (kind == PathKind::kRapid && p.head<2>() != q.head<2>()) {
    m.rapid_clearance = zmin - prm.rapid_limit;
    violate(prm.rapid_limit - zmin, ViolationKind::kRapid);
  }
  violate(prm.floor - zmin, ViolationKind::kFloor);
  if (zmin >= prm.top) return m;
  const double reach = radius_below_top(prm.cutter, prm.top - zmin) + prm.stock;
  const double d = walls.distance(p.head<2>(), q.head<2>(), prm.resolution);
  if (d < walls.cap()) m.clearance = d - reach;
  violate(reach - d, ViolationKind::kWall);
  return m;
}

}  // namespace

WallSet profile_walls(const std::vector<Region>& regions, const ProfileVerifyParams& params) {
  return WallSet(regions, params.cutter.radius + params.stock + tol::kVerifyReach);
}

VerifyReport verify_profile_moves(const WallSet& walls, const ClChunk& cl,
                                  const ProfileVerifyParams& prm, std::uint64_t first_move,
                                  std::uint32_t first_path) {
  // Results in the moves' own slots.
  const ChunkMoves mv = chunk_moves(cl);
  std::vector<MoveResult> res(mv.size());
  par::for_each(res.size(), 256, [&](std::size_t m) {
    const std::size_t i = mv.first[m];
    res[m] = check_move(walls, cl.point(i), cl.point(i + 1),
                        static_cast<PathKind>(cl.path_kinds[mv.path[m]]), prm);
  });
  VerifyReport out;
  out.keep = prm.worst;
  out.moves = res.size();
  for (std::size_t m = 0; m < res.size(); ++m) {
    out.min_clearance = std::min(out.min_clearance, res[m].clearance);
    out.min_rapid_clearance = std::min(out.min_rapid_clearance, res[m].rapid_clearance);
    if (res[m].amount > 0)
      out.add({first_move + m, first_path + mv.path[m], cl.point(mv.first[m]),
               cl.point(mv.first[m] + 1), res[m].amount, res[m].kind});
  }
  return out;
}

}  // namespace ncpath
