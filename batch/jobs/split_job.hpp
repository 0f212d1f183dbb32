#pragma once
// One large job split across MPI ranks (docs/mpi.md, "One large job on several ranks").
//
// Band b of n runs as a job of its own (band_job): for a raster, its strips b, b + n,
// b + 2n, ... (engine/raster.hpp; every band gets its share of the part, so the ranks finish
// together), each line with its link to the next one as in the whole raster. Each band is
// computed, guarded and verified on the rank that runs it, into a CL file of its own, which
// also says how many paths each of its strips has (band/strip_paths). join_bands then writes
// the whole job from the bands' files:
//   - its CL datasets are the whole job's: the strips' paths in strip order, the bands taken
//     in turn (a ClJob's bytes depend only on the concatenated data, never on how it was
//     split);
//   - its verification is the bands' reports joined, moves and paths numbered job-wide, so
//     verify/worst and the job's status are the whole job's;
//   - its statistics are the bands' merged by split_stat_rule (counts summed, extremes
//     taken, times summed over the bands), plus mpi_bands, mpi_band_ranks,
//     mpi_band_seconds and mpi_join_s (docs/hdf5-schema.md).
// A statistic the rule does not know and that differs between bands stops the join with
// std::logic_error: a merged value is never made up.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "batch/jobs/job_runner.hpp"
#include "batch/jobs/job_spec.hpp"
#include "batch/output/cl_writer.hpp"

namespace ncpath::jobs {

// Whether `job` can run as bands: a valid raster job, without G-code (one program per job),
// verified in full or not at all (a sampled verification checks every 8th move of the whole
// job, which a band cannot number).
bool splittable(const JobSpec& job);

// The job that computes band `band` of `bands` of `job` (same name, same output datasets'
// layout and attributes).
JobSpec band_job(const JobSpec& job, std::uint32_t band, std::uint32_t bands);

// How a statistic is merged over the bands. kSame: every band has the same value (the mesh,
// the rectangle, the parameters); kSum: counts, and times (unit "s": seconds of work summed
// over the bands, not wall time); kMax, kMin: extremes; kFirst: band 0's (mpi_rank);
// kJob: set by join_bands for the whole job (total_s: its wall time, join included;
// points_per_s).
enum class StatMerge : std::uint8_t { kSame, kSum, kMax, kMin, kFirst, kJob };
StatMerge split_stat_rule(const out::StatValue& stat);

// The bands' statistics (each in the order its band wrote them) merged, in band 0's order;
// kJob ones are left as band 0's. std::logic_error when the bands wrote different names or a
// kSame statistic differs.
std::vector<out::StatValue> merge_band_stats(const std::vector<std::vector<out::StatValue>>& bands);

struct Band {
  std::filesystem::path file;  // the band's CL file; absent when the band could not write one
  JobOutcome outcome;
  int rank = 0;  // where it ran
};

// Writes `job` into `file` from its bands (in band order) and returns its outcome; `waited_s`
// is the job's wall time until its last band came back, as the caller measured it (total_s
// adds the join's own time). A band that failed other than by its verification fails the job
// with its status and message (naming the band and its rank), and the job then has no paths.
// std::runtime_error when a band's file cannot be read or the output cannot be written;
// std::logic_error as merge_band_stats.
JobOutcome join_bands(out::ClFile& file, const JobSpec& job, const std::vector<Band>& bands,
                      double waited_s);

}  // namespace ncpath::jobs
