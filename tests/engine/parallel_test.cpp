// engine/parallel.hpp's tasks and shared values: TaskGroup runs every task and its `after`
// (which may start more tasks); Once computes its value once however many tasks ask at the
// same time, the others getting the same value, and after a failure the next caller tries
// again.
#include "engine/parallel.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <mutex>
#include <stdexcept>
#include <vector>

namespace ncpath {
namespace {

TEST(Parallel, TaskGroupRunsEveryTaskAndWhatItsAfterStarts) {
  par::ThreadLimit limit(2);
  par::TaskGroup tasks;
  std::atomic<int> work{0}, after{0};
  std::mutex m;
  std::vector<int> order;
  for (int i = 0; i < 8; ++i)
    tasks.run(
        [&, i] {
          par::for_each(1000, 10, [&](std::size_t) { ++work; });
          const std::lock_guard<std::mutex> lock(m);
          order.push_back(i);
        },
        [&, i] {
          ++after;
          if (i == 7)  // starts one more task from outside the isolation
            tasks.run([&] { work += 5; }, [&] { ++after; });
        });
  tasks.wait();
  EXPECT_EQ(work.load(), 8 * 1000 + 5);
  EXPECT_EQ(after.load(), 9);
  EXPECT_EQ(order.size(), 8u);
}

TEST(Parallel, OnceComputesOnceForTasksAskingTogether) {
  par::ThreadLimit limit(2);
  par::Once<std::vector<int>> once;
  std::atomic<int> made{0};
  std::vector<const std::vector<int>*> seen(16, nullptr);
  par::for_each(16, 1, [&](std::size_t k) {
    seen[k] = &once.get([&] {
      ++made;
      std::vector<int> v(100000);
      par::for_each(v.size(), 1000, [&](std::size_t i) { v[i] = static_cast<int>(i); });
      return v;
    });
  });
  EXPECT_EQ(made.load(), 1);
  for (const auto* p : seen) {
    ASSERT_EQ(p, seen[0]);
    EXPECT_EQ((*p)[99999], 99999);
  }
}

TEST(Parallel, OnceTriesAgainAfterAFailure) {
  par::Once<int> once;
  int calls = 0;
  EXPECT_THROW(once.get([&]() -> int {
    ++calls;
    throw std::runtime_error("unreadable");
  }),
               std::runtime_error);
  EXPECT_EQ(once.get([&] { return ++calls; }), 2);
  EXPECT_EQ(once.get([&] { return ++calls; }), 2);  // kept
  EXPECT_EQ(calls, 2);
}

}  // namespace
}  // namespace ncpath
