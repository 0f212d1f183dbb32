#include "batch/output/chunk_appender.hpp"

#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cstring>
#include <utility>

#include "engine/parallel.hpp"

namespace ncpath::out::h5 {

static_assert(std::endian::native == std::endian::little,
              "direct chunk writes store memory bytes as the datasets' little-endian types");

namespace {

// HDF5's shuffle filter: byte k of every element, for k = 0 .. elem_size - 1, in turn.
std::vector<std::byte> shuffled(const std::byte* src, std::size_t bytes, std::size_t elem_size) {
  std::vector<std::byte> out(bytes);
  const std::size_t n = bytes / elem_size;
  for (std::size_t k = 0; k < elem_size; ++k) {
    for (std::size_t i = 0; i < n; ++i) out[k * n + i] = src[i * elem_size + k];
  }
  return out;
}

}  // namespace

ChunkAppender::ChunkAppender(Handle dataset, std::string name, std::size_t elem_size,
                             hsize_t cols, hsize_t chunk_rows, unsigned deflate_level,
                             const Context* ctx)
    : dataset_(std::move(dataset)),
      name_(std::move(name)),
      elem_size_(elem_size),
      row_bytes_(elem_size * std::max<hsize_t>(cols, 1)),
      cols_(cols),
      chunk_rows_(chunk_rows),
      level_(deflate_level),
      ctx_(ctx) {}

void ChunkAppender::append(const void* data, std::size_t rows) {
  const auto* src = static_cast<const std::byte*>(data);
  const hsize_t batch_rows = kBatchChunks * chunk_rows_;
  while (rows > 0) {
    const std::size_t take = std::min<std::size_t>(rows, batch_rows - held_);
    held_rows_.insert(held_rows_.end(), src, src + take * row_bytes_);
    held_ += take;
    src += take * row_bytes_;
    rows -= take;
    if (held_ == batch_rows) write_held(false);
  }
}

void ChunkAppender::finish() {
  if (held_ > 0) write_held(true);
}

std::vector<unsigned char> ChunkAppender::pack(const std::byte* chunk) const {
  const std::size_t bytes = chunk_rows_ * row_bytes_;
  std::vector<std::byte> in = elem_size_ > 1 ? shuffled(chunk, bytes, elem_size_)
                                             : std::vector<std::byte>(chunk, chunk + bytes);
  // A zlib stream, as HDF5's deflate filter writes and reads it. Strategy Z_RLE: runs and
  // Huffman codes only, no string matching. On a 1.2 M-facet scan's tables (shuffled float64
  // and int64, 264 MB) it compresses 2.2x faster than level 1's default strategy (143 against
  // 66 MB/s on one core) for 15 % more bytes (ratio 0.594 against 0.515); docs/performance.md.
  z_stream z{};
  std::vector<unsigned char> out;
  if (deflateInit2(&z, static_cast<int>(level_), Z_DEFLATED, 15, 8, Z_RLE) != Z_OK) return out;
  out.resize(deflateBound(&z, static_cast<uLong>(bytes)));
  z.next_in = reinterpret_cast<Bytef*>(in.data());
  z.avail_in = static_cast<uInt>(bytes);
  z.next_out = out.data();
  z.avail_out = static_cast<uInt>(out.size());
  const int rc = deflate(&z, Z_FINISH);
  out.resize(rc == Z_STREAM_END ? z.total_out : 0);  // empty: reported by write_held
  deflateEnd(&z);
  return out;
}

void ChunkAppender::write_held(bool all) {
  const std::size_t chunk_bytes = chunk_rows_ * row_bytes_;
  const std::size_t full = held_ / chunk_rows_;
  const std::size_t chunks = all ? (held_ + chunk_rows_ - 1) / chunk_rows_ : full;
  held_rows_.resize(chunks * chunk_bytes, std::byte{0});  // the last chunk's tail: fill value
  std::vector<std::vector<unsigned char>> packed(chunks);
  par::for_each(chunks, 1, [&](std::size_t c) { packed[c] = pack(&held_rows_[c * chunk_bytes]); });

  const hsize_t rows = all ? held_ : full * chunk_rows_;
  const auto lock = library_lock();
  const hsize_t new_dims[2] = {on_disk_ + rows, cols_};
  check(H5Dset_extent(dataset_.get(), new_dims), *ctx_, "extend dataset '" + name_ + "'");
  for (std::size_t c = 0; c < chunks; ++c) {
    if (packed[c].empty()) fail(*ctx_, "compress a chunk of '" + name_ + "'");
    const hsize_t offset[2] = {on_disk_ + c * chunk_rows_, 0};
    check(H5Dwrite_chunk(dataset_.get(), H5P_DEFAULT, 0, offset, packed[c].size(),
                         packed[c].data()),
          *ctx_, "write a chunk of '" + name_ + "'");
  }
  // Keep the rows of a partial last chunk: a later append completes and rewrites it.
  const hsize_t kept = held_ - full * chunk_rows_;
  held_rows_.erase(held_rows_.begin(), held_rows_.begin() + full * chunk_bytes);
  held_rows_.resize(kept * row_bytes_);
  on_disk_ += full * chunk_rows_;
  held_ = kept;
}

}  // namespace ncpath::out::h5
