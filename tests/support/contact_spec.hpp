#pragma once
// The contact spec the tests start from: r = 0.9, m = sigma = 1, delta_max = 0.01 sigma,
// u_max = 10 sqrt(T0/m), 30 steps per contact (the md.max_overlap and md.steps_per_contact of a
// default case). ContactSpec itself has no defaults for these (md_bridge/contact_model.hpp).
#include "md_bridge/contact_model.hpp"

namespace granvv::testing {

inline md::ContactSpec test_contact_spec() {
  md::ContactSpec spec;
  spec.restitution = 0.9;
  spec.max_overlap = 0.01;
  spec.max_relative_speed = 10.0;
  spec.steps_per_contact = 30;
  return spec;
}

}  // namespace granvv::testing
