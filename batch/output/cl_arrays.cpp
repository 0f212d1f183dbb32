// ClJob::write_array and the streamed arrays (begin_array, append_rows): results other than
// CL paths (exact segments and junctions, offset loops, graphs), next to the CL datasets.
#include <hdf5.h>

#include <algorithm>
#include <stdexcept>

#include "batch/output/chunk_appender.hpp"
#include "batch/output/cl_state.hpp"
#include "batch/output/cl_writer.hpp"
#include "batch/output/h5_util.hpp"

namespace ncpath::out {

namespace {

using ArrayType = ClJob::ArrayType;

constexpr unsigned kArrayDeflate = 1;
constexpr hsize_t kArrayChunkBytes = 1 << 19;  // about half a MiB per chunk

struct TypeInfo {
  hid_t file_type;
  std::size_t size;
};

TypeInfo type_info(ArrayType type) {
  switch (type) {
    case ArrayType::kFloat64:
      return {H5T_IEEE_F64LE, sizeof(double)};
    case ArrayType::kInt64:
      return {H5T_STD_I64LE, sizeof(std::int64_t)};
    case ArrayType::kUInt8:
      return {H5T_STD_U8LE, 1};
  }
  throw std::invalid_argument("unknown array type");
}

// Creates the empty dataset /jobs/<job>/<group>/<name> (and the group when needed) with its
// attributes, and returns its appender. Chunks hold about kArrayChunkBytes, or `rows` rows
// when the whole array is smaller (rows == 0: not known).
h5::ChunkAppender make_array(detail::FileState& s, const std::string& group,
                             const std::string& name, ArrayType type, std::size_t cols,
                             std::string_view unit, std::string_view description, hsize_t rows) {
  check_link_name(group, "array group");
  check_link_name(name, "array name");
  check_no_nul(unit, "array unit");
  check_no_nul(description, "array description");
  const hid_t job = s.job->group.get();
  const htri_t has_group = H5Lexists(job, group.c_str(), H5P_DEFAULT);
  h5::check(has_group, s.ctx, "look up group '" + group + "'");
  h5::Handle g = has_group > 0
                     ? h5::own(H5Gopen2(job, group.c_str(), H5P_DEFAULT), s.ctx, "open " + group)
                     : h5::create_group(job, group, s.ctx);
  const htri_t exists = H5Lexists(g.get(), name.c_str(), H5P_DEFAULT);
  h5::check(exists, s.ctx, "look up '" + name + "'");
  if (exists > 0)
    throw std::invalid_argument("write_array: '" + group + "/" + name + "' written twice");
  const TypeInfo t = type_info(type);
  const hsize_t width = std::max<std::size_t>(cols, 1);
  hsize_t chunk_rows = std::max<hsize_t>(1, kArrayChunkBytes / (t.size * width));
  if (rows > 0) chunk_rows = std::min(chunk_rows, rows);
  h5::ChunkAppender out(
      h5::create_appendable(g.get(), name.c_str(), t.file_type, cols, chunk_rows, kArrayDeflate,
                            s.ctx),
      "/jobs/" + s.job->name + "/" + group + "/" + name, t.size, cols, chunk_rows, kArrayDeflate,
      &s.ctx);
  if (!unit.empty()) h5::write_attribute(out.dataset(), "unit", unit, s.ctx);
  if (!description.empty()) h5::write_attribute(out.dataset(), "description", description, s.ctx);
  return out;
}

std::size_t rows_of(std::size_t values, std::size_t cols, const std::string& name) {
  const std::size_t width = std::max<std::size_t>(cols, 1);
  if (values % width != 0)
    throw std::invalid_argument("write_array: " + name + " has " + std::to_string(values) +
                                " values, not a multiple of " + std::to_string(width));
  return values / width;
}

template <class T>
void write_whole(detail::FileState& s, const std::string& group, const std::string& name,
                 std::span<const T> data, std::size_t cols, std::string_view unit,
                 std::string_view description) {
  const std::size_t rows = rows_of(data.size(), cols, name);
  h5::ChunkAppender out = [&] {  // the appender compresses without the lock
    const auto lock = h5::library_lock();
    return make_array(s, group, name, array_type_of<T>(), cols, unit, description, rows);
  }();
  out.append(data.data(), rows);
  out.finish();
}

template <class T>
void append_streamed(detail::FileState& s, ClJob::ArrayId id, std::span<const T> data) {
  if (id >= s.job->arrays.size())
    throw std::invalid_argument("append_rows: no array " + std::to_string(id) + " in this job");
  detail::JobState::Streamed& a = s.job->arrays[id];
  if (a.type != array_type_of<T>())
    throw std::invalid_argument("append_rows: array " + std::to_string(id) + " has another type");
  const std::size_t rows = rows_of(data.size(), a.width, "append_rows");
  if (s.job->broken)
    throw std::runtime_error("append_rows: an earlier write to '" + s.ctx.file + "' failed");
  try {
    a.rows.append(data.data(), rows);
  } catch (...) {
    s.job->broken = true;
    throw;
  }
}

}  // namespace

void ClJob::write_array(const std::string& group, const std::string& name,
                        std::span<const double> data, std::size_t cols, std::string_view unit,
                        std::string_view description) {
  write_whole(open_file("write_array"), group, name, data, cols, unit, description);
}
void ClJob::write_array(const std::string& group, const std::string& name,
                        std::span<const std::int64_t> data, std::size_t cols, std::string_view unit,
                        std::string_view description) {
  write_whole(open_file("write_array"), group, name, data, cols, unit, description);
}
void ClJob::write_array(const std::string& group, const std::string& name,
                        std::span<const std::uint8_t> data, std::size_t cols, std::string_view unit,
                        std::string_view description) {
  write_whole(open_file("write_array"), group, name, data, cols, unit, description);
}

ClJob::ArrayId ClJob::begin_array(const std::string& group, const std::string& name,
                                  ArrayType type, std::size_t cols, std::string_view unit,
                                  std::string_view description) {
  detail::FileState& s = open_file("begin_array");
  const auto lock = h5::library_lock();
  s.job->arrays.push_back({make_array(s, group, name, type, cols, unit, description, 0), type,
                           std::max<std::size_t>(cols, 1)});
  return s.job->arrays.size() - 1;
}

void ClJob::append_rows(ArrayId id, std::span<const double> data) {
  append_streamed(open_file("append_rows"), id, data);
}
void ClJob::append_rows(ArrayId id, std::span<const std::int64_t> data) {
  append_streamed(open_file("append_rows"), id, data);
}
void ClJob::append_rows(ArrayId id, std::span<const std::uint8_t> data) {
  append_streamed(open_file("append_rows"), id, data);
}

}  // namespace ncpath::out
