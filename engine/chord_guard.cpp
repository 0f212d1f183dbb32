#include "engine/chord_guard.hpp"

#include <algorithm>
#include <cmath>

#include "engine/parallel.hpp"
#include "engine/run_control.hpp"

namespace ncpath {

namespace {

struct PathOut {
  std::vector<double> xyz;
  std::vector<std::uint8_t> contact;
  ChordGuardStats stats;
};

void put(PathOut& o, const Vec3& p, std::uint8_t contact) {
  o.xyz.insert(o.xyz.end(), {p.x(), p.y(), p.z()});
  o.contact.push_back(contact);
}

// One path: points [first, first + n) of `in`. Its moves are checked as one run, then the
// lift-overs of those that gouge as another (moves with a non-finite end are not checked).
PathOut guard_path(const MeshVerifier& mesh, const SweptTool& tool, const ClChunk& in,
                   std::size_t first, std::size_t n) {
  std::vector<Vec3> tips(n);
  for (std::size_t i = 0; i < n; ++i) tips[i] = in.point(first + i);
  std::vector<MeshVerifier::MoveCheck> checks(n > 0 ? n - 1 : 0);
  mesh.check_path(tool, tips.data(), n, tol::kVerifyGouge, 0, checks.data(),
                  MoveCheckMode::kDecide);
  // Move i - 1 (tips i - 1 -> i) is lifted across at its higher end's height, raised by
  // the lift that clears that move.
  std::vector<std::size_t> lifted;
  std::vector<Vec3> up0, up1;
  for (std::size_t i = 1; i < n; ++i) {
    if (checks[i - 1].gouge <= 0 || !std::isfinite(tips[i - 1].z()) || !std::isfinite(tips[i].z()))
      continue;
    const double zmax = std::max(tips[i - 1].z(), tips[i].z());
    lifted.push_back(i);
    up0.emplace_back(tips[i - 1].x(), tips[i - 1].y(), zmax);
    up1.emplace_back(tips[i].x(), tips[i].y(), zmax);
  }
  std::vector<MeshVerifier::MoveCheck> lifts(lifted.size());
  mesh.check_moves(tool, up0.data(), up1.data(), lifted.size(), 0, 0, lifts.data());
  PathOut o;
  std::size_t next = 0;  // into lifted
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3& b = tips[i];
    if (i > 0 && std::isfinite(b.z()) && std::isfinite(tips[i - 1].z())) ++o.stats.moves;
    if (next < lifted.size() && lifted[next] == i) {
      const Vec3& a = tips[i - 1];
      const double zmax = up0[next].z(), top = zmax + lifts[next].gouge;
      if (top > a.z()) put(o, Vec3(a.x(), a.y(), top), 0);
      if (top > b.z()) put(o, Vec3(b.x(), b.y(), top), 0);
      ++o.stats.lifted;
      o.stats.points_added += (top > a.z()) + (top > b.z());
      o.stats.max_lift = std::max(o.stats.max_lift, top - zmax);
      ++next;
    }
    put(o, b, in.contact[first + i]);
  }
  return o;
}

}  // namespace

ChordGuard::ChordGuard(std::shared_ptr<const MeshVerifier> index, const Cutter& cutter,
                       double stock)
    : mesh_(std::move(index)) {
  tool_.cutter = cutter;
  tool_.stock = stock;
}

ClChunk ChordGuard::apply(const ClChunk& in) {
  Stopwatch clock;
  ClChunk out = guard_chords(*mesh_, tool_, in, stats_);
  seconds_ += clock.seconds();
  return out;
}

void ChordGuardStats::add(const ChordGuardStats& o) {
  moves += o.moves;
  lifted += o.lifted;
  points_added += o.points_added;
  max_lift = std::max(max_lift, o.max_lift);
}

ClChunk guard_chords(const MeshVerifier& mesh, const SweptTool& tool, const ClChunk& in,
                     ChordGuardStats& stats) {
  std::vector<std::size_t> start(in.path_sizes.size() + 1, 0);
  for (std::size_t k = 0; k < in.path_sizes.size(); ++k) start[k + 1] = start[k] + in.path_sizes[k];
  std::vector<PathOut> paths(in.path_sizes.size());
  par::for_each(paths.size(), 1, [&](std::size_t k) {
    paths[k] = guard_path(mesh, tool, in, start[k], in.path_sizes[k]);
  });
  ClChunk out;
  out.path_kinds = in.path_kinds;
  for (PathOut& p : paths) {
    out.xyz.insert(out.xyz.end(), p.xyz.begin(), p.xyz.end());
    out.contact.insert(out.contact.end(), p.contact.begin(), p.contact.end());
    out.path_sizes.push_back(static_cast<std::uint32_t>(p.contact.size()));
    stats.add(p.stats);
  }
  return out;
}

}  // namespace ncpath
