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

// One path: points [first, first + n) of `in`.
PathOut guard_path(const MeshVerifier& mesh, const SweptTool& tool, const ClChunk& in,
                   std::size_t first, std::size_t n) {
  PathOut o;
  for (std::size_t i = first; i < first + n; ++i) {
    const Vec3 b = in.point(i);
    if (i > first && std::isfinite(b.z()) && std::isfinite(in.point(i - 1).z())) {
      const Vec3 a = in.point(i - 1);
      ++o.stats.moves;
      if (mesh.check_move(tool, a, b, tol::kVerifyGouge).gouge > 0) {
        // Across at the higher end's height, raised by the lift that clears that move.
        const double zmax = std::max(a.z(), b.z());
        const Vec3 a_up(a.x(), a.y(), zmax), b_up(b.x(), b.y(), zmax);
        const double top = zmax + mesh.check_move(tool, a_up, b_up, 0).gouge;
        if (top > a.z()) put(o, Vec3(a.x(), a.y(), top), 0);
        if (top > b.z()) put(o, Vec3(b.x(), b.y(), top), 0);
        ++o.stats.lifted;
        o.stats.points_added += (top > a.z()) + (top > b.z());
        o.stats.max_lift = std::max(o.stats.max_lift, top - zmax);
      }
    }
    put(o, b, in.contact[i]);
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
