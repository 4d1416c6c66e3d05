#include "models/transport_measurement.hpp"

#include <stdexcept>

#include "compare/mode_amplitudes.hpp"
#include "compare/transport_coefficients.hpp"
#include "models/model.hpp"

namespace granvv::app {
namespace {

// The hydro's amplitude at each of the times, from its snapshots at those times; the index of a
// time the hydro has no snapshot at is left out of `kept`.
std::vector<double> hydro_amplitudes(const fields::FieldSeries& hydro, const std::string& field,
                                     compare::ModePhase phase, const std::vector<double>& times,
                                     std::vector<std::size_t>& kept) {
  const fields::FieldColumn& column = fields::field_column(field);
  std::vector<double> out;
  std::vector<std::size_t> found;
  for (std::size_t s = 0; s < times.size(); ++s) {
    for (const auto& snap : hydro.snapshots) {
      if (!fields::same_time(snap.t, times[s])) continue;
      out.push_back(compare::field_mode_amplitude(snap.*column.values, field, phase));
      found.push_back(s);
      break;
    }
  }
  kept = std::move(found);
  return out;
}

}  // namespace

TransportMeasurement measure_transport(const CompareScene::Transport& transport,
                                       const std::vector<std::string>& closures,
                                       const HydroScene& hydro, const MdScene& md,
                                       const MdOutcome& md_out) {
  const compare::TransportCoefficient& coefficient =
      compare::transport_coefficient(transport.coefficient);
  const md::ParticleScene& sc = md.spec.scene;
  TransportMeasurement out;
  out.coefficient = transport.coefficient;
  out.field = transport.field;
  out.phase = compare::mode_phase_names()[transport.phase == compare::ModePhase::sine ? 0 : 1];
  out.closure = hydro.closure;

  std::vector<fields::FieldSeries> members;
  for (const auto& run : md_out.runs) members.push_back(run.fields);
  std::vector<std::vector<double>> amplitudes =
      compare::member_mode_amplitudes(members, transport.field, transport.phase);
  std::vector<double> times;
  for (std::size_t s = 0; s < amplitudes.front().size(); ++s) {
    times.push_back(sc.scaled_time(members.front().snapshots[s].t));
  }

  // The hydro at each factor of the grid, every factor key of the coefficient set to it.
  const std::size_t start = static_cast<std::size_t>(transport.start);
  std::vector<std::size_t> kept;
  for (std::size_t s = start; s < times.size(); ++s) kept.push_back(s);
  for (double factor : transport.factors) {
    HydroScene scene = hydro;
    for (const auto& key : coefficient.factor_keys) set_transport_factor(scene, key, factor);
    HydroModel model(scene, md.spec.bins);
    const fields::ModelResult result = model.run();
    if (model.outcome().run.status == hydro::RunStatus::failed) {
      throw std::runtime_error("transport: the hydro at " + coefficient.factor_keys.front() +
                               " = " + std::to_string(factor) +
                               " failed: " + model.outcome().run.stop_reason);
    }
    std::vector<std::size_t> found;
    std::vector<double> h =
        hydro_amplitudes(*result.fields, transport.field, transport.phase, times, found);
    // Keep the snapshots every run has (a run that stopped early has fewer).
    std::vector<std::size_t> both;
    for (std::size_t s : kept) {
      for (std::size_t f : found) {
        if (f == s) both.push_back(s);
      }
    }
    kept = both;
    std::vector<double> at_times(times.size(), 0.0);
    for (std::size_t i = 0; i < found.size(); ++i) at_times[found[i]] = h[i];
    out.grid.factors.push_back(factor);
    out.grid.amplitudes.push_back(std::move(at_times));
  }
  if (kept.size() < 3 || kept.front() != start) {
    throw std::runtime_error("transport: the hydro and the particles share " +
                             std::to_string(kept.size()) + " snapshot times from snapshot " +
                             std::to_string(start) +
                             " (compare.transport_start) on; the fit needs three from there");
  }
  auto select = [&](const std::vector<double>& row) {
    std::vector<double> chosen;
    for (std::size_t s : kept) chosen.push_back(row[s]);
    return chosen;
  };
  for (auto& row : out.grid.amplitudes) row = select(row);
  for (auto& row : amplitudes) row = select(row);
  out.t = select(times);

  out.fit = compare::fit_transport_factor(out.grid, amplitudes);
  for (const std::string& name : closures) {
    HydroScene scene = hydro;
    scene.closure = name;
    scene.factors = {};
    const auto closure = make_hydro_closure(scene);
    out.closures.emplace_back(name, coefficient.relative_value(*closure, scene.physics.K, 1, 1));
  }
  HydroScene own = hydro;
  own.factors = {};
  const double value = coefficient.relative_value(*make_hydro_closure(own), own.physics.K, 1, 1);
  out.measured = out.fit.factor * value;
  out.error = out.fit.error * value;
  return out;
}

}  // namespace granvv::app
