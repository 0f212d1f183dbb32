#pragma once
// The meshes of a batch, read once. Jobs that name the same input file with the same
// transform share the transformed mesh, its read statistics and the file's SHA-256, and the
// mesh's swept-tool index (engine/verify_mesh.hpp), which the job verifier and the chord
// guard both query, built on first use; scan jobs with the same ball radius on it share its
// scan elements (engine/scan.hpp: offset elements and plane indexes of both families),
// released when the last of them ends. A mesh is released when the last job using it ends.
// Thread-safe: jobs running at the same time ask for their meshes from their own threads;
// the first to ask reads a mesh (builds an index) while the others help with its parallel
// loops (par::Once).
#include <cstddef>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "batch/io/mesh_reader.hpp"
#include "batch/jobs/job_spec.hpp"
#include "engine/parallel.hpp"
#include "engine/scan.hpp"
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

  // The swept-tool index of the mesh, built on the first call (other callers help and wait).
  std::shared_ptr<const MeshVerifier> swept_index();

  // `jobs` scan jobs with a ball of `radius` will use scan_elements(radius).
  void expect_scan_jobs(double radius, std::size_t jobs);
  // The scan elements of both families with full plane indexes (any planes), built on the
  // first call (other callers help and wait). Throws like build_scan_elements.
  std::shared_ptr<const ScanElements> scan_elements(double radius);
  // A scan job that called scan_elements(radius) has ended: after the last, they are freed.
  void release_scan_elements(double radius);

 private:
  io::MeshReadResult in_;
  double scale_ = 0;
  double read_s_ = 0;
  par::Once<std::shared_ptr<const MeshVerifier>> swept_;
  struct ScanShare {
    std::size_t jobs_left = 0;
    par::Once<std::shared_ptr<const ScanElements>> elements;
  };
  std::mutex scan_mutex_;             // the map; the elements are built outside it
  std::map<double, ScanShare> scan_;  // erased when its last job ends
};

// A job's mesh and how it got it.
struct MeshUse {
  std::shared_ptr<SharedMesh> mesh;
  // An earlier job of the batch uses the same mesh: it is read once for both. Depends on
  // the batch only, not on which job happened to ask first.
  bool shared = false;
  double seconds = 0;  // reading it, or waiting while another job read it
  // Scan jobs: another scan job of the batch uses the same mesh and ball radius, so the
  // scan elements are built once for them (mesh->scan_elements); and whether an earlier one
  // does (the elements are then built by another job, as `shared` for the mesh).
  bool share_scan_elements = false;
  bool scan_elements_shared = false;
};

class MeshCache {
 public:
  explicit MeshCache(const std::vector<JobSpec>& jobs);  // jobs must outlive the cache

  // The mesh of jobs[i], read now unless another job of the same file and transform read it
  // or is reading it (then this helps and waits). Throws like SharedMesh's constructor; a mesh
  // that failed to read is not kept (a later job using it reads it again and reports the
  // error).
  MeshUse get(std::size_t i);
  // Job i has ended: its mesh is released when no other job left uses it. Call it once for
  // every job, whatever its outcome.
  void done(std::size_t i);

 private:
  struct Entry {
    std::size_t first_user = 0;
    std::size_t users_left = 0;
    std::map<double, std::vector<std::size_t>> scan_jobs;  // by ball radius, in batch order
    par::Once<std::shared_ptr<SharedMesh>> mesh;
  };
  void note_scan_share(const Entry& entry, std::size_t i, MeshUse& use) const;

  const std::vector<JobSpec>& jobs_;
  std::vector<std::string> key_;  // per job; empty for jobs without a mesh
  std::mutex mutex_;
  std::map<std::string, Entry> entries_;
};

}  // namespace ncpath::jobs
