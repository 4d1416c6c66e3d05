#pragma once
// The DEM stability and bias map of `granvv atlas` (docs/atlas.md): the soft-contact t0, P and
// P/(nT) against the hard disks as a function of the contact knobs.
#include <map>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "atlas/atlas_analysis.hpp"
#include "atlas/atlas_runs.hpp"
#include "models/model_family.hpp"

namespace granvv::app {

// The DEM map (atlas.json `dem_map`) of a family with contact knobs (max_overlap,
// steps_per_contact, adaptive_stiffness; ModelFamily::has_contact_map): every run of it (the
// largest ensemble at each contact setting) with its state and its t0, pressure and P/(nT) bias
// against the hard-disk reference, and the boundaries along each knob from the case's own setting.
// A finished run's state is t0_bias_above_tolerance when its t0 fails the σ-aware test against the
// reference (atlas/recommendation.hpp), else error_above_tolerance when another judged observable
// does, else ok. hard_disks may be null (no event-driven run); t0_theory is the Enskog
// kinetic-theory t0 (NaN: none).
nlohmann::json dem_map(const ModelFamily& family, const AtlasScene& scene,
                       const std::vector<AtlasRun>& runs,
                       const std::vector<ObservableErrors>& model_error,
                       const std::vector<std::string>& observables, const AtlasRun* hard_disks,
                       double t0_theory, double tolerance, double sigmas);

}  // namespace granvv::app
