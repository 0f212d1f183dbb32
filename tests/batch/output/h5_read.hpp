#pragma once
// Test-only HDF5 reading helpers, written directly against the C API and independent of the
// writer's own helpers (batch/output/h5_util.*), so that the tests are an outside oracle.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace ncpath::out::test {

// Owns any HDF5 id; throws when constructed from a failed call.
class Id {
 public:
  explicit Id(hid_t id, const std::string& what = "HDF5 call") : id_(id) {
    if (id_ < 0) throw std::runtime_error("test reader: " + what + " failed");
  }
  Id(const Id&) = delete;
  Id& operator=(const Id&) = delete;
  Id(Id&& other) noexcept : id_(std::exchange(other.id_, -1)) {}
  ~Id() {
    if (id_ >= 0) H5Idec_ref(id_);
  }
  operator hid_t() const { return id_; }  // NOLINT: convenience in tests

 private:
  hid_t id_;
};

inline Id open_read(const std::filesystem::path& path) {
  return Id(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), "open " + path.string());
}

struct StringInfo {
  std::string value;
  bool variable = false;
  H5T_cset_t cset = H5T_CSET_ERROR;
};

// Reads a scalar string attribute (variable or fixed length).
inline StringInfo read_string_attr(hid_t obj, const char* name) {
  Id attr(H5Aopen(obj, name, H5P_DEFAULT), std::string("open attribute ") + name);
  Id type(H5Aget_type(attr));
  if (H5Tget_class(type) != H5T_STRING) throw std::runtime_error("not a string attribute");
  StringInfo out;
  out.cset = H5Tget_cset(type);
  out.variable = H5Tis_variable_str(type) > 0;
  if (out.variable) {
    char* ptr = nullptr;
    if (H5Aread(attr, type, &ptr) < 0) throw std::runtime_error("read vlen attribute");
    out.value = ptr != nullptr ? ptr : "";
    H5free_memory(ptr);
  } else {
    std::vector<char> buf(H5Tget_size(type) + 1, '\0');
    if (H5Aread(attr, type, buf.data()) < 0) throw std::runtime_error("read attribute");
    out.value = buf.data();
  }
  return out;
}

inline std::string attr_str(hid_t obj, const char* name) {
  return read_string_attr(obj, name).value;
}

inline std::int64_t attr_i64(hid_t obj, const char* name) {
  Id attr(H5Aopen(obj, name, H5P_DEFAULT), std::string("open attribute ") + name);
  std::int64_t v = 0;
  if (H5Aread(attr, H5T_NATIVE_INT64, &v) < 0) throw std::runtime_error("read attribute");
  return v;
}

inline bool has_attr(hid_t obj, const char* name) { return H5Aexists(obj, name) > 0; }

inline std::vector<hsize_t> dims_of(hid_t ds, std::vector<hsize_t>* max_dims = nullptr) {
  Id space(H5Dget_space(ds));
  const int rank = H5Sget_simple_extent_ndims(space);
  std::vector<hsize_t> dims(rank), maxd(rank);
  H5Sget_simple_extent_dims(space, dims.data(), maxd.data());
  if (max_dims != nullptr) *max_dims = maxd;
  return dims;
}

// Reads a whole dataset converted to mem_type (T must match it).
template <typename T>
std::vector<T> read_all(hid_t file, const std::string& path, hid_t mem_type) {
  Id ds(H5Dopen2(file, path.c_str(), H5P_DEFAULT), "open " + path);
  Id space(H5Dget_space(ds));
  const hssize_t n = H5Sget_simple_extent_npoints(space);
  std::vector<T> out(static_cast<std::size_t>(n));
  if (n > 0 && H5Dread(ds, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) < 0) {
    throw std::runtime_error("read " + path);
  }
  return out;
}

inline std::vector<char> file_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<char>(std::istreambuf_iterator<char>(in), {});
}

// Byte equality of two files, reporting sizes and the first differing offset (not the bytes).
inline ::testing::AssertionResult same_bytes(const std::filesystem::path& a,
                                             const std::filesystem::path& b) {
  const std::vector<char> x = file_bytes(a), y = file_bytes(b);
  if (x.empty()) return ::testing::AssertionFailure() << a << " is empty or missing";
  if (x == y) return ::testing::AssertionSuccess();
  std::size_t i = 0;
  while (i < x.size() && i < y.size() && x[i] == y[i]) ++i;
  return ::testing::AssertionFailure() << a << " (" << x.size() << " bytes) and " << b << " ("
                                       << y.size() << " bytes) differ from byte " << i;
}

// The value of a dataset or attribute as comparable bytes: strings as their text, anything
// else as stored (its file type's bytes).
inline std::string value_bytes(hid_t obj, bool attribute) {
  Id type(attribute ? H5Aget_type(obj) : H5Dget_type(obj));
  Id space(attribute ? H5Aget_space(obj) : H5Dget_space(obj));
  const hssize_t n = H5Sget_simple_extent_npoints(space);
  if (H5Tis_variable_str(type) > 0) {
    std::vector<char*> ptrs(static_cast<std::size_t>(n), nullptr);
    const herr_t rc = attribute ? H5Aread(obj, type, ptrs.data())
                                : H5Dread(obj, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, ptrs.data());
    if (rc < 0) throw std::runtime_error("read strings");
    std::string out;
    for (char* p : ptrs) out += std::string(p ? p : "") + '\0';
    H5Dvlen_reclaim(type, space, H5P_DEFAULT, ptrs.data());
    return out;
  }
  std::string out(static_cast<std::size_t>(n) * H5Tget_size(type), '\0');
  const herr_t rc = out.empty() ? 0
                    : attribute ? H5Aread(obj, type, out.data())
                                : H5Dread(obj, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data());
  if (rc < 0) throw std::runtime_error("read values");
  return out;
}

// Every object of a file in creation order ("/jobs/a", "/jobs/a/cl", ...), with its
// attributes' names and values and, for datasets, shape and values, one line per item.
inline std::vector<std::string> content_lines(const std::filesystem::path& path) {
  Id file = open_read(path);
  std::vector<std::string> lines;
  struct Walk {
    static herr_t attr(hid_t obj, const char* name, const H5A_info_t*, void* data) {
      Id a(H5Aopen(obj, name, H5P_DEFAULT));
      static_cast<std::vector<std::string>*>(data)->push_back(std::string("  @") + name + "=" +
                                                              value_bytes(a, true));
      return 0;
    }
    static herr_t object(hid_t root, const char* name, const H5O_info_t* info, void* data) {
      auto& out = *static_cast<std::vector<std::string>*>(data);
      out.push_back(name);
      Id obj(H5Oopen(root, name, H5P_DEFAULT));
      hsize_t idx = 0;
      H5Aiterate2(obj, H5_INDEX_CRT_ORDER, H5_ITER_INC, &idx, attr, data);
      if (info->type == H5O_TYPE_DATASET) {
        std::string dims;
        for (const hsize_t d : dims_of(obj)) dims += std::to_string(d) + " ";
        out.push_back("  shape " + dims);
        out.push_back("  values " + value_bytes(obj, false));
      }
      return 0;
    }
  };
  if (H5Ovisit(file, H5_INDEX_CRT_ORDER, H5_ITER_INC, Walk::object, &lines) < 0)
    throw std::runtime_error("visit " + path.string());
  return lines;
}

// The two files hold the same objects in the same order with the same attributes and
// values, except the objects whose path `skip` accepts (for example timings).
template <class Skip>
::testing::AssertionResult same_content(const std::filesystem::path& a,
                                        const std::filesystem::path& b, Skip skip) {
  auto keep = [&](const std::vector<std::string>& lines) {
    std::vector<std::string> out;
    bool skipping = false;
    for (const std::string& l : lines) {
      if (l.rfind("  ", 0) != 0) skipping = skip(l);
      if (!skipping) out.push_back(l);
    }
    return out;
  };
  const std::vector<std::string> x = keep(content_lines(a)), y = keep(content_lines(b));
  if (x.size() < 2) return ::testing::AssertionFailure() << a << " holds nothing";
  for (std::size_t i = 0; i < std::min(x.size(), y.size()); ++i)
    if (x[i] != y[i])
      return ::testing::AssertionFailure()
             << a << " and " << b << " differ at item " << i << ": '" << x[i].substr(0, 80)
             << "' against '" << y[i].substr(0, 80) << "'";
  if (x.size() != y.size())
    return ::testing::AssertionFailure() << a << " has " << x.size() << " items, " << b
                                         << " has " << y.size();
  return ::testing::AssertionSuccess();
}

// A clean per-test output directory under the build tree.
inline std::filesystem::path out_dir(const std::string& test_name) {
  const std::filesystem::path dir =
      std::filesystem::path(NCPATH_BINARY_DIR) / "test_out" / "batch_output" / test_name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace ncpath::out::test
