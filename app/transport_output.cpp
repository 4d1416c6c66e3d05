#include "app/transport_output.hpp"

#include <H5Cpp.h>

#include "compare/transport_coefficients.hpp"
#include "fields/hdf5_datasets.hpp"
#include "scene/json_numbers.hpp"

namespace granvv::app {

nlohmann::json transport_summary(const TransportMeasurement& m) {
  nlohmann::json closures = nlohmann::json::object(), sigmas = nlohmann::json::object();
  for (const auto& [name, value] : m.closures) {
    closures[name] = number_or_null(value);
    sigmas[name] = number_or_null((value - m.measured) / m.error);
  }
  nlohmann::json entry = {
      {"measured", number_or_null(m.measured)},
      {"error", number_or_null(m.error)},
      {"closures", closures},
      {"closure_deviation_sigmas", sigmas},
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
  };
  return {{m.coefficient, entry}};
}

void write_transport_results(const std::filesystem::path& file, const TransportMeasurement& m) {
  H5::Exception::dontPrint();
  H5::H5File h5(file.string(), H5F_ACC_RDWR);
  H5::Group top =
      h5.nameExists("/transport") ? h5.openGroup("/transport") : h5.createGroup("/transport");
  H5::Group g = top.createGroup(m.coefficient);
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

}  // namespace granvv::app
