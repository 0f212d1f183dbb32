#pragma once
// The exact record tables that the scan and zlevel jobs stream next to their CL paths
// (groups scan/ and zlevel/, docs/hdf5-schema.md): columns appended chunk by chunk in cutting
// order (never held whole), the junction table both jobs share, and the shared texts of the
// element and kind columns.
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include "batch/output/cl_writer.hpp"
#include "engine/scan.hpp"

namespace ncpath::jobs {

inline constexpr const char* kJunctionKindEnum = "0=convex,1=sharp_concave,2=tangent";
inline constexpr const char* kElementText =
    "mesh element: kind (0 facet, 1 edge, 2 vertex), then indices a, b: facet index, -1; "
    "edge's two vertex indices; vertex index, -1";

// One streamed array of the job (ClJob::begin_array) and the rows of the chunk at hand.
template <class T>
class Column {
 public:
  Column(out::ClJob& cl, const std::string& group, const std::string& name, std::size_t cols,
         std::string_view unit, std::string_view description)
      : id_(cl.begin_array(group, name, out::array_type_of<T>(), cols, unit, description)) {}

  void push(T v) { rows_.push_back(v); }
  template <std::size_t N>
  void push(const std::array<T, N>& row) {
    rows_.insert(rows_.end(), row.begin(), row.end());
  }
  void push(const ElementRef& e) requires std::is_same_v<T, std::int64_t> {
    rows_.insert(rows_.end(), {e.kind, e.a, e.b});
  }
  // Appends the rows pushed since the last flush to the array.
  void flush(out::ClJob& cl) {
    cl.append_rows(id_, std::span<const T>(rows_));
    rows_.clear();
  }

 private:
  out::ClJob::ArrayId id_;
  std::vector<T> rows_;
};

// The texts of one operation's segment table (SegmentTable).
struct SegmentTexts {
  const char* path;      // segment_path's description
  const char* kind;      // segment_kind's enum text
  const char* start;     // segment_start's description
  std::size_t geometry_cols;
  const char* geometry;  // segment_geometry's description
};

// segment_path, _kind, _element, _start, _end, _geometry in `group`, created by the
// constructor; push() takes a segment record (path, kind, element, start, end, geometry).
class SegmentTable {
 public:
  SegmentTable(out::ClJob& cl, const std::string& group, const SegmentTexts& t)
      : path_(cl, group, "segment_path", 0, "", t.path),
        kind_(cl, group, "segment_kind", 0, "", t.kind),
        element_(cl, group, "segment_element", 3, "", kElementText),
        start_(cl, group, "segment_start", 3, "mm", t.start),
        end_(cl, group, "segment_end", 3, "mm",
             "tool tip x, y, z where the segment ends, in cutting order"),
        geometry_(cl, group, "segment_geometry", t.geometry_cols, "", t.geometry) {}

  template <class Segment>
  void push(const Segment& s) {
    path_.push(s.path);
    kind_.push(s.kind);
    element_.push(s.element);
    start_.push(s.start);
    end_.push(s.end);
    geometry_.push(s.geometry);
  }
  void flush(out::ClJob& cl) {
    for (auto* c : {&path_, &element_}) c->flush(cl);
    kind_.flush(cl);
    for (auto* c : {&start_, &end_, &geometry_}) c->flush(cl);
  }

 private:
  Column<std::int64_t> path_;
  Column<std::uint8_t> kind_;
  Column<std::int64_t> element_;
  Column<double> start_, end_, geometry_;
};

// junction_path, _kind, _position, _b1, _b2, _element1, _element2, _angle in `group`, created
// by the constructor; path_text and position_text describe the path and position columns.
class JunctionTable {
 public:
  JunctionTable(out::ClJob& cl, const std::string& group, const std::string& path_text,
                const std::string& position_text);
  void append(std::span<const ScanJunctionRecord> records);

 private:
  out::ClJob& cl_;
  Column<std::int64_t> path_;
  Column<std::uint8_t> kind_;
  Column<double> position_, b1_, b2_;
  Column<std::int64_t> element1_, element2_;
  Column<double> angle_;
};

}  // namespace ncpath::jobs
