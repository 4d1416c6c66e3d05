#pragma once
// The bias of one measured quantity against a reference measurement of it, both with standard
// errors (docs/atlas.md, "The DEM bias map": the soft-contact t0 and P/(nT) of LAMMPS against
// the event-driven hard disks).
namespace granvv::atlas {

struct RelativeBias {
  double value = 0.0;  // a / b - 1
  double error = 0.0;  // its standard error, first order, a and b independent
  double sigmas() const { return value / error; }
};

// a / b - 1 with error sqrt((sa/b)^2 + (a sb / b^2)^2). Errors that are NaN count as 0; a b of 0
// or a non-finite a or b gives NaN for both.
RelativeBias relative_bias(double a, double a_error, double b, double b_error);

}  // namespace granvv::atlas
