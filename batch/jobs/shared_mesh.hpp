#pragma once
// The meshes of a batch, read once. Jobs that name the same input file with the same
// transform share the transformed mesh, its read statistics and the file's SHA-256, and the
// mesh's swept-tool index (engine/verify_mesh.hpp), which the job verifier and the chord
// guard both query, built on first use. Products of the mesh that several jobs need are
// built once for them and freed after the last of them ends: the scan elements of a ball
// radius (engine/scan.hpp: offset elements and plane indexes of both families) for scan jobs,
// and the mesh conditioned for slicing (condition_for_slicing) for z-level, pencil and
// fillet jobs. A mesh is released when the last job using it ends.
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
#include "kernels/mesh/condition.hpp"

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

  // `jobs` jobs will use the product `name` (product_name()).
  void expect_jobs(const std::string& name, std::size_t jobs);
  // The scan elements of both families with full plane indexes (any planes), and the mesh
  // conditioned for slicing; built on the first call (other callers help and wait). Throw
  // like build_scan_elements and condition_for_slicing.
  std::shared_ptr<const ScanElements> scan_elements(double radius);
  std::shared_ptr<const ConditionedMesh> conditioned();
  // A job that expected product `name` has ended: after the last, the product is freed.
  void release(const std::string& name);

 private:
  template <class T, class Make>
  std::shared_ptr<const T> product(const std::string& name, Make&& make);

  io::MeshReadResult in_;
  double scale_ = 0;
  double read_s_ = 0;
  par::Once<std::shared_ptr<const MeshVerifier>> swept_;
  struct Product {
    std::size_t jobs_left = 0;
    par::Once<std::shared_ptr<const void>> value;
  };
  std::mutex products_mutex_;                // the map; products are built outside it
  std::map<std::string, Product> products_;  // erased when its last job ends
};

// The product a job shares with other jobs of its mesh ("" for none): "scan|<radius>" for
// scan jobs, "conditioned" for z-level (conditioning), pencil and fillet jobs.
std::string product_name(const JobSpec& job);

// A job's mesh and how it got it.
struct MeshUse {
  std::shared_ptr<SharedMesh> mesh;
  // An earlier job of the batch uses the same mesh: it is read once for both. Depends on
  // the batch only, not on which job happened to ask first.
  bool shared = false;
  double seconds = 0;  // reading it, or waiting while another job read it
  // The job's product (product_name) when another job of the batch needs the same one, so
  // it is built once for them (else ""); and whether an earlier job needs it (it is then
  // built by another job: the statistics elements_shared and conditioned_shared).
  std::string product;
  bool product_shared = false;
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
    std::map<std::string, std::vector<std::size_t>> product_jobs;  // in batch order
    par::Once<std::shared_ptr<SharedMesh>> mesh;
  };
  void note_product(const Entry& entry, std::size_t i, MeshUse& use) const;

  const std::vector<JobSpec>& jobs_;
  std::vector<std::string> key_;  // per job; empty for jobs without a mesh
  std::mutex mutex_;
  std::map<std::string, Entry> entries_;
};

}  // namespace ncpath::jobs
