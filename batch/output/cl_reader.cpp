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
  const auto lock = h5::library_lock();
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
    j.message = string_attribute(g.get(), "message", ctx);
    j.input_path = string_attribute(g.get(), "input_path", ctx);
    j.input_sha256 = string_attribute(g.get(), "input_sha256", ctx);
    j.tool_json = string_attribute(g.get(), "tool", ctx);
    j.params_json = string_attribute(g.get(), "params", ctx);
    out.push_back(std::move(j));
  }
  return out;
}

struct PathReader::State {
  h5::Context ctx;
  h5::Handle f, pts, contact;
  std::vector<std::int64_t> off;
  std::vector<std::uint8_t> kind;
};

PathReader::PathReader(const std::filesystem::path& file, const std::string& job)
    : s_(new State{h5::Context{file.string()}, {}, {}, {}, {}, {}}) {
  const auto lock = h5::library_lock();
  const h5::Context& ctx = s_->ctx;
  s_->f = open_file(file, ctx);
  const std::string base = "jobs/" + job + "/cl/";
  const auto open = [&](const char* name) {
    return h5::own(H5Dopen2(s_->f.get(), (base + name).c_str(), H5P_DEFAULT), ctx,
                   "open " + base + name);
  };
  s_->pts = open("points");
  s_->contact = open("contact_kind");
  h5::Handle offsets = open("path_offsets"), kinds = open("path_kind");
  read_rows(offsets.get(), H5T_NATIVE_INT64, 0, rows_of(offsets.get(), ctx), 0, s_->off, ctx);
  read_rows(kinds.get(), H5T_NATIVE_UINT8, 0, rows_of(kinds.get(), ctx), 0, s_->kind, ctx);
  if (s_->off.empty()) s_->off.push_back(0);
}

PathReader::~PathReader() {
  const auto lock = h5::library_lock();
  s_.reset();
}

std::size_t PathReader::paths() const { return s_->off.size() - 1; }

std::size_t PathReader::points(std::size_t first, std::size_t count) const {
  return static_cast<std::size_t>(s_->off.at(first + count) - s_->off.at(first));
}

void PathReader::read(std::size_t first, std::size_t count, ClChunk& c) {
  const auto lock = h5::library_lock();
  const auto p0 = static_cast<hsize_t>(s_->off.at(first));
  const auto n = static_cast<hsize_t>(s_->off.at(first + count)) - p0;
  read_rows(s_->pts.get(), H5T_NATIVE_DOUBLE, p0, n, 3, c.xyz, s_->ctx);
  read_rows(s_->contact.get(), H5T_NATIVE_UINT8, p0, n, 0, c.contact, s_->ctx);
  c.path_sizes.clear();
  c.path_kinds.clear();
  for (std::size_t k = first; k < first + count; ++k) {
    c.path_sizes.push_back(static_cast<std::uint32_t>(s_->off[k + 1] - s_->off[k]));
    c.path_kinds.push_back(s_->kind[k]);
  }
}

void read_paths(const std::filesystem::path& file, const std::string& job,
                const std::function<void(const ClChunk&)>& sink, std::size_t points) {
  PathReader reader(file, job);
  ClChunk c;
  for (std::size_t p = 0; p < reader.paths();) {
    // Whole paths from p up to about `points` points.
    std::size_t e = p + 1;
    while (e < reader.paths() && reader.points(p, e + 1 - p) <= points) ++e;
    reader.read(p, e - p, c);
    sink(c);
    p = e;
  }
}

namespace {

// One scalar statistic: int64, float64 or string by its stored type.
StatValue read_stat(hid_t group, const std::string& name, const h5::Context& ctx) {
  h5::Handle ds = h5::own(H5Dopen2(group, name.c_str(), H5P_DEFAULT), ctx, "open stats/" + name);
  h5::Handle type = h5::own(H5Dget_type(ds.get()), ctx, "type of stats/" + name);
  StatValue s{name, std::int64_t{0}, string_attribute(ds.get(), "unit", ctx)};
  const H5T_class_t cls = H5Tget_class(type.get());
  if (cls == H5T_INTEGER) {
    std::int64_t v = 0;
    h5::check(H5Dread(ds.get(), H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, &v), ctx,
              "read stats/" + name);
    s.value = v;
  } else if (cls == H5T_FLOAT) {
    double v = 0;
    h5::check(H5Dread(ds.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, &v), ctx,
              "read stats/" + name);
    s.value = v;
  } else {
    h5::Handle mem = h5::utf8_string_type(ctx);
    char* v = nullptr;
    h5::check(H5Dread(ds.get(), mem.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, &v), ctx,
              "read stats/" + name);
    s.value = std::string(v ? v : "");
    H5free_memory(v);
  }
  return s;
}

}  // namespace

std::vector<StatValue> read_stats(const std::filesystem::path& file, const std::string& job) {
  const auto lock = h5::library_lock();
  const h5::Context ctx{file.string()};
  h5::Handle f = open_file(file, ctx);
  const std::string where = "jobs/" + job + "/stats";
  h5::Handle g = h5::own(H5Gopen2(f.get(), where.c_str(), H5P_DEFAULT), ctx, "open " + where);
  std::vector<std::string> names;
  hsize_t idx = 0;
  if (H5Literate(g.get(), H5_INDEX_CRT_ORDER, H5_ITER_INC, &idx, collect, &names) < 0)
    h5::fail(ctx, "list " + where);
  std::vector<StatValue> out;
  for (const std::string& n : names) out.push_back(read_stat(g.get(), n, ctx));
  return out;
}

std::optional<Float64Array> read_float64_array(const std::filesystem::path& file,
                                               const std::string& job, const std::string& path) {
  const auto lock = h5::library_lock();
  const h5::Context ctx{file.string()};
  h5::Handle f = open_file(file, ctx);
  const std::string where = "jobs/" + job + "/" + path;
  // Each link of the path must exist before the next is looked up.
  for (std::size_t slash = where.find('/'); slash != std::string::npos;
       slash = where.find('/', slash + 1))
    if (H5Lexists(f.get(), where.substr(0, slash).c_str(), H5P_DEFAULT) <= 0) return std::nullopt;
  if (H5Lexists(f.get(), where.c_str(), H5P_DEFAULT) <= 0) return std::nullopt;
  h5::Handle ds = h5::own(H5Dopen2(f.get(), where.c_str(), H5P_DEFAULT), ctx, "open " + where);
  h5::Handle space = h5::own(H5Dget_space(ds.get()), ctx, "space of " + where);
  hsize_t dims[2] = {0, 0};
  const int rank = H5Sget_simple_extent_dims(space.get(), dims, nullptr);
  Float64Array a;
  a.cols = rank == 2 ? static_cast<std::size_t>(dims[1]) : 0;
  read_rows(ds.get(), H5T_NATIVE_DOUBLE, 0, dims[0], a.cols, a.data, ctx);
  return a;
}

}  // namespace ncpath::out
