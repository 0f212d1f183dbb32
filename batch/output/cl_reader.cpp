#include "batch/output/cl_reader.hpp"

#include <algorithm>

#include "batch/output/h5_util.hpp"

namespace ncpath::out {

namespace {

std::string string_attribute(hid_t obj, const char* name, const h5::Context& ctx) {
  if (H5Aexists(obj, name) <= 0) return "";
  h5::Handle attr =
      h5::own(H5Aopen(obj, name, H5P_DEFAULT), ctx, std::string("open attribute ") + name);
  h5::Handle type = h5::utf8_string_type(ctx);
  char* value = nullptr;
  if (H5Aread(attr.get(), type.get(), &value) < 0)
    h5::fail(ctx, std::string("read attribute ") + name);
  std::string out = value ? value : "";
  H5free_memory(value);
  return out;
}

h5::Handle open_file(const std::filesystem::path& file, const h5::Context& ctx) {
  if (!std::filesystem::exists(file)) throw std::runtime_error(file.string() + ": no such file");
  return h5::own(H5Fopen(file.string().c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), ctx, "open file");
}

herr_t collect(hid_t, const char* name, const H5L_info_t*, void* out) {
  static_cast<std::vector<std::string>*>(out)->push_back(name);
  return 0;
}

// Rows [first, first + count) of a dataset of `cols` columns (0: one-dimensional).
template <class T>
void read_rows(hid_t ds, hid_t mem_type, hsize_t first, hsize_t count, hsize_t cols,
               std::vector<T>& out, const h5::Context& ctx) {
  const hsize_t width = std::max<hsize_t>(cols, 1);
  out.resize(static_cast<std::size_t>(count * width));
  if (count == 0) return;
  h5::Handle space = h5::own(H5Dget_space(ds), ctx, "dataset space");
  const hsize_t start[2] = {first, 0}, size[2] = {count, width};
  const int rank = cols ? 2 : 1;
  if (H5Sselect_hyperslab(space.get(), H5S_SELECT_SET, start, nullptr, size, nullptr) < 0)
    h5::fail(ctx, "select rows");
  h5::Handle mem = h5::own(H5Screate_simple(rank, size, nullptr), ctx, "memory space");
  if (H5Dread(ds, mem_type, mem.get(), space.get(), H5P_DEFAULT, out.data()) < 0)
    h5::fail(ctx, "read rows");
}

hsize_t rows_of(hid_t ds, const h5::Context& ctx) {
  h5::Handle space = h5::own(H5Dget_space(ds), ctx, "dataset space");
  hsize_t dims[2] = {0, 0};
  H5Sget_simple_extent_dims(space.get(), dims, nullptr);
  return dims[0];
}

}  // namespace

std::vector<StoredJob> read_jobs(const std::filesystem::path& file) {
  const h5::Context ctx{file.string()};
  h5::Handle f = open_file(file, ctx);
  h5::Handle jobs = h5::own(H5Gopen2(f.get(), "jobs", H5P_DEFAULT), ctx, "open /jobs");
  std::vector<std::string> names;
  hsize_t idx = 0;
  if (H5Literate(jobs.get(), H5_INDEX_CRT_ORDER, H5_ITER_INC, &idx, collect, &names) < 0)
    h5::fail(ctx, "list jobs");
  std::vector<StoredJob> out;
  for (const std::string& n : names) {
    h5::Handle g = h5::own(H5Gopen2(jobs.get(), n.c_str(), H5P_DEFAULT), ctx, "open job " + n);
    StoredJob j;
    j.name = n;
    j.operation = string_attribute(g.get(), "operation", ctx);
    j.status = string_attribute(g.get(), "status", ctx);
    j.input_path = string_attribute(g.get(), "input_path", ctx);
    j.tool_json = string_attribute(g.get(), "tool", ctx);
    j.params_json = string_attribute(g.get(), "params", ctx);
    out.push_back(std::move(j));
  }
  return out;
}

void read_paths(const std::filesystem::path& file, const std::string& job,
                const std::function<void(const ClChunk&)>& sink, std::size_t points) {
  const h5::Context ctx{file.string()};
  h5::Handle f = open_file(file, ctx);
  const std::string base = "jobs/" + job + "/cl/";
  const auto open = [&](const char* name) {
    return h5::own(H5Dopen2(f.get(), (base + name).c_str(), H5P_DEFAULT), ctx,
                   "open " + base + name);
  };
  h5::Handle pts = open("points"), offsets = open("path_offsets"), kinds = open("path_kind"),
             contact = open("contact_kind");
  std::vector<std::int64_t> off;
  read_rows(offsets.get(), H5T_NATIVE_INT64, 0, rows_of(offsets.get(), ctx), 0, off, ctx);
  std::vector<std::uint8_t> kind;
  read_rows(kinds.get(), H5T_NATIVE_UINT8, 0, rows_of(kinds.get(), ctx), 0, kind, ctx);
  ClChunk c;
  for (std::size_t p = 0; p + 1 < off.size();) {
    // Whole paths from p up to about `points` points.
    std::size_t e = p + 1;
    while (e + 1 < off.size() && static_cast<std::size_t>(off[e + 1] - off[p]) <= points) ++e;
    const auto first = static_cast<hsize_t>(off[p]), count = static_cast<hsize_t>(off[e] - off[p]);
    read_rows(pts.get(), H5T_NATIVE_DOUBLE, first, count, 3, c.xyz, ctx);
    read_rows(contact.get(), H5T_NATIVE_UINT8, first, count, 0, c.contact, ctx);
    c.path_sizes.clear();
    c.path_kinds.clear();
    for (std::size_t k = p; k < e; ++k) {
      c.path_sizes.push_back(static_cast<std::uint32_t>(off[k + 1] - off[k]));
      c.path_kinds.push_back(kind[k]);
    }
    sink(c);
    p = e;
  }
}

}  // namespace ncpath::out
