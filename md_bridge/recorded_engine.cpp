#include "md_bridge/recorded_engine.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "fields/field_series.hpp"

namespace granvv::md {
namespace {

const char* const kWho = "the recorded engine";
// md.ensemble's own bound: the members of an ensemble.
constexpr double kMaxRecordedMembers = 1000.0;
// Members read per second, for the wall-time estimate of --dry-run: a member of about 200
// disks and 20-40 frames took 0.07-0.09 s (md.wall_seconds of the round-trip test's scene and of
// examples/lammps/disks.toml, 2026-12-04); larger files take proportionally longer.
constexpr double kRecordedMembersPerCoreSecond = 10.0;

std::vector<std::string> texts_of(const EngineTexts& texts, const std::string& key) {
  const auto found = texts.find(key);
  if (found == texts.end())
    throw std::invalid_argument(std::string(kWho) + " needs the setting " + key);
  return found->second;
}

RecordedOptions options_of(const EngineSettings& settings, const EngineTexts& texts) {
  RecordedOptions o;
  const auto format = texts_of(texts, "md.recorded.format");
  o.format = format.empty() ? "auto" : format.front();
  o.timestep = required_setting(settings, "md.recorded.timestep", kWho);
  o.diameter = required_setting(settings, "md.recorded.diameter", kWho);
  o.mass = required_setting(settings, "md.recorded.mass", kWho);
  return o;
}

std::string number(double x) {
  std::ostringstream os;
  os.precision(10);
  os << x;
  return os.str();
}

}  // namespace

const EngineKeys& RecordedEngine::keys() {
  using hydro::ParameterRange;
  static const EngineKeys keys = {
      {"recorded.files", std::vector<std::string>{}, ParameterRange::any(),
       "recorded: the frames another program wrote, a path or glob per member of the ensemble "
       "(a glob's files, sorted, are one run's frames)"},
      {"recorded.format", std::string("auto"),
       ParameterRange::one_of({"auto", "lammps_dump", "h5md"}),
       "recorded: the files' format; auto = from their contents and extension"},
      {"recorded.timestep", 0.0, ParameterRange::at_least(0.0),
       "recorded: time per step of a LAMMPS dump (which holds steps only), in the run's time "
       "unit; 0 = the files give the times"},
      {"recorded.diameter", 1.0, ParameterRange::greater_than(0.0),
       "recorded: the disk diameter sigma in the files' length unit (lengths are read in sigma)"},
      {"recorded.mass", 1.0, ParameterRange::greater_than(0.0),
       "recorded: the disk mass m in the files' mass unit (a dump's mass column must match it)"},
  };
  return keys;
}

ParticleWorkEstimate RecordedEngine::work(const ParticleWorkQuestion& q) {
  ParticleWorkEstimate w;
  w.work = q.ensemble;
  w.limit = kMaxRecordedMembers;
  w.unit = "members";
  w.keys = {"md.recorded.files"};
  w.rate = kRecordedMembersPerCoreSecond;
  // A member's frames are read in time order.
  const double t_end = q.t_end;
  w.member_work_until = [t_end](double t) { return t_end > 0.0 ? std::min(t / t_end, 1.0) : 1.0; };
  return w;
}

RecordedEngine::RecordedEngine(const ParticleScene& scene,
                               std::vector<std::vector<std::string>> members,
                               const RecordedOptions& options, MPI_Comm comm)
    : scene_(scene),
      members_(std::move(members)),
      options_(options),
      comm_(comm),
      made_(std::chrono::steady_clock::now()) {
  if (members_.empty()) {
    throw std::invalid_argument("md.recorded.files is empty: the recorded engine needs frames");
  }
}

std::unique_ptr<ParticleEngine> RecordedEngine::make(const ParticleEngineSetup& setup) {
  const RecordedOptions options = options_of(setup.settings, setup.texts);
  const auto files = texts_of(setup.texts, "md.recorded.files");
  if (files.empty()) {
    throw std::invalid_argument("md.recorded.files is empty: the recorded engine needs frames");
  }
  return std::make_unique<RecordedEngine>(setup.scene, recorded_members(files), options,
                                          setup.comm);
}

std::vector<std::string> RecordedEngine::input_files(const EngineTexts& texts) {
  std::vector<std::string> paths;
  for (const auto& member : recorded_members(texts_of(texts, "md.recorded.files"))) {
    paths.insert(paths.end(), member.begin(), member.end());
  }
  return paths;
}

std::optional<GivenParticles> RecordedEngine::given(const EngineSettings& settings,
                                                    const EngineTexts& texts) {
  const auto files = texts_of(texts, "md.recorded.files");
  if (files.empty()) return std::nullopt;
  const RecordedOptions options = options_of(settings, texts);
  GivenParticles out;
  out.members = recorded_members(files);
  for (std::size_t m = 0; m < out.members.size(); ++m) {
    const RecordedTrajectory t = read_recorded_member(out.members[m], options, false);
    std::vector<double> times;
    for (const RecordedFrame& f : t.frames) times.push_back(f.time);
    const std::string& file = out.members[m].front();
    if (m == 0) {
      out.particles = t.particles;
      out.box_length = t.box_length;
      out.box_width = t.box_width;
      out.times = times;
      continue;
    }
    if (t.particles != out.particles || t.box_length != out.box_length ||
        t.box_width != out.box_width) {
      throw RecordedFileError(file, "member " + std::to_string(m) + " holds " +
                                        std::to_string(t.particles) + " particles in a box " +
                                        number(t.box_length) + " x " + number(t.box_width) +
                                        ", member 0 " + std::to_string(out.particles) + " in " +
                                        number(out.box_length) + " x " + number(out.box_width) +
                                        " (members are one scene)");
    }
    bool same = times.size() == out.times.size();
    for (std::size_t i = 0; same && i < times.size(); ++i) {
      same = fields::same_time(times[i], out.times[i]);
    }
    if (!same) {
      throw RecordedFileError(file, "member " + std::to_string(m) +
                                        " has other frame times than member 0 (" +
                                        out.members[0].front() + ")");
    }
  }
  return out;
}

CollisionRuleCheck RecordedEngine::check_collision_rule() {
  return {scene_.restitution,
          "md.restitution as given: the recorded run's own (not measured from its frames)"};
}

void RecordedEngine::load(int member) {
  int initialised = 0;
  MPI_Initialized(&initialised);
  if (initialised) MPI_Comm_rank(comm_, &rank_);
  trajectory_ = read_recorded_member(members_[std::size_t(member)], options_, true);
  member_ = member;
  frame_ = 0;
  resolution_ = 0.0;
  const auto& frames = trajectory_.frames;
  for (std::size_t i = 1; i < frames.size(); ++i) {
    resolution_ = std::max(resolution_, frames[i].time - frames[i - 1].time);
  }
  mass_.assign(std::size_t(trajectory_.particles), 1.0);  // the unit of mass is m
  ++frames_visited_;
}

void RecordedEngine::set_up(const ParticleSample&) {
  load(next_member_ % int(members_.size()));
  ++next_member_;
}

void RecordedEngine::set_up_sampled(const RangeSampler&) {
  set_up(ParticleSample{});
}

double RecordedEngine::advance_to(double t) {
  const auto& frames = trajectory_.frames;
  if (frame_ + 1 >= frames.size()) {
    throw std::runtime_error(members_[std::size_t(member_)].back() +
                             ": the recorded frames end at t = " + number(frames.back().time) +
                             ", before t = " + number(t) + " (md.t_end)");
  }
  std::size_t best = frame_ + 1;
  for (std::size_t i = best + 1; i < frames.size(); ++i) {
    if (std::abs(frames[i].time - t) < std::abs(frames[best].time - t)) best = i;
    if (frames[i].time > t) break;
  }
  frames_visited_ += (long long)(best - frame_);
  frame_ = best;
  return frame().time;
}

long long RecordedEngine::steps() const {
  return trajectory_.frames.empty() ? 0 : frame().step - trajectory_.frames.front().step;
}

long long RecordedEngine::frame_step() const {
  return trajectory_.frames.empty() ? 0 : frame().step;
}

LocalParticles RecordedEngine::local_particles() {
  if (rank_ != 0 || trajectory_.frames.empty()) return {};
  const RecordedFrame& f = frame();
  return {f.x.data(), f.v.data(), mass_.data(), int(trajectory_.particles)};
}

std::vector<long long> RecordedEngine::local_ids() {
  std::vector<long long> ids(std::size_t(local_particles().count));
  for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = (long long)i + 1;  // frames in ID order
  return ids;
}

ParticleFrame RecordedEngine::gather_frame() {
  if (trajectory_.frames.empty()) return {};
  return {frame().x, frame().v};
}

EngineState RecordedEngine::save_state(bool with_particles) {
  EngineState s;
  const bool running = with_particles && !trajectory_.frames.empty();
  if (running) s.particles = gather_frame();
  s.numbers = {{"member", double(member_)},
               {"next_member", double(next_member_)},
               {"frame", double(frame_)},
               {"frames_visited", double(frames_visited_)}};
  return s;
}

void RecordedEngine::restore_state(const EngineState& state) {
  auto number_of = [&](const std::string& name) {
    for (const auto& [key, value] : state.numbers) {
      if (key == name) return value;
    }
    throw std::invalid_argument("not a state of the recorded engine (no " + name + ")");
  };
  const int member = int(number_of("member"));
  next_member_ = int(number_of("next_member"));
  const long long visited = (long long)number_of("frames_visited");
  if (!state.particles.x.empty()) {
    if (member < 0 || member >= int(members_.size())) {
      throw std::invalid_argument("a recorded-engine state of member " + std::to_string(member) +
                                  ", beyond md.recorded.files");
    }
    load(member);
    frame_ = std::size_t(number_of("frame"));
    if (frame_ >= trajectory_.frames.size() || state.particles.x != frame().x) {
      throw std::invalid_argument("the recorded files changed since the state was saved");
    }
  }
  frames_visited_ = visited;
}

EngineCost RecordedEngine::cost() const {
  EngineCost c;
  c.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - made_).count();
  c.work = double(frames_visited_);
  c.work_unit = "frames";
  return c;
}

EngineDetails RecordedEngine::details() const {
  std::string files;
  for (const auto& member : members_) {
    for (const auto& f : member) files += (files.empty() ? "" : " ") + f;
  }
  return {{"recorded.format", options_.format},
          {"recorded.members", (long long)members_.size()},
          {"recorded.frames", (long long)trajectory_.frames.size()},
          {"recorded.diameter", options_.diameter},
          {"recorded.mass", options_.mass},
          {"recorded.files", files}};
}

}  // namespace granvv::md
