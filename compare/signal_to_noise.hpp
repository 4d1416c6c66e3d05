#pragma once
// How clearly an imposed initial flow stands out of the thermal noise of N disks
// (docs/physics.md §8), in the hydro's scaled units (x in [-1/2, 1/2), T0 = m = 1). Three
// forms, each a signal against its noise:
//   velocity: the largest initial flow component max(|v0|, |v_y0|) against the thermal noise of a
//   bin mean,
//             (n0 Ly l)^{-1/2} on the coarse-graining scale l = Lx / bins;
//   gradient: the largest imposed gradient max|v0'| against the noise of the velocity gradient
//             on the shortest unstable wavelength l = Lx / k_max, k_max sqrt(k_max / N): how
//             strongly the imposed flow, rather than the noise, seeds the clusters;
//   mode:     the sin 2 pi x amplitude b1 = 2 <v0 sin 2 pi x> against its thermal noise
//             sqrt(2 / N): how clearly the imposed mode as a whole, which averages over every
//             bin, stands out.
#include <functional>

namespace granvv::compare {

struct SignalToNoise {
  double signal = 0.0, noise = 0.0;
  double ratio() const { return signal / noise; }
};

// The largest value of f on the 4096 cell centres of [-1/2, 1/2).
double profile_maximum(const std::function<double(double)>& f);

// The largest flow component of the initial state at x, max(|v|, |v_y|): the profile of the
// velocity form, which counts a transverse flow (a shear wave) as the flow it is, since the
// bin mean of either component has the same thermal noise. vy empty: no transverse flow.
std::function<double(double)> largest_flow_component(std::function<double(double)> v,
                                                     std::function<double(double)> vy);

// v: the initial velocity profile; number_density n0, box_width Ly and box_length Lx in MD
// units; bins the coarse-graining bins over Lx.
SignalToNoise velocity_signal_to_noise(const std::function<double(double)>& v,
                                       double number_density, double box_width, double box_length,
                                       int bins);

// dv: the initial velocity gradient (empty: no smooth imposed velocity, signal 0, ratio 0);
// unstable_modes k_max (0: NaN noise and ratio); particles N.
SignalToNoise gradient_signal_to_noise(const std::function<double(double)>& dv, int unstable_modes,
                                       long long particles);

// v: the initial velocity profile; b1 by the midpoint rule on 4096 cells (exact for a single
// mode up to rounding); particles N.
SignalToNoise mode_signal_to_noise(const std::function<double(double)>& v, long long particles);

}  // namespace granvv::compare
