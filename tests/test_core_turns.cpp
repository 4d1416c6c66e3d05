// The cores passed round among more members than cores (scene/core_turns.hpp): never more
// holders than cores, every waiting thread gets its turn, a holder that fails gives its core
// back, and with a slice of zero the cores rotate at every yield point.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <optional>
#include <stdexcept>
#include <thread>
#include <vector>

#include "scene/core_turns.hpp"

namespace granvv::app {
namespace {

struct HolderCount {
  std::atomic<int> now{0};
  std::atomic<int> most{0};
  void enter() {
    const int n = ++now;
    int seen = most.load();
    while (n > seen && !most.compare_exchange_weak(seen, n)) {
    }
  }
  void leave() { --now; }
};

TEST(CoreTurns, NeverMoreHoldersThanCoresAndEveryThreadFinishes) {
  for (const int cores : {1, 2, 3}) {
    CoreTurns turns(cores, 0.0);
    HolderCount holders;
    std::atomic<int> finished{0};
    std::vector<std::thread> threads;
    for (int k = 0; k < 7; ++k) {
      threads.emplace_back([&] {
        CoreTurn turn(&turns);
        for (int step = 0; step < 200; ++step) {
          holders.enter();
          std::this_thread::yield();
          holders.leave();
          turn.offer();  // slice 0: the core passes whenever another thread waits
        }
        ++finished;
      });
    }
    for (auto& t : threads) t.join();
    EXPECT_EQ(finished.load(), 7);
    EXPECT_LE(holders.most.load(), cores) << cores << " cores";
    EXPECT_GE(holders.most.load(), 1);
  }
}

// With more threads than cores and a slice of zero, a thread does not run to its end before the
// others start: each thread's steps interleave with the others' (processor sharing), so the
// first thread to finish has seen every other thread make progress.
TEST(CoreTurns, ASliceOfZeroRotatesTheCores) {
  CoreTurns turns(1, 0.0);
  constexpr int kThreads = 3, kSteps = 100;
  std::vector<std::atomic<int>> steps(kThreads);
  std::vector<int> others_at_first_finish;
  std::atomic<bool> first_done{false};
  std::optional<CoreTurn> gate;  // holds the core until every thread waits for it
  gate.emplace(&turns);
  std::vector<std::thread> threads;
  for (int k = 0; k < kThreads; ++k) {
    threads.emplace_back([&, k] {
      CoreTurn turn(&turns);
      for (int s = 0; s < kSteps; ++s) {
        ++steps[k];
        turn.offer();
      }
      bool expected = false;
      if (first_done.compare_exchange_strong(expected, true)) {
        for (int j = 0; j < kThreads; ++j) {
          if (j != k) others_at_first_finish.push_back(steps[j].load());
        }
      }
    });
  }
  while (turns.waiting() < kThreads) std::this_thread::yield();
  gate.reset();
  for (auto& t : threads) t.join();
  ASSERT_EQ(others_at_first_finish.size(), std::size_t(kThreads - 1));
  // Run to completion in turn, the first to finish would see the others at 0 (not started) or
  // at kSteps; in turns, they are part of the way.
  for (const int s : others_at_first_finish) {
    EXPECT_GT(s, kSteps / 2) << "the cores did not rotate";
  }
}

// A long slice: a holder keeps its core while the slice lasts, whoever waits; the waiter gets
// it when the holder's scope ends (as it ends when a member's run throws).
TEST(CoreTurns, AHolderKeepsItsCoreWithinTheSliceAndGivesItBackAtTheEnd) {
  CoreTurns turns(1, 3600.0);
  std::atomic<int> waiter_steps{0};
  std::optional<CoreTurn> holder;
  holder.emplace(&turns);
  std::thread waiter([&] {
    CoreTurn turn(&turns);
    ++waiter_steps;
  });
  while (turns.waiting() < 1) std::this_thread::yield();
  for (int s = 0; s < 100; ++s) holder->offer();
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  EXPECT_EQ(waiter_steps.load(), 0);
  holder.reset();
  waiter.join();
  EXPECT_EQ(waiter_steps.load(), 1);
}

TEST(CoreTurns, NoCoresOrANegativeSliceIsRefused) {
  EXPECT_THROW(CoreTurns(0, 0.5), std::invalid_argument);
  EXPECT_THROW(CoreTurns(2, -1.0), std::invalid_argument);
}

}  // namespace
}  // namespace granvv::app
