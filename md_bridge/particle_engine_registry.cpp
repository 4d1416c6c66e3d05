#include "md_bridge/particle_engine_registry.hpp"

#include <stdexcept>
#include <utility>

#include "md_bridge/event_driven_engine.hpp"
#include "md_bridge/lammps_engine.hpp"

namespace granvv::md {

namespace {

using Maker = std::unique_ptr<ParticleEngine> (*)(const ParticleEngineSetup&);

// One row per engine: its md.engine value and its maker.
const std::vector<std::pair<std::string, Maker>>& engines() {
  static const std::vector<std::pair<std::string, Maker>> rows = {
      {"lammps", &LammpsEngine::make},
      {"event_driven", &EventDrivenEngine::make},
  };
  return rows;
}

}  // namespace

std::vector<std::string> particle_engine_names() {
  std::vector<std::string> names;
  for (const auto& [name, make] : engines()) names.push_back(name);
  return names;
}

std::unique_ptr<ParticleEngine> make_particle_engine(const std::string& name,
                                                     const ParticleEngineSetup& setup) {
  std::string known;
  for (const auto& [engine, make] : engines()) {
    if (engine == name) return make(setup);
    known += (known.empty() ? "" : ", ") + engine;
  }
  throw std::invalid_argument("unknown particle engine \"" + name + "\" (known: " + known + ")");
}

}  // namespace granvv::md
