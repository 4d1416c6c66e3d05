#!/usr/bin/python3
"""How wide a channel a clean particle test of the single mode needs (docs/physics.md §8).

Reads the runs of `md_single_mode` (K = 1e-2, q = 0.05, event-driven engine) at several box
widths Ly, one output folder per width (summary.json and results.h5 as granvv wrote them), and
plots against Ly:
  - the initial signal-to-noise of the summary's md block (bin, gradient and mode forms, all
    computed by granvv from N and the imposed mode), and the measured one: |a| over the
    single-member velocity noise on the bins at t = 0, i.e. the ensemble error of the mean
    /compare/fields/v_x/md_error at t = 0 (mean over the bins) times sqrt(members);
  - the comparison's agreement window (compare.agreement_window, scaled time);
  - the peak-density error at one output time: |md_n - hydro_n| / hydro_n of compare.peak (the
    ensemble mean against the hydro) and the single-member scatter md_n_error sqrt(members) /
    hydro_n.
Power laws y = c Ly^p are fitted by least squares in log-log (the slope's error from the fit's
residuals); the prediction for noise-limited quantities is p = 1/2 (signal-to-noise) and -1/2
(noise).

    scripts/box_size_study.py --runs /work/runs/boxsize --widths 10 40 160 640 \\
        --out docs/box_size_noise.png --json docs/box_size_noise.json
"""
import argparse
import json
import math
import os

import h5py
import numpy as np


def fit_power_law(x, y):
    """Slope p and its standard error of log y = log c + p log x (None with < 3 points)."""
    x, y = np.log(np.asarray(x, float)), np.log(np.asarray(y, float))
    ok = np.isfinite(x) & np.isfinite(y)
    x, y = x[ok], y[ok]
    if len(x) < 2:
        return None
    (p, c), cov = np.polyfit(x, y, 1, cov=len(x) > 2) if len(x) > 2 else (np.polyfit(x, y, 1), None)
    error = math.sqrt(cov[0][0]) if cov is not None else None
    return {"exponent": float(p), "exponent_error": error, "prefactor": float(math.exp(c)),
            "points": int(len(x))}


def read_width(folder, peak_time_md):
    with open(os.path.join(folder, "summary.json")) as f:
        s = json.load(f)
    md, cmp = s["md"], s["compare"]
    members = int(cmp["cost"]["md"]["ensemble"])
    times_md = cmp["times_md"]
    k = int(np.argmin([abs(t - peak_time_md) for t in times_md]))
    peak = cmp["peak"]
    hydro_n, md_n, md_n_error = peak["hydro_n"][k], peak["md_n"][k], peak["md_n_error"][k]
    with h5py.File(os.path.join(folder, "results.h5"), "r") as h:
        v_error_t0 = float(np.nanmean(h["compare/fields/v_x/md_error"][0, :]))
    return {
        "box_width": float(s["md"]["box_width"]) if "box_width" in s["md"] else None,
        "particles": int(cmp["cost"]["md"]["particles"]),
        "members": members,
        "md_wall_seconds": float(cmp["cost"]["md"]["wall_seconds"]),
        "collisions": float(cmp["cost"]["md"].get("collisions", float("nan"))),
        "signal_to_noise_initial": md["signal_to_noise_initial"],
        "signal_to_noise_gradient_initial": md["signal_to_noise_gradient_initial"],
        "signal_to_noise_mode_initial": md["signal_to_noise_mode_initial"],
        "signal_velocity_initial": md["signal_velocity_initial"],
        "noise_velocity_initial": md["noise_velocity_initial"],
        "noise_velocity_measured": v_error_t0 * math.sqrt(members),
        "signal_to_noise_measured": md["signal_velocity_initial"] / (v_error_t0 * math.sqrt(members)),
        "agreement_window": cmp["agreement_window"],
        "left_at": cmp["left_at"],
        "first_field_to_leave": cmp["first_field_to_leave"],
        "disagreement": cmp["disagreement"],
        "peak_time_md": times_md[k],
        "peak_time": cmp["times"][k],
        "peak_hydro_n": hydro_n,
        "peak_md_n": md_n,
        "peak_md_n_error": md_n_error,
        "peak_error_mean": abs(md_n - hydro_n) / hydro_n,
        "peak_scatter_member": md_n_error * math.sqrt(members) / hydro_n,
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--runs", required=True, help="folder holding Ly<width>/ output folders")
    ap.add_argument("--widths", type=float, nargs="+", required=True)
    ap.add_argument("--peak-time", type=float, default=900.0, help="MD time of the peak-density error")
    ap.add_argument("--out", required=True)
    ap.add_argument("--json", required=True)
    a = ap.parse_args()

    rows = []
    for w in a.widths:
        folder = os.path.join(a.runs, "Ly%g" % w)
        row = read_width(folder, a.peak_time)
        row["box_width"] = w
        rows.append(row)
    ly = [r["box_width"] for r in rows]
    keys = ["signal_to_noise_initial", "signal_to_noise_measured", "noise_velocity_measured",
            "agreement_window", "peak_error_mean", "peak_scatter_member"]
    fits = {k: fit_power_law(ly, [r[k] if r[k] is not None else float("nan") for r in rows])
            for k in keys}
    with open(a.json, "w") as f:
        json.dump({"scene": "md_single_mode, md.engine = event_driven", "widths": rows,
                   "fits": fits, "predicted_exponent_signal_to_noise": 0.5}, f, indent=1)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 3, figsize=(13, 4))
    lyv = np.array(ly)
    for key, label, mark in [("signal_to_noise_initial", "S/N bins (summary)", "o"),
                             ("signal_to_noise_measured", "S/N bins, measured at t = 0", "s"),
                             ("signal_to_noise_gradient_initial", "S/N gradient (summary)", "^"),
                             ("signal_to_noise_mode_initial", "S/N mode (summary)", "v")]:
        ax[0].loglog(lyv, [r[key] for r in rows], mark + "-", label=label)
    ref = rows[0]["signal_to_noise_initial"] * (lyv / lyv[0]) ** 0.5
    ax[0].loglog(lyv, ref, "k:", label=r"$\propto L_y^{1/2}$")
    ax[0].set_xlabel(r"$L_y/\sigma$")
    ax[0].set_title("initial signal-to-noise")
    ax[0].legend(fontsize=7)
    win = [r["agreement_window"] if r["agreement_window"] is not None else np.nan for r in rows]
    ax[1].semilogx(lyv, win, "o-")
    ax[1].set_xlabel(r"$L_y/\sigma$")
    ax[1].set_ylabel("scaled t")
    ax[1].set_title("agreement window (every field within 3 sigma)")
    ax[2].loglog(lyv, [r["peak_error_mean"] for r in rows], "o-", label="|ensemble mean - hydro| / hydro")
    ax[2].loglog(lyv, [r["peak_scatter_member"] for r in rows], "s-", label="one member's scatter / hydro")
    ref = rows[0]["peak_scatter_member"] * (lyv / lyv[0]) ** -0.5
    ax[2].loglog(lyv, ref, "k:", label=r"$\propto L_y^{-1/2}$")
    ax[2].set_xlabel(r"$L_y/\sigma$")
    ax[2].set_title("peak density at t_MD = %g" % rows[0]["peak_time_md"])
    ax[2].legend(fontsize=7)
    fig.suptitle("md_single_mode (K = 0.01, q = 0.05, a = -0.25), event-driven, %s members per width"
                 % ", ".join(str(r["members"]) for r in rows), fontsize=9)
    fig.tight_layout()
    fig.savefig(a.out, dpi=110)
    for k, v in fits.items():
        print(k, v)


if __name__ == "__main__":
    main()
