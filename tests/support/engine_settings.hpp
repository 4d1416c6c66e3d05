#pragma once
// What a particle engine is made with in the tests: the one place they take its settings from.
#include <string>

#include "md_bridge/particle_engine.hpp"
#include "md_bridge/particle_scene.hpp"

namespace granvv::testing {

// The settings `engine` gets from a case that sets none of its keys: the case schema's defaults
// of every number and boolean of [md], as the run passes them (scene/md_scene.cpp), booleans as
// 1 or 0. Every engine gets the same map today and reads the keys it understands.
md::EngineSettings default_engine_settings(const std::string& engine);

// `engine`'s setup for a scene: default_engine_settings, no log, MPI_COMM_WORLD.
md::ParticleEngineSetup default_engine_setup(const std::string& engine,
                                             const md::ParticleScene& scene);

}  // namespace granvv::testing
