#pragma once
// What of a flow by inertia (paper Eqs. 4-7) survives in a noisy particle run: measures of a
// binned profile on the periodic bins of [-1/2, 1/2) (scaled units, n relative to its mean)
// that average over many bins and so over the noise-born clusters, and the one that does not.
//   - the mode-1 Fourier amplitudes of v (its sin 2 pi x part, the imposed mode) and of n (its
//     cos 2 pi x part: v0 = a sin 2 pi x is odd about x = 0, so the density it gathers is even and
//     its sin part vanishes by symmetry);
//   - the mass within the central window |x| < w: the mass the flow gathers towards x = 0;
//   - the density at x = 0 itself, a single bin, which noise-born clusters saturate.
// docs/physics.md §8 ("What still agrees").
#include <vector>

namespace granvv::compare {

// Half-width w of the central window, scaled: a tenth of the box. Under the paper's single mode
// (a = -0.05) flow by inertia gathers 38 % of the mass into it at t = 3 (10 % at t = 0).
inline constexpr double kCentralWindowHalfWidth = 0.05;

// b_k with f = ... + b_k sin(2 pi k x) + ...: b_k = -2 Im c_k for the bin coefficient c_k
// (compare/density_modes.hpp), i.e. 2 sum_b f_b sin(2 pi k x_b) / bins. For f = a sin(2 pi k x)
// sampled at the bin centres it is exactly a (bins > 2 k). NaN if any value is.
double sine_mode_amplitude(const std::vector<double>& values, int k);

// a_k with f = ... + a_k cos(2 pi k x) + ...: a_k = 2 Re c_k = 2 sum_b f_b cos(2 pi k x_b) / bins.
double cosine_mode_amplitude(const std::vector<double>& values, int k);

// The mass in the bins whose centres lie in |x| < half_width: sum n_b / bins (a fraction of the
// box's mass when n has mean 1). When +-half_width fall on bin edges it is the exact mass of
// the window for bin-averaged n.
double central_window_mass(const std::vector<double>& n, double half_width);

// The density at x = 0: the bin that holds it (odd bin counts), or the mean of the two that
// share the edge at x = 0 (even counts).
double central_density(const std::vector<double>& n);

}  // namespace granvv::compare
