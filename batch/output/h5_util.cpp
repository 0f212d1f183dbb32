#include "batch/output/h5_util.hpp"

#include <stdexcept>

namespace ncpath::out::h5 {
namespace {

// H5Ewalk2 callback: keeps the first (innermost, with H5E_WALK_UPWARD) description, which is
// the most specific one (e.g. the errno text of a failed open).
herr_t keep_innermost(unsigned n, const H5E_error2_t* err, void* data) {
  auto* out = static_cast<std::string*>(data);
  if (n == 0 && err != nullptr && err->desc != nullptr) {
    *out = std::string(err->func_name != nullptr ? err->func_name : "?") + ": " + err->desc;
  }
  return 0;
}

void require_no_nul(std::string_view value, const char* what) {
  if (value.find('\0') != std::string_view::npos) {
    throw std::invalid_argument(std::string(what) + " contains a NUL character");
  }
}

}  // namespace

std::unique_lock<std::recursive_mutex> library_lock() {
  static std::recursive_mutex mutex;
  return std::unique_lock<std::recursive_mutex>(mutex);
}

Handle& Handle::operator=(Handle&& o) noexcept {
  if (this != &o) {
    reset();
    id_ = o.id_;
    o.id_ = H5I_INVALID_HID;
  }
  return *this;
}

void Handle::reset() noexcept {
  if (id_ < 0) return;
  const auto lock = library_lock();
  H5Idec_ref(id_);
  id_ = H5I_INVALID_HID;
}

void fail(const Context& ctx, std::string_view op) {
  std::string detail;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, keep_innermost, &detail);
  H5Eclear2(H5E_DEFAULT);
  std::string msg = "HDF5: " + std::string(op) + " failed in '" + ctx.file + "'";
  if (!detail.empty()) msg += ": " + detail;
  throw std::runtime_error(msg);
}

hid_t check(hid_t id, const Context& ctx, std::string_view op) {
  if (id < 0) fail(ctx, op);
  return id;
}

Handle own(hid_t id, const Context& ctx, std::string_view op) { return Handle(check(id, ctx, op)); }

Handle untimed_create_plist(hid_t cls, const Context& ctx) {
  Handle plist = own(H5Pcreate(cls), ctx, "create property list");
  check(H5Pset_obj_track_times(plist.get(), false), ctx, "disable time tracking");
  return plist;
}

Handle utf8_link_plist(const Context& ctx) {
  Handle plist = own(H5Pcreate(H5P_LINK_CREATE), ctx, "create link property list");
  check(H5Pset_char_encoding(plist.get(), H5T_CSET_UTF8), ctx, "set UTF-8 link names");
  return plist;
}

Handle create_group(hid_t parent, const std::string& name, const Context& ctx) {
  Handle gcpl = untimed_create_plist(H5P_GROUP_CREATE, ctx);
  check(H5Pset_link_creation_order(gcpl.get(), H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED), ctx,
        "track link creation order");
  Handle lcpl = utf8_link_plist(ctx);
  return own(H5Gcreate2(parent, name.c_str(), lcpl.get(), gcpl.get(), H5P_DEFAULT), ctx,
             "create group '" + name + "'");
}

Handle utf8_string_type(const Context& ctx) {
  Handle type = own(H5Tcopy(H5T_C_S1), ctx, "copy string type");
  check(H5Tset_size(type.get(), H5T_VARIABLE), ctx, "make string type variable-length");
  check(H5Tset_cset(type.get(), H5T_CSET_UTF8), ctx, "make string type UTF-8");
  return type;
}

namespace {

// Creates scalar attribute `name` of `type` (replacing an existing one) and writes *data.
void write_attribute_raw(hid_t obj, const char* name, hid_t file_type, hid_t mem_type,
                         const void* data, const Context& ctx) {
  const std::string what = std::string("attribute '") + name + "'";
  const htri_t exists = H5Aexists(obj, name);
  check(exists, ctx, "look up " + what);
  if (exists > 0) check(H5Adelete(obj, name), ctx, "replace " + what);
  Handle space = own(H5Screate(H5S_SCALAR), ctx, "create scalar dataspace");
  Handle attr = own(H5Acreate2(obj, name, file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT), ctx,
                    "create " + what);
  check(H5Awrite(attr.get(), mem_type, data), ctx, "write " + what);
}

void write_scalar_raw(hid_t parent, const std::string& name, hid_t file_type, hid_t mem_type,
                      const void* data, const Context& ctx) {
  const std::string what = "dataset '" + name + "'";
  Handle space = own(H5Screate(H5S_SCALAR), ctx, "create scalar dataspace");
  Handle dcpl = untimed_create_plist(H5P_DATASET_CREATE, ctx);
  Handle lcpl = utf8_link_plist(ctx);
  Handle ds = own(
      H5Dcreate2(parent, name.c_str(), file_type, space.get(), lcpl.get(), dcpl.get(), H5P_DEFAULT),
      ctx, "create " + what);
  check(H5Dwrite(ds.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), ctx, "write " + what);
}

}  // namespace

void write_attribute(hid_t obj, const char* name, std::string_view value, const Context& ctx) {
  require_no_nul(value, name);
  Handle type = utf8_string_type(ctx);
  const std::string copy(value);  // NUL-terminated for the C API
  const char* ptr = copy.c_str();
  write_attribute_raw(obj, name, type.get(), type.get(), &ptr, ctx);
}

void write_attribute(hid_t obj, const char* name, std::int64_t value, const Context& ctx) {
  write_attribute_raw(obj, name, H5T_STD_I64LE, H5T_NATIVE_INT64, &value, ctx);
}

void write_scalar(hid_t parent, const std::string& name, std::string_view value,
                  const Context& ctx) {
  require_no_nul(value, name.c_str());
  Handle type = utf8_string_type(ctx);
  const std::string copy(value);
  const char* ptr = copy.c_str();
  write_scalar_raw(parent, name, type.get(), type.get(), &ptr, ctx);
}

void write_scalar(hid_t parent, const std::string& name, std::int64_t value, const Context& ctx) {
  write_scalar_raw(parent, name, H5T_STD_I64LE, H5T_NATIVE_INT64, &value, ctx);
}

void write_scalar(hid_t parent, const std::string& name, double value, const Context& ctx) {
  write_scalar_raw(parent, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &value, ctx);
}

Handle create_appendable(hid_t parent, const char* name, hid_t file_type, hsize_t cols,
                         hsize_t chunk_rows, unsigned deflate_level, const Context& ctx) {
  const std::string what = std::string("dataset '") + name + "'";
  const int rank = cols == 0 ? 1 : 2;
  const hsize_t dims[2] = {0, cols};
  const hsize_t max_dims[2] = {H5S_UNLIMITED, cols};
  const hsize_t chunk[2] = {chunk_rows, cols};
  Handle space = own(H5Screate_simple(rank, dims, max_dims), ctx, "create dataspace");

  Handle dcpl = untimed_create_plist(H5P_DATASET_CREATE, ctx);
  check(H5Pset_chunk(dcpl.get(), rank, chunk), ctx, "set chunking of " + what);
  check(H5Pset_shuffle(dcpl.get()), ctx, "set shuffle filter of " + what);
  check(H5Pset_deflate(dcpl.get(), deflate_level), ctx, "set deflate filter of " + what);
  // An explicit zero fill makes the unused tail of the last (edge) chunk deterministic.
  const std::uint64_t zero[1] = {0};  // 8 bytes: wide enough for every type used here
  check(H5Pset_fill_value(dcpl.get(), file_type, zero), ctx, "set fill value of " + what);
  check(H5Pset_fill_time(dcpl.get(), H5D_FILL_TIME_IFSET), ctx, "set fill time of " + what);

  // Chunks are assembled by ChunkAppender and written whole, once: a cache would only copy.
  Handle dapl = own(H5Pcreate(H5P_DATASET_ACCESS), ctx, "create dataset access list");
  check(
      H5Pset_chunk_cache(dapl.get(), H5D_CHUNK_CACHE_NSLOTS_DEFAULT, 0, H5D_CHUNK_CACHE_W0_DEFAULT),
      ctx, "disable chunk cache of " + what);

  Handle lcpl = utf8_link_plist(ctx);
  return own(H5Dcreate2(parent, name, file_type, space.get(), lcpl.get(), dcpl.get(), dapl.get()),
             ctx, "create " + what);
}

}  // namespace ncpath::out::h5
