#pragma once
// The particle engines by name: the case key md.engine selects one.
#include <memory>
#include <string>
#include <vector>

#include "md_bridge/particle_engine.hpp"

namespace granvv::md {

// The allowed values of md.engine (its default is in app/case_schema.cpp).
std::vector<std::string> particle_engine_names();

// Throws std::invalid_argument for an unknown name (listing the known ones) or settings the
// engine refuses.
std::unique_ptr<ParticleEngine> make_particle_engine(const std::string& name,
                                                     const ParticleEngineSetup& setup);

}  // namespace granvv::md
