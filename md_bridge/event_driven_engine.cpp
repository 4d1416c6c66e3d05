#include "md_bridge/event_driven_engine.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

#include "md_bridge/hard_disk_collision.hpp"

namespace granvv::md {

namespace {

constexpr double kSigma = 1.0;  // disk diameter and mass are the units (particle_scene.hpp)
// Cells hold about this many disks on average (at least sigma wide): fewer cells mean more
// pairs to test per prediction, more cells more crossing events. 1 was the fastest of 0.7, 1
// and 2 in both a dilute and a dense gas (docs/md_benchmarks.md §4).
constexpr double kDisksPerCell = 1.0;
// The cell edge exceeds sigma by this much, so that a partner at contact is always in the
// neighbourhood despite the round-off of positions near a face.
constexpr double kCellMargin = 1e-9;
// After this many events per disk the disks are renumbered in the order of their cells, so
// that neighbours stay near each other in memory as the gas mixes (a disk crosses a cell about
// every event); the renumbering also tunes the calendar's buckets to the present event times.
// 2 was faster than 1 (by 3-4 %) and as fast as 4 (docs/md_benchmarks.md §4).
constexpr double kEventsPerReorder = 2.0;
// Cell crossings allowed per collision of the md.max_collision_rate budget: a dilute gas makes
// about 4 events per collision at phi = 0.05 and about 30 at phi = 0.01 (mean free path over
// cell size), so a segment beyond this many events is a loop of crossings, not a gas.
constexpr double kEventsPerBudgetedCollision = 100.0;

// The event-rate runaway rule, applied to every window of this many collisions per disk within
// a segment and to the whole segment: the collisions per disk and unit time over it must stay
// below md.max_collision_rate (1000 by default; the Enskog rate of md_haff's gas at T0 is 0.245,
// docs/physics.md §10). Inelastic collapse makes the collisions pile up while the clock stalls;
// a window catches it after 10 N collisions however long the segment, where the segment's own
// budget, md.max_collision_rate N (t - now), can be minutes of collisions.
constexpr double kRateWindowCollisionsPerDisk = 10.0;
// Events between two calls of the run's within-segment check (progress lines, signals,
// checkpoints): about 0.1 s of a core at the engine's rate of about 5e5 events per second.
constexpr long long kEventsPerCheck = 1 << 16;

constexpr const char* kWho = "the event-driven engine";

}  // namespace

// The help of each key begins with the engine's name, as the resolved case.toml shows it.
const EngineKeys& EventDrivenEngine::keys() {
  using hydro::ParameterRange;
  static const EngineKeys keys = {
      {"collapse_speed", 0.01, ParameterRange::closed(0, 10),
       "event_driven: impact speed u0 (sqrt(T0/m)) below which the restitution rises to 1, "
       "Bizon et al. 1998 (ends inelastic collapse); 0 = off"},
      {"contact_duration", 0.0, ParameterRange::closed(0, 1e6),
       "event_driven: t_c of the TC model (Luding & McNamara 1998), MD time: an impact within "
       "t_c of either disk's previous impact is elastic (ends inelastic collapse under load); "
       "0 = off"},
      {"contact_speed", 0.0, ParameterRange::closed(0, 10),
       "event_driven: the TC rule (md.contact_duration) applies only to impacts slower than this "
       "(sqrt(T0/m)), those of a packing rather than of the gas; 0 = to every impact"},
      {"elastic_speed", 0.0, ParameterRange::closed(0, 10),
       "event_driven: impact speed delta (sqrt(T0/m)) below which an impact is elastic, Ben-Naim "
       "et al. 1999 (ends inelastic collapse of a packing under load); 0 = off"},
      {"max_collision_rate", 1000.0, ParameterRange::closed(1, 1e9),
       "event_driven: collisions per disk and unit MD time beyond which a segment stops the run "
       "(event-rate runaway)"},
  };
  return keys;
}

const EngineKeys& EventDrivenEngine::atlas_keys() {
  using hydro::ParameterRange;
  static const EngineKeys keys = {
      {"particle_factors", std::vector<double>{},
       ParameterRange::increasing(ParameterRange::closed(0.01, 100)),
       "event_driven: particle counts as factors on the case's (md.box_width, and md.particles "
       "where set, times each; Lx and the area fraction kept), each at md.ensemble ([] = the "
       "case's count only)"},
      {"collapse_rule_limit", 0.01, ParameterRange::closed(0, 1),
       "event_driven: runs whose collapse rules changed more than this fraction of the "
       "collisions fail as collapse_rule_active"},
  };
  return keys;
}

EventDrivenEngine::EventDrivenEngine(EventDrivenOptions options)
    : options_(std::move(options)), made_(std::chrono::steady_clock::now()) {
  const CollapseRule& rule = options_.collapse;
  for (const auto& [key, value] : {std::pair{"md.collapse_speed", rule.collapse_speed},
                                   std::pair{"md.contact_duration", rule.contact_duration},
                                   std::pair{"md.elastic_speed", rule.elastic_speed},
                                   std::pair{"md.contact_speed", rule.contact_speed}}) {
    if (!(value >= 0.0 && std::isfinite(value)))
      throw std::invalid_argument(std::string(key) + " must be >= 0 and finite");
  }
  if (!(options_.max_collision_rate > 0.0))
    throw std::invalid_argument("md.max_collision_rate must be > 0");
  if (options_.virial_bins < 1) throw std::invalid_argument("md.bins must be >= 1");
  const double density = double(options_.particles) / (options_.box_length * options_.box_width);
  const double width = std::max(kSigma * (1.0 + kCellMargin), std::sqrt(kDisksPerCell / density));
  cells_ = std::make_unique<PeriodicCells>(
      options_.box_length, options_.box_width,
      std::min(width, std::min(options_.box_length, options_.box_width) / 3.0),
      int(options_.particles));
  if (cells_->cell_length() < kSigma || cells_->cell_width() < kSigma) {
    throw std::invalid_argument("the event-driven engine needs a box at least 3 sigma wide");
  }
}

std::unique_ptr<ParticleEngine> EventDrivenEngine::make(const ParticleEngineSetup& setup) {
  EventDrivenOptions o;
  o.restitution = setup.scene.restitution;
  o.box_length = setup.scene.box_length;
  o.box_width = setup.scene.box_width;
  o.particles = setup.scene.particles;
  o.collapse.collapse_speed = required_setting(setup.settings, "md.collapse_speed", kWho);
  o.collapse.contact_duration = required_setting(setup.settings, "md.contact_duration", kWho);
  o.collapse.elastic_speed = required_setting(setup.settings, "md.elastic_speed", kWho);
  o.collapse.contact_speed = required_setting(setup.settings, "md.contact_speed", kWho);
  o.max_collision_rate = required_setting(setup.settings, "md.max_collision_rate", kWho);
  o.virial_bins = int(std::lround(required_setting(setup.settings, "md.bins", kWho)));
  o.comm = setup.comm;
  return std::make_unique<EventDrivenEngine>(std::move(o));
}

CollisionRuleCheck EventDrivenEngine::check_collision_rule() {
  // Two disks alone in this engine's box, head on along x at approach speed kCheckSpeed.
  EventDrivenOptions alone = options_;
  alone.particles = 2;
  alone.comm = MPI_COMM_SELF;
  EventDrivenEngine pair(alone);
  const double u = std::max(
      {kCheckSpeed, 2.0 * options_.collapse.collapse_speed, 2.0 * options_.collapse.elastic_speed});
  // 1.5 sigma apart (at most half of any box the engine runs): they touch at t = 0.5 / u.
  pair.start({-0.75, 0.0, 0.0, 0.75, 0.0, 0.0}, {0.5 * u, 0.0, 0.0, -0.5 * u, 0.0, 0.0}, 0.0);
  pair.advance_to(1.0 / u);
  const double recoil = pair.v_[3] - pair.v_[0];
  const double r = pair.collisions() == 1 ? recoil / u : 0.0;
  std::ostringstream what;
  what << "a head-on collision at approach speed " << u
       << " through the event-driven engine: r = " << r
       << "; below md.collapse_speed = " << options_.collapse.collapse_speed
       << " r rises to 1 (Bizon et al. 1998)";
  if (options_.collapse.elastic_speed > 0.0)
    what << ", below md.elastic_speed = " << options_.collapse.elastic_speed << " it is 1";
  return {r, what.str()};
}

void EventDrivenEngine::start(const std::vector<double>& x, const std::vector<double>& v,
                              double t) {
  int initialised = 0;
  MPI_Initialized(&initialised);
  if (initialised) MPI_Comm_rank(options_.comm, &rank_);
  const int n = int(x.size() / 3);
  if (n != options_.particles) {
    throw std::invalid_argument("event-driven engine: " + std::to_string(n) +
                                " particles for a scene of " + std::to_string(options_.particles));
  }
  disks_.assign(std::size_t(n), Disk{});
  count_.assign(std::size_t(n), 0);
  event_.assign(std::size_t(n), kCollision);
  epoch_ = t;
  soonest_.assign(std::size_t(n), Soonest{});
  last_impact_.assign(std::size_t(n), -kNever);
  id_.assign(std::size_t(n), 0);
  cells_->clear();
  for (int i = 0; i < n; ++i) {
    Disk& d = disks_[std::size_t(i)];
    d.x = periodic_image(x[3 * std::size_t(i)], options_.box_length);
    d.y = periodic_image(x[3 * std::size_t(i) + 1], options_.box_width);
    d.vx = v[3 * std::size_t(i)];
    d.vy = v[3 * std::size_t(i) + 1];
    id_[std::size_t(i)] = i;
    cells_->insert(i, cells_->cell_at(d.x, d.y));
  }
  t_ = t;
  calendar_.reset(n);
  order_by_cell(t);
  for (int i = 0; i < n; ++i) predict(i, t);
  mass_.assign(std::size_t(n), 1.0);
  x_.assign(3 * std::size_t(n), 0.0);
  v_.assign(3 * std::size_t(n), 0.0);
  virial_sum_.assign(std::size_t(options_.virial_bins), 0.0);
  virial_ = CollisionVirial{t, t, 0.0, std::vector<double>(std::size_t(options_.virial_bins), 0.0)};
  collision_rate_ = 0.0;
  segment_ = Segment{};
  synchronise();
}

void EventDrivenEngine::set_up(const ParticleSample& sample) {
  start(sample.x, sample.v, 0.0);
  tally_.clear();
  events_ = collisions_ = crossings_ = changed_ = tc_elastic_ = speed_elastic_ = ordered_at_ = 0;
  stops_ = 0;
  ++runs_;
}

double EventDrivenEngine::minimum_image(double d, double length) const {
  if (d > 0.5 * length) return d - length;
  if (d < -0.5 * length) return d + length;
  return d;
}

void EventDrivenEngine::rebase(double t) {
  for (Disk& d : disks_) {
    d.x = x_at(d, t);
    d.y = y_at(d, t);
  }
  epoch_ = t;
}

// The disks of the given cells seen from disk i now (each computed without moving it, in its
// cell's periodic image). The candidate columns are held in locals: stores through them could
// otherwise alias the engine's members and force a reload of every pointer per candidate.
void EventDrivenEngine::gather(int i, double now, const PeriodicCells::Neighbour* cells,
                               int count) {
  const Disk a = disks_[std::size_t(i)];
  const double since = now - epoch_;
  const Disk* const disks = disks_.data();
  const int* const next = cells_->members();
  Candidates& c = candidates_;
  std::size_t k = c.size, capacity = c.disk.size();
  double *dx = c.dx.data(), *dy = c.dy.data(), *dvx = c.dvx.data(), *dvy = c.dvy.data();
  int* disk = c.disk.data();
  // The cells' first members, all looked up and their records fetched before the walk, whose
  // end of each list is a mispredicted branch that would otherwise hold the next lookup back.
  std::array<int, PeriodicCells::kNeighbourhood> heads{};
  if (count > int(heads.size())) throw std::logic_error("gather: more cells than a neighbourhood");
  for (int m = 0; m < count; ++m) heads[std::size_t(m)] = cells_->first(cells[m].cell);
  for (int m = 0; m < count; ++m) __builtin_prefetch(&disks[std::max(heads[std::size_t(m)], 0)]);
  for (int m = 0; m < count; ++m) {
    const PeriodicCells::Neighbour& cell = cells[m];
    for (int j = heads[std::size_t(m)]; j >= 0; j = next[j]) {
      if (k == capacity) {  // a dense cluster has no fixed bound on candidates
        capacity = std::max<std::size_t>(64, 2 * k);
        for (auto* column : {&c.dx, &c.dy, &c.dvx, &c.dvy}) column->resize(capacity);
        for (auto* column : {&c.disk, &c.touching}) column->resize(capacity);
        dx = c.dx.data(), dy = c.dy.data(), dvx = c.dvx.data(), dvy = c.dvy.data();
        disk = c.disk.data();
      }
      const Disk& b = disks[j];  // b = a itself never touches (contact_time)
      const double vx = a.vx - b.vx, vy = a.vy - b.vy;
      dvx[k] = vx;
      dvy[k] = vy;
      dx[k] = a.x - b.x + vx * since - cell.shift_x;
      dy[k] = a.y - b.y + vy * since - cell.shift_y;
      disk[k] = j;
      ++k;
    }
  }
  c.size = k;
}

// The first of the earliest contacts. Most candidates recede or miss, so those that touch are
// listed first (without branches: whether one touches is a coin toss) and only their few roots,
// with a division and a square root each, are computed and compared.
void EventDrivenEngine::choose_soonest(int i, double now) {
  Candidates& c = candidates_;
  const std::size_t n = c.size;
  const double* dx = c.dx.data();
  const double* dy = c.dy.data();
  const double* dvx = c.dvx.data();
  const double* dvy = c.dvy.data();
  int* touching = c.touching.data();
  std::size_t m = 0;
  for (std::size_t k = 0; k < n; ++k) {
    touching[m] = int(k);
    m += contact_quadratic(dx[k], dy[k], dvx[k], dvy[k], kSigma).touches() ? 1 : 0;
  }
  Soonest& s = soonest_[std::size_t(i)];
  double soonest = s.t;
  int found = -1;
  for (std::size_t h = 0; h < m; ++h) {
    const int k = touching[h];
    const std::size_t u = std::size_t(k);
    const double at = now + contact_quadratic(dx[u], dy[u], dvx[u], dvy[u], kSigma).time();
    found = at < soonest ? k : found;  // the first of equal times
    soonest = std::min(soonest, at);
  }
  if (found >= 0) {
    s.t = soonest;
    s.partner = c.disk[std::size_t(found)];
    s.partner_count = count_[std::size_t(s.partner)];
  }
  c.size = 0;
}

namespace {

// Time until a coordinate x moving at v leaves [low, low + width] (kNever at rest). Without
// branches: the sign of v is a coin toss.
double exit_time(double x, double v, double low, double width) {
  const double edge = low + width * double(v > 0.0);  // arithmetic, not a select: no branch
  const double t = std::max(0.0, (edge - x) / v);     // inf or NaN at rest: not taken
  return v != 0.0 ? t : kNever;
}

}  // namespace

// The earliest of its soonest collision and leaving its cell across either face (on equal
// times: the collision, then x).
void EventDrivenEngine::schedule(int i, double now) {
  const Disk& a = disks_[std::size_t(i)];
  double soonest = soonest_[std::size_t(i)].t;
  const double t_x = now + exit_time(x_at(a, now), a.vx, cells_->x_low(i), cells_->cell_length());
  const double t_y = now + exit_time(y_at(a, now), a.vy, cells_->y_low(i), cells_->cell_width());
  // Selected by arithmetic on the comparisons (GCC turns selects of doubles into branches).
  const int x_first = int(t_x < soonest);
  soonest = std::min(soonest, t_x);
  const int y_first = int(t_y < soonest);
  soonest = std::min(soonest, t_y);
  const int after_x = kCollision - x_first * kCollision;  // 0 if x is first
  event_[std::size_t(i)] = std::int8_t(after_x + y_first * (1 - after_x));
  calendar_.set(i, soonest);  // never if at rest and alone: others will find it
}

void EventDrivenEngine::predict(int i, double now) {
  soonest_[std::size_t(i)] = {kNever, -1, 0};
  const auto around = cells_->neighbourhood_of(i);
  gather(i, now, around.data(), int(around.size()));
  choose_soonest(i, now);
  schedule(i, now);
}

// Disks of the old neighbourhood that changed course since the last scan have looked for this
// one themselves; those that did not cannot collide sooner than the soonest found then, unless
// that partner has changed course (then the whole neighbourhood is scanned again).
void EventDrivenEngine::predict_after_crossing(int i, double now, int axis, int direction) {
  const Soonest& s = soonest_[std::size_t(i)];
  if (s.partner >= 0 && count_[std::size_t(s.partner)] != s.partner_count) {
    predict(i, now);
    return;
  }
  const auto joined = cells_->entering(i, axis, direction);
  gather(i, now, joined.data(), int(joined.size()));
  choose_soonest(i, now);
  schedule(i, now);
}

void EventDrivenEngine::collide(int i, int j, double now) {
  Disk& a = disks_[std::size_t(i)];
  Disk& b = disks_[std::size_t(j)];
  const double since_epoch = now - epoch_;
  const double dx = minimum_image(x_at(a, now) - x_at(b, now), options_.box_length);
  const double dy = minimum_image(y_at(a, now) - y_at(b, now), options_.box_width);
  // The impulse along the separation itself, not a normalised normal: then the elastic map
  // conserves energy in floating point without the bias of rounding |n| to 1 (1e-12 over 1e7
  // collisions needs it).
  const double separation2 = dx * dx + dy * dy;
  const double closing = (a.vx - b.vx) * dx + (a.vy - b.vy) * dy;  // -u |r|
  if (closing < 0.0) {
    const double distance = std::sqrt(separation2);
    const double approach = -closing / distance;
    const double since = now - std::max(last_impact_[std::size_t(i)], last_impact_[std::size_t(j)]);
    const auto [r, elastic_by] =
        collision_restitution(options_.restitution, approach, since, options_.collapse);
    if (r != options_.restitution) ++changed_, ++all_changed_;
    if (options_.restitution != 1.0) {
      if (elastic_by == ElasticBy::kContactDuration) ++tc_elastic_, ++all_tc_elastic_;
      if (elastic_by == ElasticBy::kSpeed) ++speed_elastic_, ++all_speed_elastic_;
    }
    last_impact_[std::size_t(i)] = last_impact_[std::size_t(j)] = now;
    const double k = normal_impulse(-closing, r) / separation2;  // J / |r|
    const double energy_a = a.vx * a.vx + a.vy * a.vy, energy_b = b.vx * b.vx + b.vy * b.vy;
    // New velocities, and the epoch positions moved so that the positions now stay.
    a.vx += k * dx;
    a.vy += k * dy;
    b.vx -= k * dx;
    b.vy -= k * dy;
    a.x -= k * dx * since_epoch;
    a.y -= k * dy * since_epoch;
    b.x += k * dx * since_epoch;
    b.y += k * dy * since_epoch;
    approach_sum_ += approach;
    recoil_sum_ += r * approach;
    // The pair's midpoint picks the bin of its virial, r_ij . Delta p_i = k |r|^2.
    const double mid = periodic_image(x_at(b, now) + 0.5 * dx, options_.box_length);
    const int bin =
        std::clamp(int(std::floor((mid / options_.box_length + 0.5) * options_.virial_bins)), 0,
                   options_.virial_bins - 1);
    virial_sum_[std::size_t(bin)] += k * separation2;
    // (dE_a - dE_b) / 2 moves from b to a (unit mass: dE = d|v|^2 / 2).
    const double transfer =
        0.25 * ((a.vx * a.vx + a.vy * a.vy - energy_a) - (b.vx * b.vx + b.vy * b.vy - energy_b));
    tally_.add(id_[std::size_t(i)], id_[std::size_t(j)], k * dx * dx, k * dy * dy, dx * transfer);
  }
  ++count_[std::size_t(i)];
  ++count_[std::size_t(j)];
  ++collisions_, ++all_collisions_, ++segment_collisions_;
  predict(i, now);
  predict(j, now);
}

void EventDrivenEngine::cross(int i, int axis, double now) {
  Disk& a = disks_[std::size_t(i)];
  const int direction = (axis == 0 ? a.vx : a.vy) > 0.0 ? 1 : -1;
  if (cells_->step(i, axis, direction)) {
    if (axis == 0) a.x -= direction * options_.box_length;
    if (axis == 1) a.y -= direction * options_.box_width;
  }
  ++crossings_, ++all_crossings_;
  predict_after_crossing(i, now, axis, direction);
}

double EventDrivenEngine::advance_to(double t) {
  if (disks_.empty()) throw std::logic_error("EventDrivenEngine::advance_to before set_up");
  if (!segment_.open) {  // else a segment restored from inside it goes on
    segment_ = {true, t_, t_, t_, events_, 0};
    segment_collisions_ = 0;
    std::fill(virial_sum_.begin(), virial_sum_.end(), 0.0);
    tally_.begin(disks_.size());
  }
  const double begin = segment_.begin;
  const double n = double(disks_.size());
  const double budget = options_.max_collision_rate * n * std::max(0.0, t - begin) + n;
  const long long events_at_begin = segment_.events_at_begin;
  const auto runaway = [&](double now, double since, long long collisions) {
    std::ostringstream why;
    why << "event-driven engine: event-rate runaway at t = " << now << " (" << collisions
        << " collisions of " << disks_.size() << " disks from t = " << since
        << ", beyond md.max_collision_rate = " << options_.max_collision_rate
        << " per disk and unit time): inelastic collapse; set md.elastic_speed (a packing "
           "under load), raise md.collapse_speed or set md.contact_duration (TC rule)";
    throw std::runtime_error(why.str());
  };
  const long long window = std::llround(std::ceil(kRateWindowCollisionsPerDisk * n));
  double& window_begin = segment_.window_begin;
  long long& window_collisions = segment_.window_collisions;
  while (calendar_.next_time() <= t) {
    if (double(events_ - ordered_at_) > kEventsPerReorder * n) order_by_cell(calendar_.next_time());
    const int i = calendar_.next();
    const double now = calendar_.next_time();
    const int axis = event_[std::size_t(i)];
    const Soonest s = soonest_[std::size_t(i)];
    if (axis == kCollision && s.partner_count != count_[std::size_t(s.partner)]) {
      predict(i, now);  // the partner changed course: look again from here
      continue;
    }
    ++events_, ++all_events_;
    if (axis == kCollision) {
      collide(i, s.partner, now);
      if (double(segment_collisions_) > budget) runaway(now, begin, segment_collisions_);
      if (++window_collisions == window) {
        if (double(window) > options_.max_collision_rate * n * (now - window_begin))
          runaway(now, window_begin, window);
        window_begin = now;
        window_collisions = 0;
      }
    } else {
      cross(i, axis, now);
      if (double(events_ - events_at_begin) > kEventsPerBudgetedCollision * budget) {
        std::ostringstream why;
        why << "event-driven engine: " << events_ - events_at_begin << " events from t = " << begin
            << " to " << now << " with " << segment_collisions_ << " collisions of "
            << disks_.size() << " disks: disks cross cells without colliding, beyond "
            << kEventsPerBudgetedCollision
            << " events per collision that md.max_collision_rate = " << options_.max_collision_rate
            << " allows (an engine fault; please report)";
        throw std::runtime_error(why.str());
      }
    }
    // Between two events: every disk's flight, prediction and calendar entry are whole, so a
    // checkpoint taken by the check continues from here with the same digits.
    if ((events_ - events_at_begin) % kEventsPerCheck == 0) {
      segment_.now = now;
      within_segment(now);
    }
  }
  segment_.open = false;
  t_ = t;
  const double interval = t - begin;
  if (interval > 0.0) ++stops_;
  tally_.finish(interval);
  virial_.t_begin = begin;
  virial_.t_end = t;
  virial_.box = 0.0;
  const double bin_area = options_.box_length * options_.box_width / options_.virial_bins;
  for (std::size_t k = 0; k < virial_sum_.size(); ++k) {
    virial_.bins[k] = interval > 0.0 ? virial_sum_[k] / (2.0 * bin_area * interval) : 0.0;
    virial_.box += virial_.bins[k] / double(virial_sum_.size());
  }
  collision_rate_ = interval > 0.0 ? 2.0 * double(segment_collisions_) / (n * interval) : 0.0;
  synchronise();
  return t_;
}

void EventDrivenEngine::order_by_cell(double now) {
  rebase(now);
  const std::size_t n = disks_.size();
  // A counting sort by cell (stable: within a cell, the order they had).
  std::vector<int> begin(std::size_t(cells_->columns()) * std::size_t(cells_->rows()) + 1, 0);
  for (std::size_t i = 0; i < n; ++i) ++begin[std::size_t(cells_->cell_of(int(i))) + 1];
  for (std::size_t c = 1; c < begin.size(); ++c) begin[c] += begin[c - 1];
  std::vector<int> renumbered(n);  // new number of each disk
  std::vector<int> by_cell(n);     // old number of each new one
  for (std::size_t i = 0; i < n; ++i) {
    const int k = begin[std::size_t(cells_->cell_of(int(i)))]++;
    renumbered[i] = k;
    by_cell[std::size_t(k)] = int(i);
  }
  std::vector<int> cell(n);
  for (std::size_t k = 0; k < n; ++k) cell[k] = cells_->cell_of(by_cell[k]);
  const auto partner = [&](int j) { return j >= 0 ? renumbered[std::size_t(j)] : j; };
  std::vector<Disk> disks(n);
  std::vector<std::uint32_t> count(n);
  std::vector<std::int8_t> event(n);
  std::vector<Soonest> soonest(n);
  std::vector<double> last_impact(n);
  std::vector<int> id(n);
  std::vector<double> times(n);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = std::size_t(by_cell[k]);
    disks[k] = disks_[i];
    count[k] = count_[i];
    event[k] = event_[i];
    soonest[k] = soonest_[i];
    soonest[k].partner = partner(soonest[k].partner);
    last_impact[k] = last_impact_[i];
    id[k] = id_[i];
    times[k] = calendar_.time(int(i));
  }
  disks_.swap(disks);
  count_.swap(count);
  event_.swap(event);
  soonest_.swap(soonest);
  last_impact_.swap(last_impact);
  id_.swap(id);
  calendar_.reset(times);
  cells_->clear();
  // Inserted at the head: from the last, so that every cell lists its disks in memory order.
  for (std::size_t k = n; k-- > 0;) cells_->insert(int(k), cell[k]);
  ordered_at_ = events_;
}

void EventDrivenEngine::synchronise() {
  rebase(t_);
  for (std::size_t i = 0; i < disks_.size(); ++i) {
    const Disk& d = disks_[i];
    const std::size_t id = std::size_t(id_[i]);
    x_[3 * id] = periodic_image(d.x, options_.box_length);
    x_[3 * id + 1] = periodic_image(d.y, options_.box_width);
    v_[3 * id] = d.vx;
    v_[3 * id + 1] = d.vy;
  }
}

LocalParticles EventDrivenEngine::local_particles() {
  if (rank_ != 0) return {};
  return {x_.data(), v_.data(), mass_.data(), int(disks_.size())};
}

std::vector<long long> EventDrivenEngine::local_ids() {
  std::vector<long long> ids(std::size_t(local_particles().count));
  for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = (long long)i + 1;  // x_ is in ID order
  return ids;
}

LocalVirial EventDrivenEngine::local_virial() {
  return rank_ == 0 ? tally_.last() : LocalVirial{};
}

ParticleFrame EventDrivenEngine::gather_frame() {
  return {x_, v_};
}

EngineValues EventDrivenEngine::series_values() const {
  return {{"collision_virial_pressure", virial_.box},
          {"collisions_per_particle_time", collision_rate_}};
}

double EventDrivenEngine::smallest_separation() const {
  double closest = kNever;
  for (std::size_t i = 0; i < disks_.size(); ++i) {
    const Disk& a = disks_[i];  // every disk is at t_ = epoch_ (synchronise)
    for (const auto& c : cells_->neighbourhood_of(int(i))) {
      for (int j = cells_->first(c.cell); j >= 0; j = cells_->next(j)) {
        if (std::size_t(j) <= i) continue;
        const Disk& b = disks_[std::size_t(j)];
        const double dx = minimum_image(a.x - b.x, options_.box_length);
        const double dy = minimum_image(a.y - b.y, options_.box_width);
        closest = std::min(closest, std::sqrt(dx * dx + dy * dy));
      }
    }
  }
  return closest;
}

EngineState EventDrivenEngine::save_state(bool with_particles) {
  EngineState state;
  if (with_particles && !disks_.empty()) {
    state.particles = gather_frame();  // the disks at t, the last sample
    state.arrays = whole_state();
  }
  if (with_particles && !disks_.empty() && segment_.open) {
    state.numbers = {{"segment_time", segment_.now},
                     {"segment_begin", segment_.begin},
                     {"segment_window_begin", segment_.window_begin},
                     {"segment_events_at_begin", double(segment_.events_at_begin)},
                     {"segment_window_collisions", double(segment_.window_collisions)},
                     {"segment_collisions", double(segment_collisions_)}};
  }
  if (with_particles && !disks_.empty()) {
    state.numbers.push_back({"epoch", epoch_});
    state.numbers.push_back({"ordered_at", double(ordered_at_)});
  }
  state.numbers.insert(state.numbers.end(), {{"t", t_},
                                             {"events", double(events_)},
                                             {"stops", double(stops_)},
                                             {"collisions", double(collisions_)},
                                             {"crossings", double(crossings_)},
                                             {"changed", double(changed_)},
                                             {"tc_elastic", double(tc_elastic_)},
                                             {"all_tc_elastic", double(all_tc_elastic_)},
                                             {"speed_elastic", double(speed_elastic_)},
                                             {"all_speed_elastic", double(all_speed_elastic_)},
                                             {"runs", double(runs_)},
                                             {"all_events", double(all_events_)},
                                             {"all_collisions", double(all_collisions_)},
                                             {"all_crossings", double(all_crossings_)},
                                             {"all_changed", double(all_changed_)},
                                             {"approach_sum", approach_sum_},
                                             {"recoil_sum", recoil_sum_},
                                             {"wall_seconds", cost().wall_seconds}});
  return state;
}

void EventDrivenEngine::restore_state(const EngineState& state) {
  std::map<std::string, double> number;
  for (const auto& [name, value] : state.numbers) number[name] = value;
  const auto get = [&](const std::string& name) {
    const auto found = number.find(name);
    if (found == number.end() || !std::isfinite(found->second))
      throw std::invalid_argument("event-driven engine state without a finite '" + name + "'");
    return found->second;
  };
  const auto& p = state.particles;
  if (!p.x.empty() &&
      (p.x.size() != 3 * std::size_t(options_.particles) || p.v.size() != p.x.size())) {
    throw std::invalid_argument("event-driven engine state with " + std::to_string(p.x.size() / 3) +
                                " particles for a scene of " + std::to_string(options_.particles));
  }
  const double t = get("t");
  events_ = std::llround(get("events"));
  collisions_ = std::llround(get("collisions"));
  crossings_ = std::llround(get("crossings"));
  changed_ = std::llround(get("changed"));
  // Absent from checkpoints written before stops were counted, whose frames have the events.
  stops_ = number.count("stops") ? std::llround(get("stops")) : 0;
  // Absent from checkpoints written before the TC rule existed.
  tc_elastic_ = number.count("tc_elastic") ? std::llround(get("tc_elastic")) : 0;
  all_tc_elastic_ = number.count("all_tc_elastic") ? std::llround(get("all_tc_elastic")) : 0;
  // Absent from checkpoints written before md.elastic_speed existed.
  speed_elastic_ = number.count("speed_elastic") ? std::llround(get("speed_elastic")) : 0;
  all_speed_elastic_ =
      number.count("all_speed_elastic") ? std::llround(get("all_speed_elastic")) : 0;
  runs_ = int(std::lround(get("runs")));
  all_events_ = std::llround(get("all_events"));
  all_collisions_ = std::llround(get("all_collisions"));
  all_crossings_ = std::llround(get("all_crossings"));
  all_changed_ = std::llround(get("all_changed"));
  approach_sum_ = get("approach_sum");
  recoil_sum_ = get("recoil_sum");
  wall_before_ = get("wall_seconds");
  made_ = std::chrono::steady_clock::now();
  disks_.clear();
  t_ = t;
  tally_.clear();
  segment_ = Segment{};
  if (!p.x.empty() && !state.arrays.empty()) {
    restore_whole(state, number.count("segment_time") ? get("segment_time") : t);
  } else if (!p.x.empty()) {  // a checkpoint of the particles alone: predictions made anew
    start(p.x, p.v, t);
  }
}

std::string EventDrivenEngine::state_problem(const EngineState& state) const {
  EventDrivenEngine probe(options_);
  try {
    probe.restore_state(state);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

void EventDrivenEngine::add_totals(const EngineState& other) {
  EventDrivenEngine run(options_);
  run.restore_state({{}, 1, 0, other.numbers, {}});
  // The later run's own counts, as after it on one engine; the totals summed.
  events_ = run.events_;
  stops_ = run.stops_;
  collisions_ = run.collisions_;
  crossings_ = run.crossings_;
  changed_ = run.changed_;
  tc_elastic_ = run.tc_elastic_;
  speed_elastic_ = run.speed_elastic_;
  t_ = run.t_;
  runs_ += run.runs_;
  all_events_ += run.all_events_;
  all_collisions_ += run.all_collisions_;
  all_crossings_ += run.all_crossings_;
  all_changed_ += run.all_changed_;
  all_tc_elastic_ += run.all_tc_elastic_;
  all_speed_elastic_ += run.all_speed_elastic_;
  approach_sum_ += run.approach_sum_;
  recoil_sum_ += run.recoil_sum_;
  wall_before_ += run.wall_before_;
}

EngineCost EventDrivenEngine::cost() const {
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - made_).count();
  return {wall_before_ + wall, double(all_collisions_), "collisions"};
}

EngineDetails EventDrivenEngine::details() const {
  const EngineCost c = cost();
  EngineDetails d = {
      {"events", all_events_},
      {"events_per_second", double(all_events_) / std::max(c.wall_seconds, 1e-12)},
      {"crossings", all_crossings_},
      {"collapse_rule.rule",
       std::string(options_.collapse.elastic_speed > 0.0
                       ? "elastic below impact speed delta (Ben-Naim, Chen, Doolen & Redner, PRL "
                         "83, 4069 (1999)); "
                       : "") +
           "restitution 1 - (1 - r)(u/u0)^(3/4) below impact speed u0 (Bizon et al., PRL 80, 57 "
           "(1998))" +
           (options_.collapse.contact_duration > 0.0
                ? std::string("; elastic within t_c of either disk's previous impact (TC "
                              "model, Luding & McNamara, Granular Matter 1, 113 (1998))") +
                      (options_.collapse.contact_speed > 0.0 ? " if slower than u_c" : "")
                : std::string())},
      {"collapse_rule.collapse_speed", options_.collapse.collapse_speed},
      {"collapse_rule.collisions_changed", all_changed_},
      {"collapse_rule.fraction_changed",
       all_collisions_ > 0 ? double(all_changed_) / double(all_collisions_) : 0.0},
      {"collapse_rule.contact_duration", options_.collapse.contact_duration},
      {"collapse_rule.contact_speed", options_.collapse.contact_speed},
      {"collapse_rule.collisions_made_elastic", all_tc_elastic_},
      {"collapse_rule.elastic_speed", options_.collapse.elastic_speed},
      {"collapse_rule.collisions_below_elastic_speed", all_speed_elastic_},
      {"max_collision_rate", options_.max_collision_rate},
      {"cells.columns", static_cast<long long>(cells_->columns())},
      {"cells.rows", static_cast<long long>(cells_->rows())}};
  if (approach_sum_ > 0.0) d.push_back({"restitution_effective", recoil_sum_ / approach_sum_});
  return d;
}

}  // namespace granvv::md
