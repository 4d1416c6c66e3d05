#include "scene/core_turns.hpp"

#include <stdexcept>

namespace granvv::app {

CoreTurns::CoreTurns(int cores, double slice_seconds)
    : admitted_(cores > 0 ? std::uint64_t(cores) : 0),
      slice_(std::chrono::duration_cast<clock::duration>(
          std::chrono::duration<double>(slice_seconds))) {
  if (cores < 1 || !(slice_seconds >= 0.0)) {
    throw std::invalid_argument("CoreTurns: cores must be >= 1 and the slice >= 0 seconds");
  }
}

void CoreTurns::take(std::unique_lock<std::mutex>& lock) {
  const std::uint64_t ticket = issued_++;
  turn_.wait(lock, [&] { return ticket < admitted_; });
}

void CoreTurns::take() {
  std::unique_lock<std::mutex> lock(mutex_);
  take(lock);
}

void CoreTurns::give_back() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    ++admitted_;
  }
  turn_.notify_all();
}

void CoreTurns::offer(clock::time_point& since) {
  std::unique_lock<std::mutex> lock(mutex_);
  if (issued_ <= admitted_ || clock::now() - since < slice_) return;  // nobody waits, or too soon
  ++admitted_;
  turn_.notify_all();
  take(lock);
  since = clock::now();
}

int CoreTurns::waiting() {
  const std::lock_guard<std::mutex> lock(mutex_);
  return issued_ > admitted_ ? int(issued_ - admitted_) : 0;
}

}  // namespace granvv::app
