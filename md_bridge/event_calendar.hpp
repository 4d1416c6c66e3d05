#pragma once
// The event calendar of an event-driven particle engine: the time of every particle's next event
// (a collision, or leaving its cell; what it is, the engine keeps), one entry per particle,
// replaced in place when the particle's prediction changes, and the earliest of them.
//
// A bucket queue in the manner of Paul, J. Comput. Phys. 221, 615 (2007) (after Brown's
// calendar queue, Commun. ACM 31, 1220 (1988)): time is cut into buckets of a fixed width, a
// ring of them covers the near future, and each particle's entry sits in the doubly linked list
// of its bucket (or of an overflow list beyond the ring). Replacing an entry is an unlink and a
// link, O(1); the earliest entry is the smallest of the first non-empty bucket (found through a
// bit per bucket, 64 buckets to a word), by looking at its few members. The width is tuned to
// about half an entry per bucket near the front from the times themselves (at every reset, and
// again when the lists grow long), so the cost does not grow with the number of particles as a
// tree's log N does. The order is exact: the earliest time, ties to the lowest particle, whatever
// the width. A collision entry is checked when it comes due, by the partner's collision count
// (Lubachevsky, J. Comput. Phys. 94, 255 (1991); Rapaport, The Art of Molecular Dynamics
// Simulation, ch. 14).
#include <cstdint>
#include <limits>
#include <vector>

#include "md_bridge/linked_lists.hpp"

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
  double time(int i) const { return time_[std::size_t(i)]; }
  // The particle whose event is the earliest (ties: the lowest index, the same on every
  // platform), and its time (kNoEvent when no particle has an event).
  int next();
  double next_time();

 private:
  static constexpr std::int64_t kBeyond = std::numeric_limits<std::int64_t>::max();
  std::int64_t bucket_at(double t) const;
  // The list an entry of bucket k is in: its ring slot, or the overflow list (index ring_).
  std::size_t list_of(std::int64_t bucket) const;
  // Puts entry i in the list of its bucket, and takes it out.
  void link(int i, std::int64_t bucket);
  void unlink(int i);
  // Bucket width and ring from the present times; every entry placed again.
  void tune();
  // The ring starting at bucket `base`, and every entry placed in it or beyond it.
  void place_all(std::int64_t base);
  void find_leader();

  std::vector<double> time_;
  std::vector<std::int64_t> bucket_;     // absolute bucket of each entry, kBeyond in overflow
  LinkedLists lists_;                    // one per ring slot, then the overflow list
  std::vector<std::uint64_t> occupied_;  // a bit per ring slot: its list is not empty
  std::size_t ring_ = 1;                 // slots in the ring (a power of 2)
  double per_width_ = 1.0;               // 1 / the bucket width
  std::int64_t base_ = 0;                // the ring holds buckets base_ .. base_ + ring_ - 1
  std::int64_t current_ = 0;             // buckets base_ .. current_ - 1 are empty
  int leader_ = -1;                      // the earliest entry, -1 until found again
  // Entries looked at to find leaders since the last tuning, and how many leaders.
  std::uint64_t looked_at_ = 0, found_ = 0;
};

}  // namespace granvv::md
