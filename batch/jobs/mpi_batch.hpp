#pragma once
// A batch over MPI ranks (`mpirun -np N ncpath-mpi run batch.toml`, docs/mpi.md): the same
// one output file as run_batch, with the same datasets, whatever the number of ranks.
//
// Rank 0 hands tasks out one at a time, largest first (by estimate_job_bytes, then batch
// order), to the rank that asks: a slow job does not hold up the others' hand-out. A task is
// a job, or one band of a raster job more than its share of the batch, which runs as one band
// per rank (split_job.hpp); rank 0 joins a split job's bands into one job once all are back.
// Every rank runs the tasks it is given, each alone into a CL file of its own (run_batch on
// a one-job batch: the same datasets as in a whole batch) in its temporary folder; rank 0
// runs tasks too, in a thread beside the one that talks MPI. A rank other than 0 sends its file's
// bytes to rank 0, which copies the jobs into the output in batch order as they come in
// (out::ClFile::copy_job, flushed after each), so that a batch whose ranks die leaves a
// readable file with every job copied so far. A job that fails fails alone, on whichever
// rank ran it.
//
// Built only when MPI is found (target ncpath-mpi); the serial ncpath does not use it.
#include <string>
#include <vector>

#include "batch/jobs/job_runner.hpp"
#include "batch/jobs/job_spec.hpp"

namespace ncpath::jobs {

// Every job's outcome and where it ran ("rank 2", "3 bands on ranks 0 2 1"), in batch
// order; filled on rank 0 only.
struct MpiBatchResult {
  std::vector<JobOutcome> outcomes;
  std::vector<std::string> where;
};

// Collective over MPI_COMM_WORLD (MPI initialised with at least MPI_THREAD_FUNNELED). Rank 0
// returns every job's outcome; the other ranks return an empty result. Throws
// std::runtime_error on rank 0 when the output file cannot be written. The observer's
// job_finished is called on rank 0, from its MPI thread, as each job's result comes in.
MpiBatchResult run_batch_mpi(const BatchSpec& batch, const BatchObserver& observer);

}  // namespace ncpath::jobs
