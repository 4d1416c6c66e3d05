#pragma once
// The k = 1 Fourier amplitude of one field in every member of a particle ensemble at every
// snapshot: the signal a transport measurement follows (docs/physics.md §14). A shear wave
// v_y = A sin 2 pi x is read by its sine part, a temperature or density mode A cos 2 pi x by its
// cosine part, each member on its own, so that the members' scatter gives the error of the mean
// amplitude with its correlations across bins and snapshots (compare/jackknife.hpp) instead of
// the per-bin errors projected as if the bins were independent.
#include <string>
#include <vector>

#include "fields/field_series.hpp"

namespace granvv::compare {

enum class ModePhase { sine, cosine };

// "sin" or "cos" (the case's compare.transport_phase); throws std::invalid_argument otherwise.
ModePhase mode_phase(const std::string& name);
const std::vector<std::string>& mode_phase_names();

// The k = 1 amplitude of a profile on the periodic bins of [-1/2, 1/2): b1 = 2 <f sin 2 pi x> or
// a1 = 2 <f cos 2 pi x> over the bin centres (compare/inertia_measures.hpp), exact for a single
// mode sampled at the bin centres.
double mode_amplitude(const std::vector<double>& values, ModePhase phase);

// Whether a field's mode is read relative to the field's box mean (the mean over the bins): n
// and T, whose perturbations the linear theory of the cooling state follows as n/<n> and
// T/<T> (docs/physics.md §2), so that the homogeneous cooling, whose rate the closure sets and
// the particles may have otherwise, leaves a temperature mode's amplitude alone; and the units
// of n drop out. The velocities are read as they are (in sqrt(T0/m), the same in both models).
bool read_relative_to_mean(const std::string& field);

// The amplitude of `field`'s mode in one profile, relative to its mean where the field is read so.
double field_mode_amplitude(const std::vector<double>& values, const std::string& field,
                            ModePhase phase);

// amplitudes[m][s]: member m's field_mode_amplitude of `field` (a fields::field_columns() name)
// at snapshot s, for the snapshots every member has (the shortest member's count). Throws
// std::invalid_argument without members or for an unknown field.
std::vector<std::vector<double>> member_mode_amplitudes(
    const std::vector<fields::FieldSeries>& members, const std::string& field, ModePhase phase);

}  // namespace granvv::compare
