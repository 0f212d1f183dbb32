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
  if (!swept_) swept_ = std::make_shared<const MeshVerifier>(in_.mesh);
  return swept_;
}

MeshCache::MeshCache(const std::vector<JobSpec>& jobs) : jobs_(jobs), key_(jobs.size()) {
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    if (!uses_mesh(jobs[i])) continue;
    key_[i] = mesh_key(jobs[i]);
    last_use_[key_[i]] = i;
  }
}

std::shared_ptr<SharedMesh> MeshCache::get(std::size_t i, bool& shared) {
  const std::string& key = key_.at(i);
  if (key.empty())
    throw std::logic_error("MeshCache::get: job " + std::to_string(i) + " has no mesh");
  auto it = meshes_.find(key);
  shared = it != meshes_.end();
  if (shared) return it->second;
  auto mesh = std::make_shared<SharedMesh>(jobs_[i]);
  meshes_.emplace(key, mesh);
  return mesh;
}

void MeshCache::done(std::size_t i) {
  const std::string& key = key_.at(i);
  if (!key.empty() && last_use_[key] == i) meshes_.erase(key);
}

}  // namespace ncpath::jobs
