#!/usr/bin/python3
"""The heat-flux coefficients of the particles measured at their definition (docs/physics.md §14,
"The heat flux at its definition").

Reads the H5MD particle frames of one or more runs of the same scene (`md.snapshot_interval`,
one particles_m<k>.h5 per member; several folders with other `md.seed` make one larger
ensemble) and fits, snapshot by snapshot, the k = 1 sine amplitude of the particles' kinetic heat
flux to

    q_x = -kappa dT/dx - mu dn/dx + beta d2v_x/dx2

(Brey, Dufty, Kim & Santos, PRE 58, 4638 (1998), with the linear Burnett term of the heat flux),
with every value relative to the elastic dilute one of hard disks (kappa0 = 2 sqrt(T/(pi m))/sigma,
mu0 = T kappa0/n; MD units sigma = m = 1). Errors: delete-one jackknife over members.

The flow subtracted from each particle's velocity is the ensemble's mean flow in its bin, the
local flow of kinetic theory; a member's own flow fluctuation then carries enthalpy (e + P_xx)
times its k = 1 velocity deviation through the heat flux at linear order, which is noise and is
removed. Subtracting each member's own bin mean instead biases the third moment by about 3/N for
N particles per bin (measured: kappa 5 % lower at 64 bins than at 16).

usage: heat_flux_fit.py RUN_DIR [RUN_DIR ...] [--bins B] [--start S] [--no-burnett]
                        [--json FILE]
Exit 2 with a one-line message on bad input (missing frames, members that disagree).
"""
import argparse
import glob
import json
import os
import re
import sys

import h5py
import numpy as np


def fail(message):
    print("heat_flux_fit: " + message, file=sys.stderr)
    sys.exit(2)


def member_files(folders):
    files = []
    for folder in folders:
        found = glob.glob(os.path.join(folder, "particles_m*.h5"))
        found = [f for f in found if re.fullmatch(r"particles_m\d+\.h5", os.path.basename(f))]
        if not found:
            fail(f"{folder}: no particles_m<k>.h5 (run the scene with md.snapshot_interval > 0)")
        files += sorted(found, key=lambda f: int(re.findall(r"\d+", os.path.basename(f))[0]))
    if len(files) < 8:
        fail(f"{len(files)} members: the jackknife needs at least 8")
    return files


def read_member(path):
    try:
        with h5py.File(path, "r") as f:
            edges = np.asarray(f["particles/all/box/edges"][()], dtype=float)
            pos = np.asarray(f["particles/all/position/value"][()], dtype=float)
            vel = np.asarray(f["particles/all/velocity/value"][()], dtype=float)
            t = np.asarray(f["particles/all/position/time"][()], dtype=float)
    except (OSError, KeyError) as e:
        fail(f"{path}: not an H5MD particle file of granvv ({e})")
    if edges.shape != (2,) or not np.all(np.isfinite(edges)) or np.any(edges <= 0):
        fail(f"{path}: box edges {edges.tolist()}, expected two positive lengths")
    if pos.ndim != 3 or pos.shape[2] != 2 or vel.shape != pos.shape or len(t) != pos.shape[0]:
        fail(f"{path}: positions {pos.shape}, velocities {vel.shape}, {len(t)} times do not agree")
    if not (np.all(np.isfinite(pos)) and np.all(np.isfinite(vel))):
        fail(f"{path}: non-finite positions or velocities")
    return edges, pos, vel, t


class Bins:
    def __init__(self, Lx, bins, pos):
        self.frames = pos.shape[0]
        self.bins = bins
        b = np.floor((pos[:, :, 0] + Lx / 2) / Lx * bins).astype(int) % bins
        self.index = b
        self.flat = (np.arange(self.frames)[:, None] * bins + b).ravel()

    def sum(self, values):
        total = np.bincount(self.flat, weights=values.ravel(), minlength=self.frames * self.bins)
        return total.reshape(self.frames, self.bins)


def amplitudes(files, bins):
    """Per member and frame: n, T relative to the box mean (cos part), the heat flux and the
    flow (sin part), and the box means n, T."""
    first = read_member(files[0])
    edges, t = first[0], first[3]
    Lx, Ly = edges
    # The ensemble's mean flow per bin and frame (first pass).
    count = mom_x = mom_y = 0.0
    for path in files:
        e, pos, vel, tm = read_member(path) if path != files[0] else first
        if not (np.allclose(e, edges) and len(tm) == len(t) and np.allclose(tm, t)):
            fail(f"{path}: its box or frame times differ from {files[0]}'s")
        g = Bins(Lx, bins, pos)
        count = count + g.sum(np.ones(pos.shape[:2]))
        mom_x = mom_x + g.sum(vel[:, :, 0])
        mom_y = mom_y + g.sum(vel[:, :, 1])
    if np.any(count == 0):
        fail(f"--bins {bins}: a bin holds no particle in some frame; use fewer bins")
    flow_x, flow_y = mom_x / count, mom_y / count
    centres = (np.arange(bins) + 0.5) / bins
    cos, sin = np.cos(2 * np.pi * centres), np.sin(2 * np.pi * centres)
    bin_area, box_area = Lx * Ly / bins, Lx * Ly
    ensemble_flow = 2 * (flow_x * sin).mean(1)
    rows = {k: [] for k in ("n", "T", "q", "v", "n_mean", "T_mean")}
    for path in files:
        _, pos, vel, _ = read_member(path)
        g = Bins(Lx, bins, pos)
        cx = vel[:, :, 0] - np.take_along_axis(flow_x, g.index, 1)
        cy = vel[:, :, 1] - np.take_along_axis(flow_y, g.index, 1)
        c2 = cx * cx + cy * cy
        N = g.sum(np.ones(pos.shape[:2]))
        with np.errstate(invalid="ignore", divide="ignore"):
            T = np.where(N > 0, 0.5 * g.sum(c2) / np.maximum(N, 1), np.nan)
        if np.any(np.isnan(T)):
            fail(f"{path}: --bins {bins} leaves a bin empty; use fewer bins")
        n = N / bin_area
        q = 0.5 * g.sum(c2 * cx) / bin_area  # kinetic heat flux, 2D: (1/2) m |c|^2 c_x
        v = g.sum(vel[:, :, 0]) / N
        n_mean = n.mean(1)
        T_mean = 0.5 * c2.sum(1) / c2.shape[1]
        energy, p_xx = 0.5 * c2.sum(1) / box_area, (cx * cx).sum(1) / box_area
        v_sin = 2 * (v * sin).mean(1)
        rows["n"].append(2 * (n * cos).mean(1) / n_mean)
        rows["T"].append(2 * (T * cos).mean(1) / T_mean)
        rows["q"].append(2 * (q * sin).mean(1) - (energy + p_xx) * (v_sin - ensemble_flow))
        rows["v"].append(v_sin)
        rows["n_mean"].append(n_mean)
        rows["T_mean"].append(T_mean)
    return t, Lx, {k: np.array(v) for k, v in rows.items()}


def regression(a, members, k, start, burnett):
    """The ensemble-mean response y = q_sin/(k kappa0 T) and its regressors at each frame:
    y = (kappa/kappa0) T_cos + (mu/mu0) n_cos + b v_sin/sqrt(T) (a cosine mode's gradient has a
    sine profile; beta = -b kappa0 sqrt(T)/k per unit d2v/dx2)."""
    mean = {key: value[members].mean(0)[start:] for key, value in a.items()}
    kappa0 = 2 * np.sqrt(mean["T_mean"] / np.pi)
    y = mean["q"] / (k * kappa0 * mean["T_mean"])
    columns = [mean["T"], mean["n"]]
    if burnett:
        columns.append(mean["v"] / np.sqrt(mean["T_mean"]))
    return y, np.array(columns).T


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("folders", nargs="+")
    parser.add_argument("--bins", type=int, default=32)
    parser.add_argument("--start", type=int, default=1, help="first frame fitted (default 1)")
    parser.add_argument("--no-burnett", action="store_true", help="fit kappa and mu alone")
    parser.add_argument("--json", help="write the result here")
    args = parser.parse_args()
    if not 2 <= args.bins <= 4096:
        fail(f"--bins {args.bins}: allowed 2 to 4096")
    files = member_files(args.folders)
    t, Lx, a = amplitudes(files, args.bins)
    if not 0 <= args.start <= len(t) - 5:
        fail(f"--start {args.start}: allowed 0 to {len(t) - 5} ({len(t)} frames)")
    M, k, burnett = len(files), 2 * np.pi / Lx, not args.no_burnett
    everyone = np.ones(M, bool)
    leave_out = [np.arange(M) != i for i in range(M)]

    y, X = regression(a, everyone, k, args.start, burnett)
    spread = np.array([regression(a, keep, k, args.start, burnett)[0] for keep in leave_out])
    y_error = np.sqrt((M - 1) / M * ((spread - spread.mean(0)) ** 2).sum(0))
    correlation_Tn = np.corrcoef(X[:, 0], X[:, 1])[0, 1]
    if abs(correlation_Tn) > 0.98:
        fail(f"the density and temperature modes are proportional (correlation "
             f"{correlation_Tn:.3f}, a scene at pressure balance): kappa and mu cannot be separated")

    def fit(keep):
        yy, XX = regression(a, keep, k, args.start, burnett)
        return np.linalg.lstsq(XX / y_error[:, None], yy / y_error, rcond=None)[0]

    p = fit(everyone)
    jack = np.array([fit(keep) for keep in leave_out])
    cov = (M - 1) / M * (jack - jack.mean(0)).T @ (jack - jack.mean(0))
    err = np.sqrt(np.diag(cov))
    chi2 = float((((y - X @ p) / y_error) ** 2).sum())
    names = ["conductivity", "mu", "burnett"][: len(p)]
    result = {
        "members": M, "bins": args.bins, "frames_fitted": len(y),
        "t_first": float(t[args.start]), "t_last": float(t[-1]),
        "chi2": chi2, "degrees_of_freedom": len(y) - len(p),
        "correlation_conductivity_mu": float(cov[0, 1] / (err[0] * err[1])),
    }
    for name, value, error in zip(names, p, err):
        result[name] = {"measured": float(value), "error": float(error),
                        "sigmas_from_zero": float(value / error)}
    print(f"{M} members, {args.bins} bins, frames {args.start}..{len(t) - 1} "
          f"(t = {t[args.start]:g} .. {t[-1]:g}), chi2 {chi2:.1f} / {len(y) - len(p)}")
    for name in names:
        r = result[name]
        print(f"  {name:13s} {r['measured']:+.4f} +- {r['error']:.4f}  "
              f"({r['sigmas_from_zero']:.1f} sigma from 0)")
    print(f"  correlation of kappa and mu: {result['correlation_conductivity_mu']:+.2f}")
    if args.json:
        tmp = args.json + ".part"
        with open(tmp, "w") as f:
            json.dump(result, f, indent=1)
        os.replace(tmp, args.json)


if __name__ == "__main__":
    main()
