#include "models/particle_cost.hpp"

#include <cmath>

namespace granvv::atlas {
namespace {

// The run's duration in first time steps (units of the initial step).
double first_steps(bool adaptive, double t_end, double t_haff) {
  if (!adaptive || !std::isfinite(t_haff) || !(t_haff > 0.0)) return t_end;
  return t_haff * std::log1p(t_end / t_haff);
}

double work(const ContactKnobs& k, double t_end, double t_haff) {
  return double(k.ensemble) * double(k.steps_per_contact) / k.max_overlap *
         first_steps(k.adaptive_stiffness, t_end, t_haff);
}

}  // namespace

double dem_work_ratio(const ContactKnobs& run, const ContactKnobs& pilot, double t_end,
                      double t_haff) {
  return work(run, t_end, t_haff) / work(pilot, t_end, t_haff);
}

}  // namespace granvv::atlas
