#pragma once
// The side-by-side judgement of a hydro against a particle ensemble (docs/physics.md §8): the
// fields' tracks bin by bin within `sigmas` standard errors, the agreement window, and the kind
// of the disagreement (compare/verdict.hpp) with the box-mean offset of the first field to part
// at the time it parted. `granvv run` judges its comparison with it, and `granvv atlas` its
// comparison power (hydros with injected model errors against the same particles).
#include <string>
#include <vector>

#include "compare/field_metrics.hpp"
#include "compare/verdict.hpp"
#include "fields/field_series.hpp"

namespace granvv::compare {

struct SideBySide {
  std::vector<std::pair<std::size_t, std::size_t>> pairs;  // (particle, hydro) snapshots
  std::vector<double> t;                                   // their times
  std::vector<FieldTrack> tracks;                          // one per named field
  AgreementWindow window;
  double offset_sigmas = 0.0;  // box-mean offset of the first field to part (0: none parted)
  Disagreement kind = Disagreement::none;
};

// The fields a side-by-side comparison weighs: the hydrodynamic fields (n, v_x, T, and v_y when
// the hydro carries the transverse flow).
std::vector<std::string> compared_fields(bool transverse);

// The particles' ensemble mean (with the standard errors of that mean) against the hydro on
// the same bins, at the times both have. signal_to_noise is the particles' initial one.
SideBySide judge_side_by_side(const fields::FieldSeries& particles,
                              const fields::FieldSeries& hydro,
                              const std::vector<std::string>& field_names, double sigmas,
                              double agreement_fraction, double signal_to_noise,
                              const VerdictRule& rule);

}  // namespace granvv::compare
