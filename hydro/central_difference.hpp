#pragma once
// f'(x) by the fourth-order central difference with step h: truncation h^4 |f^(5)| / 30 and
// round-off about 1.5 eps |f| / h (eps = 2.2e-16), so a step h ~ 1e-3 of the scale on which
// f varies gives ~1e-12 relative to f / scale.
namespace granvv::hydro {

template <class F>
double central_derivative(const F& f, double x, double h) {
  return (8.0 * (f(x + h) - f(x - h)) - (f(x + 2.0 * h) - f(x - 2.0 * h))) / (12.0 * h);
}

}  // namespace granvv::hydro
