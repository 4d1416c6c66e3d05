#pragma once
// Where a homogeneously cooling particle gas stops being homogeneous (docs/physics.md §12): the
// Haff fit runs only over the samples before the box's lowest Fourier modes first carry more
// than a threshold fraction of the kinetic energy (md_bridge/box_modes.hpp). A gas that already
// starts above the threshold (an imposed flow: the single-mode scenes) is not a cooling state
// that becomes unstable, and its fit window stays the whole run.
#include <vector>

namespace granvv::compare {

struct HomogeneousWindow {
  double t_max = 0.0;              // end of the fit window
  double onset = 0.0;              // first sample time above the threshold (NaN: never)
  bool starts_homogeneous = true;  // the first sample lies at or below the threshold
};

// t: sample times; fraction: the ensemble's mean mode-energy fraction at each (NaN samples are
// skipped); t_end: the window when the threshold is never crossed or is crossed at the start.
// The window ends at the last sample before the onset.
HomogeneousWindow homogeneous_window(const std::vector<double>& t,
                                     const std::vector<double>& fraction, double threshold,
                                     double t_end);

}  // namespace granvv::compare
