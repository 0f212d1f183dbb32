#pragma once
// The streaming loop of the operations that write while they compute: chunks of work units
// are computed on the workers while the calling thread hands the previous chunk to the sink
// (the writer, which must stay on one thread). The sink sees the chunks in order, so the
// output does not depend on the thread count.
#include <algorithm>
#include <cstddef>
#include <utility>

#include "engine/parallel.hpp"
#include "engine/run_control.hpp"

namespace ncpath {

// Units [0, n) in chunks of per_chunk: compute(c0, chunk) fills the chunk starting at unit c0
// (it may run on the workers); sink(chunk) consumes them in order on the calling thread;
// done(units) after each chunk (for progress). Checks control.cancel before every chunk
// (throws Cancelled). Adds the wall time of computing and of sinking to compute_s, sink_s.
template <class Chunk, class Compute, class Sink, class Done>
void stream_chunks(std::size_t n, std::size_t per_chunk, Compute&& compute, Sink&& sink,
                   Done&& done, RunControl& control, double& compute_s, double& sink_s) {
  if (n == 0) return;
  Chunk ready, next;
  {
    Stopwatch clock;
    compute(std::size_t{0}, ready);
    compute_s += clock.seconds();
  }
  for (std::size_t c0 = 0; c0 < n; c0 += per_chunk) {
    if (control.cancel.load()) throw Cancelled{};
    const std::size_t n0 = c0 + per_chunk;
    double background_s = 0, foreground_s = 0;
    par::overlap(
        [&] {
          if (n0 >= n) return;
          Stopwatch clock;
          compute(n0, next);
          background_s = clock.seconds();
        },
        [&] {
          Stopwatch clock;
          sink(ready);
          foreground_s = clock.seconds();
        });
    compute_s += background_s;
    sink_s += foreground_s;
    std::swap(ready, next);
    done(std::min(n, n0));
  }
}

}  // namespace ncpath
