#include "md_bridge/particle_engine_registry.hpp"

#include <stdexcept>
#include <utility>

#include "md_bridge/event_driven_engine.hpp"
#include "md_bridge/lammps_engine.hpp"
#include "md_bridge/recorded_engine.hpp"

namespace granvv::md {

namespace {

using Maker = std::unique_ptr<ParticleEngine> (*)(const ParticleEngineSetup&);
using WorkEstimator = ParticleWorkEstimate (*)(const ParticleWorkQuestion&);

using KeyDeclaration = const EngineKeys& (*)();
using GivenReader = std::optional<GivenParticles> (*)(const EngineSettings&, const EngineTexts&);
using InputFiles = std::vector<std::string> (*)(const EngineTexts&);

// One row per engine: its md.engine value, its maker, its work estimate, its own keys, its
// atlas grid's keys (nullptr: none) and, for an engine that replays given particles, what its
// files fix and which files it reads (nullptr: the engine moves particles sampled from the
// scene).
struct EngineRow {
  std::string name;
  Maker make;
  WorkEstimator work;
  KeyDeclaration keys;
  KeyDeclaration atlas_keys = nullptr;
  GivenReader given = nullptr;
  InputFiles input_files = nullptr;
};

const std::vector<EngineRow>& engines() {
  static const std::vector<EngineRow> rows = {
      {"lammps", &LammpsEngine::make, &lammps_work, &LammpsEngine::keys, &LammpsEngine::atlas_keys},
      {"event_driven", &EventDrivenEngine::make, &event_driven_work, &EventDrivenEngine::keys,
       &EventDrivenEngine::atlas_keys},
      {"recorded", &RecordedEngine::make, &RecordedEngine::work, &RecordedEngine::keys, nullptr,
       &RecordedEngine::given, &RecordedEngine::input_files},
  };
  return rows;
}

const EngineRow& engine_row(const std::string& name) {
  std::string known;
  for (const EngineRow& row : engines()) {
    if (row.name == name) return row;
    known += (known.empty() ? "" : ", ") + row.name;
  }
  throw std::invalid_argument("unknown particle engine \"" + name + "\" (known: " + known + ")");
}

}  // namespace

std::vector<std::string> particle_engine_names() {
  std::vector<std::string> names;
  for (const EngineRow& row : engines()) names.push_back(row.name);
  return names;
}

const std::vector<ParticleEngineKey>& particle_engine_keys() {
  static const std::vector<ParticleEngineKey> keys = [] {
    std::vector<ParticleEngineKey> out;
    auto add = [&out](const EngineRow& row, const EngineKeys& keys, const std::string& section) {
      for (const hydro::ParameterSpec& spec : keys) {
        const ParticleEngineKey key{spec, row.name, section};
        for (const ParticleEngineKey& other : out) {
          if (other.key() == key.key()) {
            throw std::logic_error("particle engines " + other.engine + " and " + row.name +
                                   " both declare " + key.key());
          }
        }
        out.push_back(key);
      }
    };
    for (const EngineRow& row : engines()) {
      add(row, row.keys(), "md");
      if (row.atlas_keys) add(row, row.atlas_keys(), "atlas");
    }
    return out;
  }();
  return keys;
}

std::unique_ptr<ParticleEngine> make_particle_engine(const std::string& name,
                                                     const ParticleEngineSetup& setup) {
  return engine_row(name).make(setup);
}

bool replays_given_particles(const std::string& name) {
  return engine_row(name).given != nullptr;
}

std::vector<std::string> engine_input_files(const std::string& name, const EngineTexts& texts) {
  const EngineRow& row = engine_row(name);
  return row.input_files ? row.input_files(texts) : std::vector<std::string>{};
}

std::optional<GivenParticles> given_particles(const std::string& name,
                                              const EngineSettings& settings,
                                              const EngineTexts& texts) {
  const EngineRow& row = engine_row(name);
  if (!row.given) return std::nullopt;
  return row.given(settings, texts);
}

ParticleWorkEstimate estimate_particle_work(const std::string& name,
                                            const ParticleWorkQuestion& question) {
  return engine_row(name).work(question);
}

}  // namespace granvv::md
