// ParallelLoop: every item once, parts contiguous, small loops on the
// caller, errors rethrown on the caller.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <numeric>
#include <stdexcept>
#include <thread>
#include <vector>

#include "core/clock.hpp"
#include "core/interrupt.hpp"
#include "core/parallel_loop.hpp"

using ashlar::ParallelLoop;

TEST(ParallelLoop, CoversEveryItemOnceInContiguousParts) {
  ParallelLoop loop(2, 10);
  for (int n : {10, 11, 1001}) {
    std::vector<int> hits(n, 0), part_of(n, -1);
    loop.run(n, [&](int begin, int end, int part) {
      for (int i = begin; i < end; ++i) {
        ++hits[i];
        part_of[i] = part;
      }
    });
    for (int i = 0; i < n; ++i) EXPECT_EQ(hits[i], 1) << n;
    EXPECT_EQ(part_of.front(), 0);
    EXPECT_EQ(part_of.back(), 1);
    EXPECT_TRUE(std::is_sorted(part_of.begin(), part_of.end()));
  }
}

TEST(ParallelLoop, SmallLoopsRunOnTheCaller) {
  ParallelLoop loop(2, 100);
  EXPECT_EQ(loop.parts_for(99), 1);
  const std::thread::id caller = std::this_thread::get_id();
  bool on_caller = false;
  loop.run(99, [&](int begin, int end, int part) {
    on_caller = std::this_thread::get_id() == caller && begin == 0 && end == 99 && part == 0;
  });
  EXPECT_TRUE(on_caller);
}

TEST(ParallelLoop, SumsMatchASerialSumOverManyCalls) {
  ParallelLoop loop(2, 1);
  std::vector<long long> values(100000);
  std::iota(values.begin(), values.end(), 1);
  for (int call = 0; call < 200; ++call) {
    std::vector<long long> sums(loop.parts(), 0);
    loop.run(static_cast<int>(values.size()), [&](int begin, int end, int part) {
      for (int i = begin; i < end; ++i) sums[part] += values[i];
    });
    EXPECT_EQ(std::accumulate(sums.begin(), sums.end(), 0LL), 100000LL * 100001 / 2);
  }
}

TEST(ParallelLoop, AnErrorInAHelperReachesTheCaller) {
  ParallelLoop loop(2, 1);
  EXPECT_THROW(loop.run(10, [](int, int, int part) {
    if (part == 1) throw std::runtime_error("helper failed");
  }), std::runtime_error);
  // The loop still works afterwards.
  std::atomic<int> items{0};
  loop.run(10, [&](int begin, int end, int) { items += end - begin; });
  EXPECT_EQ(items.load(), 10);
}

TEST(ParallelLoop, AnErrorInOnePartStopsTheOthers) {
  // Part 1 throws at once; part 0 runs until stop_requested() (or 10 s, a
  // lost stop): it must see the stop, and the error reach the caller.
  ParallelLoop loop(2, 1);
  std::atomic<bool> saw_stop{false};
  EXPECT_THROW(loop.run_parts(2, [&](int part) {
    if (part == 1) throw std::runtime_error("worker failed");
    const auto start = ashlar::Clock::now();
    while (!ashlar::stop_requested() && ashlar::seconds_since(start) < 10.0) std::this_thread::yield();
    saw_stop = ashlar::stop_requested();
  }), std::runtime_error);
  EXPECT_TRUE(saw_stop.load());
  // The next call starts without the stop, and the caller never had it.
  EXPECT_FALSE(ashlar::stop_requested());
  std::atomic<int> stopped{0};
  loop.run_parts(2, [&](int) { stopped += ashlar::stop_requested(); });
  EXPECT_EQ(stopped.load(), 0);
}

TEST(ParallelLoop, EveryPartAnswersToTheCallersDeadline) {
  ParallelLoop loop(3, 1);
  std::atomic<int> stopped{0};
  {
    const ashlar::DeadlineScope passed(ashlar::Clock::now() - std::chrono::seconds(1));
    loop.run_parts(3, [&](int) { stopped += ashlar::stop_requested(); });
  }
  EXPECT_EQ(stopped.load(), 3);
  // A call without a deadline gives its parts none.
  stopped = 0;
  loop.run_parts(3, [&](int) { stopped += ashlar::stop_requested(); });
  EXPECT_EQ(stopped.load(), 0);
}
