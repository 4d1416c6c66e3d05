#include "md_bridge/event_calendar.hpp"

#include <algorithm>
#include <cmath>

namespace granvv::md {

namespace {

// Entries per bucket near the front of the calendar that the width aims at: fewer leave more
// empty buckets to step over (64 at a time in occupied_), more make every search for the
// earliest look at more entries. 0.25 and 0.5 were as fast, 1 3-7 % slower (10^4 disks,
// docs/md_benchmarks.md §4).
constexpr double kEntriesPerBucket = 0.5;
// The width is tuned again when finding the earliest entry looked at more than this many
// entries on average (the times have spread or gathered since the last tuning).
constexpr std::uint64_t kLookedAtPerFind = 8;
// Ring buckets per entry.
constexpr double kRingPerEntry = 4.0;

}  // namespace

void EventCalendar::reset(int particles) {
  reset(std::vector<double>(std::size_t(std::max(particles, 0)), kNoEvent));
}

void EventCalendar::reset(const std::vector<double>& times) {
  time_ = times;
  bucket_.assign(times.size(), kBeyond);
  tune();
}

std::int64_t EventCalendar::bucket_at(double t) const {
  if (!(t < kNoEvent)) return kBeyond;
  // Scaled by a positive number, truncated, and clamped far inside the range of the integer:
  // each monotone, so the order of the buckets stays that of the times.
  constexpr double kFar = 4e18;
  return std::int64_t(std::clamp(t * per_width_, -kFar, kFar));
}

std::size_t EventCalendar::list_of(std::int64_t bucket) const {
  if (bucket == kBeyond || bucket - base_ >= std::int64_t(ring_)) return ring_;
  return std::size_t(bucket) & (ring_ - 1);
}

void EventCalendar::link(int i, std::int64_t bucket) {
  const std::size_t list = list_of(bucket);
  bucket_[std::size_t(i)] = list == ring_ ? kBeyond : bucket;
  lists_.push_front(list, i);
  if (list != ring_) occupied_[list / 64] |= std::uint64_t(1) << (list % 64);
}

void EventCalendar::unlink(int i) {
  const std::size_t list = list_of(bucket_[std::size_t(i)]);
  lists_.remove(list, i);
  // The slot's bit cleared if that emptied it (without a branch: it is a coin toss).
  if (list != ring_)
    occupied_[list / 64] &= ~(std::uint64_t(lists_.first(list) < 0) << (list % 64));
}

void EventCalendar::tune() {
  double earliest = kNoEvent, sum = 0.0;
  std::size_t finite = 0;
  for (const double t : time_) {
    if (!(t < kNoEvent)) continue;
    earliest = std::min(earliest, t);
    sum += t, ++finite;
  }
  // The mean time to the entries from the earliest, tau: near the front about finite / tau
  // entries per unit time.
  const double tau = finite > 0 ? sum / double(finite) - earliest : 0.0;
  const double width = finite > 1 && tau > 0.0 && std::isfinite(tau)
                           ? kEntriesPerBucket * tau / double(finite)
                           : 1.0;
  per_width_ = 1.0 / width;
  // A ring of at least kRingPerEntry buckets per entry spans about kEntriesPerBucket kRingPerEntry
  // tau, so that it empties, and every entry is placed again, only that often.
  ring_ = 64;  // at least one word of occupied_
  while (double(ring_) < kRingPerEntry * double(finite)) ring_ *= 2;
  looked_at_ = found_ = 0;
  place_all(finite > 0 ? bucket_at(earliest) : 0);
}

void EventCalendar::place_all(std::int64_t base) {
  base_ = current_ = base;
  lists_.reset(ring_ + 1, time_.size());
  occupied_.assign(ring_ / 64, 0);
  for (std::size_t i = time_.size(); i-- > 0;) link(int(i), bucket_at(time_[i]));
  leader_ = -1;
}

void EventCalendar::set(int i, double t) {
  unlink(i);
  time_[std::size_t(i)] = t;
  const std::int64_t bucket = bucket_at(t);
  if (bucket < base_) {  // before the ring (never in the engine: events come after now)
    place_all(bucket);
    return;
  }
  link(i, bucket);
  current_ = std::min(current_, bucket);
  if (leader_ == i) {
    leader_ = -1;
  } else if (leader_ >= 0) {
    const double lead = time_[std::size_t(leader_)];
    if (t < lead || (t == lead && i < leader_)) leader_ = i;
  }
}

void EventCalendar::find_leader() {
  const std::int64_t end = base_ + std::int64_t(ring_);
  // The first occupied slot from current_ on, a word of 64 slots at a time.
  while (current_ < end) {
    const std::size_t slot = std::size_t(current_) & (ring_ - 1);
    const std::uint64_t ahead = occupied_[slot / 64] >> (slot % 64);
    if (ahead != 0) {
      current_ = std::min(end, current_ + __builtin_ctzll(ahead));
      break;
    }
    current_ += std::int64_t(64 - slot % 64);
  }
  current_ = std::min(current_, end);
  if (current_ == end) {
    // The ring is empty: every entry is in the overflow list. The next ring starts at the
    // earliest of them; with none finite, the lowest particle leads (at kNoEvent).
    double earliest = kNoEvent;
    int lowest = -1;
    for (int j = lists_.first(ring_); j >= 0; j = lists_.next(j)) {
      earliest = std::min(earliest, time_[std::size_t(j)]);
      lowest = lowest < 0 ? j : std::min(lowest, j);
    }
    if (earliest == kNoEvent) {
      leader_ = lowest;
      return;
    }
    place_all(bucket_at(earliest));
    find_leader();
    return;
  }
  // The earliest in the slot, ties to the lowest particle, chosen without branches.
  int best = lists_.first(std::size_t(current_) & (ring_ - 1));
  double earliest = time_[std::size_t(best)];
  for (int j = lists_.next(best); j >= 0; j = lists_.next(j)) {
    const double tj = time_[std::size_t(j)];
    best = tj < earliest || (tj == earliest && j < best) ? j : best;
    earliest = std::min(earliest, tj);
    ++looked_at_;
  }
  ++looked_at_;
  leader_ = best;
  ++found_;
  // Amortised: a tuning costs about one pass over the entries.
  if (found_ >= std::max<std::uint64_t>(1024, time_.size() / 4) &&
      looked_at_ > kLookedAtPerFind * found_) {
    tune();
    find_leader();
  }
}

int EventCalendar::next() {
  if (leader_ < 0) find_leader();
  return std::max(leader_, 0);
}

double EventCalendar::next_time() {
  if (leader_ < 0) find_leader();
  return leader_ < 0 ? kNoEvent : time_[std::size_t(leader_)];
}

}  // namespace granvv::md
