#include "batch/output/chunk_appender.hpp"

#include <algorithm>
#include <cstring>
#include <utility>

namespace ncpath::out::h5 {

ChunkAppender::ChunkAppender(Handle dataset, std::string name, hid_t mem_type,
                             std::size_t elem_size, hsize_t cols, hsize_t chunk_rows,
                             const Context* ctx)
    : dataset_(std::move(dataset)),
      name_(std::move(name)),
      mem_type_(mem_type),
      row_bytes_(elem_size * std::max<hsize_t>(cols, 1)),
      cols_(cols),
      chunk_rows_(chunk_rows),
      ctx_(ctx),
      buffer_(static_cast<std::size_t>(chunk_rows) * row_bytes_) {}

void ChunkAppender::append(const void* data, std::size_t rows) {
  const auto* src = static_cast<const std::byte*>(data);
  while (rows > 0) {
    const std::size_t take = std::min<std::size_t>(rows, chunk_rows_ - buffered_);
    std::memcpy(buffer_.data() + buffered_ * row_bytes_, src, take * row_bytes_);
    buffered_ += take;
    src += take * row_bytes_;
    rows -= take;
    if (buffered_ == chunk_rows_) write_buffer();
  }
}

void ChunkAppender::finish() {
  if (buffered_ > 0) write_buffer();
}

void ChunkAppender::write_buffer() {
  const int rank = cols_ == 0 ? 1 : 2;
  const hsize_t new_dims[2] = {on_disk_ + buffered_, cols_};
  check(H5Dset_extent(dataset_.get(), new_dims), *ctx_, "extend dataset '" + name_ + "'");
  Handle file_space = own(H5Dget_space(dataset_.get()), *ctx_, "get dataspace of '" + name_ + "'");
  const hsize_t start[2] = {on_disk_, 0};
  const hsize_t count[2] = {buffered_, cols_};
  check(H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start, nullptr, count, nullptr),
        *ctx_, "select rows in '" + name_ + "'");
  Handle mem_space =
      own(H5Screate_simple(rank, count, nullptr), *ctx_, "create dataspace of '" + name_ + "'");
  check(H5Dwrite(dataset_.get(), mem_type_, mem_space.get(), file_space.get(), H5P_DEFAULT,
                 buffer_.data()),
        *ctx_, "write rows to '" + name_ + "'");
  on_disk_ += buffered_;
  buffered_ = 0;
}

}  // namespace ncpath::out::h5
