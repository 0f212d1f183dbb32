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
  PrecheckedMoves checked;  // of the path's moves out, when asked for
};

void put(PathOut& o, const Vec3& p, std::uint8_t contact) {
  o.xyz.insert(o.xyz.end(), {p.x(), p.y(), p.z()});
  o.contact.push_back(contact);
}

// The checks of a path's moves out: a move kept is the move checked (the verifier's check
// of it: known), each move a lift-over makes is unknown.
void note_moves(PrecheckedMoves& out, const MeshVerifier::MoveCheck* kept, const Vec3& a,
                const Vec3& b, std::size_t made) {
  if (kept) {
    out.checks.push_back(*kept);
    out.known.push_back(1);
    out.from.push_back(a);
    out.to.push_back(b);
  }
  out.checks.resize(out.checks.size() + made);
  out.known.resize(out.known.size() + made, 0);
  out.from.resize(out.from.size() + made, Vec3::Zero());
  out.to.resize(out.to.size() + made, Vec3::Zero());
}

// The moves of a path that touch a raised point (`up` > 0 at either end), checked again.
void recheck_raised(const MeshVerifier& mesh, const SweptTool& tool, const std::vector<Vec3>& tips,
                    const std::vector<double>& up, std::vector<MeshVerifier::MoveCheck>& checks) {
  std::vector<std::size_t> moves;
  std::vector<Vec3> from, to;
  for (std::size_t i = 1; i < tips.size(); ++i)
    if (up[i - 1] > 0 || up[i] > 0) {
      moves.push_back(i - 1);
      from.push_back(tips[i - 1]);
      to.push_back(tips[i]);
    }
  std::vector<MeshVerifier::MoveCheck> again(moves.size());
  mesh.check_moves(tool, from.data(), to.data(), moves.size(), tol::kVerifyGouge, 0, again.data());
  for (std::size_t k = 0; k < moves.size(); ++k) checks[moves[k]] = again[k];
}

// A move that cuts in by at most `raise` has both its ends raised by its gouge (the lift that
// clears it), but for the path's first and last points, where paths meet; the moves next to
// raised points are checked again.
void raise_shallow(const MeshVerifier& mesh, const SweptTool& tool, double raise,
                   std::vector<Vec3>& tips, std::vector<MeshVerifier::MoveCheck>& checks,
                   ChordGuardStats& st) {
  const std::size_t n = tips.size();
  std::vector<double> up(n, 0);
  for (std::size_t i = 1; i < n; ++i) {
    const double g = checks[i - 1].gouge;
    if (!(g > 0 && g <= raise) || !std::isfinite(tips[i - 1].z()) || !std::isfinite(tips[i].z()))
      continue;
    if (i - 1 > 0) up[i - 1] = std::max(up[i - 1], g);
    if (i + 1 < n) up[i] = std::max(up[i], g);
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!(up[i] > 0)) continue;
    tips[i].z() += up[i];
    ++st.raised;
    st.max_raise = std::max(st.max_raise, up[i]);
  }
  recheck_raised(mesh, tool, tips, up, checks);  // nothing when no point moved
}

// One path: points [first, first + n) of `in`. Its moves are measured as one run; shallow
// cuts are cleared by raising points (raise_shallow), the moves still cutting in get
// lift-overs, checked as another run (moves with a non-finite end are not checked).
// `checked`: receives the checks of the moves out (not for a rapid's: the verifier needs its
// clearance; the lift-overs' moves unknown).
PathOut guard_path(const MeshVerifier& mesh, const SweptTool& tool, double raise,
                   const ClChunk& in, std::size_t first, std::size_t n, bool emit_checks) {
  std::vector<Vec3> tips(n);
  for (std::size_t i = 0; i < n; ++i) tips[i] = in.point(first + i);
  std::vector<MeshVerifier::MoveCheck> checks(n > 0 ? n - 1 : 0);
  mesh.check_path(tool, tips.data(), n, tol::kVerifyGouge, 0, checks.data());
  PathOut o;
  raise_shallow(mesh, tool, raise, tips, checks, o.stats);
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
      const std::size_t added = (top > a.z()) + (top > b.z());
      o.stats.points_added += added;
      o.stats.max_lift = std::max(o.stats.max_lift, top - zmax);
      if (emit_checks) note_moves(o.checked, nullptr, a, b, added + 1);
      ++next;
    } else if (emit_checks && i > 0) {
      note_moves(o.checked, &checks[i - 1], tips[i - 1], b, 0);
    }
    put(o, b, in.contact[first + i]);
  }
  return o;
}

}  // namespace

ChordGuard::ChordGuard(std::shared_ptr<const MeshVerifier> index, const Cutter& cutter,
                       double stock, double raise)
    : mesh_(std::move(index)), raise_(raise) {
  tool_.cutter = cutter;
  tool_.stock = stock;
}

ClChunk ChordGuard::apply(const ClChunk& in, PrecheckedMoves* checked) {
  Stopwatch clock;
  ClChunk out = guard_chords(*mesh_, tool_, in, stats_, checked, raise_);
  seconds_ += clock.seconds();
  return out;
}

void ChordGuardStats::add(const ChordGuardStats& o) {
  moves += o.moves;
  raised += o.raised;
  max_raise = std::max(max_raise, o.max_raise);
  lifted += o.lifted;
  points_added += o.points_added;
  max_lift = std::max(max_lift, o.max_lift);
}

ClChunk guard_chords(const MeshVerifier& mesh, const SweptTool& tool, const ClChunk& in,
                     ChordGuardStats& stats, PrecheckedMoves* checked, double raise) {
  std::vector<std::size_t> start(in.path_sizes.size() + 1, 0);
  for (std::size_t k = 0; k < in.path_sizes.size(); ++k) start[k + 1] = start[k] + in.path_sizes[k];
  std::vector<PathOut> paths(in.path_sizes.size());
  par::for_each(paths.size(), 1, [&](std::size_t k) {
    paths[k] = guard_path(mesh, tool, raise, in, start[k], in.path_sizes[k], checked != nullptr);
  });
  ClChunk out;
  out.path_kinds = in.path_kinds;
  if (checked) *checked = {};
  for (std::size_t k = 0; k < paths.size(); ++k) {
    PathOut& p = paths[k];
    out.xyz.insert(out.xyz.end(), p.xyz.begin(), p.xyz.end());
    out.contact.insert(out.contact.end(), p.contact.begin(), p.contact.end());
    out.path_sizes.push_back(static_cast<std::uint32_t>(p.contact.size()));
    stats.add(p.stats);
    if (!checked) continue;
    // A rapid's moves are the verifier's to check (it measures their clearance).
    if (in.path_kinds[k] == static_cast<std::uint8_t>(PathKind::kRapid))
      std::fill(p.checked.known.begin(), p.checked.known.end(), 0);
    checked->checks.insert(checked->checks.end(), p.checked.checks.begin(), p.checked.checks.end());
    checked->known.insert(checked->known.end(), p.checked.known.begin(), p.checked.known.end());
    checked->from.insert(checked->from.end(), p.checked.from.begin(), p.checked.from.end());
    checked->to.insert(checked->to.end(), p.checked.to.begin(), p.checked.to.end());
  }
  return out;
}

}  // namespace ncpath
