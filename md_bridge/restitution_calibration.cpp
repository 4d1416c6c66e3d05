#include "md_bridge/restitution_calibration.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "md_bridge/lammps_session.hpp"

namespace granvv::md {

namespace {

std::string show(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

// Steps before the first contact (plus the phase fraction) and the cap on the whole run in
// contact times; the box is sized for the cap, so no pair can meet a periodic image.
constexpr int kApproachSteps = 2;
constexpr double kMaxContactTimes = 20.0;
// Above this undamped overlap the linear spring is far from a hard-disk collision.
constexpr double kMaxOverlapFraction = 0.25;

}  // namespace

RestitutionCalibration::RestitutionCalibration(ContactModel model,
                                               RestitutionCalibrationOptions options)
    : model_(model), options_(std::move(options)) {
  validate(model_);
  if (options_.phases < 1 || options_.phases > 4096)
    throw std::invalid_argument("restitution calibration: phases = " +
                                std::to_string(options_.phases) + ": must be in [1, 4096]");
}

RestitutionMeasurement RestitutionCalibration::measure(double approach_speed) {
  const auto start = std::chrono::steady_clock::now();
  const double u = approach_speed;
  const double sigma = model_.diameter;
  const double m_eff = effective_mass(model_.mass);
  const double bound = undamped_max_overlap(model_.kn, m_eff, u);
  if (!(std::isfinite(u) && u > 0.0))
    throw std::invalid_argument("restitution calibration: approach speed = " + show(u) +
                                ": must be finite and > 0");
  if (!(bound <= kMaxOverlapFraction * sigma))
    throw std::invalid_argument("restitution calibration: approach speed = " + show(u) +
                                ": the overlap u sqrt(m_eff/kn) = " + show(bound) +
                                " exceeds 0.25 sigma; this model "
                                "resolves relative speeds up to " +
                                show(kMaxOverlapFraction * sigma / std::sqrt(m_eff / model_.kn)));

  const int pairs = options_.phases;
  const double dt = model_.dt;
  const double tc = model_.contact_time;
  const long long max_steps =
      kApproachSteps + 2 + static_cast<long long>(std::ceil(kMaxContactTimes * tc / dt));
  // Largest |x| any disk reaches: each moves at most u/2 (momentum conservation in the
  // pair), starting from (sigma + gap)/2 with gap < (kApproachSteps + 1) u dt.
  const double gap_max = (kApproachSteps + 1) * u * dt;
  const double reach = 0.5 * (sigma + gap_max) + 0.5 * u * dt * static_cast<double>(max_steps);
  const double skin = 0.25 * sigma;
  const double half_x = reach + sigma + skin + sigma;  // images stay > sigma + skin apart
  const double row = 2.0 * sigma;  // rows never touch: distance 2 sigma > cutoff sigma + skin
  const double y_lo = -0.5 * row;
  const double y_hi = y_lo + row * pairs;
  if (!std::isfinite(half_x) || half_x > 1e6 * sigma)
    throw std::invalid_argument("restitution calibration: box of half-width " + show(half_x) +
                                " sigma too large (dt = " + show(dt) + ", u = " + show(u) + ")");

  commands_.clear();
  LammpsSessionOptions session_options;
  session_options.log_file = options_.log_file;
  session_options.comm = options_.comm;
  session_options.on_command = [this](const std::string& line) {
    commands_.push_back(line);
    if (options_.on_command) options_.on_command(line);
  };
  LammpsSession lmp(std::move(session_options));

  const std::string n = lammps_number(-half_x), p = lammps_number(half_x);
  lmp.commands({
      "units lj",
      "dimension 2",
      "atom_style sphere",
      "boundary p p p",
      "comm_modify vel yes",  // gran pairs need ghost velocities
      "region box block " + n + " " + p + " " + lammps_number(y_lo) + " " + lammps_number(y_hi) +
          " " + lammps_number(-0.5 * sigma) + " " + lammps_number(0.5 * sigma),
      "create_box 1 box",
  });

  // Pair k: disks 2k+1 (left, +u/2) and 2k+2 (right, -u/2) in row y = 2 sigma k, with the
  // surface gap (kApproachSteps + s_k) u dt: the first overlap appears at phase s_k.
  AtomBatch batch;
  for (int k = 0; k < pairs; ++k) {
    const double s = (k + 0.5) / pairs;
    const double gap = (kApproachSteps + s) * u * dt;
    const double y = row * k;
    for (const double side : {-1.0, 1.0}) {
      batch.type.push_back(1);
      batch.x.insert(batch.x.end(), {side * 0.5 * (sigma + gap), y, 0.0});
      batch.v.insert(batch.v.end(), {-side * 0.5 * u, 0.0, 0.0});
      batch.diameter.push_back(sigma);
      batch.mass.push_back(model_.mass);
    }
  }
  const LammpsTag first = lmp.create_atoms(batch);
  if (first != 1) throw std::logic_error("restitution calibration: atom IDs do not start at 1");

  lmp.commands({
      pair_style_command(model_),
      pair_coeff_command(),
      // nsq: a few hundred atoms in a long box; every-step checks keep the list exact
      // through the many steps of a contact.
      "neighbor " + lammps_number(skin) + " nsq",
      "neigh_modify every 1 delay 0 check yes",
      "fix integrate all nve/sphere disc",
      "fix planar all enforce2d",
      timestep_command(model_),
      "thermo_style custom step",
      "thermo 0",
  });

  RestitutionMeasurement result;
  result.approach_speed = u;
  result.undamped_overlap_bound = bound;
  std::vector<char> touched(pairs, 0), done(pairs, 0);
  int remaining = pairs;
  long long step = 0;
  // One step per run: the overlap of every pair is seen at every step (all a contact is).
  while (remaining > 0) {
    if (step >= max_steps)
      throw std::runtime_error("restitution calibration: " + std::to_string(remaining) +
                               " pairs still in contact after " + std::to_string(step) +
                               " steps (" + show(kMaxContactTimes) + " contact times)");
    lmp.run(1, step == 0);
    ++step;
    const std::vector<double> x = lmp.gather_atoms("x", 3);
    for (int k = 0; k < pairs; ++k) {
      if (done[k]) continue;
      const double overlap = sigma - (x[3 * (2 * k + 1)] - x[3 * (2 * k)]);
      if (overlap > 0.0) {
        touched[k] = 1;
        result.max_overlap = std::max(result.max_overlap, overlap);
      } else if (touched[k]) {
        // No force from this step on (the force of step j uses x_j): v is final.
        done[k] = 1;
        --remaining;
      }
    }
  }
  const std::vector<double> v = lmp.gather_atoms("v", 3);
  result.steps = step;
  double sum = 0.0, sum_sq = 0.0;
  for (int k = 0; k < pairs; ++k) {
    const double r = (v[3 * (2 * k + 1)] - v[3 * (2 * k)]) / u;
    if (!(r > 0.0))
      throw std::runtime_error("restitution calibration: pair " + std::to_string(k) +
                               " does not separate (r = " + show(r) + ")");
    result.per_phase.push_back(r);
    sum += r;
    sum_sq += r * r;
  }
  result.restitution = sum / pairs;
  result.restitution_energy = std::sqrt(sum_sq / pairs);
  const auto [lo, hi] = std::minmax_element(result.per_phase.begin(), result.per_phase.end());
  result.restitution_min = *lo;
  result.restitution_max = *hi;
  result.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

double measure_restitution(const ContactModel& model, double approach_speed, std::string log_file) {
  RestitutionCalibrationOptions options;
  options.log_file = std::move(log_file);
  return RestitutionCalibration(model, std::move(options)).measure(approach_speed).restitution;
}

ContactModel calibrate_damping(const ContactModel& model, double approach_speed, double tolerance,
                               int max_iterations, RestitutionCalibrationOptions options) {
  if (!(tolerance > 0.0) || max_iterations < 1)
    throw std::invalid_argument("calibrate_damping: tolerance must be > 0, iterations >= 1");
  ContactModel current = model;
  if (model.restitution >= 1.0 && model.gamma_n == 0.0) return current;
  const double m_eff = effective_mass(model.mass);
  double measured = 0.0;
  for (int i = 0; i < max_iterations; ++i) {
    RestitutionCalibration calibration(current, options);
    measured = calibration.measure(approach_speed).restitution;
    if (std::abs(measured - model.restitution) <= tolerance) return current;
    ContactModel next = current;
    next.gamma_n = model.restitution >= 1.0
                       ? 0.0
                       : current.gamma_n * std::log(model.restitution) / std::log(measured);
    next.contact_time = contact_duration(next.kn, next.gamma_n, m_eff);
    validate(next);
    current = next;
  }
  throw std::runtime_error("calibrate_damping: r = " + show(measured) + " after " +
                           std::to_string(max_iterations) + " measurements, target " +
                           show(model.restitution));
}

}  // namespace granvv::md
