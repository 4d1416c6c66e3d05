#pragma once
// The particles' pressure against the equation of state of a comparison's hydro closure
// (docs/physics.md §11): the /compare/pressure group of results.h5, MD units (T0/sigma^2).
#include <filesystem>
#include <string>
#include <vector>

#include "scene/hydro_scene.hpp"
#include "scene/md_scene.hpp"

namespace granvv::app {

// Adds /compare/pressure to an existing results.h5 that holds /compare: per snapshot and bin
// the particles' (P_xx + P_yy)/2 (ensemble mean and its error) and the closure's p(n, T) at the
// particles' own n and T (n T F_p for "enskog", n T for "dilute"); per sample the box's, with the
// closure's p at the mean density and the ensemble's T. Nothing when the particles carry no
// pressure (an engine without a contact virial). With several closures (compare.closures),
// `eos` and `box_eos` are the first closure's and /compare/pressure/closures/<name> holds every
// listed closure's; `peak_bin` is the bin of largest particle density at each snapshot.
void write_pressure_comparison(const std::filesystem::path& file, const HydroScene& hydro,
                               const std::vector<std::string>& closures, const MdScene& md,
                               const MdOutcome& out);

}  // namespace granvv::app
