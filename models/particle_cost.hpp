#pragma once
// The work of a soft-contact (DEM) particle run relative to a pilot run of the same scene, from
// its contact knobs (docs/physics.md §5, docs/atlas.md "The grid, the budget and the cache"):
// the step is tc / md.steps_per_contact with tc proportional to md.max_overlap, so the steps
// grow as steps_per_contact / max_overlap; with adaptive stiffness the step grows as the gas
// cools, u ~ 1/(1 + t/t0), and the steps to t_end are t0 ln(1 + t_end/t0) first steps instead
// of t_end. The work is the ensemble times the steps.
namespace granvv::atlas {

struct ContactKnobs {
  int ensemble = 1;
  double max_overlap = 0.01;
  int steps_per_contact = 30;
  bool adaptive_stiffness = true;
};

// work(run) / work(pilot); t_haff is the Haff time in the units of t_end (infinite or <= 0:
// no cooling, and adaptive stiffness then changes nothing).
double dem_work_ratio(const ContactKnobs& run, const ContactKnobs& pilot, double t_end,
                      double t_haff);

}  // namespace granvv::atlas
