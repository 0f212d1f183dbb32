#pragma once
// Private to ncpath_output (includes hdf5.h; never include it from a public header).
// Small RAII and error helpers over the HDF5 C API: every failure becomes a
// std::runtime_error that names the file, the operation and HDF5's own reason.
#include <hdf5.h>

#include <cstdint>
#include <mutex>
#include <string>
#include <string_view>

namespace ncpath::out::h5 {

// Debian's HDF5 is not a thread-safe build: every HDF5 call of the process is made holding
// this lock, so that jobs running at the same time may each write a file of their own.
// ClFile and ClJob take it in their members; ChunkAppender only around its HDF5 calls (it
// compresses without it). Recursive: members call one another.
std::unique_lock<std::recursive_mutex> library_lock();

// Owns one HDF5 identifier of any kind; releases it with H5Idec_ref.
class Handle {
 public:
  Handle() = default;
  explicit Handle(hid_t id) : id_(id) {}
  Handle(Handle&& o) noexcept : id_(o.id_) { o.id_ = H5I_INVALID_HID; }
  Handle& operator=(Handle&& o) noexcept;
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() { reset(); }

  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }
  void reset() noexcept;
  // Gives up ownership (for a close call whose error must be checked, like H5Fclose).
  hid_t release() noexcept {
    const hid_t id = id_;
    id_ = H5I_INVALID_HID;
    return id;
  }

 private:
  hid_t id_ = H5I_INVALID_HID;
};

// Where errors happen, for messages: the file path.
struct Context {
  std::string file;
};

// Throws std::runtime_error("HDF5: <op> failed in '<file>': <innermost HDF5 message>").
[[noreturn]] void fail(const Context& ctx, std::string_view op);

// Returns id, or throws when it is negative.
hid_t check(hid_t id, const Context& ctx, std::string_view op);
// Wraps a new identifier in a Handle, or throws when it is negative.
Handle own(hid_t id, const Context& ctx, std::string_view op);

// Object creation property list of class `cls` (H5P_GROUP_CREATE, H5P_DATASET_CREATE,
// H5P_FILE_CREATE) with modification-time tracking off: same data, same file bytes.
Handle untimed_create_plist(hid_t cls, const Context& ctx);
// Link creation property list that stores names as UTF-8.
Handle utf8_link_plist(const Context& ctx);

// A group whose links are tracked in creation order (h5py lists them in that order).
Handle create_group(hid_t parent, const std::string& name, const Context& ctx);

// Variable-length UTF-8 string type (h5py reads it as str).
Handle utf8_string_type(const Context& ctx);

// Scalar attributes; an existing attribute of that name is replaced.
void write_attribute(hid_t obj, const char* name, std::string_view value, const Context& ctx);
void write_attribute(hid_t obj, const char* name, std::int64_t value, const Context& ctx);

// Scalar datasets (the statistics).
void write_scalar(hid_t parent, const std::string& name, std::string_view value,
                  const Context& ctx);
void write_scalar(hid_t parent, const std::string& name, std::int64_t value, const Context& ctx);
void write_scalar(hid_t parent, const std::string& name, double value, const Context& ctx);

// An empty, appendable dataset: shape [0] (cols == 0) or [0, cols], unlimited rows, chunks
// of chunk_rows rows, shuffle + deflate(level), fill value 0, no time tracking, no chunk
// cache (ChunkAppender writes whole compressed chunks directly, exactly once).
Handle create_appendable(hid_t parent, const char* name, hid_t file_type, hsize_t cols,
                         hsize_t chunk_rows, unsigned deflate_level, const Context& ctx);

}  // namespace ncpath::out::h5
