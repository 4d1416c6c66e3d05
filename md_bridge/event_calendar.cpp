#include "md_bridge/event_calendar.hpp"

namespace granvv::md {

void EventCalendar::clear() {
  std::vector<ParticleEvent> storage;
  storage.reserve(queue_.size());
  queue_ = decltype(queue_)(Later{}, std::move(storage));
}

}  // namespace granvv::md
