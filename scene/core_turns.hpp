#pragma once
// Turns on the cores for more members than cores. Members of a clustering scene differ in work
// by factors of two or more (each seed's clusters form differently), and which one is heavy
// shows only late in its run. Started in member order on J workers, a heavy member that comes
// last runs alone at the end while the other cores idle. Running one member more than there are
// cores, with the cores passed round in turn, shares them as processor sharing does: no member
// waits behind another, and the ensemble ends near max(heaviest member, total work / J)
// whatever the order of their weights. A member gives its core up only at its own yield points
// (samples and segment reports) and only after holding it for a slice, so the cost is one cache
// refill per slice. Members are independent: their results do not depend on the turns.
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>

namespace granvv::app {

class CoreTurns {
 public:
  using clock = std::chrono::steady_clock;
  // cores >= 1 held at a time; a holder yields after slice_seconds when another waits.
  CoreTurns(int cores, double slice_seconds);

  // Blocks until the calling thread holds a core; waiting threads are served first come, first
  // served.
  void take();
  void give_back();
  // At a yield point of a thread that holds a core since `since`: if another thread waits and
  // the slice is over, the core passes to the longest waiting one and this thread queues again;
  // `since` is then reset to when it got a core back.
  void offer(clock::time_point& since);
  // Threads waiting for a core now.
  int waiting();

 private:
  void take(std::unique_lock<std::mutex>& lock);
  std::mutex mutex_;
  std::condition_variable turn_;
  std::uint64_t issued_ = 0;    // tickets handed out, one per take
  std::uint64_t admitted_ = 0;  // tickets below this hold or held a core: cores + gives back
  clock::duration slice_;
};

// Holds a core for a scope (the member's run), given back however the scope ends.
class CoreTurn {
 public:
  explicit CoreTurn(CoreTurns* turns) : turns_(turns) {
    if (turns_) turns_->take();
    since_ = CoreTurns::clock::now();
  }
  ~CoreTurn() {
    if (turns_) turns_->give_back();
  }
  CoreTurn(const CoreTurn&) = delete;
  CoreTurn& operator=(const CoreTurn&) = delete;
  void offer() {
    if (turns_) turns_->offer(since_);
  }

 private:
  CoreTurns* turns_;
  CoreTurns::clock::time_point since_;
};

}  // namespace granvv::app
