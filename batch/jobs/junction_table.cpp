#include "batch/jobs/junction_table.hpp"

#include <span>

namespace ncpath::jobs {

void push_row(std::vector<double>& to, const std::array<double, 3>& v) {
  to.insert(to.end(), v.begin(), v.end());
}

void push_row(std::vector<std::int64_t>& to, const ElementRef& e) {
  to.insert(to.end(), {e.kind, e.a, e.b});
}

void JunctionTable::add(const ScanJunctionRecord& j) {
  path.push_back(j.path);
  kind.push_back(j.kind);
  push_row(position, j.position);
  push_row(b1, j.b1);
  push_row(b2, j.b2);
  push_row(element1, j.element1);
  push_row(element2, j.element2);
  angle.push_back(j.angle);
}

void JunctionTable::write(out::ClJob& cl, const std::string& g, const std::string& path_text,
                          const std::string& position_text) const {
  auto all = [](const auto& v) { return std::span(v); };
  cl.write_array(g, "junction_path", all(path), 0, "", path_text);
  cl.write_array(g, "junction_kind", all(kind), 0, "", kJunctionKindEnum);
  cl.write_array(g, "junction_position", all(position), 3, "mm", position_text);
  cl.write_array(g, "junction_b1", all(b1), 3, "",
                 "unit vector from the contact on the element before the junction (in cutting "
                 "order) to the ball centre");
  cl.write_array(g, "junction_b2", all(b2), 3, "",
                 "unit vector from the contact on the element after the junction (in cutting "
                 "order) to the ball centre");
  cl.write_array(g, "junction_element1", all(element1), 3, "",
                 std::string("element before the junction; ") + kElementText);
  cl.write_array(g, "junction_element2", all(element2), 3, "",
                 std::string("element after the junction; ") + kElementText);
  cl.write_array(g, "junction_angle", all(angle), 0, "rad",
                 "angle between junction_b1 and junction_b2");
}

}  // namespace ncpath::jobs
