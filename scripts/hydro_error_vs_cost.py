#!/usr/bin/python3
"""Error against cost of the continuum engine on the paper's single-mode and clustering scenes.

For each scene, runs `granvv run SCENE` over mesh sizes and time-step presets and once with the
shipped defaults (the case file and the schema, nothing set), measures the error of the
peak-density crossing times (n_max = 10, 100, 1000, 1e6) against a tight reference run (8000
cells, small steps), and plots error against cost (cells x steps: the engine's time is that
times a rate that barely depends on the mesh, and unlike a wall time it does not depend on
what else the machine runs) with the Pareto front (the runs that no other run beats on both
error and cost) and the default marked.

    /usr/bin/python3 scripts/hydro_error_vs_cost.py [OUTDIR]   (default docs/)
writes OUTDIR/hydro_error_vs_cost.png and .json (with the engine's own wall times of single runs
on this machine); the JSON says whether the default is on each scene's front.
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
SCENES = ["single_mode", "clustering"]
KEYS = ("cfl", "dt_max", "max_compression", "max_temperature_change")
PRESETS = {  # time-step control: hydro.cfl, dt_max, max_compression, max_temperature_change
    "x-tight": (0.25, 0.005, 0.025, 0.2),
    "tight": (0.5, 0.01, 0.05, 0.2),
    "medium": (1.0, 0.02, 0.1, 0.2),
    "wide": (2.0, 0.05, 0.1, 0.2),
    "loose": (5.0, 0.1, 0.2, 0.2),
}
REFERENCE = (8000, (0.25, 0.005, 0.02, 0.05))
CELLS = [500, 1000, 2000, 4000]
LEVELS = ["10", "100", "1000", "1e6"]


def run(scene, workdir, cells=None, preset=None):
    """summary.json's hydro block of one run; cells and preset None: the shipped default."""
    tag = "default" if preset is None else "_".join(map(str, (cells,) + preset))
    out = os.path.join(workdir, f"{scene}_{tag}")
    sets = ["convergence.cells=[]", "hydro.output_times=[]"]
    if cells is not None:
        sets.append(f"hydro.cells={cells}")
    if preset is not None:
        sets += [f"hydro.{k}={v}" for k, v in zip(KEYS, preset)]
    subprocess.run([GRANVV, "run", scene, "--out", out, "--quiet", "--no-report"]
                   + [a for s in sets for a in ("--set", s)], check=True)
    with open(os.path.join(out, "summary.json")) as f:
        return json.load(f)["hydro"]


def error(run_, ref):
    return max(abs(run_["peak_density_times"][k] / ref["peak_density_times"][k] - 1) for k in LEVELS)


def row(name, preset, r, ref):
    return {"preset": name, **({} if preset is None else dict(zip(KEYS, preset))),
            "cells": r["cells"], "steps": r["steps"], "cell_steps": r["cells"] * r["steps"],
            "wall_seconds": r["wall_seconds"],
            "cell_steps_per_second": r["cell_steps_per_second"],
            "crossing_time_error": error(r, ref),
            "blowup_time_error": abs(r["blowup_time"] / ref["blowup_time"] - 1)}


def pareto_front(rows):
    """The rows no other row beats on both cost (cell-steps) and crossing-time error."""
    def point(r):
        return r["cell_steps"], r["crossing_time_error"]
    return [r for r in rows if not any(point(o) != point(r) and point(o)[0] <= point(r)[0]
                                       and point(o)[1] <= point(r)[1] for o in rows)]


def measure(scene, work):
    ref = run(scene, work, REFERENCE[0], REFERENCE[1])
    rows = []
    for name, preset in PRESETS.items():
        for cells in CELLS:
            rows.append(row(name, preset, run(scene, work, cells, preset), ref))
    rows.append(row("default", None, run(scene, work), ref))
    for r in rows:
        print(f"{scene:12s} {r['preset']:8s} {r['cells']:5d} cells {r['steps']:6d} steps "
              f"{r['wall_seconds']:.3f} s crossing err {r['crossing_time_error']:.2e}")
    front = pareto_front(rows)
    return {"reference": {"cells": REFERENCE[0], **dict(zip(KEYS, REFERENCE[1])),
                          "steps": ref["steps"], "wall_seconds": ref["wall_seconds"],
                          "blowup_time": ref["blowup_time"],
                          "peak_density_times": ref["peak_density_times"]},
            "runs": rows, "pareto_front": [rows.index(r) for r in front],
            "default_on_pareto_front": rows[-1] in front}


def plot(ax, scene, result):
    rows = result["runs"]
    for i, name in enumerate(PRESETS):
        sel = [r for r in rows if r["preset"] == name]
        ax.loglog([r["cell_steps"] for r in sel], [r["crossing_time_error"] for r in sel],
                  "o-", color=f"C{i}", ms=4, label=f"{name}: cfl, dt_max, compr., heating = "
                  f"{PRESETS[name]}")
        for r in sel:
            ax.annotate(str(r["cells"]), (r["cell_steps"], r["crossing_time_error"]),
                        textcoords="offset points", xytext=(4, 4), fontsize=7, color=f"C{i}")
    front = sorted((rows[i] for i in result["pareto_front"]), key=lambda r: r["cell_steps"])
    ax.step([r["cell_steps"] for r in front], [r["crossing_time_error"] for r in front],
            where="post", color="0.4", lw=1, label="Pareto front")
    d = rows[-1]
    ax.plot(d["cell_steps"], d["crossing_time_error"], "*", color="k", ms=13,
            label=f"default ({d['cells']} cells, {d['steps']} steps)"
            + ("" if result["default_on_pareto_front"] else " NOT on the front"))
    ax.axhline(1e-4, color="k", ls=":", lw=1, label="acceptance: 1e-4")
    ax.set_xlabel("cost: cells x steps to n_max = 1e6")
    ax.set_ylabel("max rel. error of crossing times, n_max = 10..1e6")
    ax.set_title(f"{scene} (reference: {REFERENCE[0]} cells, "
                 f"{result['reference']['steps']} steps)", fontsize=10)
    ax.legend(fontsize=6)


def main():
    outdir = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "docs")
    os.makedirs(outdir, exist_ok=True)
    with tempfile.TemporaryDirectory() as work:
        results = {scene: measure(scene, work) for scene in SCENES}
    fig, axes = plt.subplots(1, len(SCENES), figsize=(12.8, 4.8), layout="constrained")
    for ax, scene in zip(axes, SCENES):
        plot(ax, scene, results[scene])
    fig.savefig(os.path.join(outdir, "hydro_error_vs_cost.png"), dpi=110)
    with open(os.path.join(outdir, "hydro_error_vs_cost.json"), "w") as f:
        json.dump(results, f, indent=1)


if __name__ == "__main__":
    main()
