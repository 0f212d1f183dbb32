#include "batch/jobs/shared_mesh.hpp"

#include <cstdio>
#include <filesystem>
#include <stdexcept>

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
  const std::lock_guard<std::mutex> lock(swept_mutex_);
  if (!swept_) swept_ = std::make_shared<const MeshVerifier>(in_.mesh);
  return swept_;
}

MeshCache::MeshCache(const std::vector<JobSpec>& jobs) : jobs_(jobs), key_(jobs.size()) {
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    if (!uses_mesh(jobs[i])) continue;
    key_[i] = mesh_key(jobs[i]);
    auto [it, fresh] = entries_.try_emplace(key_[i]);
    if (fresh) it->second.first_user = i;
    ++it->second.users_left;
  }
}

MeshUse MeshCache::get(std::size_t i) {
  const std::string& key = key_.at(i);
  if (key.empty())
    throw std::logic_error("MeshCache::get: job " + std::to_string(i) + " has no mesh");
  Stopwatch clock;
  MeshUse use;
  std::unique_lock<std::mutex> lock(mutex_);
  Entry& entry = entries_.at(key);
  use.shared = entry.first_user != i;
  if (entry.reading) {
    const std::shared_future<std::shared_ptr<SharedMesh>> mesh = entry.mesh;
    lock.unlock();
    use.mesh = mesh.get();
    use.seconds = clock.seconds();
    return use;
  }
  std::promise<std::shared_ptr<SharedMesh>> promise;
  entry.mesh = promise.get_future().share();
  entry.reading = true;
  lock.unlock();
  try {
    use.mesh = std::make_shared<SharedMesh>(jobs_[i]);
    promise.set_value(use.mesh);
  } catch (...) {
    promise.set_exception(std::current_exception());  // for the jobs waiting now
    lock.lock();
    entry.reading = false;  // later jobs try again
    throw;
  }
  use.seconds = use.mesh->read_s();
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
