#pragma once
// A scene's transport measurement in the outputs (docs/outputs.md): summary.json's `transport`
// block and results.h5's /transport group.
#include <filesystem>
#include <nlohmann/json_fwd.hpp>

#include "models/heat_flux_measurement.hpp"
#include "models/transport_measurement.hpp"
#include "models/transport_pair_measurement.hpp"

namespace granvv::app {

// {<coefficient>: {"measured", "error", "closures": {name: value}, ...}}: every value relative
// to the elastic dilute coefficient of hard disks, with the fit behind it (the factor F on
// hydro.closure's coefficient, its error, chi^2 and its degrees of freedom, whether F is at the
// end of the grid, the field and its phase, the grid's factors and their case keys).
nlohmann::json transport_summary(const TransportMeasurement& m);

// /transport/<coefficient> in an existing results.h5: t, the particles' mean amplitude and its
// jackknife error, the residual's error, the hydro's curves at F = 1 and at the fitted F, and the
// hydro's amplitudes at every factor of the grid; the fit's numbers as attributes.
void write_transport_results(const std::filesystem::path& file, const TransportMeasurement& m);

// A pair's two coefficients, each an entry of the shape above (its factor on the closure's value,
// the grid of its factors, the signals fitted), with `paired_with`, the `correlation` of the two
// errors, `sigmas_from_zero` (measured / error) and the joint fit's chi^2 in both.
nlohmann::json transport_pair_summary(const TransportPairMeasurement& m);

// /transport/<pair name>: t, per signal the particles' mean amplitude, its jackknife error, the
// residual's error and the fitted hydro; the two factor axes and the fit's numbers as attributes.
void write_transport_pair_results(const std::filesystem::path& file,
                                  const TransportPairMeasurement& m);

// kappa and mu from the particles' heat flux (and the Burnett term), each an entry
// {"measured", "error", "closures", "closure_deviation_sigmas"} with `sigmas_from_zero`,
// `method` (the compare.transport name), `contact_transfer` (whether the flux includes the
// contacts' transfer of energy), the `correlation` of kappa's and mu's errors, the fit's
// chi^2 and degrees of freedom, and the fitted snapshots' first and last scaled times.
nlohmann::json heat_flux_summary(const HeatFluxMeasurement& m);

// /transport/<name>: t, the response q / (k kappa0 T) with its jackknife error, the fit, its
// Navier-Stokes part and mu's part (-mu dn/dx); the coefficients and the fit's numbers as
// attributes.
void write_heat_flux_results(const std::filesystem::path& file, const HeatFluxMeasurement& m);

}  // namespace granvv::app
