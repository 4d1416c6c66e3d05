#pragma once
// Classical fourth-order Runge-Kutta for y' = f(t, y) over [t0, t1] in n steps: the
// independent integrator the tests check closed forms against (scalars or Eigen vectors).
#include <functional>

namespace granvv::testing {

template <class T>
struct NonDeduced {
  using type = T;
};

// Y is deduced from y alone, so f may be any callable (a lambda) taking (double, const Y&).
template <class Y>
Y rk4(const typename NonDeduced<std::function<Y(double, const Y&)>>::type& f, Y y, double t0,
      double t1, int n) {
  const double h = (t1 - t0) / n;
  for (int i = 0; i < n; ++i) {
    const double t = t0 + i * h;
    const Y k1 = f(t, y);
    const Y k2 = f(t + h / 2, y + h / 2 * k1);
    const Y k3 = f(t + h / 2, y + h / 2 * k2);
    const Y k4 = f(t + h, y + h * k3);
    y += h / 6 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
  }
  return y;
}

}  // namespace granvv::testing
