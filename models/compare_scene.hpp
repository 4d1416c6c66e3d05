#pragma once
// A case's side-by-side part ([compare]): the hydro aligned with the particle run (same times,
// optionally started from the particles' own coarse-grained t = 0 fields), and the comparison
// of the two on the particles' bins, in the hydro's scaled units (docs/physics.md §4).
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "compare/binned_fields.hpp"
#include "compare/field_metrics.hpp"
#include "compare/mode_amplitudes.hpp"
#include "compare/verdict.hpp"
#include "scene/case_config.hpp"
#include "scene/hydro_scene.hpp"
#include "scene/md_scene.hpp"

namespace granvv::app {

// The case's compare.* keys; their defaults are in the case schema only (scene/case_schema.cpp).
struct CompareScene {
  bool hydro_from_md = false;
  double sigmas = 0.0;
  double agreement_fraction = 0.0;
  compare::VerdictRule verdict_rule;  // its offset_sigmas is compare.sigmas
  int density_modes = 0;
  // compare.closures: the hydro closures run against the one particle ensemble, each compared
  // on its own; the first is hydro.closure and fills the hydro and compare blocks.
  std::vector<std::string> closures;
  // compare.transport*: the coefficient the scene measures, from which field's k = 1 mode, and
  // the factors at which the hydro runs for the fit (models/transport_measurement.hpp); none
  // for compare.transport = "none".
  struct Transport {
    std::string coefficient, field;
    compare::ModePhase phase = compare::ModePhase::sine;
    int start = 0;  // compare.transport_start: the snapshot the fit starts from
    std::vector<double> factors;
    // compare.transport_signals, each field with its phase; [field, phase] when the key is [].
    std::vector<std::pair<std::string, compare::ModePhase>> signals;
  };
  std::optional<Transport> transport;
};

// Reads [compare]; std::nullopt if compare.enabled is false. Throws ConfigError, naming
// compare.closures, for a closure list whose first entry is not hydro.closure or whose closures
// cannot model the particle scene (e.g. enskog outside its area fractions).
std::optional<CompareScene> compare_scene_from(const CaseConfig& config);

// The hydro of a comparison models the particles' own scene: K and q from the particle scene
// (which md.particles or the rounding of N may set apart from physics.K), the particles' end
// time, and snapshots at their actual snapshot times (which land on MD steps), all in scaled
// units.
void align_hydro_with_md(HydroScene& hydro, const md::ParticleScene& scene, double md_t_end,
                         const fields::FieldSeries& md_fields);

// The hydro of a comparison, from the case's: started from the particles' coarse-grained t = 0
// fields where compare.hydro_initial = "md", and aligned with them (align_hydro_with_md).
void prepare_comparison_hydro(HydroScene& hydro, const CompareScene& compare, const MdScene& md,
                              const fields::FieldSeries& md_fields);

// Continuous fields through the ensemble-mean bin values of one MD snapshot (scaled units),
// periodic and piecewise linear between bin centres.
hydro::InitialFields fields_from_snapshot(const fields::FieldSnapshot& snapshot,
                                          const md::ParticleScene& scene);

// The comparison of one field over the output times.
struct FieldComparison {
  std::string name;  // "n", "v_x", "v_y", "T"
  compare::FieldTrack track;
  std::string error_source;  // compare::error_source_label: ensemble-calibrated or one snapshot
};

struct CompareOutcome {
  std::vector<double> t;  // scaled output times both engines reached
  std::vector<double> x;  // bin centres, scaled
  // Both sides on the particles' bins at the times t, scaled units: the hydro binned like the
  // particles (compare/binned_fields.hpp), and the particles' ensemble mean with the error of
  // that mean (compare/ensemble_error_model.hpp) as its *_stderr.
  fields::FieldSeries hydro_on_bins, md_on_bins;
  std::vector<FieldComparison> fields;
  compare::AgreementWindow window;
  // Per output time, from the binned fields of both sides (per particle, scaled units):
  // peak density, |dv/dx| at the peak (centred difference on the bins), thermal and flow energy
  // (compare/binned_energies.hpp: the particles' flow energy without the bin means' noise).
  std::vector<double> hydro_n_peak, md_n_peak, md_n_peak_error;
  std::vector<double> hydro_dvdx_peak, md_dvdx_peak;
  std::vector<double> hydro_energy_thermal, md_energy_thermal;
  std::vector<double> hydro_energy_kinetic, md_energy_kinetic;
  // Flow by inertia (paper Eq. 5) on the same bins, where the case's initial velocity is
  // smooth and the time is before its singularity; NaN rows otherwise.
  std::vector<std::vector<double>> inertia_n, inertia_v;
  std::vector<double> inertia_n_peak;
  // What of the flow by inertia survives noise (compare/inertia_measures.hpp), per output time:
  // the sin 2 pi x amplitude of v and the cos 2 pi x amplitude of n, the mass within |x| <
  // central_window, and the density at x = 0. The particles' is the mean over members of each
  // member's measure, with the error of that mean (NaN with one member); NaN where a side has no
  // value (inertia past tau).
  struct InertiaMeasure {
    std::vector<double> md, md_error, hydro, inertia;
  };
  double central_window = 0.0;
  InertiaMeasure v_mode, n_mode, window_mass, n_centre;
  // Density Fourier modes |n_k|, k = 1..density_modes (rows: times), and the linear theory's
  // growth exponent Re lambda(k) (collision clock) of the fastest branch.
  std::vector<std::vector<double>> hydro_modes, md_modes, md_modes_error, theory_modes;
  std::vector<double> theory_rate;
  std::vector<double> collision_clock;  // s(t) of Haff's law at each output time
  double signal_to_noise = 0.0;
  // Which kind a disagreement is, by CompareScene::verdict_rule (compare/verdict.hpp,
  // docs/physics.md §8): "none", "model" or "noise".
  std::string disagreement;
  double offset_sigmas = 0.0;  // box-mean offset of the first field to part, in its std. errors
  std::string verdict;
};

// The monitors (hydro/validity_monitors.hpp, by summary name) that had crossed their
// thresholds at or before the time the first field parted (empty when nothing parted).
std::vector<std::string> monitors_fired_by(const hydro::ValidityRecord& validity,
                                           const compare::AgreementWindow& window);

CompareOutcome compare_engines(const CompareScene& scene, const HydroScene& hydro,
                               const HydroOutcome& hydro_out, const MdScene& md,
                               const MdOutcome& md_out);

}  // namespace granvv::app
