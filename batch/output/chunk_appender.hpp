#pragma once
// Private to ncpath_output (includes hdf5.h).
//
// Appends rows to an extendible, chunked HDF5 dataset created by h5::create_appendable
// (shuffle + deflate). The appender runs those two filters itself, on a batch of chunks at a
// time in parallel (par::for_each), and hands the compressed chunks to HDF5 with direct chunk
// writes (H5Dwrite_chunk), in row order, on the calling thread. Each chunk is what HDF5's
// filters would have to decode: HDF5's byte shuffle of the whole chunk (the unused rows of
// the last one zero, the dataset's fill value), then a zlib stream (a faster deflate strategy
// than HDF5's own: see pack()), so any HDF5 reader (h5py, h5dump) reads it with its standard
// filters. The HDF5 calls, and so the file bytes, depend only on the sequence of rows: never
// on how the caller split it, nor on the number of threads.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "batch/output/h5_util.hpp"

namespace ncpath::out::h5 {

class ChunkAppender {
 public:
  // `dataset` (named `name` in messages) has shape [rows] (cols == 0) or [rows, cols] with
  // chunks of chunk_rows rows, elements of elem_size bytes stored little-endian (the memory
  // layout on every platform ncpath builds on), and the filters shuffle + deflate(level).
  // Rows are given row-major. `ctx` must outlive the appender.
  ChunkAppender(Handle dataset, std::string name, std::size_t elem_size, hsize_t cols,
                hsize_t chunk_rows, unsigned deflate_level, const Context* ctx);

  // Appends `rows` rows starting at `data`. Memory: at most kBatchChunks chunks are held.
  void append(const void* data, std::size_t rows);
  // Writes the held rows, the last chunk partial. Further appends continue after them (the
  // partial chunk is then written again, whole), so call it once, at the end.
  void finish();
  // Closes the dataset (after finish()).
  void close() { dataset_.reset(); }
  hid_t dataset() const { return dataset_.get(); }  // for attributes

  std::int64_t rows() const { return static_cast<std::int64_t>(on_disk_ + held_); }

  // Chunks compressed together (one per task).
  static constexpr std::size_t kBatchChunks = 8;

 private:
  // Compresses the held rows' chunks in parallel and writes them; keeps a partial last chunk
  // held unless `all`.
  void write_held(bool all);
  std::vector<unsigned char> pack(const std::byte* chunk) const;

  Handle dataset_;
  std::string name_;
  std::size_t elem_size_;
  std::size_t row_bytes_;
  hsize_t cols_;
  hsize_t chunk_rows_;
  unsigned level_;
  const Context* ctx_;
  std::vector<std::byte> held_rows_;  // up to kBatchChunks chunks, row-major
  hsize_t held_ = 0;                  // rows in held_rows_
  hsize_t on_disk_ = 0;               // rows before held_rows_ (a multiple of chunk_rows_)
};

}  // namespace ncpath::out::h5
