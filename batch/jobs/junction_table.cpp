#include "batch/jobs/junction_table.hpp"

namespace ncpath::jobs {

JunctionTable::JunctionTable(out::ClJob& cl, const std::string& g, const std::string& path_text,
                             const std::string& position_text)
    : cl_(cl),
      path_(cl, g, "junction_path", 0, "", path_text),
      kind_(cl, g, "junction_kind", 0, "", kJunctionKindEnum),
      position_(cl, g, "junction_position", 3, "mm", position_text),
      b1_(cl, g, "junction_b1", 3, "",
          "unit vector from the contact on the element before the junction (in cutting order) "
          "to the ball centre"),
      b2_(cl, g, "junction_b2", 3, "",
          "unit vector from the contact on the element after the junction (in cutting order) "
          "to the ball centre"),
      element1_(cl, g, "junction_element1", 3, "",
                std::string("element before the junction; ") + kElementText),
      element2_(cl, g, "junction_element2", 3, "",
                std::string("element after the junction; ") + kElementText),
      angle_(cl, g, "junction_angle", 0, "rad", "angle between junction_b1 and junction_b2") {}

void JunctionTable::append(std::span<const ScanJunctionRecord> records) {
  for (const ScanJunctionRecord& j : records) {
    path_.push(j.path);
    kind_.push(j.kind);
    position_.push(j.position);
    b1_.push(j.b1);
    b2_.push(j.b2);
    element1_.push(j.element1);
    element2_.push(j.element2);
    angle_.push(j.angle);
  }
  path_.flush(cl_);
  kind_.flush(cl_);
  position_.flush(cl_);
  b1_.flush(cl_);
  b2_.flush(cl_);
  element1_.flush(cl_);
  element2_.flush(cl_);
  angle_.flush(cl_);
}

}  // namespace ncpath::jobs
