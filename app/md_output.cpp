#include "app/md_output.hpp"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <variant>

#include "compare/haff_fit.hpp"
#include "fields/field_series_file.hpp"
#include "fields/hdf5_datasets.hpp"
#include "hydro/haff.hpp"
#include "md_bridge/hard_disk_theory.hpp"
#include "scene/initial_provenance.hpp"
#include "scene/json_numbers.hpp"

namespace granvv::app {
namespace {

using h5::write_attribute;
using h5::write_matrix;
using h5::write_vector;
using nlohmann::json;

// The engine's own results at their dotted keys ("contact_initial.kn" -> {"contact_initial":
// {"kn": ...}}).
void add_engine_details(json& block, const md::EngineDetails& details) {
  for (const auto& detail : details) {
    std::string pointer = "/" + detail.key;
    std::replace(pointer.begin(), pointer.end(), '.', '/');
    std::visit([&](const auto& value) { block[json::json_pointer(pointer)] = value; },
               detail.value);
  }
}

// The files given particles were read from, each with its member, size and SHA-256.
json given_files_summary(const md::GivenParticles& given) {
  json files = json::array();
  for (std::size_t m = 0; m < given.members.size(); ++m) {
    for (const std::string& path : given.members[m]) {
      json file = file_provenance(path);
      file["member"] = m;
      files.push_back(std::move(file));
    }
  }
  return files;
}

}  // namespace

json md_cost_summary(const MdOutcome& out) {
  return {{"wall_seconds", out.wall_seconds},
          {out.cost.work_unit, out.cost.work},
          {out.cost.work_unit + "_per_second", number_or_null(out.cost.per_second())}};
}

json md_summary(const MdScene& scene, const MdOutcome& out) {
  const auto& sc = scene.spec.scene;
  const SignalToNoise sn = initial_signal_to_noise(scene);
  const SignalToNoise gradient = initial_gradient_signal_to_noise(scene);
  const SignalToNoise mode = initial_mode_signal_to_noise(scene);
  const auto physics = sc.physics();
  long long steps = 0;
  for (const auto& run : out.runs) steps += run.steps;
  json snaps = json::array();
  for (const auto& s : out.runs.front().fields.snapshots) snaps.push_back(s.t);
  const double deviation = compare::relative_deviation(out.haff.t0, out.haff_t0_theory);
  const double t0_paper = sc.md_time(hydro::haff_time_scale(physics));
  json block = {
      {"status", out.runs.back().status},
      {"engine", out.engine},
      {"particles", sc.particles},
      {"box_length", sc.box_length},
      {"box_width", sc.box_width},
      {"area_fraction", sc.area_fraction},
      {"restitution", sc.restitution},
      {"restitution_measured", out.collision_rule.restitution},
      {"restitution_check", out.collision_rule.description},
      {"restitution_tolerance", md::kRestitutionTolerance},
      {"K", physics.K},
      {"q", physics.q},
      {"unstable_modes", sc.unstable_modes()},
      {"shear_unstable_modes", sc.shear_unstable_modes()},
      {"ensemble", scene.ensemble},
      {"seed", scene.spec.seed},
      {"t_end", scene.spec.t_end},
      {"steps", steps},
      {"haff_t0_measured", number_or_null(out.haff.t0)},
      {"haff_t0_measured_error", number_or_null(out.haff.t0_error)},
      {"haff_T0_measured", number_or_null(out.haff.T0)},
      {"haff_fit_window", {out.haff.t_min, out.haff.t_max}},
      {"haff_t0_theory", out.haff_t0_theory},
      {"haff_t0_theory_dilute", out.haff_t0_theory_dilute},
      {"haff_t0_deviation", number_or_null(deviation)},
      {"haff_t0_deviation_dilute",
       number_or_null(compare::relative_deviation(out.haff.t0, out.haff_t0_theory_dilute))},
      {"haff_t0_deviation_sigmas",
       number_or_null((out.haff.t0 - out.haff_t0_theory) / out.haff.t0_error)},
      {"haff_t0_tolerance", compare::kHaffTimeTolerance},
      {"haff_t0_within_tolerance", bool_or_null(compare::haff_time_within_tolerance(deviation))},
      {"haff_t0_paper", t0_paper},
      {"haff_t0_deviation_paper",
       number_or_null(compare::relative_deviation(out.haff.t0, t0_paper))},
      {"haff_mode_energy_fraction", scene.haff_mode_energy_fraction},
      {"haff_starts_homogeneous", out.homogeneous.starts_homogeneous},
      {"haff_onset_measured", number_or_null(out.homogeneous.onset)},
      {"haff_onset_linear", number_or_null(out.linear_mode_onset)},
      {"pressure", number_or_null(out.pressure.mean)},
      {"pressure_error", number_or_null(out.pressure.error)},
      {"compressibility", number_or_null(out.compressibility.mean)},
      {"compressibility_error", number_or_null(out.compressibility.error)},
      {"compressibility_enskog", md::enskog_compressibility(sc)},
      {"snapshot_times", snaps},
      {"noise_velocity_initial", sn.noise},
      {"signal_velocity_initial", sn.signal},
      {"signal_to_noise_initial", sn.ratio()},
      {"noise_gradient_initial", number_or_null(gradient.noise)},
      {"signal_gradient_initial", gradient.signal},
      {"signal_to_noise_gradient_initial", number_or_null(gradient.ratio())},
      {"noise_mode_initial", mode.noise},
      {"signal_mode_initial", mode.signal},
      {"signal_to_noise_mode_initial", mode.ratio()},
  };
  block.update(md_cost_summary(out));
  add_engine_details(block, out.engine_details);
  if (scene.given) block["input_files"] = given_files_summary(*scene.given);
  block["checkpoints"] = {
      {"interval_seconds", scene.checkpoint_interval},
      {"written", out.checkpoints_written},
      {"resumed", out.resumed_member >= 0 || out.members_restored > 0},
      {"members_restored", out.members_restored},
      {"resumed_member", out.resumed_member >= 0 ? json(out.resumed_member) : json()},
      {"resumed_t", out.resumed_member >= 0 ? json(out.resumed_t) : json()}};
  return block;
}

void write_md_results(const std::filesystem::path& file, const MdScene& scene,
                      const MdOutcome& out) {
  H5::Exception::dontPrint();
  H5::H5File h5(file.string(), H5F_ACC_RDWR);
  H5::Group md = h5.createGroup("/md");
  const auto& sc = scene.spec.scene;
  write_attribute(md, "particles", double(sc.particles));
  write_attribute(md, "box_length", sc.box_length);
  write_attribute(md, "box_width", sc.box_width);
  write_attribute(md, "area_fraction", sc.area_fraction);
  write_attribute(md, "restitution", sc.restitution);
  write_attribute(md, "restitution_measured", out.collision_rule.restitution);
  write_attribute(md, "haff_t0_measured", out.haff.t0);
  write_attribute(md, "haff_t0_measured_error", out.haff.t0_error);
  write_attribute(md, "haff_T0_measured", out.haff.T0);
  write_attribute(md, "haff_t0_theory", out.haff_t0_theory);
  write_attribute(md, "haff_t0_theory_dilute", out.haff_t0_theory_dilute);

  H5::Group ts = h5.createGroup("/md/timeseries");
  const auto& base = out.runs.front().series;
  write_vector(ts, "t", base.t);
  write_vector(ts, "T_mean", out.T.mean);
  write_vector(ts, "T_stderr", out.T.standard_error);
  write_vector(ts, "mode_energy_fraction_mean", out.mode_energy_fraction.mean);
  const hsize_t members = out.runs.size();
  auto stack = [&](std::vector<double> md::MdSeries::*member) {
    std::vector<double> all;
    for (const auto& run : out.runs) {
      auto v = run.series.*member;
      v.resize(base.t.size(), std::nan(""));
      all.insert(all.end(), v.begin(), v.end());
    }
    return all;
  };
  for (const auto& column : md::md_series_columns()) {
    if (column.values != &md::MdSeries::t)
      write_matrix(ts, column.name, stack(column.values), members);
  }
  for (std::size_t i = 0; i < base.engine.size(); ++i) {  // the engine's own series
    std::vector<double> all;
    for (const auto& run : out.runs) {
      auto v = run.series.engine.at(i).second;
      v.resize(base.t.size(), std::nan(""));
      all.insert(all.end(), v.begin(), v.end());
    }
    write_matrix(ts, base.engine[i].first, all, members);
  }
  write_vector(ts, "haff_fit", compare::haff_curve(base.t, out.haff.T0, out.haff.t0));
  write_vector(ts, "haff_theory", compare::haff_curve(base.t, out.haff.T0, out.haff_t0_theory));
  write_vector(ts, "haff_theory_dilute",
               compare::haff_curve(base.t, out.haff.T0, out.haff_t0_theory_dilute));

  H5::Group fields = h5.createGroup("/md/fields");
  fields::write_field_series(fields, out.fields);
}

}  // namespace granvv::app
