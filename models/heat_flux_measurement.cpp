#include "models/heat_flux_measurement.hpp"

#include <stdexcept>

#include "fields/constants.hpp"
#include "md_bridge/particle_scene.hpp"
#include "models/transport_measurement.hpp"

namespace granvv::app {

HeatFluxMeasurement measure_heat_flux(const compare::TransportFluxFit& kind,
                                      const CompareScene::Transport& transport,
                                      const std::vector<std::string>& closures,
                                      const HydroScene& hydro, const MdScene& md,
                                      const MdOutcome& md_out) {
  HeatFluxMeasurement out;
  out.kind = kind;
  out.closure = hydro.closure;
  std::vector<fields::FieldSeries> members;
  for (const auto& run : md_out.runs) members.push_back(run.fields);
  const md::ParticleScene& sc = md.spec.scene;
  try {
    const compare::HeatFluxAmplitudes a = compare::heat_flux_amplitudes(members, md::kDiskMass);
    out.fit = compare::fit_heat_flux(a, kTwoPi / sc.box_length, md::kDiskMass, md::kDiskDiameter,
                                     static_cast<std::size_t>(transport.start), true);
    for (std::size_t s : out.fit.snapshots) out.t.push_back(sc.scaled_time(a.t[s]));
    out.contact_transfer = a.contact_transfer;
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error("transport: compare.transport = \"" + kind.name + "\": " + e.what());
  }
  const std::vector<std::pair<double, double>> values = {
      {out.fit.conductivity, out.fit.conductivity_error},
      {out.fit.mu, out.fit.mu_error},
      {out.fit.burnett, out.fit.burnett_error}};
  std::vector<std::string> names = kind.coefficients;
  names.push_back(kind.extra);
  for (std::size_t c = 0; c < names.size(); ++c) {
    HeatFluxMeasurement::Coefficient entry{names[c], values[c].first, values[c].second, {}};
    for (const std::string& name : closures) {
      const bool known = names[c] != kind.extra;
      entry.closures.emplace_back(
          name,
          known ? closure_coefficient_value(compare::transport_coefficient(names[c]), hydro, name)
                : 0.0);
    }
    out.coefficients.push_back(std::move(entry));
  }
  return out;
}

}  // namespace granvv::app
