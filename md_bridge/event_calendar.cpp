#include "md_bridge/event_calendar.hpp"

#include <algorithm>

namespace granvv::md {

void EventCalendar::reset(int particles) {
  reset(std::vector<double>(std::size_t(std::max(particles, 0)), kNoEvent));
}

// Entrant k of a match leads the subtree of the k-th quarter of its particles, so on equal
// times the lower entrant holds the lower particle: a strict comparison of times alone breaks
// ties by the lowest particle. The choice is made on indices, without branches: the outcome
// of comparing event times is random, and a mispredicted branch per comparison cost more than
// the comparisons themselves.
EventCalendar::Leader EventCalendar::Match::winner() const {
  const int a = int(entrant[1].t < entrant[0].t);
  const int b = 2 + int(entrant[3].t < entrant[2].t);
  return entrant[a + (b - a) * int(entrant[b].t < entrant[a].t)];
}

void EventCalendar::reset(const std::vector<double>& times) {
  particles_ = times.size();
  // Internal nodes 1 + 4 + ... + 4^(levels - 1) above 4^levels leaves.
  std::size_t leaves = 4, internal = 1;
  while (leaves < particles_) internal += leaves, leaves *= 4;
  first_leaf_ = internal;
  matches_.assign(internal, Match{});
  for (std::size_t k = 0; k < leaves; ++k) {
    const std::size_t node = first_leaf_ + k;
    matches_[(node - 1) / 4].entrant[(node - 1) % 4] = {k < particles_ ? times[k] : kNoEvent,
                                                        int(k)};
  }
  for (std::size_t node = internal; node-- > 1;)
    matches_[(node - 1) / 4].entrant[(node - 1) % 4] = matches_[node].winner();
  root_ = matches_[0].winner();
}

double EventCalendar::time(int i) const {
  const std::size_t node = first_leaf_ + std::size_t(i);
  return matches_[(node - 1) / 4].entrant[(node - 1) % 4].t;
}

void EventCalendar::set(int i, double t) {
  std::size_t node = first_leaf_ + std::size_t(i);
  matches_[(node - 1) / 4].entrant[(node - 1) % 4].t = t;
  // Replays the matches up the path; a match whose winner and time stay the same leaves every
  // match above it unchanged.
  for (node = (node - 1) / 4; node >= 1; node = (node - 1) / 4) {
    const Leader won = matches_[node].winner();
    Leader& held = matches_[(node - 1) / 4].entrant[(node - 1) % 4];
    if (won.i == held.i && won.t == held.t) return;
    held = won;
  }
  root_ = matches_[0].winner();
}

}  // namespace granvv::md
