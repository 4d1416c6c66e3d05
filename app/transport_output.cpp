#include "app/transport_output.hpp"

#include <H5Cpp.h>

#include <nlohmann/json.hpp>
#include <string>
#include <tuple>
#include <vector>

#include "compare/transport_coefficients.hpp"
#include "fields/hdf5_datasets.hpp"
#include "scene/json_numbers.hpp"

namespace granvv::app {

namespace {

// measured, error, closures and each closure's distance in errors.
nlohmann::json measured_against_closures(
    double measured, double error, const std::vector<std::pair<std::string, double>>& values) {
  nlohmann::json closures = nlohmann::json::object(), sigmas = nlohmann::json::object();
  for (const auto& [name, value] : values) {
    closures[name] = number_or_null(value);
    sigmas[name] = number_or_null((value - measured) / error);
  }
  return {{"measured", number_or_null(measured)},
          {"error", number_or_null(error)},
          {"closures", closures},
          {"closure_deviation_sigmas", sigmas}};
}

// Each coefficient's measured value and error, and the joint fit's correlation and chi^2, as
// attributes of a /transport group.
void write_joint_fit_attributes(H5::Group& g,
                                const std::vector<std::tuple<std::string, double, double>>& values,
                                double correlation, double chi2, int degrees_of_freedom) {
  for (const auto& [name, measured, error] : values) {
    h5::write_attribute(g, name + "_measured", measured);
    h5::write_attribute(g, name + "_error", error);
  }
  h5::write_attribute(g, "correlation", correlation);
  h5::write_attribute(g, "chi2", chi2);
  h5::write_attribute(g, "degrees_of_freedom", double(degrees_of_freedom));
}

// /transport/<name>, made in `h5` (and /transport with it on the first measurement).
H5::Group new_transport_group(H5::H5File& h5, const std::string& name) {
  H5::Group top =
      h5.nameExists("/transport") ? h5.openGroup("/transport") : h5.createGroup("/transport");
  return top.createGroup(name);
}

}  // namespace

nlohmann::json transport_summary(const TransportMeasurement& m) {
  nlohmann::json entry = measured_against_closures(m.measured, m.error, m.closures);
  entry.update({
      {"closure", m.closure},
      {"factor", number_or_null(m.fit.factor)},
      {"factor_error", number_or_null(m.fit.error)},
      {"chi2", number_or_null(m.fit.chi2)},
      {"degrees_of_freedom", m.fit.degrees_of_freedom},
      {"factor_at_grid_edge", m.fit.at_grid_edge},
      {"field", m.field},
      {"phase", m.phase},
      {"factors", m.grid.factors},
      {"factor_keys", compare::transport_coefficient(m.coefficient).factor_keys},
  });
  return {{m.coefficient, entry}};
}

nlohmann::json transport_pair_summary(const TransportPairMeasurement& m) {
  nlohmann::json out = nlohmann::json::object();
  const auto entry = [&](const TransportPairMeasurement::Coefficient& c,
                         const TransportPairMeasurement::Coefficient& other,
                         const std::vector<double>& factors) {
    nlohmann::json e = measured_against_closures(c.measured, c.error, c.closures);
    e.update({
        {"sigmas_from_zero", number_or_null(c.measured / c.error)},
        {"paired_with", other.name},
        {"correlation", number_or_null(m.fit.correlation)},
        {"closure", m.closure},
        {"factor", number_or_null(c.factor)},
        {"factor_error", number_or_null(c.factor_error)},
        {"chi2", number_or_null(m.fit.chi2)},
        {"degrees_of_freedom", m.fit.degrees_of_freedom},
        {"factor_at_grid_edge", m.fit.at_grid_edge},
        {"signals", m.signals},
        {"factors", factors},
        {"factor_keys", compare::transport_coefficient(c.name).factor_keys},
    });
    return e;
  };
  out[m.first.name] = entry(m.first, m.second, m.grid.factors_a);
  out[m.second.name] = entry(m.second, m.first, m.grid.factors_b);
  return out;
}

void write_transport_pair_results(const std::filesystem::path& file,
                                  const TransportPairMeasurement& m) {
  H5::Exception::dontPrint();
  H5::H5File h5(file.string(), H5F_ACC_RDWR);
  H5::Group g = new_transport_group(h5, m.pair.name);
  h5::write_attribute(g, "closure", m.closure);
  for (const auto* c : {&m.first, &m.second}) {
    h5::write_attribute(g, c->name + "_factor", c->factor);
    h5::write_attribute(g, c->name + "_factor_error", c->factor_error);
  }
  write_joint_fit_attributes(g,
                             {{m.first.name, m.first.measured, m.first.error},
                              {m.second.name, m.second.measured, m.second.error}},
                             m.fit.correlation, m.fit.chi2, m.fit.degrees_of_freedom);
  h5::write_attribute(g, "scale", m.fit.scale);
  h5::write_vector(g, "t", m.t);
  h5::write_vector(g, m.first.name + "_factors", m.grid.factors_a);
  h5::write_vector(g, m.second.name + "_factors", m.grid.factors_b);
  for (std::size_t k = 0; k < m.signals.size(); ++k) {
    H5::Group s = g.createGroup(m.signals[k]);
    h5::write_vector(s, "amplitude", m.fit.amplitude[k]);
    h5::write_vector(s, "amplitude_error", m.fit.amplitude_error[k]);
    h5::write_vector(s, "residual_error", m.fit.residual_error[k]);
    h5::write_vector(s, "hydro_fitted", m.fit.fitted[k]);
    // The hydro at every grid point, row i * (second factors) + j at (first[i], second[j]).
    std::vector<double> flat;
    for (const auto& row : m.hydro_and_members[k].hydro) {
      for (const auto& h : row) flat.insert(flat.end(), h.begin(), h.end());
    }
    h5::write_matrix(s, "hydro_grid", flat, m.grid.factors_a.size() * m.grid.factors_b.size());
    flat.clear();
    for (const auto& a : m.hydro_and_members[k].members)
      flat.insert(flat.end(), a.begin(), a.end());
    h5::write_matrix(s, "member_amplitudes", flat, m.hydro_and_members[k].members.size());
  }
}

void write_transport_results(const std::filesystem::path& file, const TransportMeasurement& m) {
  H5::Exception::dontPrint();
  H5::H5File h5(file.string(), H5F_ACC_RDWR);
  H5::Group g = new_transport_group(h5, m.coefficient);
  h5::write_attribute(g, "field", m.field);
  h5::write_attribute(g, "phase", m.phase);
  h5::write_attribute(g, "closure", m.closure);
  h5::write_attribute(g, "factor", m.fit.factor);
  h5::write_attribute(g, "factor_error", m.fit.error);
  h5::write_attribute(g, "start_amplitude", m.fit.start);
  h5::write_attribute(g, "chi2", m.fit.chi2);
  h5::write_attribute(g, "degrees_of_freedom", double(m.fit.degrees_of_freedom));
  h5::write_attribute(g, "measured", m.measured);
  h5::write_attribute(g, "error", m.error);
  h5::write_vector(g, "t", m.t);
  h5::write_vector(g, "amplitude", m.fit.amplitude);
  h5::write_vector(g, "amplitude_error", m.fit.amplitude_error);
  h5::write_vector(g, "residual_error", m.fit.residual_error);
  h5::write_vector(g, "hydro_unit_factor", m.fit.unit_factor);
  h5::write_vector(g, "hydro_fitted", m.fit.fitted);
  h5::write_vector(g, "factors", m.grid.factors);
  std::vector<double> flat;
  for (const auto& row : m.grid.amplitudes) flat.insert(flat.end(), row.begin(), row.end());
  h5::write_matrix(g, "hydro_grid", flat, m.grid.factors.size());
}

nlohmann::json heat_flux_summary(const HeatFluxMeasurement& m) {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& c : m.coefficients) {
    nlohmann::json e = measured_against_closures(c.measured, c.error, c.closures);
    e.update({
        {"sigmas_from_zero", number_or_null(c.measured / c.error)},
        {"method", m.kind.name},
        {"contact_transfer", m.contact_transfer},
        {"correlation", number_or_null(m.fit.correlation)},
        {"closure", m.closure},
        {"chi2", number_or_null(m.fit.chi2)},
        {"degrees_of_freedom", m.fit.degrees_of_freedom},
        {"t_first", number_or_null(m.t.front())},
        {"t_last", number_or_null(m.t.back())},
    });
    out[c.name] = e;
  }
  return out;
}

void write_heat_flux_results(const std::filesystem::path& file, const HeatFluxMeasurement& m) {
  H5::Exception::dontPrint();
  H5::H5File h5(file.string(), H5F_ACC_RDWR);
  H5::Group g = new_transport_group(h5, m.kind.name);
  h5::write_attribute(g, "method", m.kind.name);
  h5::write_attribute(g, "contact_transfer", m.contact_transfer ? "yes" : "no");
  h5::write_attribute(g, "closure", m.closure);
  std::vector<std::tuple<std::string, double, double>> values;
  for (const auto& c : m.coefficients) values.emplace_back(c.name, c.measured, c.error);
  write_joint_fit_attributes(g, values, m.fit.correlation, m.fit.chi2, m.fit.degrees_of_freedom);
  h5::write_vector(g, "t", m.t);
  h5::write_vector(g, "response", m.fit.response);
  h5::write_vector(g, "response_error", m.fit.response_error);
  h5::write_vector(g, "fitted", m.fit.fitted);
  h5::write_vector(g, "navier_stokes", m.fit.navier_stokes);
  h5::write_vector(g, "density_part", m.fit.density_part);
}

}  // namespace granvv::app
