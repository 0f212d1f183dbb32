// verify_moves and merge (engine/verify_mesh.hpp): a chunk's moves through
// MeshVerifier::check_path in parallel blocks, and the reports they make.
#include <algorithm>
#include <string>

#include "engine/parallel.hpp"
#include "engine/verify_mesh.hpp"

namespace ncpath {

namespace {

// Better of two (value, move) pairs for "smallest value, then lowest move".
bool closer(double a, std::uint64_t move_a, double b, std::uint64_t move_b) {
  return a < b || (a == b && move_a < move_b);
}

bool worse(const MoveViolation& a, const MoveViolation& b) {
  return a.amount > b.amount || (a.amount == b.amount && a.move < b.move);
}

void keep_worst(std::vector<MoveViolation>& v, std::size_t capacity) {
  std::sort(v.begin(), v.end(), worse);
  if (v.size() > capacity) v.resize(capacity);
}

}  // namespace

void merge(MeshVerifyReport& into, const MeshVerifyReport& from) {
  if (from.rapid_moves > 0 &&
      (into.rapid_moves == 0 || closer(from.min_rapid_clearance, from.closest_rapid.move,
                                       into.min_rapid_clearance, into.closest_rapid.move))) {
    into.min_rapid_clearance = from.min_rapid_clearance;
    into.closest_rapid = from.closest_rapid;
  }
  into.moves += from.moves;
  into.rapid_moves += from.rapid_moves;
  into.gouging_moves += from.gouging_moves;
  into.unsafe_rapids += from.unsafe_rapids;
  into.candidates += from.candidates;
  into.gjk_calls += from.gjk_calls;
  into.max_gouge = std::max(into.max_gouge, from.max_gouge);
  into.worst_capacity = std::max(into.worst_capacity, from.worst_capacity);
  into.worst.insert(into.worst.end(), from.worst.begin(), from.worst.end());
  keep_worst(into.worst, into.worst_capacity);
  if (into.error.empty()) into.error = from.error;
}

namespace {

// The chunk's paths as move ranges: path k holds moves [move_start[k], move_start[k + 1])
// starting at point point_start[k].
struct MoveIndex {
  std::vector<std::uint64_t> move_start, point_start;
  std::string error;
};

MoveIndex index_moves(const ClChunk& cl) {
  MoveIndex m;
  const std::size_t paths = cl.path_sizes.size();
  m.move_start.assign(paths + 1, 0);
  m.point_start.assign(paths + 1, 0);
  for (std::size_t k = 0; k < paths; ++k) {
    const std::uint64_t n = cl.path_sizes[k];
    m.point_start[k + 1] = m.point_start[k] + n;
    m.move_start[k + 1] = m.move_start[k] + (n > 0 ? n - 1 : 0);
  }
  if (cl.path_kinds.size() != paths || cl.xyz.size() != 3 * m.point_start[paths]) {
    m.error = "CL chunk sizes disagree: " + std::to_string(cl.xyz.size()) + " coordinates, " +
              std::to_string(paths) + " path sizes (" + std::to_string(m.point_start[paths]) +
              " points), " + std::to_string(cl.path_kinds.size()) + " path kinds";
    m.move_start.assign(1, 0);
  }
  return m;
}

Vec3 point_at(const ClChunk& cl, std::uint64_t i) {
  return {cl.xyz[3 * i], cl.xyz[3 * i + 1], cl.xyz[3 * i + 2]};
}

// Counts one checked move into a block's report.
void tally(MeshVerifyReport& out, MoveViolation v, const MeshVerifier::MoveCheck& c, bool rapid,
           double cap, double safe_clearance) {
  ++out.moves;
  out.candidates += c.candidates;
  out.gjk_calls += c.gjk_calls;
  if (c.gouge > 0) {
    ++out.gouging_moves;
    out.max_gouge = std::max(out.max_gouge, c.gouge);
    v.amount = c.gouge;
    v.facet = c.gouge_facet;
    out.worst.push_back(v);
  }
  if (!rapid) return;
  const double clearance = std::min(c.clearance, cap);
  if (++out.rapid_moves == 1 ||
      closer(clearance, v.move, out.min_rapid_clearance, out.closest_rapid.move)) {
    out.min_rapid_clearance = clearance;
    out.closest_rapid = v;
    out.closest_rapid.amount = clearance;
    out.closest_rapid.facet = c.clearance_facet;
  }
  if (clearance < safe_clearance) ++out.unsafe_rapids;
}

// The checks of one run of a path's moves (tips[r] -> tips[r + 1]): those `pre` knows (from
// move m0 on) are taken from it, the others checked, in groups of consecutive moves.
void check_run(const MeshVerifier& verifier, const SweptTool& tool, const std::vector<Vec3>& tips,
               double floor, double cap, const PrecheckedMoves* pre, std::uint64_t m0,
               std::vector<MeshVerifier::MoveCheck>& checks) {
  const std::size_t n = tips.size() - 1;
  checks.resize(n);
  if (!pre) return verifier.check_path(tool, tips.data(), tips.size(), floor, cap, checks.data());
  auto known = [&](std::size_t r) {
    return pre->known[m0 + r] && pre->from[m0 + r] == tips[r] && pre->to[m0 + r] == tips[r + 1];
  };
  for (std::size_t r = 0; r < n;) {
    if (known(r)) {
      checks[r] = pre->checks[m0 + r];
      ++r;
      continue;
    }
    std::size_t e = r + 1;
    while (e < n && !known(e)) ++e;
    verifier.check_path(tool, tips.data() + r, e - r + 1, floor, cap, checks.data() + r);
    r = e;
  }
}

}  // namespace

MeshVerifyReport verify_moves(const MeshVerifier& verifier, const Cutter& cutter, const ClChunk& cl,
                              const MeshVerifyParams& params, std::uint64_t first_move_index,
                              std::uint32_t first_path_index, const PrecheckedMoves* prechecked) {
  MeshVerifyReport report;
  report.worst_capacity = static_cast<std::size_t>(std::max(0, params.worst));
  const MoveIndex index = index_moves(cl);
  report.error = index.error;
  const SweptTool tool{cutter, params.shank, params.stock};
  const double cap = params.clearance_cap > 0 ? params.clearance_cap : 1.0;

  constexpr std::uint64_t kBlock = 256;  // moves per task and per partial report
  const std::uint64_t moves = index.move_start.back();
  const PrecheckedMoves* pre = prechecked && prechecked->checks.size() == moves &&
                                       prechecked->known.size() == moves &&
                                       prechecked->from.size() == moves &&
                                       prechecked->to.size() == moves
                                   ? prechecked
                                   : nullptr;
  const std::size_t blocks = static_cast<std::size_t>((moves + kBlock - 1) / kBlock);
  std::vector<MeshVerifyReport> part(blocks);
  par::for_each(blocks, 1, [&](std::size_t bi) {
    MeshVerifyReport& out = part[bi];
    out.worst_capacity = report.worst_capacity;
    const std::uint64_t m0 = bi * kBlock, m1 = std::min(moves, m0 + kBlock);
    std::size_t k = std::upper_bound(index.move_start.begin(), index.move_start.end(), m0) -
                    index.move_start.begin() - 1;
    std::vector<Vec3> tips;
    std::vector<MeshVerifier::MoveCheck> checks;
    for (std::uint64_t m = m0; m < m1; ++k) {
      // Moves [m, m_end) of path k, from point i on, checked as one run.
      const std::uint64_t m_end = std::min(m1, index.move_start[k + 1]);
      if (m_end <= m) continue;
      const std::uint64_t i = index.point_start[k] + (m - index.move_start[k]);
      tips.clear();
      for (std::uint64_t j = i; j <= i + (m_end - m); ++j) tips.push_back(point_at(cl, j));
      const bool rapid = cl.path_kinds[k] == static_cast<std::uint8_t>(PathKind::kRapid);
      check_run(verifier, tool, tips, std::max(0.0, params.gouge_tolerance), rapid ? cap : 0,
                rapid ? nullptr : pre, m, checks);
      for (std::size_t r = 0; r < checks.size(); ++r, ++m) {
        MoveViolation v;
        v.move = first_move_index + m;
        v.path = first_path_index + static_cast<std::uint32_t>(k);
        v.from = tips[r];
        v.to = tips[r + 1];
        if (!v.from.allFinite() || !v.to.allFinite()) {
          if (out.error.empty())
            out.error = "move " + std::to_string(v.move) + " has a non-finite point";
          continue;
        }
        tally(out, v, checks[r], rapid, cap, params.safe_clearance);
      }
    }
    keep_worst(out.worst, out.worst_capacity);
  });
  for (const MeshVerifyReport& p : part) merge(report, p);
  return report;
}

}  // namespace ncpath
