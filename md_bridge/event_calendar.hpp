#pragma once
// The event calendar of an event-driven particle engine: every particle's next event (a
// collision with a partner, or leaving its cell) in a priority queue, earliest first. Entries
// are never removed when they go stale: each carries the collision counts of its particles at
// the time it was predicted, and is valid only while both counts are unchanged (lazy
// invalidation; Lubachevsky, J. Comput. Phys. 94, 255 (1991); Rapaport, The Art of Molecular
// Dynamics Simulation, ch. 14).
#include <cstdint>
#include <queue>
#include <vector>

namespace granvv::md {

struct ParticleEvent {
  double t = 0.0;
  int i = 0;                  // the particle whose next event this is
  int partner = -1;           // the other disk of a collision; -1: i leaves its cell
  std::uint32_t count_i = 0;  // collision counts when predicted
  std::uint32_t count_partner = 0;
  bool is_collision() const { return partner >= 0; }
};

class EventCalendar {
 public:
  void clear();
  void push(const ParticleEvent& e) { queue_.push(e); }
  bool empty() const { return queue_.empty(); }
  const ParticleEvent& next() const { return queue_.top(); }
  void pop() { queue_.pop(); }
  std::size_t size() const { return queue_.size(); }

 private:
  // Earliest first; ties by particle, so that the order is the same on every platform.
  struct Later {
    bool operator()(const ParticleEvent& a, const ParticleEvent& b) const {
      return a.t > b.t || (a.t == b.t && a.i > b.i);
    }
  };
  std::priority_queue<ParticleEvent, std::vector<ParticleEvent>, Later> queue_;
};

}  // namespace granvv::md
