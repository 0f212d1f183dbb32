#pragma once
// The meshes of a batch, read once. Jobs that name the same input file with the same
// transform share the transformed mesh, its read statistics and the file's SHA-256, and the
// mesh's swept-tool index (engine/verify_mesh.hpp), which the job verifier and the chord
// guard both query, built on first use. A mesh is released when the last job using it ends.
// Jobs run one after another (run_batch); none of this is thread-safe.
#include <cstddef>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "batch/io/mesh_reader.hpp"
#include "batch/jobs/job_spec.hpp"
#include "engine/verify_mesh.hpp"

namespace ncpath::jobs {

class SharedMesh {
 public:
  // Reads and transforms job.input: io::ReadError, std::invalid_argument ("transform. ...").
  explicit SharedMesh(const JobSpec& job);

  const io::MeshReadResult& in() const { return in_; }
  const TriangleMesh& mesh() const { return in_.mesh; }
  double transform_scale() const { return scale_; }
  double read_s() const { return read_s_; }  // reading and transforming (once)

  // The swept-tool index of the mesh, built on the first call.
  std::shared_ptr<const MeshVerifier> swept_index();

 private:
  io::MeshReadResult in_;
  double scale_ = 0;
  double read_s_ = 0;
  std::shared_ptr<const MeshVerifier> swept_;
};

class MeshCache {
 public:
  explicit MeshCache(const std::vector<JobSpec>& jobs);  // jobs must outlive the cache

  // The mesh of jobs[i], read now unless an earlier job of the same file and transform read
  // it (`shared` tells which). Throws like SharedMesh's constructor; a mesh that failed to
  // read is not kept (each job using it reports the error).
  std::shared_ptr<SharedMesh> get(std::size_t i, bool& shared);
  // Job i has ended: its mesh is released unless a later job uses it.
  void done(std::size_t i);

 private:
  const std::vector<JobSpec>& jobs_;
  std::vector<std::string> key_;                // per job; empty for jobs without a mesh
  std::map<std::string, std::size_t> last_use_;  // key -> last job index using it
  std::map<std::string, std::shared_ptr<SharedMesh>> meshes_;
};

}  // namespace ncpath::jobs
