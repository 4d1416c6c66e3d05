#!/usr/bin/python3
"""DEVELOPER AID ONLY -- builds a *synthetic* results.h5 + summary.json.

The files follow the layout the granvv C++ code writes (see scripts/report.py),
so that the report script can be developed and checked before (or without) a
real run. Nothing here is a simulation result: the "single_mode" scene is the
flow-by-inertia exact solution of Efrati, Livne & Meerson, PRL 94, 088001
(2005), Eq. (5), for v0 = a sin(2 pi x) with a slightly reduced amplitude (so the
numbers look like a real run that misses the inertia estimate by about 1 %),
sampled on a Lagrangian mesh; the temperature and the growth-rate curves are
made up. Never feed these files to a test or a comparison.

Usage:
    /usr/bin/python3 scripts/make_demo_results.py [OUTDIR] [--case single_mode|haff|random]

Without OUTDIR a fresh temporary directory is created; its path is printed.
"""
import argparse
import json
import os
import sys
import tempfile

import h5py
import numpy as np

VERSION = "0.1.0+demo"


def config_text(case, K, q, cells, amplitude):
    return (f'# SYNTHETIC demo configuration (scripts/make_demo_results.py)\n'
            f'[case]\nname = "{case}"\n'
            f'reference = "Efrati, Livne & Meerson, PRL 94, 088001 (2005), Figs. 2-4"\n'
            f'[physics]\nK = {K}\nq = {q}\n'
            f'[hydro]\ncells = {cells}\ncfl = 0.2\nstop_density = 1e6\n'
            f'[initial]\nprofile = "single_mode"\namplitude = {amplitude}\nmode = 1\n'
            f'[output]\ntimes = [1.0, 2.0, 3.0, 3.209, 3.225]\n')


def theory(K, q, kmax=400):
    k = np.arange(1, kmax + 1, dtype=float)
    kc = np.sqrt(q) / (np.pi * K)          # clustering threshold pi k K = sqrt(q)
    ks = 2.0 * np.sqrt(q) / (np.pi * K)    # made-up shear threshold
    clus = 0.5 * (1.0 - (k / kc) ** 2)
    shear = 0.5 * (1.0 - (k / ks) ** 2)
    return k, clus, shear, int(np.sum(clus > 0)), int(np.sum(shear > 0))


def inertia_state(xi, t, a_eff, h):
    """Flow-by-inertia state of a periodic Lagrangian mesh with nodes at xi."""
    v = a_eff * np.sin(2 * np.pi * xi)
    x = xi + t * v
    dx = np.diff(np.append(x, x[0] + 1.0))
    dv = np.diff(np.append(v, v[0]))
    n = h / dx
    return x, v, n, dv / dx


def build_single_mode(out, case="single_mode", random_modes=False):
    K, q, N, a = 4e-4, 0.01, 2000, -0.05
    t0 = K / (4 * q)
    tau_inertia = 1.0 / (2 * np.pi * abs(a))
    tau_eff = 3.23
    a_eff = a * tau_inertia / tau_eff
    h = 1.0 / N
    xi0 = -0.5 + (np.arange(N) + 0.5) * h          # a cell centred on x = 0
    mass = np.full(N, h)
    rng = np.random.default_rng(1)
    if random_modes:  # a few modes on top: not an exact solution any more
        extra = sum(0.001 * rng.standard_normal() * np.sin(2 * np.pi * m * xi0 + rng.uniform(0, 6.3))
                    for m in range(2, 12))
    else:
        extra = 0.0

    def state(t):
        x, v, n, dvdx = inertia_state(xi0, t, a_eff, h)
        if random_modes:
            v = v + extra
            x = xi0 + t * v
            dx = np.diff(np.append(x, x[0] + 1.0))
            n = h / dx
            dvdx = np.diff(np.append(v, v[0])) / dx
        T = (1 + t / t0) ** -2 * np.abs(n) ** 0.3
        return x, v, n, dvdx, T

    # time series: dt shrinking towards the singularity, stop at n_max = 1e6
    ts = [0.0]
    while True:
        t = ts[-1]
        dt = min(0.02, 0.02 * (tau_eff - t))
        t_new = t + dt
        n_new = state(t_new)[2]
        n_max = np.max(n_new)
        if n_max >= 1e6 or np.min(n_new) <= 0 or t_new > tau_eff or len(ts) > 5000:
            break
        ts.append(t_new)
    ts = np.array(ts)
    rows = {k: [] for k in ["n_max", "x_peak", "dvdx_peak", "T_min", "T_mean", "energy",
                            "energy_thermal", "energy_kinetic", "energy_kinetic_y",
                            "momentum"]}
    for t in ts:
        x, v, n, dvdx, T = state(t)
        i = int(np.argmax(n))
        xc = x + 0.5 * np.diff(np.append(x, x[0] + 1.0))
        rows["n_max"].append(n[i])
        rows["x_peak"].append(((xc[i] + 0.5) % 1.0) - 0.5)
        rows["dvdx_peak"].append(dvdx[i])
        rows["T_min"].append(T.min())
        rows["T_mean"].append(np.sum(mass * T))
        eth = np.sum(mass * T)
        ek = np.sum(mass * v ** 2 / 2)
        rows["energy_thermal"].append(eth)
        rows["energy_kinetic"].append(ek)
        rows["energy_kinetic_y"].append(0.0)
        rows["energy"].append(eth + ek)
        rows["momentum"].append(np.sum(mass * v) + 1e-18 * rng.standard_normal())
    rows = {k: np.array(v) for k, v in rows.items()}
    E0 = rows["energy"][0]
    rows["energy_cooled"] = E0 - rows["energy"] + 1e-16 * rng.standard_normal(ts.size)
    rows["haff_T"] = (1 + ts / t0) ** -2
    rows["t"] = ts
    rows["dt"] = np.append(np.diff(ts), 0.0)

    snap_t = [0.0] + [s for s in (1.0, 2.0, 3.0, 3.209, 3.225) if s < ts[-1]] + [ts[-1]]
    labels = ["initial"] + ["output"] * (len(snap_t) - 2) + ["final"]
    F = {k: [] for k in ["x", "n", "v_x", "T", "node_x", "node_v_x", "xi", "inertia_v0"]}
    snaps = []
    for t in snap_t:
        x, v, n, dvdx, T = state(t)
        xc = x + 0.5 * np.diff(np.append(x, x[0] + 1.0))
        vc = 0.5 * (v + np.roll(v, -1))
        xi = x - t * v
        v0 = a * np.sin(2 * np.pi * xi)
        F["x"].append(xc); F["n"].append(n); F["v_x"].append(vc); F["T"].append(T)
        F["node_x"].append(x); F["node_v_x"].append(v); F["xi"].append(xi); F["inertia_v0"].append(v0)
        eth, ek = np.sum(mass * T), np.sum(mass * v ** 2 / 2)
        snaps.append({"t": t, "n_max": float(n.max()), "T_min": float(T.min()),
                      "energy": float(eth + ek), "energy_thermal": float(eth),
                      "energy_kinetic": float(ek),
                      "collapse_error": float(np.max(np.abs(v - v0)) / abs(a))})

    k, clus, shear, nu, nsu = theory(K, q)

    with h5py.File(out / "results.h5", "w") as f:
        f.attrs["granvv_version"] = VERSION
        f.attrs["case"] = case
        f.attrs["config_toml"] = config_text(case, K, q, N, a)
        f.attrs["physics.K"] = K
        f.attrs["physics.q"] = q
        f.attrs["hydro.cells"] = N
        f.attrs["initial.amplitude"] = a
        g = f.create_group("hydro/timeseries")
        for name, val in rows.items():
            g.create_dataset(name, data=val)
        g = f.create_group("hydro/fields")
        g.create_dataset("t", data=np.array(snap_t))
        g.create_dataset("label", data=np.array(labels, dtype=h5py.string_dtype()))
        for name in ["x", "n", "v_x", "T"]:
            g.create_dataset(name, data=np.array(F[name]))
        g = f.create_group("hydro/lagrangian")
        for name in ["node_x", "node_v_x", "xi", "inertia_v0"]:
            g.create_dataset(name, data=np.array(F[name]))
        g.create_dataset("cell_mass", data=mass)
        g = f.create_group("hydro/theory")
        g.create_dataset("mode_k", data=k)
        g.create_dataset("clustering_rate", data=clus)
        g.create_dataset("shear_rate", data=shear)
        g.attrs["t0"] = t0
        g.attrs["unstable_modes"] = nu
        g.attrs["shear_unstable_modes"] = nsu
        g.attrs["inertia_tau"] = tau_inertia
        g = f.create_group("hydro/convergence")
        cells = np.array([250, 500, 1000, 2000, 4000])
        base = {"x": 3e-3, "v": 8e-3, "T": 5e-3, "n": 2e-2}
        for key, c0 in base.items():
            err = c0 * (cells[:-1] / 250.0) ** -2.0 * (1 + 0.05 * rng.standard_normal(cells.size - 1))
            g.create_dataset("error_" + key, data=err)
            g.attrs["order_" + key] = float(-np.polyfit(np.log(cells[:-1]), np.log(err), 1)[0])
        g.create_dataset("cells", data=cells)
        g.attrs["t"] = 1.0
        orders = {"order_" + key: float(g.attrs["order_" + key]) for key in base}

    def t_at(level):
        i = np.argmax(rows["n_max"] >= level)
        return float(ts[i]) if rows["n_max"][i] >= level else None

    win = (rows["n_max"] >= 10) & (rows["n_max"] <= 1e4)
    tw = ts[win]
    inv = 1.0 / rows["n_max"][win]
    slope, icpt = np.polyfit(tw, inv, 1)
    tau_fit = -icpt / slope
    final = state(snap_t[-2])
    xc = final[0] + 0.5 * np.diff(np.append(final[0], final[0][0] + 1.0))
    sel = (np.abs(xc) > 1e-3) & (np.abs(xc) < 2e-2)
    pslope = np.polyfit(np.log(np.abs(xc[sel])), np.log(final[2][sel]), 1)[0] if not random_modes else 0.0
    hydro = {
        "status": "singularity", "wall_seconds": 0.08, "cells": N, "steps": int(ts.size - 1),
        "cell_steps_per_second": 2.0e7, "unstable_modes": nu, "shear_unstable_modes": nsu,
        "stop_reason": "peak density 1e6 reached" if rows["n_max"][-1] > 5e5 else "step limit",
        "singularity_time": float(tau_fit),
        "tau_fit_window": {"n_min": 10, "n_max": 10000, "t_min": float(tw[0]), "t_max": float(tw[-1])},
        "inertia_singularity_time": float(tau_inertia),
        "singularity_time_deviation": float(abs(tau_fit - tau_inertia) / tau_inertia),
        "peak_density_times": {"10": t_at(10), "100": t_at(100), "1000": t_at(1000), "1e6": t_at(1e6)},
        "snapshots": snaps[1:],
        "profile_slope": {"t": snap_t[-2], "slope": float(pslope), "x_min": 1e-3, "x_max": 2e-2},
        "energy_drift": 1e-15, "momentum_drift": 1e-17,
        "haff_max_relative_error": float(np.max(np.abs(rows["T_mean"] / rows["haff_T"] - 1))),
        "convergence": {"t": 1.0, "cells": [250, 500, 1000, 2000, 4000], **orders},
    }
    if random_modes:
        for key in ["inertia_singularity_time", "singularity_time_deviation", "profile_slope"]:
            hydro[key] = None
        hydro["convergence"] = None
    return {"case": case, "status": "singularity", "granvv_version": VERSION,
            "hydro": hydro, "md": None, "compare": None}


def build_haff(out):
    K, q, N = 0.02, 0.01, 200
    t0 = K / (4 * q)
    ts = np.linspace(0, 50 * t0, 301)
    T = (1 + ts / t0) ** -2
    with h5py.File(out / "results.h5", "w") as f:
        f.attrs["granvv_version"] = VERSION
        f.attrs["case"] = "haff"
        f.attrs["config_toml"] = config_text("haff", K, q, N, 0.0)
        f.attrs["physics.K"] = K
        f.attrs["physics.q"] = q
        g = f.create_group("hydro/timeseries")
        z = np.zeros_like(ts)
        for name, val in {"t": ts, "dt": np.append(np.diff(ts), 0), "n_max": 1 + z, "x_peak": z,
                          "dvdx_peak": z, "T_min": T * (1 - 1e-13), "T_mean": T * (1 + 1e-13),
                          "energy": T, "energy_thermal": T, "energy_kinetic": z,
                          "energy_kinetic_y": z, "energy_cooled": 1 - T, "momentum": z,
                          "haff_T": T}.items():
            g.create_dataset(name, data=val)
        g = f.create_group("hydro/theory")
        k, clus, shear, nu, nsu = theory(K, q, kmax=40)
        g.create_dataset("mode_k", data=k)
        g.create_dataset("clustering_rate", data=clus)
        g.create_dataset("shear_rate", data=shear)
        g.attrs["t0"] = t0
        g.attrs["unstable_modes"] = nu
        g.attrs["shear_unstable_modes"] = nsu
        g.attrs["inertia_tau"] = np.nan
    hydro = {"status": "ok", "wall_seconds": 0.01, "cells": N, "steps": 300,
             "cell_steps_per_second": 6e6, "unstable_modes": nu, "shear_unstable_modes": nsu,
             "stop_reason": "end time reached", "energy_drift": 2e-16, "momentum_drift": 0.0,
             "haff_max_relative_error": 1e-13, "singularity_time": None}
    return {"case": "haff", "status": "ok", "granvv_version": VERSION,
            "hydro": hydro, "md": None, "compare": None}


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("outdir", nargs="?")
    p.add_argument("--case", default="single_mode", choices=["single_mode", "haff", "random"])
    args = p.parse_args()
    out = args.outdir or tempfile.mkdtemp(prefix="granvv-demo-")
    os.makedirs(out, exist_ok=True)
    from pathlib import Path
    out = Path(out)
    if args.case == "haff":
        summary = build_haff(out)
    elif args.case == "random":
        summary = build_single_mode(out, case="random_modes", random_modes=True)
    else:
        summary = build_single_mode(out)
    with open(out / "summary.json", "w") as f:
        json.dump(summary, f, indent=2)
    print(out)


if __name__ == "__main__":
    sys.exit(main())
