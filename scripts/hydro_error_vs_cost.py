#!/usr/bin/python3
"""Error against cost of the continuum engine on the paper's single-mode scene.

Runs `granvv run single_mode` over mesh sizes and time-step presets, measures the error of the
peak-density crossing times (n_max = 10, 100, 1000, 1e6) and of the blow-up time against a
tight reference run (8000 cells, small steps), and plots error against wall seconds.

    /usr/bin/python3 scripts/hydro_error_vs_cost.py [OUTDIR]   (default docs/)
writes OUTDIR/hydro_error_vs_cost.png and .json. Wall times are single runs on this machine.
"""
import json
import os
import subprocess
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
GRANVV = os.path.join(ROOT, "build", "granvv")
PRESETS = {  # time-step control: (cfl, dt_max, max_compression)
    "tight": (0.5, 0.01, 0.05),
    "default": (2.0, 0.05, 0.1),
    "loose": (5.0, 0.1, 0.2),
}
REFERENCE = (8000, (0.25, 0.005, 0.02))
CELLS = [500, 1000, 2000, 4000]
LEVELS = ["10", "100", "1000", "1e6"]


def run(cells, preset, workdir):
    cfl, dt_max, comp = preset
    out = os.path.join(workdir, f"c{cells}_{cfl}_{dt_max}_{comp}")
    subprocess.run([GRANVV, "run", "single_mode", "--out", out, "--quiet", "--no-report",
                    "--set", f"hydro.cells={cells}", "--set", "convergence.cells=[]",
                    "--set", "hydro.output_times=[]", "--set", f"hydro.cfl={cfl}",
                    "--set", f"hydro.dt_max={dt_max}", "--set", f"hydro.max_compression={comp}"],
                   check=True)
    with open(os.path.join(out, "summary.json")) as f:
        return json.load(f)["hydro"]


def error(run_, ref):
    times = [abs(run_["peak_density_times"][k] / ref["peak_density_times"][k] - 1) for k in LEVELS]
    return max(times), abs(run_["blowup_time"] / ref["blowup_time"] - 1)


def main():
    outdir = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "docs")
    os.makedirs(outdir, exist_ok=True)
    with tempfile.TemporaryDirectory() as work:
        ref = run(REFERENCE[0], REFERENCE[1], work)
        rows = []
        for name, preset in PRESETS.items():
            for cells in CELLS:
                r = run(cells, preset, work)
                e_cross, e_blow = error(r, ref)
                rows.append({"preset": name, "cfl": preset[0], "dt_max": preset[1],
                             "max_compression": preset[2], "cells": cells, "steps": r["steps"],
                             "wall_seconds": r["wall_seconds"],
                             "cell_steps_per_second": r["cell_steps_per_second"],
                             "crossing_time_error": e_cross, "blowup_time_error": e_blow})
                print(f"{name:8s} {cells:5d} cells {r['steps']:6d} steps {r['wall_seconds']:.3f} s "
                      f"crossing err {e_cross:.2e} blow-up err {e_blow:.2e}")
    fig, ax = plt.subplots(figsize=(6.4, 4.4), layout="constrained")
    for i, name in enumerate(PRESETS):
        sel = [r for r in rows if r["preset"] == name]
        ax.loglog([r["wall_seconds"] for r in sel], [r["crossing_time_error"] for r in sel],
                  "o-", color=f"C{i}", label=f"{name}: cfl, dt_max, compression = {PRESETS[name]}")
        for r in sel:
            ax.annotate(str(r["cells"]), (r["wall_seconds"], r["crossing_time_error"]),
                        textcoords="offset points", xytext=(4, 4), fontsize=7, color=f"C{i}")
    ax.axhline(1e-4, color="k", ls=":", lw=1, label="acceptance: 1e-4")
    ax.axvline(0.1, color="0.5", ls="--", lw=1, label="speed target: 0.1 s")
    ax.set_xlabel("wall seconds, single-mode scene to n_max = 1e6 (one core)")
    ax.set_ylabel("max rel. error of crossing times, n_max = 10..1e6")
    ax.set_title(f"Hydro error against cost (reference: {REFERENCE[0]} cells, "
                 f"{ref['steps']} steps)", fontsize=10)
    ax.legend(fontsize=7)
    fig.savefig(os.path.join(outdir, "hydro_error_vs_cost.png"), dpi=110)
    with open(os.path.join(outdir, "hydro_error_vs_cost.json"), "w") as f:
        json.dump({"reference": {"cells": REFERENCE[0], "preset": REFERENCE[1],
                                 "steps": ref["steps"], "wall_seconds": ref["wall_seconds"],
                                 "blowup_time": ref["blowup_time"],
                                 "peak_density_times": ref["peak_density_times"]},
                   "runs": rows}, f, indent=1)


if __name__ == "__main__":
    main()
