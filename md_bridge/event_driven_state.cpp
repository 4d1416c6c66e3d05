// The event-driven engine's whole state for a checkpoint (EventDrivenEngine::save_state's
// arrays) and its restore: every disk's straight flight from the epoch, its cell and place in
// the cell's list (the order its neighbours are gathered in), its collision count, its predicted
// partner and calendar entry, and, inside a segment, the segment's collision virial so far. With
// these the restored engine processes the same events in the same order with the same
// arithmetic as the uninterrupted one (docs/outputs.md, "What a resume reproduces").
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>

#include "md_bridge/event_driven_engine.hpp"

namespace granvv::md {

EngineArrays EventDrivenEngine::whole_state() const {
  const std::size_t n = disks_.size();
  EngineArrays a;
  const auto column = [&](const char* name, auto value) {
    std::vector<double> c(n);
    for (std::size_t i = 0; i < n; ++i) c[i] = double(value(i));
    a.push_back({name, std::move(c)});
  };
  column("disk_x", [&](std::size_t i) { return disks_[i].x; });
  column("disk_y", [&](std::size_t i) { return disks_[i].y; });
  column("disk_vx", [&](std::size_t i) { return disks_[i].vx; });
  column("disk_vy", [&](std::size_t i) { return disks_[i].vy; });
  column("id", [&](std::size_t i) { return id_[i]; });
  column("collisions", [&](std::size_t i) { return count_[i]; });
  column("event", [&](std::size_t i) { return event_[i]; });
  column("soonest_t", [&](std::size_t i) { return soonest_[i].t; });
  column("soonest_partner", [&](std::size_t i) { return soonest_[i].partner; });
  column("soonest_partner_collisions", [&](std::size_t i) { return soonest_[i].partner_count; });
  column("last_impact", [&](std::size_t i) { return last_impact_[i]; });
  column("calendar_t", [&](std::size_t i) { return calendar_.time(int(i)); });
  column("cell", [&](std::size_t i) { return cells_->cell_of(int(i)); });
  // Each disk's place in its cell's list: the order the candidates are gathered in.
  std::vector<double> place(n, 0.0);
  for (int c = 0; c < cells_->columns() * cells_->rows(); ++c) {
    int k = 0;
    for (int j = cells_->first(c); j >= 0; j = cells_->next(j)) place[std::size_t(j)] = k++;
  }
  a.push_back({"cell_place", std::move(place)});
  if (segment_.open) {
    a.push_back({"segment_virial", virial_sum_});
    a.push_back({"segment_tally", tally_.sums()});
  }
  return a;
}

void EventDrivenEngine::restore_whole(const EngineState& state, double segment_time) {
  const std::size_t n = std::size_t(options_.particles);
  const int cell_count = cells_->columns() * cells_->rows();
  std::map<std::string, const std::vector<double>*> arrays;
  for (const auto& [name, values] : state.arrays) arrays[name] = &values;
  const auto bad = [](const std::string& what) {
    throw std::invalid_argument("event-driven engine state: " + what);
  };
  const auto array = [&](const std::string& name, std::size_t size) -> const std::vector<double>& {
    const auto found = arrays.find(name);
    if (found == arrays.end()) bad("no array '" + name + "'");
    if (found->second->size() != size)
      bad("'" + name + "' has " + std::to_string(found->second->size()) + " values, not " +
          std::to_string(size));
    for (const double v : *found->second)
      if (std::isnan(v)) bad("'" + name + "' holds NaN");
    return *found->second;
  };
  // An integer column within [low, high].
  const auto integers = [&](const std::string& name, double low, double high) {
    const std::vector<double>& c = array(name, n);
    for (const double v : c)
      if (!(v >= low && v <= high && v == std::floor(v)))
        bad("'" + name + "' holds " + std::to_string(v) + ", outside the integers " +
            std::to_string(low) + " .. " + std::to_string(high));
    return c;
  };
  const auto finite = [&](const std::string& name) {
    const std::vector<double>& c = array(name, n);
    for (const double v : c)
      if (!std::isfinite(v)) bad("'" + name + "' holds " + std::to_string(v));
    return c;
  };
  const double count_limit = double(std::numeric_limits<std::uint32_t>::max());
  const auto& x = finite("disk_x");
  const auto& y = finite("disk_y");
  const auto& vx = finite("disk_vx");
  const auto& vy = finite("disk_vy");
  const auto& id = integers("id", 0, double(n) - 1);
  const auto& collisions = integers("collisions", 0, count_limit);
  const auto& event = integers("event", kCollision, 1);
  // Times of events still to come: none before the last sample. A disk's soonest collision is
  // never before its calendar entry (the earliest of it and its cell crossings), so neither is;
  // one in the past would be taken at once and move its disks back by that time.
  const auto still_to_come = [&](const std::string& name) -> const std::vector<double>& {
    const std::vector<double>& c = array(name, n);
    for (const double v : c)
      if (!(v >= t_))
        bad("'" + name + "' holds " + std::to_string(v) + ", before t = " + std::to_string(t_));
    return c;
  };
  const auto& soonest_t = still_to_come("soonest_t");
  const auto& partner = integers("soonest_partner", -1, double(n) - 1);
  const auto& partner_collisions = integers("soonest_partner_collisions", 0, count_limit);
  const auto& last_impact = array("last_impact", n);
  for (const double v : last_impact)  // an impact that happened (or none: -inf)
    if (!(v <= segment_time))
      bad("'last_impact' holds " + std::to_string(v) + ", after the state's time " +
          std::to_string(segment_time));
  const auto& calendar = still_to_come("calendar_t");
  // A collision on the calendar is with another disk; only a disk at rest and alone, never due,
  // has a collision entry without a partner.
  for (std::size_t i = 0; i < n; ++i)
    if (event[i] == kCollision && calendar[i] != kNever &&
        !(partner[i] >= 0.0 && partner[i] != double(i)))
      bad("disk " + std::to_string(i) + " is due to collide at t = " + std::to_string(calendar[i]) +
          " with partner " + std::to_string(partner[i]));
  const auto& cell = integers("cell", 0, cell_count - 1);
  const auto& place = integers("cell_place", 0, double(n) - 1);
  std::vector<char> seen(n, 0);
  for (const double i : id) {
    if (seen[std::size_t(i)]++) bad("'id' repeats " + std::to_string(i));
  }
  const auto number = [&](const std::string& name) {
    for (const auto& [key, value] : state.numbers)
      if (key == name && std::isfinite(value)) return value;
    bad("no finite '" + name + "'");
    return 0.0;
  };
  int initialised = 0;
  MPI_Initialized(&initialised);
  if (initialised) MPI_Comm_rank(options_.comm, &rank_);
  disks_.assign(n, Disk{});
  count_.assign(n, 0);
  event_.assign(n, kCollision);
  soonest_.assign(n, Soonest{});
  last_impact_.assign(n, -kNever);
  id_.assign(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    disks_[i] = {x[i], y[i], vx[i], vy[i]};
    id_[i] = int(id[i]);
    count_[i] = std::uint32_t(collisions[i]);
    event_[i] = std::int8_t(event[i]);
    soonest_[i] = {soonest_t[i], int(partner[i]), std::uint32_t(partner_collisions[i])};
    last_impact_[i] = last_impact[i];
  }
  epoch_ = number("epoch");
  ordered_at_ = std::llround(number("ordered_at"));
  // Each cell's list in its saved order: inserted at the head, the last place first.
  std::vector<std::size_t> by_place(n);
  for (std::size_t i = 0; i < n; ++i) by_place[i] = i;
  std::stable_sort(by_place.begin(), by_place.end(),
                   [&](std::size_t a, std::size_t b) { return place[a] > place[b]; });
  cells_->clear();
  for (const std::size_t i : by_place) cells_->insert(int(i), int(cell[i]));
  calendar_.reset(int(n));
  calendar_.reset(calendar);
  mass_.assign(n, 1.0);
  const ParticleFrame& p = state.particles;
  x_ = p.x.size() == 3 * n ? p.x : std::vector<double>(3 * n, 0.0);
  v_ = p.v.size() == 3 * n ? p.v : std::vector<double>(3 * n, 0.0);
  const std::size_t bins = std::size_t(options_.virial_bins);
  virial_sum_.assign(bins, 0.0);
  virial_ = CollisionVirial{t_, t_, 0.0, std::vector<double>(bins, 0.0)};
  collision_rate_ = 0.0;
  if (arrays.count("segment_virial")) {  // saved inside a segment: it goes on from there
    virial_sum_ = array("segment_virial", bins);
    tally_.begin(n);
    tally_.continue_from(array("segment_tally", CollisionVirialTally::kPerParticle * n));
    segment_.open = true;
    segment_.begin = number("segment_begin");
    segment_.window_begin = number("segment_window_begin");
    segment_.now = segment_time;
    segment_.events_at_begin = std::llround(number("segment_events_at_begin"));
    segment_.window_collisions = std::llround(number("segment_window_collisions"));
    segment_collisions_ = std::llround(number("segment_collisions"));
  }
}

}  // namespace granvv::md
