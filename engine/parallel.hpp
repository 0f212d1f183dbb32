#pragma once
// The one wrapper around oneTBB (STYLE.md habit 2). Everything in ncpath that runs in
// parallel goes through these functions; kernels never see them. With threads == 1 the
// same code runs sequentially, in index order, on the calling thread.
#include <algorithm>
#include <cstddef>
#include <memory>
#include <numeric>
#include <optional>
#include <span>

#include <tbb/blocked_range.h>
#include <tbb/collaborative_call_once.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>
#include <tbb/task_arena.h>
#include <tbb/task_group.h>

namespace ncpath::par {

// Caps the number of worker threads for the lifetime of the object (0 = all cores).
class ThreadLimit {
 public:
  explicit ThreadLimit(int threads) {
    if (threads > 0)
      control_ = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                       static_cast<std::size_t>(threads));
  }

 private:
  std::unique_ptr<tbb::global_control> control_;
};

// Threads the next parallel call may use.
inline int max_threads() {
  return static_cast<int>(
      tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
}

// One T per thread that uses it, made on the thread's first local() call and kept until the
// object ends: scratch buffers that parallel bodies reuse from one call to the next. What a
// body computes must not depend on what an earlier body left in them.
template <class T>
class PerThread {
 public:
  T& local() { return slots_.local(); }

 private:
  tbb::enumerable_thread_specific<T> slots_;
};

// Calls body(begin, end) over disjoint sub-ranges covering [0, n). `grain` is the smallest
// sub-range worth a task. Bodies must write only to slots they own (count, scan, fill).
template <class Body>
void for_ranges(std::size_t n, std::size_t grain, Body&& body) {
  if (n == 0) return;
  if (max_threads() <= 1 || n <= grain) {
    body(std::size_t{0}, n);
    return;
  }
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, grain == 0 ? 1 : grain),
                    [&](const tbb::blocked_range<std::size_t>& r) { body(r.begin(), r.end()); });
}

// Calls body(i) for every i in [0, n).
template <class Body>
void for_each(std::size_t n, std::size_t grain, Body&& body) {
  for_ranges(n, grain, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) body(i);
  });
}

// Runs background() on the workers while the calling thread runs foreground(), and
// returns when both are done (exceptions from either are rethrown). With one thread:
// background() first, then foreground(), on the calling thread.
template <class Background, class Foreground>
void overlap(Background&& background, Foreground&& foreground) {
  if (max_threads() <= 1) {
    background();
    foreground();
    return;
  }
  tbb::task_group group;
  group.run([&] { background(); });
  try {
    foreground();
  } catch (...) {
    group.wait();  // background() refers to the caller's locals: let it finish first
    throw;
  }
  group.wait();
}

// Tasks that run at the same time, such as the jobs of a batch. Each task's work is isolated:
// a thread waiting inside one task's parallel loops helps only with that task's loops, never
// starts another task, so a task's locks and per-thread buffers stay its own. wait() runs
// tasks on the calling thread too. With one thread they run one after another.
class TaskGroup {
 public:
  // Runs work() as a task, then after() outside the isolation (it may run() more tasks).
  // Exceptions must not escape work() or after(): catch them there.
  template <class Work, class After>
  void run(Work work, After after) {
    group_.run([work = std::move(work), after = std::move(after)] {
      tbb::this_task_arena::isolate([&] { work(); });
      after();
    });
  }
  void wait() { group_.wait(); }

 private:
  tbb::task_group group_;
};

// A value computed once for threads (tasks) that may ask for it at the same time, e.g. jobs
// of a batch sharing a mesh: the first caller runs make(); the others help with its parallel
// loops (oneTBB collaborative_call_once) instead of blocking threads the computation could
// use. When make() throws, that caller gets the exception and the next caller tries again.
template <class T>
class Once {
 public:
  template <class Make>
  const T& get(Make&& make) {
    tbb::collaborative_call_once(flag_, [&] { value_.emplace(make()); });
    return *value_;
  }

 private:
  tbb::collaborative_once_flag flag_;
  std::optional<T> value_;
};

// Sorts [first, last) by `less`, which must be a strict total order (break ties!) so that
// the result does not depend on the thread count.
template <class It, class Less>
void sort(It first, It last, Less less) {
  if (max_threads() <= 1)
    std::sort(first, last, less);
  else
    tbb::parallel_sort(first, last, less);
}

// Exclusive prefix sum of counts into offsets (offsets.size() == counts.size() + 1). Cheap
// and sequential: it is the "scan" between a parallel count and a parallel fill.
template <class T, class U>
void exclusive_scan(std::span<const T> counts, std::span<U> offsets) {
  offsets[0] = 0;
  for (std::size_t i = 0; i < counts.size(); ++i) offsets[i + 1] = offsets[i] + counts[i];
}

}  // namespace ncpath::par
