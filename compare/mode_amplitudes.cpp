#include "compare/mode_amplitudes.hpp"

#include <algorithm>
#include <stdexcept>

#include "compare/inertia_measures.hpp"

namespace granvv::compare {

const std::vector<std::string>& mode_phase_names() {
  static const std::vector<std::string> names = {"sin", "cos"};
  return names;
}

ModePhase mode_phase(const std::string& name) {
  if (name == "sin") return ModePhase::sine;
  if (name == "cos") return ModePhase::cosine;
  throw std::invalid_argument("unknown mode phase \"" + name + "\" (allowed: sin, cos)");
}

double mode_amplitude(const std::vector<double>& values, ModePhase phase) {
  return phase == ModePhase::sine ? sine_mode_amplitude(values, 1)
                                  : cosine_mode_amplitude(values, 1);
}

bool read_relative_to_mean(const std::string& field) {
  return field == "n" || field == "T";
}

double field_mode_amplitude(const std::vector<double>& values, const std::string& field,
                            ModePhase phase) {
  const double amplitude = mode_amplitude(values, phase);
  if (!read_relative_to_mean(field)) return amplitude;
  double mean = 0.0;
  for (double v : values) mean += v / double(values.size());
  return amplitude / mean;
}

std::vector<std::vector<double>> member_mode_amplitudes(
    const std::vector<fields::FieldSeries>& members, const std::string& field, ModePhase phase) {
  if (members.empty()) throw std::invalid_argument("member_mode_amplitudes: no members");
  const fields::FieldColumn& column = fields::field_column(field);
  std::size_t snapshots = members.front().snapshots.size();
  for (const auto& m : members) snapshots = std::min(snapshots, m.snapshots.size());
  std::vector<std::vector<double>> out;
  for (const auto& m : members) {
    std::vector<double> row;
    for (std::size_t s = 0; s < snapshots; ++s) {
      row.push_back(field_mode_amplitude(m.snapshots[s].*column.values, field, phase));
    }
    out.push_back(std::move(row));
  }
  return out;
}

}  // namespace granvv::compare
