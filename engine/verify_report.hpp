#pragma once
// What the verifier says about a job's CL data: the worst violations with where they are,
// and the figures every job records (stats/verify_*, docs/hdf5-schema.md). Shared by the
// mesh verifier (engine/verify_mesh.hpp) and the profile verifier (engine/verify_profile.hpp).
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "kernels/geom/vec.hpp"

namespace ncpath {

// What a move violates.
enum class ViolationKind : std::uint8_t {
  kWall = 0,    // the tool cuts into a wall or island of a pocket (beyond stock)
  kFloor = 1,   // below a pocket's floor
  kMesh = 2,    // into a mesh part (beyond stock)
  kRapid = 3,   // a rapid below the part's top plus clearance
  kBottom = 4,  // into a sculptured pocket bottom
};
const char* violation_name(ViolationKind kind);  // "wall", "floor", "mesh", "rapid", "bottom"

struct VerifyViolation {
  std::uint64_t move = 0;  // index among the job's moves (consecutive points of one path)
  std::uint32_t path = 0;  // index of the job's path
  Vec3 from = Vec3::Zero(), to = Vec3::Zero();  // the move's tool-tip points, mm
  double amount = 0;                            // mm cut in (rapids: mm below the limit)
  ViolationKind kind = ViolationKind::kWall;
};

struct VerifyReport {
  std::uint64_t moves = 0;
  double max_gouge = 0;  // mm, largest amount over every violation (0: none)
  // mm, smallest gap between the tool (grown by stock) and the part over the cutting and
  // linking moves that came near it; +inf when none did (within the verifier's reach).
  double min_clearance = std::numeric_limits<double>::infinity();
  // mm, lowest rapid above its limit (the part's top plus clearance); +inf without rapids.
  double min_rapid_clearance = std::numeric_limits<double>::infinity();
  std::vector<VerifyViolation> worst;  // largest first (ties: lower move), at most `keep`
  std::size_t keep = 8;

  // Adds a violation, keeping the `keep` worst.
  void add(const VerifyViolation& v);
  // Folds in the report of the moves that follow (chunk by chunk); deterministic.
  void merge(const VerifyReport& later);
  // "move 812 (path 3, (x, y, z) -> (x, y, z)) cuts 0.0123 mm into a wall"; "" when clean.
  std::string message() const;
};

}  // namespace ncpath
