#pragma once
// Private to ncpath_output (includes hdf5.h).
//
// Appends rows to an extendible, chunked HDF5 dataset through a one-chunk buffer: a chunk is
// written when it is full, exactly once and whole, and the last partial chunk at finish().
// Hence the HDF5 calls made, and so the file bytes, depend only on the sequence of rows,
// never on how the caller split it; and compression runs once per chunk instead of
// re-compressing a chunk for every small append.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "batch/output/h5_util.hpp"

namespace ncpath::out::h5 {

class ChunkAppender {
 public:
  // `dataset` (named `name` in messages) has shape [rows] (cols == 0) or [rows, cols] with
  // chunks of chunk_rows rows; rows are given in memory as `mem_type` elements of elem_size
  // bytes, row-major. `ctx` must outlive the appender.
  ChunkAppender(Handle dataset, std::string name, hid_t mem_type, std::size_t elem_size,
                hsize_t cols, hsize_t chunk_rows, const Context* ctx);

  // Appends `rows` rows starting at `data`.
  void append(const void* data, std::size_t rows);
  // Writes the buffered partial chunk (if any). Further appends continue after it, but then
  // that chunk gets rewritten, so call it once, at the end.
  void finish();
  // Closes the dataset (after finish()).
  void close() { dataset_.reset(); }

  std::int64_t rows() const { return static_cast<std::int64_t>(on_disk_ + buffered_); }

 private:
  void write_buffer();

  Handle dataset_;
  std::string name_;
  hid_t mem_type_;
  std::size_t row_bytes_;
  hsize_t cols_;
  hsize_t chunk_rows_;
  const Context* ctx_;
  std::vector<std::byte> buffer_;  // chunk_rows * row_bytes
  hsize_t buffered_ = 0;           // rows in buffer_
  hsize_t on_disk_ = 0;            // rows already in the dataset
};

}  // namespace ncpath::out::h5
