#pragma once
// The particle engines by name: the case key md.engine selects one, and with it the estimate
// of a run's work and the engine's own case keys.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "md_bridge/particle_engine.hpp"
#include "md_bridge/particle_work.hpp"

namespace granvv::md {

// The allowed values of md.engine (its default is in scene/case_schema.cpp).
std::vector<std::string> particle_engine_names();

// A key an engine declares as its own: the case key md.<spec.name> of its settings (keys()), or
// atlas.<spec.name> of the grid the atlas runs it on (atlas_keys(), read by the engine's model
// family in models/).
struct ParticleEngineKey {
  hydro::ParameterSpec spec;
  std::string engine;          // the md.engine it belongs to
  std::string section = "md";  // "md" or "atlas"
  std::string key() const { return section + "." + spec.name; }
};
// Every engine's own keys, engine by engine in registry order, its md keys then its atlas keys,
// each in its declared order. Two engines may not declare the same key (std::logic_error).
const std::vector<ParticleEngineKey>& particle_engine_keys();

// Throws std::invalid_argument for an unknown name (listing the known ones) or settings the
// engine refuses.
std::unique_ptr<ParticleEngine> make_particle_engine(const std::string& name,
                                                     const ParticleEngineSetup& setup);

// What the files of an engine that replays given particles fix (particle_engine.hpp,
// GivenParticles): N, the box and the frame times; std::nullopt for an engine that moves the
// particles it is given at t = 0, or one without files. Throws std::invalid_argument for files
// it refuses (naming the file and the problem) or an unknown name.
// Whether the engine replays given particles (the recorded engine) rather than moving the
// particles it is set up with.
bool replays_given_particles(const std::string& name);
// The files the engine reads (its given particles' files, globs expanded; none for an engine
// that reads no file), unread. Throws std::invalid_argument for an entry that matches no file.
std::vector<std::string> engine_input_files(const std::string& name, const EngineTexts& texts);
std::optional<GivenParticles> given_particles(const std::string& name,
                                              const EngineSettings& settings,
                                              const EngineTexts& texts);

// The engine's estimate of a run's work (particle_work.hpp); throws std::invalid_argument for
// an unknown name.
ParticleWorkEstimate estimate_particle_work(const std::string& name,
                                            const ParticleWorkQuestion& question);

}  // namespace granvv::md
