#!/usr/bin/python3
"""A vectorised-Python reference of the hydro's Lagrangian scheme, as a benchmark.

The scheme of docs/physics.md and docs/method.md, written independently of the C++ in numpy
(whole-mesh array operations, one Python loop over the time steps) with LAPACK's dpttrf/dpttrs
through scipy for the periodic tridiagonal solves (Sherman-Morrison for the periodic corner):
  - the dilute closure p = n T, B = 2p, eta = (K/4) T^1/2, kappa = K T^1/2,
    cooling dT/dt = -(8q/K) n T^3/2 integrated exactly at frozen density;
  - Strang splitting C(dt/2) H(dt) C(dt/2), H a predictor-corrector pair of passes with implicit
    viscosity, implicit adiabatic pressure response, Crank-Nicolson conduction and the
    compatible work exchange between nodes and cells;
  - the driver's step controls: sound crossing (cfl), compression per step, heating per step,
    dt_max, output and end times hit exactly, halving on a rejected step, stop at
    stop_density or min_cell_width.

It runs the single-mode scene (cases/single_mode.toml) at a given number of cells with the
keys granvv resolved for the same case (read from the case.toml of a granvv run), checks that
it takes the same steps and reaches the same final fields as granvv, and times both: the
reference by its process CPU time, granvv by `granvv_bench`'s SingleModeShippedControls (CPU
time, the same scene, cells and step controls). Alternate runs, medians; the load average is
printed beside them (the machine may be shared).

  bench/single_mode_reference.py [--cells 2000] [--repeats 5] [--build build]

With --repeats 0 it checks the agreement alone (the slow-labelled ctest
bench.python_reference_agrees).

Not a test of the suite: it prints figures, and exits 1 only if the two disagree beyond the
tolerances it states.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
import tomllib
from pathlib import Path

import numpy as np
from scipy.linalg import lapack

REPOSITORY = Path(__file__).resolve().parent.parent

# 5-point Gauss-Legendre on [-1, 1] (the initial cells are integrals of the fields over each
# half cell, as granvv builds them: exact to round-off for these smooth fields).
GAUSS_NODES, GAUSS_WEIGHTS = np.polynomial.legendre.leggauss(5)


def single_mode_state(cells, amplitude, mode, node_offset):
    """Conservative initial cells of n = T = 1, v = a sin(2 pi k x) on [-1/2, 1/2)."""
    h = 1.0 / cells
    x = -0.5 + (np.arange(cells) + node_offset) * h
    kx = 2.0 * np.pi * mode

    def half_cell_totals(start):
        # Integrals of n, n v and n (T + v^2/2) over [start, start + h/2].
        half = 0.25 * h
        u = start[:, None] + half * (1.0 + GAUSS_NODES[None, :])
        w = half * GAUSS_WEIGHTS[None, :]
        v = amplitude * np.sin(kx * u)
        return (w.sum(axis=1) * np.ones_like(start), (w * v).sum(axis=1),
                (w * (1.0 + 0.5 * v * v)).sum(axis=1))

    m_left, p_left, e_left = half_cell_totals(x)
    m_right, p_right, e_right = half_cell_totals(x + 0.5 * h)
    mass = m_left + m_right
    node_mass = 0.5 * (np.roll(mass, 1) + mass)
    v = (np.roll(p_right, 1) + p_left) / node_mass
    kinetic = 0.5 * node_mass * v * v
    T = (e_left + e_right - 0.5 * (kinetic + np.roll(kinetic, -1))) / mass
    return x, v, mass, T


class PeriodicSpdSystem:
    """A symmetric positive-definite periodic tridiagonal system: diag[i] = A(i,i),
    upper[i] = A(i, i+1 mod n). The corner is moved out by Sherman-Morrison,
    A = B - w w^T / gamma with w = (gamma, 0, ..., 0, -corner), gamma = A(0,0): B is tridiagonal
    and SPD, factorised by dpttrf; x = y + z (w.y)/(gamma - w.z) with B y = b, B z = w."""

    def __init__(self, diag, upper):
        n = diag.size
        self.gamma, self.corner = diag[0], upper[-1]
        d = diag.copy()
        d[0] += self.gamma
        d[-1] += self.corner * self.corner / self.gamma
        self.d, self.e, info = lapack.dpttrf(d, upper[:-1].copy())
        self.ok = info == 0
        self.w = np.zeros(n)
        self.w[0], self.w[-1] = self.gamma, -self.corner

    def solve(self, rhs):
        columns, info = lapack.dpttrs(self.d, self.e, np.column_stack((rhs, self.w)))
        y, z = columns[:, 0], columns[:, 1]
        denominator = self.gamma - (self.gamma * z[0] - self.corner * z[-1])
        return y + z * ((self.gamma * y[0] - self.corner * y[-1]) / denominator)


class Scheme:
    def __init__(self, K, q):
        self.K = K
        self.cooling = 8.0 * q / K  # Lambda = (8q/K) n T^3/2 (the paper's small-q rate)

    def cool(self, n, T, dt):
        # d(T^-1/2)/dt = c n / 2 at fixed n
        g = 1.0 + 0.5 * self.cooling * n * np.sqrt(T) * dt
        return T / (g * g)

    def freeze(self, mass, width, T, dt, dv_ref):
        inverse_width = 1.0 / width
        n = mass * inverse_width
        root_T = np.sqrt(T)
        p = n * T
        kappa = self.K * root_T
        return {
            "p": p,
            "a": 0.25 * self.K * root_T * inverse_width,  # eta / dx
            "alpha": 0.5 * dt * (2.0 * p) * inverse_width,  # B dt / (2 dx)
            # kappa over the centre-to-centre distance at node j (between cells j-1 and j)
            "b": (np.roll(kappa, 1) + kappa) / (np.roll(width, 1) + width),
            "dv_ref": dv_ref,
        }

    def advance(self, x, v, mass, T, c, dt):
        """One pass: momentum for the time-centred velocity, nodes moved, energy with the
        same stress's work and Crank-Nicolson conduction. None if unphysical."""
        p, a, alpha, b, dv_ref = c["p"], c["a"], c["alpha"], c["b"], c["dv_ref"]
        inverse_dt = 1.0 / dt
        inertia = 2.0 * (0.5 * (np.roll(mass, 1) + mass)) * inverse_dt
        stiffness = a + alpha
        momentum = PeriodicSpdSystem(inertia + stiffness + np.roll(stiffness, 1), -stiffness)
        b_right = np.roll(b, -1)
        energy = PeriodicSpdSystem(mass * inverse_dt + 0.5 * (b_right + b), -0.5 * b_right)
        if not (momentum.ok and energy.ok):
            return None
        explicit_stress = -p - alpha * dv_ref
        v_mid = momentum.solve(inertia * v + explicit_stress - np.roll(explicit_stress, 1))
        x_new = x + dt * v_mid
        v_new = 2.0 * v_mid - v
        dv = np.roll(v_mid, -1) - v_mid
        work = (-p + alpha * (dv - dv_ref) + a * dv) * dv
        conduction = b_right * (np.roll(T, -1) - T) - b * (T - np.roll(T, 1))
        T_new = energy.solve(mass * inverse_dt * T + work + 0.5 * conduction)
        if not (np.all(T_new > 0.0) and np.all(np.isfinite(T_new))):
            return None
        if not (np.all(np.diff(x_new) > 0.0) and x_new[0] + 1.0 - x_new[-1] > 0.0):
            return None
        return x_new, v_new, T_new, dv, np.max(np.abs(T_new / T - 1.0))

    def step(self, x, v, mass, T, width, n, dt):
        T_start = self.cool(n, T, 0.5 * dt)
        c = self.freeze(mass, width, T_start, dt, np.zeros_like(T))
        predicted = self.advance(x, v, mass, T_start, c, dt)
        if predicted is None:
            return None
        x_p, _, T_p, dv_p, _ = predicted
        c = self.freeze(mass, 0.5 * (width + widths(x_p)), 0.5 * (T_start + T_p), dt, dv_p)
        corrected = self.advance(x, v, mass, T_start, c, dt)
        if corrected is None:
            return None
        x_c, v_c, T_c, _, heating = corrected
        width_c = widths(x_c)
        n_c = mass / width_c
        return x_c, v_c, self.cool(n_c, T_c, 0.5 * dt), width_c, n_c, heating


def widths(x):
    return np.append(np.diff(x), x[0] + 1.0 - x[-1])


def run(case, cells):
    """The scene to its stop; returns the step count, the final state and the n_max series."""
    physics, hydro, initial = case["physics"], case["hydro"], case["initial"]
    scheme = Scheme(physics["K"], physics["q"])
    x, v, mass, T = single_mode_state(cells, initial["velocity_amplitude"], initial["mode"],
                                      hydro["node_offset"])
    cfl, compression_limit = hydro["cfl"], hydro["max_compression"]
    heating_change, dt_max = hydro["max_temperature_change"], hydro["dt_max"]
    outputs = [t for t in hydro["output_times"] if t > 0.0]
    t, steps, rejected, next_output = 0.0, 0, 0, 0
    width = widths(x)
    n = mass / width
    heating_limit = dt_max
    n_max = [n.max()]
    while t < hydro["t_end"]:
        dv = np.abs(np.roll(v, -1) - v)
        moving = dv > 0.0
        dt = min(dt_max, cfl * np.min(width / np.sqrt(2.0 * T)), heating_limit)
        if moving.any():
            dt = min(dt, compression_limit * np.min(width[moving] / dv[moving]))
        target = outputs[next_output] if next_output < len(outputs) else hydro["t_end"]
        clamped = t + dt >= target * (1.0 - 1e-14)
        if clamped:
            dt = target - t
        for _ in range(30):
            result = scheme.step(x, v, mass, T, width, n, dt)
            if result is not None:
                break
            rejected += 1
            clamped = False
            dt *= 0.5
        if result is None:
            raise RuntimeError(f"no admissible step at t = {t}")
        x, v, T, width, n, heating = result
        t = target if clamped else t + dt
        if clamped and next_output < len(outputs):
            next_output += 1
        steps += 1
        heating_limit = dt * heating_change / heating if heating > 0.0 else dt_max
        heating_limit = max(heating_limit, 0.5 * dt)
        n_max.append(n.max())
        if n_max[-1] >= hydro["stop_density"] or width.min() <= hydro["min_cell_width"]:
            break
    return {"steps": steps, "rejected": rejected, "t": t, "x": x, "v": v, "T": T, "n": n,
            "mass": mass, "n_max": np.array(n_max)}


def granvv_run(build, cells, folder):
    """granvv's run of the same scene: its resolved case, steps and final native state."""
    import h5py

    env = dict(os.environ, GRANVV_DATA_DIR=str(REPOSITORY))
    subprocess.run([str(build / "granvv"), "run", "single_mode", "--out", str(folder), "--quiet",
                    "--no-report", "--set", f"hydro.cells={cells}", "--set",
                    "convergence.cells=[]"], check=True, env=env)
    case = tomllib.loads((folder / "case.toml").read_text())
    summary = json.loads((folder / "summary.json").read_text())
    with h5py.File(folder / "results.h5", "r") as f:
        lagrangian, fields = f["hydro/lagrangian"], f["hydro/fields"]
        final = {"x": lagrangian["node_x"][-1], "v": lagrangian["node_v_x"][-1],
                 "T": fields["T"][-1], "n": fields["n"][-1], "t": fields["t"][-1],
                 "n_max": f["hydro/timeseries/n_max"][:]}
    return case, summary["hydro"]["steps"], final


def largest_difference(a, b):
    """The largest |a - b| relative to the largest |b|."""
    return float(np.max(np.abs(a - b)) / np.max(np.abs(b)))


def granvv_bench_cpu_ms(build, cells):
    out = subprocess.run(
        [str(build / "granvv_bench"), f"--benchmark_filter=^SingleModeShippedControls/{cells}$",
         "--benchmark_format=json", "--benchmark_min_time=0.3"],
        check=True, capture_output=True, text=True).stdout
    bench = json.loads(out)["benchmarks"][0]
    scale = {"ms": 1.0, "us": 1e-3, "ns": 1e-6, "s": 1e3}[bench["time_unit"]]
    return bench["cpu_time"] * scale, int(bench["steps"])


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cells", type=int, default=2000)
    parser.add_argument("--repeats", type=int, default=5,
                        help="timed runs of each side (0: the agreement check alone)")
    parser.add_argument("--build", type=Path, default=REPOSITORY / "build")
    args = parser.parse_args()

    with tempfile.TemporaryDirectory(prefix="granvv-reference-") as tmp:
        case, granvv_steps, final = granvv_run(args.build, args.cells, Path(tmp) / "run")
    reference = run(case, args.cells)

    # Agreement. The two differ in rounding order only (summation order, the solver), and the
    # flow is run into a finite-time singularity, so differences grow as 1/(tau - t) near it.
    agreement = {
        "steps": (reference["steps"], granvv_steps),
        "t_final": abs(reference["t"] - final["t"]),
        "node_x": largest_difference(reference["x"], final["x"]),
        "node_v": largest_difference(reference["v"], final["v"]),
        "T": largest_difference(reference["T"], final["T"]),
        "n": largest_difference(reference["n"], final["n"]),
    }
    same_length = reference["n_max"].size == final["n_max"].size
    agreement["n_max_series"] = (largest_difference(reference["n_max"], final["n_max"])
                                 if same_length else float("inf"))
    print(f"steps: reference {reference['steps']}, granvv {granvv_steps}; "
          f"rejected in the reference: {reference['rejected']}")
    print("largest difference of the final state, relative to the largest value: "
          + ", ".join(f"{k} {agreement[k]:.2e}" for k in ("node_x", "node_v", "T", "n"))
          + f"; final t {agreement['t_final']:.1e}; n_max series {agreement['n_max_series']:.1e}")
    # 1e-10: the two agree to 3e-13 of the largest value (2000 cells, the last state at
    # n_max = 1e6), far below any difference of the scheme (a changed term or step control moves
    # the step count or these fields by far more).
    tolerance = 1e-10
    agrees = (reference["steps"] == granvv_steps and
              max(agreement[k] for k in ("node_x", "node_v", "T", "n", "n_max_series")) < tolerance)
    print(f"agreement within {tolerance:g}: {'yes' if agrees else 'NO'}")

    if args.repeats == 0:
        return 0 if agrees else 1
    python_ms, granvv_ms = [], []
    for _ in range(args.repeats):
        start = time.process_time()
        run(case, args.cells)
        python_ms.append(1e3 * (time.process_time() - start))
        granvv_ms.append(granvv_bench_cpu_ms(args.build, args.cells)[0])
    p, g = statistics.median(python_ms), statistics.median(granvv_ms)
    cell_steps = reference["steps"] * args.cells
    print(f"load average {os.getloadavg()[0]:.2f}")
    print(f"reference (numpy + LAPACK): CPU {p:.1f} ms median of {args.repeats} "
          f"({', '.join(f'{t:.0f}' for t in python_ms)}), {cell_steps / p * 1e3:.3g} cell-steps/s")
    print(f"granvv (granvv_bench SingleModeShippedControls/{args.cells}): CPU {g:.1f} ms median "
          f"({', '.join(f'{t:.1f}' for t in granvv_ms)}), {cell_steps / g * 1e3:.3g} cell-steps/s")
    print(f"ratio reference / granvv: {p / g:.2f}")
    return 0 if agrees else 1


if __name__ == "__main__":
    sys.exit(main())
