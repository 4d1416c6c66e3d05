#include "md_bridge/particle_engine_registry.hpp"

#include <stdexcept>
#include <utility>

#include "md_bridge/event_driven_engine.hpp"
#include "md_bridge/lammps_engine.hpp"

namespace granvv::md {

namespace {

using Maker = std::unique_ptr<ParticleEngine> (*)(const ParticleEngineSetup&);
using WorkEstimator = ParticleWorkEstimate (*)(const ParticleWorkQuestion&);

using KeyDeclaration = const EngineKeys& (*)();

// One row per engine: its md.engine value, its maker, its work estimate and its own keys.
struct EngineRow {
  std::string name;
  Maker make;
  WorkEstimator work;
  KeyDeclaration keys;
};

const std::vector<EngineRow>& engines() {
  static const std::vector<EngineRow> rows = {
      {"lammps", &LammpsEngine::make, &lammps_work, &LammpsEngine::keys},
      {"event_driven", &EventDrivenEngine::make, &event_driven_work, &EventDrivenEngine::keys},
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
    for (const EngineRow& row : engines()) {
      for (const hydro::ParameterSpec& spec : row.keys()) {
        for (const ParticleEngineKey& other : out) {
          if (other.spec.name == spec.name) {
            throw std::logic_error("particle engines " + other.engine + " and " + row.name +
                                   " both declare md." + spec.name);
          }
        }
        out.push_back({spec, row.name});
      }
    }
    return out;
  }();
  return keys;
}

std::unique_ptr<ParticleEngine> make_particle_engine(const std::string& name,
                                                     const ParticleEngineSetup& setup) {
  return engine_row(name).make(setup);
}

ParticleWorkEstimate estimate_particle_work(const std::string& name,
                                            const ParticleWorkQuestion& question) {
  return engine_row(name).work(question);
}

}  // namespace granvv::md
