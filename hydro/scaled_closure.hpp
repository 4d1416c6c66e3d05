#pragma once
// A closure with injected model errors (hydro/transport_factors.hpp): every coefficient of the
// wrapped closure, with the viscosities, the conductivity and the cooling sink multiplied by
// their factors. The pressure, its adiabatic response and the sound speed are the wrapped
// closure's. make_closure wraps a closure in it when any factor differs from 1.
#include <memory>

#include "hydro/closure.hpp"
#include "hydro/transport_factors.hpp"

namespace granvv::hydro {

class ScaledClosure final : public Closure {
 public:
  ScaledClosure(std::unique_ptr<Closure> closure, const TransportFactors& factors);

  std::string name() const override { return closure_->name(); }
  void cell_coefficients(const std::vector<double>& n, const std::vector<double>& T,
                         CellCoefficients& out) const override;
  void sound_speed(const std::vector<double>& n, const std::vector<double>& T,
                   std::vector<double>& c) const override;
  void cooling_rate(const std::vector<double>& n, const std::vector<double>& T,
                    std::vector<double>& rate) const override;
  void cool(const std::vector<double>& n, const std::vector<double>& T, double dt,
            std::vector<double>& cooled) const override;
  HcsLinearisation hcs_linearisation() const override;
  ValidityScales validity_scales() const override { return closure_->validity_scales(); }
  std::string validity_problem(const std::vector<double>& n) const override {
    return closure_->validity_problem(n);
  }

 private:
  std::unique_ptr<Closure> closure_;
  TransportFactors factors_;
};

}  // namespace granvv::hydro
