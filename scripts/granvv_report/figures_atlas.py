"""Figures of an atlas (atlas.json of `granvv atlas`, docs/atlas.md): a1 work-precision diagrams, one
panel per judged observable; a2 the stability map of each hydro over cells and step factor; a3 the
ladder timeline. Errors are relative, against the richest model's finest run; costs in wall seconds."""
import math

import matplotlib.pyplot as plt
import numpy as np

from .data import Skip
from .formatting import fmt
from .registry import Drawn, figure

MODEL_STYLE = {"haff_ode": ("C2", "s"), "flow_by_inertia": ("C1", "D"), "hydro/dilute": ("C0", "o"),
               "hydro/enskog": ("C3", "^"), "particles/lammps": ("C4", "v")}
STATE_COLOR = {"ok": "C2", "error_above_tolerance": "C1", "refused": "0.6"}


def style_of(model):
    return MODEL_STYLE.get(model, ("k", "x"))


def model_error(run, name):
    e = (run.get("model_error") or {}).get(name)
    return e if isinstance(e, (int, float)) and e > 0 else None


@figure(file="a1_work_precision.png", section="atlas", anchor="work_precision",
        title="Work-precision: error against cost",
        caption=("Each point is one run; its error is relative, against the richest model's finest run "
                 "(the reference, whose own error is estimated from its neighbours one step coarser: "
                 "dotted line). Circled points are on the Pareto front of their panel: no other run is "
                 "both cheaper and closer. The dashed line is the tolerance {tolerance}."))
def fig_work_precision(run):
    names = run.atlas("observables") or []
    runs = [r for r in run.runs() if r.get("status") == "ok"]
    if not names or not runs:
        raise Skip("no judged observables or no finished runs")
    cols = min(4, len(names))
    rows = math.ceil(len(names) / cols)
    fig, axes = plt.subplots(rows, cols, figsize=(3.3 * cols, 2.9 * rows), layout="constrained", squeeze=False)
    tol = run.atlas("tolerance")
    floor = run.atlas("reference", "convergence") or {}
    for ax, name in zip(axes.flat, names):
        for model in run.models():
            pts = [(r["wall_seconds"], model_error(r, name), name in (r.get("pareto") or []))
                   for r in runs if r.get("model") == model and model_error(r, name)]
            if not pts:
                continue
            c, m = style_of(model)
            w, e, front = (np.array(v) for v in zip(*pts))
            ax.scatter(w, e, color=c, marker=m, s=18, label=model, zorder=3)
            ax.scatter(w[front], e[front], facecolors="none", edgecolors="k", s=70, lw=0.9, zorder=4)
        if isinstance(tol, (int, float)):
            ax.axhline(tol, color="k", ls="--", lw=0.8)
        f = floor.get(name)
        if isinstance(f, (int, float)) and f > 0:
            ax.axhline(f, color="k", ls=":", lw=0.8)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_title(name.replace("_", " "), fontsize=9)
        ax.set_xlabel("wall seconds", fontsize=8)
        ax.set_ylabel("relative error", fontsize=8)
        ax.tick_params(labelsize=7)
        ax.grid(True, which="major", alpha=0.3)
    for ax in list(axes.flat)[len(names):]:
        ax.axis("off")
    entries = {}
    for ax in axes.flat:
        for h, lab in zip(*ax.get_legend_handles_labels()):
            entries.setdefault(lab, h)
    if entries:
        axes.flat[0].legend(list(entries.values()), list(entries.keys()), fontsize=7, loc="best")
    measured = [("runs finished", str(len(runs)), None),
                ("reference", f"{run.atlas('reference', 'setting', 'model')} at "
                 f"{run.atlas('reference', 'setting', 'cells')} cells, step factor "
                 f"{run.atlas('reference', 'setting', 'step_factor')}", None)]
    return Drawn(fig, measured, caption_values={"tolerance": fmt(tol)})


@figure(file="a2_stability.png", section="atlas", anchor="stability",
        title="Stability map of each hydro: cells × step factor",
        caption=("Each run of the grid and of the boundary searches, coloured by how it ended against its "
                 "own finest run at the tolerance {tolerance}: ok, error above tolerance, or the failure "
                 "the solver reported (inadmissible step, non-finite state, unresolved singularity, a "
                 "setting the case schema refuses). The star is the case's own setting; arrows mark the "
                 "boundaries found by pushing one knob from it, with the failure named."))
def fig_stability(run):
    maps = run.atlas("stability") or []
    if not maps:
        raise Skip("no hydro ran")
    fig, axes = plt.subplots(1, len(maps), figsize=(5.6 * len(maps), 4.4), layout="constrained", squeeze=False)
    measured = []
    for ax, m in zip(axes.flat, maps):
        states = sorted({p["state"] for p in m["grid"]})
        for k, state in enumerate(states):
            pts = [(p["step_factor"], p["cells"]) for p in m["grid"] if p["state"] == state]
            f, c = zip(*pts)
            ax.scatter(f, c, s=60, marker="s", color=STATE_COLOR.get(state, f"C{3 + k}"), label=state)
        d = m.get("default") or {}
        ax.scatter([d.get("step_factor")], [d.get("cells")], marker="*", s=220, color="k", zorder=5,
                   label="case's own setting")
        for b in m.get("boundaries") or []:
            if b.get("failed") is None:
                continue
            if b["knob"] == "step_factor":
                xy, text = (b["failed"], d.get("cells")), f"{b['failure']} at factor {fmt(b['failed'], 3)}"
            else:
                xy, text = (d.get("step_factor"), b["failed"]), f"{b['failure']} at {fmt(b['failed'], 3)} cells"
            ax.annotate(text, xy=xy, xytext=(8, 8), textcoords="offset points", fontsize=7,
                        arrowprops={"arrowstyle": "->", "lw": 0.7})
            measured.append((f"{m['model']}: {b['knob']} {b['direction']}",
                             f"stable to {fmt(b['stable'], 3)}, fails at {fmt(b['failed'], 3)} ({b['failure']})", None))
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("step factor (on hydro.cfl, dt_max, max_compression)")
        ax.set_ylabel("cells")
        ax.set_title(m["model"])
        ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    return Drawn(fig, measured, caption_values={"tolerance": fmt(run.atlas("tolerance"))})


@figure(file="a3_timeline.png", section="atlas", anchor="timeline",
        title="Ladder timeline: how long each model stays within tolerance",
        caption=("For each model, its best run (the finest of a hydro), the largest relative error of the "
                 "time-resolved observables it gives (energies, fields) against the reference at each "
                 "compared time. The bar is green while it stays within the tolerance {tolerance}."))
def fig_timeline(run):
    rows = run.atlas("timeline") or []
    if not rows:
        raise Skip("no model has a timeline")
    tol = run.atlas("tolerance")
    fig, (ax, ax2) = plt.subplots(2, 1, figsize=(8.0, 1.2 + 0.9 * len(rows) + 2.6), layout="constrained",
                                  height_ratios=[0.9 * len(rows) + 0.4, 2.6])
    measured = []
    for i, r in enumerate(rows):
        t = np.array(r["times"], float)
        e = np.array([np.nan if x is None else x for x in r["error"]], float)
        ok = e <= tol
        ax.scatter(t[ok], np.full(ok.sum(), i), color="C2", s=60, marker="s")
        ax.scatter(t[~ok], np.full((~ok).sum(), i), color="C3", s=60, marker="x")
        c, m = style_of(r["model"])
        ax2.semilogy(t, np.where(e > 0, e, np.nan), marker=m, color=c, label=r["model"])
        until = r.get("adequate_until")
        measured.append((r["model"], "adequate to t = " + fmt(until) if until is not None
                         else "not adequate at the first compared time", None))
    ax.set_yticks(range(len(rows)), [r["model"] for r in rows])
    ax.set_ylim(-0.6, len(rows) - 0.4)
    ax.set_xlabel("t (scaled)")
    ax2.axhline(tol, color="k", ls="--", lw=0.8, label="tolerance")
    ax2.set_xlabel("t (scaled)")
    ax2.set_ylabel("largest relative error")
    ax2.legend(fontsize=7)
    return Drawn(fig, measured, caption_values={"tolerance": fmt(tol)})
