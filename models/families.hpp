#pragma once
// The makers of the ladder's families (models/model_family.hpp), one file each: only
// models/model_family.cpp calls them, in the ladder's order.
#include <string>
#include <vector>

#include "models/model_family.hpp"

namespace granvv::app {

// The Haff ODE and flow by inertia (models/family_exact.cpp).
std::vector<const ModelFamily*> exact_families();
// The hydro with a registered closure (models/family_hydro.cpp).
const ModelFamily* hydro_family(const std::string& closure);
// The particles with a registered engine (models/family_particles.cpp): the engine's own family
// where it has knobs or failure modes beyond the ensemble size, else the plain one.
const ModelFamily* particle_family(const std::string& engine);

}  // namespace granvv::app
