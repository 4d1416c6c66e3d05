#pragma once
// The particle rungs of `granvv atlas` (docs/atlas.md): their grids of cost knobs (the
// event-driven engine over its ensemble size, LAMMPS over max_overlap x steps_per_contact and
// adaptive stiffness), their cost estimates from a pilot, which run of an engine is its finest,
// and the DEM stability and bias map: the soft-contact t0, P and P/(nT) against the event-driven
// hard disks as a function of the contact knobs.
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "atlas/atlas_analysis.hpp"
#include "atlas/atlas_runs.hpp"

namespace granvv::app {

// The event-driven engine at each ensemble size (its only knob: it has no contact).
// The event-driven engine at each ensemble size (the case's particles), and at the case's own
// ensemble with each particle factor other than 1.
std::vector<AtlasSetting> event_driven_grid(const std::vector<int>& ensembles,
                                            const std::vector<double>& particle_factors,
                                            int case_ensemble);
// LAMMPS at the case's ensemble over max_overlaps x steps_per_contacts with the case's adaptive
// stiffness, and over max_overlaps at the case's steps_per_contact with it flipped.
std::vector<AtlasSetting> lammps_grid(const AtlasScene& scene,
                                      const std::vector<double>& max_overlaps,
                                      const std::vector<int>& steps_per_contacts);
// The pilot of an engine: the case's own setting at ensemble 1.
AtlasSetting particle_pilot(const AtlasScene& scene, const std::string& model);

// A particle run's estimated wall seconds from its engine's pilot: proportional to the ensemble
// (event-driven: the collisions per member do not depend on any knob) and, for LAMMPS, to its
// steps (atlas/particle_cost.hpp).
double particle_estimate(const AtlasSetting& s, const AtlasRun& pilot, const AtlasScene& scene);

// Whether a is a finer run of its engine than b: the larger ensemble; then for LAMMPS the
// smaller max_overlap, the more steps per contact, and the fixed (stiffest) contact.
bool finer_particle_run(const AtlasSetting& a, const AtlasSetting& b);

// The DEM map (atlas.json `dem_map`): every LAMMPS run (the largest ensemble at each contact
// setting) with its state and its t0, pressure and P/(nT) bias against the hard-disk
// reference, and the boundaries along each knob from the case's own setting. A finished run's
// state is t0_bias_above_tolerance when its t0 fails the σ-aware test against the reference
// (atlas/recommendation.hpp), else error_above_tolerance when another judged observable does,
// else ok. hard_disks may be null (no event-driven run); t0_theory is the Enskog kinetic-theory
// t0 (NaN: none).
nlohmann::json dem_map(const AtlasScene& scene, const std::vector<AtlasRun>& runs,
                       const std::vector<ObservableErrors>& model_error,
                       const std::vector<std::string>& observables, const AtlasRun* hard_disks,
                       double t0_theory, double tolerance, double sigmas);

}  // namespace granvv::app
