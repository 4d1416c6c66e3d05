// The event calendar (md_bridge/event_calendar.hpp) against a linear search: after every
// replacement its root is the earliest event, ties going to the lowest particle, for particle
// counts that fill the tree's last level partly, exactly and by one more.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "md_bridge/event_calendar.hpp"

namespace {

using granvv::md::EventCalendar;
using granvv::md::kNoEvent;

// The earliest time and its lowest particle, by looking at every one.
std::pair<int, double> earliest(const std::vector<double>& times) {
  int best = 0;
  for (int i = 1; i < int(times.size()); ++i) {
    if (times[std::size_t(i)] < times[std::size_t(best)]) best = i;
  }
  return {best, times[std::size_t(best)]};
}

TEST(EventCalendar, RootIsTheEarliestEventWithTiesToTheLowestParticle) {
  for (const int n : {1, 3, 4, 5, 16, 17, 63, 64, 65, 1000}) {
    std::mt19937_64 random{std::uint64_t(n)};
    // Times drawn from a few values, so that ties are frequent, and sometimes no event at all.
    std::uniform_int_distribution<int> value(0, 7);
    std::uniform_int_distribution<int> particle(0, n - 1);
    const auto draw = [&] { return value(random) == 7 ? kNoEvent : double(value(random)); };
    std::vector<double> times(static_cast<std::size_t>(n));
    for (double& t : times) t = draw();
    EventCalendar calendar;
    calendar.reset(times);
    for (int k = 0; k < 20 * n + 100; ++k) {
      const auto [i, t] = earliest(times);
      ASSERT_EQ(calendar.next_time(), t) << "n = " << n << ", replacement " << k;
      if (t != kNoEvent) {
        ASSERT_EQ(calendar.next(), i) << "n = " << n << ", replacement " << k;
      }
      // Replace the leader half the time (as the engine does after every event), else any one.
      const int j = k % 2 == 0 ? calendar.next() : particle(random);
      times[std::size_t(j)] = draw();
      calendar.set(j, times[std::size_t(j)]);
      ASSERT_EQ(calendar.time(j), times[std::size_t(j)]);
    }
  }
}

TEST(EventCalendar, EmptyAndUnsetCalendarsHaveNoEvent) {
  EventCalendar calendar;
  calendar.reset(5);
  EXPECT_EQ(calendar.next_time(), kNoEvent);
  calendar.set(3, 2.5);
  EXPECT_EQ(calendar.next(), 3);
  EXPECT_EQ(calendar.next_time(), 2.5);
  calendar.set(3, kNoEvent);
  EXPECT_EQ(calendar.next_time(), kNoEvent);
}

}  // namespace
