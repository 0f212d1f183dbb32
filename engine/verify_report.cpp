#include "engine/verify_report.hpp"

#include <algorithm>
#include <sstream>

namespace ncpath {

const char* violation_name(ViolationKind kind) {
  switch (kind) {
    case ViolationKind::kWall:
      return "wall";
    case ViolationKind::kFloor:
      return "floor";
    case ViolationKind::kMesh:
      return "mesh";
    case ViolationKind::kRapid:
      return "rapid";
    case ViolationKind::kBottom:
      return "bottom";
  }
  return "?";
}

namespace {

bool worse(const VerifyViolation& a, const VerifyViolation& b) {
  if (a.amount != b.amount) return a.amount > b.amount;
  return a.move < b.move;
}

}  // namespace

void VerifyReport::add(const VerifyViolation& v) {
  max_gouge = std::max(max_gouge, v.amount);
  worst.insert(std::upper_bound(worst.begin(), worst.end(), v, worse), v);
  if (worst.size() > keep) worst.resize(keep);
}

void VerifyReport::merge(const VerifyReport& later) {
  moves += later.moves;
  max_gouge = std::max(max_gouge, later.max_gouge);
  min_clearance = std::min(min_clearance, later.min_clearance);
  min_rapid_clearance = std::min(min_rapid_clearance, later.min_rapid_clearance);
  for (const VerifyViolation& v : later.worst) add(v);
}

std::string VerifyReport::message() const {
  if (worst.empty()) return "";
  const VerifyViolation& v = worst.front();
  std::ostringstream os;
  os.precision(6);
  os << "move " << v.move << " (path " << v.path << ", (" << v.from.x() << ", " << v.from.y()
     << ", " << v.from.z() << ") -> (" << v.to.x() << ", " << v.to.y() << ", " << v.to.z() << ")) ";
  if (v.kind == ViolationKind::kRapid)
    os << "is a rapid " << v.amount << " mm below the part's top plus clearance";
  else
    os << "cuts " << v.amount << " mm into the " << violation_name(v.kind);
  return os.str();
}

}  // namespace ncpath
