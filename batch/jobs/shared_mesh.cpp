#include "batch/jobs/shared_mesh.hpp"

#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "engine/offset_elements_build.hpp"
#include "engine/run_control.hpp"
#include "kernels/mesh/mesh_transform.hpp"

namespace ncpath::jobs {

namespace {

bool uses_mesh(const JobSpec& job) {
  switch (job.operation) {
    case Operation::kRaster:
    case Operation::kScan:
    case Operation::kZLevel:
    case Operation::kPencil:
    case Operation::kFillet:
    case Operation::kDrop:
      return job.error.empty();
    default:
      return false;
  }
}

std::string product_name_scan(double radius) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "scan|%a", radius);
  return buf;
}

// The file (made absolute, lexically normal) and the transform's values, exactly (hex floats).
std::string mesh_key(const JobSpec& job) {
  std::error_code ec;
  const std::filesystem::path file = std::filesystem::absolute(job.input, ec).lexically_normal();
  const MeshTransform& t = job.transform;
  char buf[256];
  std::snprintf(buf, sizeof buf, "|%a|%a,%a,%a|%a", t.scale, t.translate.x(), t.translate.y(),
                t.translate.z(), t.fit_xy_mm.value_or(-1.0));
  return (ec ? job.input : file).string() + buf;
}

}  // namespace

SharedMesh::SharedMesh(const JobSpec& job) {
  Stopwatch clock;
  in_ = io::read_mesh(job.input);
  const TransformOutcome tr = apply_transform(job.transform, in_.mesh);
  if (!tr.ok()) throw std::invalid_argument("transform." + tr.error);
  scale_ = tr.scale;
  read_s_ = clock.seconds();
}

std::shared_ptr<const MeshVerifier> SharedMesh::swept_index() {
  return swept_.get([&] { return std::make_shared<const MeshVerifier>(in_.mesh); });
}

void SharedMesh::expect_jobs(const std::string& name, std::size_t jobs) {
  const std::lock_guard<std::mutex> lock(products_mutex_);
  products_[name].jobs_left = jobs;
}

template <class T, class Make>
std::shared_ptr<const T> SharedMesh::product(const std::string& name, Make&& make) {
  Product* p;
  {
    const std::lock_guard<std::mutex> lock(products_mutex_);
    p = &products_[name];  // map nodes stay put until erased, after their last job
  }
  return std::static_pointer_cast<const T>(
      p->value.get([&] { return std::shared_ptr<const void>(make()); }));
}

std::shared_ptr<const ScanElements> SharedMesh::scan_elements(double radius) {
  return product<ScanElements>(product_name_scan(radius), [&] {
    return std::make_shared<const ScanElements>(build_scan_elements(in_.mesh, radius));
  });
}

std::shared_ptr<const ConditionedMesh> SharedMesh::conditioned() {
  return product<ConditionedMesh>("conditioned", [&] {
    return std::make_shared<const ConditionedMesh>(condition_for_slicing(in_.mesh));
  });
}

void SharedMesh::release(const std::string& name) {
  const std::lock_guard<std::mutex> lock(products_mutex_);
  auto it = products_.find(name);
  if (it != products_.end() && it->second.jobs_left > 0 && --it->second.jobs_left == 0)
    products_.erase(it);
}

std::string product_name(const JobSpec& job) {
  if (!job.error.empty()) return "";
  switch (job.operation) {
    case Operation::kScan:  // a scan job with another tool fails before it needs elements
      return job.tool.type == CutterType::kBall ? product_name_scan(job.tool.radius) : "";
    case Operation::kZLevel:
      return job.zlevel.condition ? "conditioned" : "";
    case Operation::kPencil:
    case Operation::kFillet:
      return "conditioned";
    default:
      return "";
  }
}

MeshCache::MeshCache(const std::vector<JobSpec>& jobs) : jobs_(jobs), key_(jobs.size()) {
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    if (!uses_mesh(jobs[i])) continue;
    key_[i] = mesh_key(jobs[i]);
    auto [it, fresh] = entries_.try_emplace(key_[i]);
    if (fresh) it->second.first_user = i;
    ++it->second.users_left;
    if (const std::string name = product_name(jobs[i]); !name.empty())
      it->second.product_jobs[name].push_back(i);
  }
}

void MeshCache::note_product(const Entry& entry, std::size_t i, MeshUse& use) const {
  const std::string name = product_name(jobs_[i]);
  if (name.empty()) return;
  const std::vector<std::size_t>& group = entry.product_jobs.at(name);
  if (group.size() < 2) return;
  use.product = name;
  use.product_shared = group.front() != i;
}

MeshUse MeshCache::get(std::size_t i) {
  const std::string& key = key_.at(i);
  if (key.empty())
    throw std::logic_error("MeshCache::get: job " + std::to_string(i) + " has no mesh");
  Stopwatch clock;
  MeshUse use;
  Entry* entry;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    entry = &entries_.at(key);  // stays put: erased only after this job's done(i)
  }
  use.shared = entry->first_user != i;
  note_product(*entry, i, use);
  bool read_here = false;
  use.mesh = entry->mesh.get([&] {
    read_here = true;
    auto mesh = std::make_shared<SharedMesh>(jobs_[i]);
    for (const auto& [name, group] : entry->product_jobs)
      if (group.size() > 1) mesh->expect_jobs(name, group.size());
    return mesh;
  });
  use.seconds = read_here ? use.mesh->read_s() : clock.seconds();
  return use;
}

void MeshCache::done(std::size_t i) {
  const std::string& key = key_.at(i);
  if (key.empty()) return;
  const std::lock_guard<std::mutex> lock(mutex_);
  auto it = entries_.find(key);
  if (it != entries_.end() && --it->second.users_left == 0) entries_.erase(it);
}

}  // namespace ncpath::jobs
