#pragma once
// The event calendar of an event-driven particle engine: the time of every particle's next event
// (a collision, or leaving its cell; what it is, the engine keeps), one entry per particle,
// replaced in place when the particle's prediction changes, and the earliest of them. A complete
// tournament tree over the particles holds the earliest time of every subtree, so that replacing
// one entry replays only the matches on its path to the root (no allocation, no stale entries,
// Marin, Risso & Cordero, J. Comput. Phys. 109, 306 (1993)). Each match is among four, whose
// entries share one cache line: log4 N dependent loads per update. A collision entry is checked
// when it comes due, by the partner's collision count (Lubachevsky, J. Comput. Phys. 94, 255
// (1991); Rapaport, The Art of Molecular Dynamics Simulation, ch. 14).
#include <limits>
#include <vector>

namespace granvv::md {

constexpr double kNoEvent = std::numeric_limits<double>::infinity();

class EventCalendar {
 public:
  // Room for particles 0 .. particles - 1, none of them with an event (time kNoEvent).
  void reset(int particles);
  // The event times of particles 0 .. times.size() - 1 at once (linear time).
  void reset(const std::vector<double>& times);
  // Replaces the time of the next event of particle i.
  void set(int i, double t);
  double time(int i) const;
  // The particle whose event is the earliest (ties: the lowest index, the same on every
  // platform), and its time (kNoEvent when no particle has an event).
  int next() const { return root_.i; }
  double next_time() const { return root_.t; }

 private:
  struct Leader {
    double t;
    int i;
  };
  // The four children of one node, in one cache line.
  struct alignas(64) Match {
    Leader entrant[4];
    Leader winner() const;  // the earliest; ties: the lowest particle
  };
  // Node k's children are nodes 4k + 1 .. 4k + 4, held in matches_[k]; node 0 is the root, the
  // particles are the nodes from first_leaf_ on. Node k >= 1 is entrant (k - 1) % 4 of
  // matches_[(k - 1) / 4].
  std::size_t first_leaf_ = 0;
  std::size_t particles_ = 0;
  std::vector<Match> matches_;
  Leader root_{kNoEvent, 0};
};

}  // namespace granvv::md
