// ClJob::write_array: whole arrays next to the CL datasets (offset loops, graphs, ...).
#include <hdf5.h>

#include <algorithm>
#include <stdexcept>

#include "batch/output/cl_state.hpp"
#include "batch/output/cl_writer.hpp"
#include "batch/output/h5_util.hpp"

namespace ncpath::out {

namespace {

constexpr unsigned kArrayDeflate = 1;
constexpr hsize_t kArrayChunkBytes = 1 << 19;  // about half a MiB per chunk

template <class T>
void write_whole(detail::FileState& s, const std::string& group, const std::string& name,
                 std::span<const T> data, std::size_t cols, std::string_view unit,
                 std::string_view description, hid_t type) {
  check_link_name(group, "array group");
  check_link_name(name, "array name");
  check_no_nul(unit, "array unit");
  check_no_nul(description, "array description");
  const std::size_t width = cols == 0 ? 1 : cols;
  if (data.size() % width != 0)
    throw std::invalid_argument("write_array: " + name + " has " + std::to_string(data.size()) +
                                " values, not a multiple of " + std::to_string(width));
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
  const hsize_t rows = data.size() / width;
  const hsize_t chunk_rows = std::max<hsize_t>(
      1, std::min<hsize_t>(std::max<hsize_t>(rows, 1), kArrayChunkBytes / (sizeof(T) * width)));
  h5::Handle ds =
      h5::create_appendable(g.get(), name.c_str(), type, cols, chunk_rows, kArrayDeflate, s.ctx);
  if (rows > 0) {
    const hsize_t dims[2] = {rows, cols};
    h5::check(H5Dset_extent(ds.get(), dims), s.ctx, "extend '" + name + "'");
    h5::check(H5Dwrite(ds.get(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()), s.ctx,
              "write '" + name + "'");
  }
  if (!unit.empty()) h5::write_attribute(ds.get(), "unit", unit, s.ctx);
  if (!description.empty()) h5::write_attribute(ds.get(), "description", description, s.ctx);
}

}  // namespace

void ClJob::write_array(const std::string& group, const std::string& name,
                        std::span<const double> data, std::size_t cols, std::string_view unit,
                        std::string_view description) {
  write_whole(open_file("write_array"), group, name, data, cols, unit, description,
              H5T_NATIVE_DOUBLE);
}
void ClJob::write_array(const std::string& group, const std::string& name,
                        std::span<const std::int64_t> data, std::size_t cols, std::string_view unit,
                        std::string_view description) {
  write_whole(open_file("write_array"), group, name, data, cols, unit, description,
              H5T_NATIVE_INT64);
}
void ClJob::write_array(const std::string& group, const std::string& name,
                        std::span<const std::uint8_t> data, std::size_t cols, std::string_view unit,
                        std::string_view description) {
  write_whole(open_file("write_array"), group, name, data, cols, unit, description,
              H5T_NATIVE_UINT8);
}

}  // namespace ncpath::out
