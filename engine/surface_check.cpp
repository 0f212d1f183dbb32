#include "engine/surface_check.hpp"

#include <algorithm>
#include <cmath>

namespace ncpath {

double surface_deficit(const DropIndex& index, double floor_z, const Vec3& q) {
  // On or above at q itself: no gouge whatever the neighbours say (one query, the common case).
  double d = std::max(floor_z, index.query(q.x(), q.y()).tip_z) - q.z();
  if (d <= tol::kSurfaceSlack) return std::min(d, 0.0);
  for (int dx = -1; dx <= 1; ++dx)
    for (int dy = -1; dy <= 1; ++dy) {
      const double z = index.query(q.x() + 1e-6 * dx, q.y() + 1e-6 * dy).tip_z;
      d = std::min(d, std::max(floor_z, z) - q.z());
    }
  return d;
}

bool reachable(const PartProbe& part, const Vec3& q) {
  if (q.z() < part.floor_z - tol::kReachSlack) return false;
  if (part.index.query(q.x(), q.y()).tip_z - q.z() <= tol::kSurfaceSlack) return true;
  const Vec3 centre = q + Vec3(0, 0, part.radius);
  const double r = part.radius - tol::kReachSlack;
  if (part.distance.closest(centre, part.radius).distance <= r) return false;  // in the part
  const double rise = part.top_z - q.z() + tol::kReachSlack;
  return !part.distance.march(centre, Vec3::UnitZ(), r, rise);
}

std::size_t lift_swept(const MeshDistance& distance, const DropIndex& index, double floor_z,
                       double radius, double max_lift, double spacing, std::vector<Vec3>& pts,
                       int rounds, std::vector<bool>* touching,
                       const std::vector<Vec3>* directions) {
  const std::size_t n = pts.size();
  std::vector<bool> raised(n, false);
  for (std::size_t i = 0; i < n; ++i)
    if (pts[i].z() < floor_z) {
      pts[i].z() = floor_z;
      raised[i] = true;
    }
  const Vec3 up(0, 0, radius);
  const double r = radius - tol::kSweepSlack;
  // The lift chord i needs where its tip is at `tip`, plus the slack: along z, the
  // drop-cutter deficit and at least the ball's penetration; along the chord's own direction
  // u, the penetration over the cosine between u and the contact normal (moving by that along
  // u clears the contact).
  auto need = [&](std::size_t i, const Vec3& tip) {
    double d = 0;
    if (!directions) {
      d = std::max(surface_deficit(index, floor_z, tip),
                   radius - distance.closest(tip + up, radius).distance);
    } else {
      const MeshDistance::Closest c = distance.closest(tip + up, radius);
      if (c.distance < radius) {
        // The chord's direction: its ends' mean, the start's where they oppose (a zero mean
        // would give NaN, which reads as clear).
        const Vec3 sum = (*directions)[i] + (*directions)[i + 1];
        const Vec3 u = sum.norm() > tol::kLiftMinCosine ? Vec3(sum.normalized())
                                                        : (*directions)[i];
        const Vec3 normal = (tip + up - c.point) / std::max(c.distance, tol::kSweepSlack);
        d = (radius - c.distance) / std::max(normal.dot(u), tol::kLiftMinCosine);
      }
    }
    return std::max(d, tol::kSweepSlack) + tol::kSweepSlack;
  };
  // Point i lifted by `by` along its direction; straight up when that would leave it below
  // the drop-cutter surface (under an overhang's edge, where no 3-axis ball can go).
  auto moved = [&](std::size_t i, double by) {
    if (directions) {
      const Vec3 q = pts[i] + by * (*directions)[i];
      if (surface_deficit(index, floor_z, q) <= 0) return q;
    }
    return Vec3(pts[i] + Vec3(0, 0, by));
  };
  // Sweeps chord i; the lift it needs where the ball first touches (0 when clear).
  auto sweep = [&](std::size_t i) {
    const Vec3 a = pts[i] + up, b = pts[i + 1] + up;
    const double len = (b - a).norm();
    std::optional<double> s;
    if (distance.closest(a, radius).distance <= r)
      s = 0.0;  // the start touches already
    else if (len > 0)
      s = distance.march(a, (b - a) / len, r, len);
    if (!s) return 0.0;
    const Vec3 tip = pts[i] + (pts[i + 1] - pts[i]) * (len > 0 ? *s / len : 0.0);
    return need(i, tip);
  };
  // The first contact is where the dip starts, not where it is deepest: a chord touching
  // again is lifted by at least twice its previous lift (a dip of depth h is cleared within
  // log2(h / tol::kSweepSlack) rounds, over-lifting by less than h). A chord whose lifts would
  // add up to more than max_lift (a wall in the way, which lifting cannot clear) is left
  // alone and reported.
  std::vector<bool> check(n > 0 ? n - 1 : 0, true), stuck(check.size(), false);
  std::vector<double> last(check.size(), 0), total(check.size(), 0);
  std::vector<bool> sampled(check.size(), false);
  for (int round = 0; round < rounds; ++round) {
    std::vector<double> lift(n, 0);
    bool any = false;
    for (std::size_t i = 0; i + 1 < n; ++i) {
      if (!check[i] || stuck[i]) continue;
      double d = sweep(i);
      if (!(d > 0)) continue;
      const bool first = !sampled[i] && spacing > 0;
      if (first) {
        // First touch: the largest sampled deficit is a better first lift than the deficit
        // where the dip starts.
        const Vec3 a = pts[i], b = pts[i + 1];
        const int m = std::max(2, int(std::ceil((b - a).norm() / spacing)));
        for (int j = 1; j < m && d <= max_lift; ++j) {
          const Vec3 q = a + (b - a) * (double(j) / m);
          d = std::max(d, directions ? need(i, q)
                                     : surface_deficit(index, floor_z, q) + tol::kSweepSlack);
        }
        sampled[i] = true;
      } else {
        d = std::max(d, 2 * last[i]);  // what is left between the samples: doubling
      }
      if (total[i] + d > max_lift) {
        stuck[i] = true;
        continue;
      }
      last[i] = first ? 0 : d;  // the doubling starts after the sampled lift
      total[i] += d;
      any = true;
      lift[i] = std::max(lift[i], d);
      lift[i + 1] = std::max(lift[i + 1], d);
    }
    std::fill(check.begin(), check.end(), false);
    if (!any) break;
    for (std::size_t i = 0; i < n; ++i)
      if (lift[i] > 0) {
        pts[i] = moved(i, lift[i]);
        raised[i] = true;
        if (i > 0) check[i - 1] = true;
        if (i < check.size()) check[i] = true;
      }
  }
  if (touching) {
    // Stuck chords, and those the last round's lifts leave touching.
    touching->assign(check.size(), false);
    for (std::size_t i = 0; i + 1 < n; ++i)
      (*touching)[i] = stuck[i] || (check[i] && sweep(i) > 0);
  }
  return std::size_t(std::count(raised.begin(), raised.end(), true));
}

std::vector<Vec3> away_from_contacts(const std::vector<std::array<Vec3, 2>>& b) {
  std::vector<Vec3> out;
  out.reserve(b.size());
  for (const auto& n : b) {
    const Vec3 s = n[0] + n[1];
    const bool towards_both = 0.5 * s.norm() > tol::kLiftMinCosine;
    out.push_back(towards_both ? Vec3(s.normalized()) : Vec3(Vec3::UnitZ()));
  }
  return out;
}

}  // namespace ncpath
