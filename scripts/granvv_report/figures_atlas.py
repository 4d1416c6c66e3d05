"""Figures of an atlas (atlas.json of `granvv atlas`, docs/atlas.md): a1 work-precision diagrams, one
panel per judged observable; a2 the stability map of each hydro over cells and step factor; a3 the
ladder timeline; a4 the DEM stability and bias map over max_overlap x steps_per_contact, against the
event-driven hard disks; a5 the comparison power, the smallest injected model error of the hydro that the
side-by-side comparison catches, against the particles' cost; a6 the same judged by the transport fit
of a scene that measures a coefficient. Errors are relative, against the richest model's finest run; costs in wall
seconds."""
import math

import matplotlib.pyplot as plt
import numpy as np

from .data import Skip
from .formatting import fmt
from .registry import Drawn, figure

STATE_COLOR = {"ok": "C2", "error_above_tolerance": "C1", "t0_bias_above_tolerance": "C3", "refused": "0.6"}


def model_error(run, name):
    e = (run.get("model_error") or {}).get(name)
    return e if isinstance(e, (int, float)) and e > 0 else None


@figure(file="a1_work_precision.png", section="atlas", anchor="work_precision",
        title="Work-precision: error against cost",
        caption=("Each point is one run; its error is relative, against the richest model's finest run "
                 "(the reference, whose own error is estimated from its neighbours one step coarser: "
                 "dotted line). Where the reference is a particle ensemble, its statistical error (the "
                 "ensemble standard error) is the floor no comparison with it can go below: dash-dotted "
                 "line, with the σ-aware threshold tolerance + {sigmas}σ dashed in grey. Circled points "
                 "are on the Pareto front of their panel: no other run is both cheaper and closer. The "
                 "dashed black line is the tolerance {tolerance}."))
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
    statistical = run.atlas("reference", "statistical_error") or {}
    sigmas = run.atlas("sigmas")
    for ax, name in zip(axes.flat, names):
        for model in run.models():
            pts = [(r["wall_seconds"], model_error(r, name), name in (r.get("pareto") or []))
                   for r in runs if r.get("model") == model and model_error(r, name)]
            if not pts:
                continue
            c, m = run.model_style(model)
            w, e, front = (np.array(v) for v in zip(*pts))
            ax.scatter(w, e, color=c, marker=m, s=18, label=model, zorder=3)
            ax.scatter(w[front], e[front], facecolors="none", edgecolors="k", s=70, lw=0.9, zorder=4)
        if isinstance(tol, (int, float)):
            ax.axhline(tol, color="k", ls="--", lw=0.8)
        f = floor.get(name)
        s = statistical.get(name)
        if isinstance(s, (int, float)) and s > 0:
            ax.axhline(s, color="C5", ls="-.", lw=1.0)
            if isinstance(tol, (int, float)) and isinstance(sigmas, (int, float)):
                ax.axhline(tol + sigmas * s, color="0.5", ls="--", lw=0.8)
        elif isinstance(f, (int, float)) and f > 0:
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
    ref = run.atlas("reference", "setting") or {}
    if "cells" in ref:
        where = f"{ref.get('cells')} cells, step factor {ref.get('step_factor')}"
    else:
        where = f"ensemble of {ref.get('ensemble')}"
    measured = [("runs finished", str(len(runs)), None),
                ("reference", f"{ref.get('model')} at {where}", None)]
    for name, v in sorted(statistical.items()):
        measured.append((f"reference's statistical error: {name}", fmt(v, 3), None))
    return Drawn(fig, measured, caption_values={"tolerance": fmt(tol), "sigmas": fmt(sigmas)})


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
                 "compared time. The bar is green while it stays within the tolerance {tolerance}. A black bar "
                 "on a hydro's row marks the first time one of its validity monitors (docs/physics.md §9) "
                 "reached its threshold, named beside it."))
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
        c, m = run.model_style(r["model"])
        ax2.semilogy(t, np.where(e > 0, e, np.nan), marker=m, color=c, label=r["model"])
        for name, when in sorted((r.get("monitors") or {}).items(), key=lambda kv: kv[1]):
            ax.scatter([when], [i], color="k", marker="|", s=260, zorder=4)
            ax.annotate(name.replace("_", " "), (when, i), xytext=(3, 7), textcoords="offset points", fontsize=6)
            measured.append((f"{r['model']}: monitor {name}", f"reached its threshold at t = {fmt(when, 4)}", None))
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


@figure(file="a4_dem_map.png", section="atlas", anchor="dem_map",
        title="DEM stability and bias map: max_overlap × steps_per_contact against the hard disks",
        caption=("Left: every LAMMPS run of the atlas (the largest ensemble at each contact setting, adaptive "
                 "stiffness as in the case), coloured by its state at the tolerance {tolerance}: ok, t0 bias "
                 "above tolerance (σ-aware against the event-driven hard disks), another observable above "
                 "tolerance, or how the engine failed; the star is the case's own contact. Right: the soft-contact "
                 "bias against the event-driven engine at the largest ensemble that ran ({against}), of the Haff "
                 "t0 and of P/(nT), against md.max_overlap, with one standard error (both ensembles); open "
                 "markers are runs with the adaptive stiffness flipped; grey squares, the DEM's t0 against the "
                 "Enskog kinetic-theory t0 (with χ(φ))."))
def fig_dem_map(run):
    dem = run.atlas("dem_map")
    if not isinstance(dem, dict) or not dem.get("points"):
        raise Skip("no LAMMPS run in this atlas")
    pts = dem["points"]
    d = dem.get("default") or {}
    own_adaptive = d.get("adaptive_stiffness")
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(11.5, 4.3), layout="constrained")
    main = [p for p in pts if p.get("adaptive_stiffness") == own_adaptive]
    for k, state in enumerate(sorted({p["state"] for p in main})):
        sel = [p for p in main if p["state"] == state]
        ax.scatter([p["max_overlap"] for p in sel], [p["steps_per_contact"] for p in sel], s=70, marker="s",
                   color=STATE_COLOR.get(state, f"C{4 + k}"), label=state)
    ax.scatter([d.get("max_overlap")], [d.get("steps_per_contact")], marker="*", s=220, color="k", zorder=5,
               label="case's own contact")
    measured = []
    for b in dem.get("boundaries") or []:
        if b.get("failed") is not None:
            measured.append((f"{b['knob']} {b['direction']}",
                             f"ok to {fmt(b['stable'], 3)}, fails at {fmt(b['failed'], 3)} ({b['failure']})", None))
        elif b.get("note"):
            measured.append((f"{b['knob']} {b['direction']}", b["note"], None))
        else:
            measured.append((f"{b['knob']} {b['direction']}", f"ok over the grid, to {fmt(b.get('stable'), 3)}", None))
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("md.max_overlap (σ)")
    ax.set_ylabel("md.steps_per_contact")
    ax.legend(fontsize=7, loc="best")
    against = dem.get("against") or {}
    drawn = False
    for key, label, color in (("t0", "Haff t0", "C0"), ("compressibility", "P/(nT)", "C1")):
        for adaptive, face in ((own_adaptive, color), (not own_adaptive, "none")):
            sel = [p for p in pts if p.get("adaptive_stiffness") == adaptive and p.get("steps_per_contact") ==
                   d.get("steps_per_contact") and p.get(f"{key}_bias") is not None]
            if not sel:
                continue
            sel.sort(key=lambda p: p["max_overlap"])
            x = np.array([p["max_overlap"] for p in sel], float) * (1.04 if key == "compressibility" else 1.0)
            y = np.array([p[f"{key}_bias"] for p in sel], float)
            e = np.array([p.get(f"{key}_bias_error") or 0.0 for p in sel], float)
            ax2.errorbar(x, y, yerr=e, fmt="o-" if face != "none" else "o", color=color, mfc=face, capsize=3,
                         label=f"{label}" + ("" if face != "none" else " (adaptive stiffness flipped)"))
            drawn = True
            if face != "none":
                for p in sel:
                    measured.append((f"{label} bias at max_overlap {fmt(p['max_overlap'], 3)}",
                                     f"{fmt(100 * p[f'{key}_bias'], 3)} ± {fmt(100 * (p.get(f'{key}_bias_error') or 0), 2)} % "
                                     f"(ensemble {p['ensemble']}, {fmt(p['wall_seconds'], 3)} s)", None))
    theory = sorted([p for p in pts if p.get("adaptive_stiffness") == own_adaptive and p.get("steps_per_contact") ==
                     d.get("steps_per_contact") and p.get("t0_bias_kinetic_theory") is not None],
                    key=lambda p: p["max_overlap"])
    if theory:
        ax2.plot([p["max_overlap"] for p in theory], [p["t0_bias_kinetic_theory"] for p in theory], "s--",
                 color="0.4", label="Haff t0 against Enskog kinetic theory (with χ)")
        for p in theory:
            measured.append((f"Haff t0 against kinetic theory at max_overlap {fmt(p['max_overlap'], 3)}",
                             f"{fmt(100 * p['t0_bias_kinetic_theory'], 3)} %", None))
        drawn = True
    if not drawn:
        ax2.text(0.5, 0.5, "no event-driven reference: no bias", ha="center", va="center", transform=ax2.transAxes)
    tol = run.atlas("tolerance")
    ax2.axhline(0.0, color="k", lw=0.8)
    if isinstance(tol, (int, float)):
        ax2.axhspan(-tol, tol, color="C2", alpha=0.12, lw=0, label="± tolerance")
    ax2.set_xscale("log")
    ax2.set_xlabel(f"md.max_overlap (σ), steps_per_contact = {d.get('steps_per_contact')}")
    ax2.set_ylabel("DEM / hard disks − 1")
    ax2.legend(fontsize=7, loc="best")
    return Drawn(fig, measured, caption_values={"tolerance": fmt(tol), "against": against.get("setting", "none")})


POWER_COLOR = {"viscosity_factor": "C0", "conductivity_factor": "C1", "mu_factor": "C2", "cooling_factor": "C3"}


def plot_smallest_eps(ax, rows, cost, keys, eps, detectable_of, measured):
    """Per key and direction the smallest caught ε of each particle run (detectable_of(row) holds
    detectable.<key>.<up|down>): a line where caught, a triangle at the top where none is; one
    measured row each, with the run's members and wall seconds."""
    top = max(eps) * 1.6 if eps else 1.0
    for key in keys:
        color = POWER_COLOR.get(key, "k")
        for direction, ls in (("up", "-"), ("down", "--")):
            label = f"{key.replace('_factor', '')} {'×' if direction == 'up' else '÷'} (1 + ε)"
            x, y, missed = [], [], []
            for r in rows:
                d = ((detectable_of(r) or {}).get(key) or {}).get(direction)
                if d is None:
                    missed.append(cost[id(r)])
                else:
                    x.append(cost[id(r)])
                    y.append(d)
                what = f"ε ≥ {fmt(d, 3)}" if d is not None else f"none caught up to ε = {fmt(max(eps) if eps else None, 3)}"
                members = (r.get("setting") or {}).get("ensemble")
                measured.append((f"{label}, {members} members ({fmt(r.get('wall_seconds'), 3)} s)", what, None))
            if x:
                ax.plot(x, y, ls=ls, marker="o", color=color, mfc=color if direction == "up" else "none", label=label)
            if missed:
                ax.scatter(missed, [top] * len(missed), marker="^", color=color,
                           facecolors=color if direction == "up" else "none", label=None if x else label + " (none caught)")


@figure(file="a5_comparison_power.png", section="atlas", anchor="comparison_power",
        title="Comparison power: the smallest model error the particles can catch",
        caption=("The hydro at the case's own setting ({hydro}) with one transport coefficient multiplied by "
                 "(1 + ε) (solid) or divided by it (dashed), judged side by side against each particle run of the "
                 "reference engine as granvv run judges its comparison (signal/noise {sn}). A point is the "
                 "smallest ε from which every larger ε on the grid ({grid}) is flagged as a model disagreement "
                 "that the unperturbed hydro does not have; a triangle at the top means no ε up to the largest "
                 "was caught. A grey cross at the bottom marks a particle run against which the unperturbed hydro "
                 "is itself flagged as a model disagreement: only an earlier parting can then count. The particle "
                 "cost is N × ensemble, the disks simulated ({per} per member)."))
def fig_comparison_power(run):
    power = run.atlas("comparison_power")
    if not isinstance(power, dict) or not power.get("particles"):
        why = power.get("skipped") if isinstance(power, dict) else None
        raise Skip(why or "no particle reference in this atlas: no comparison power")
    per = power.get("disks_per_member") or 1
    rows = sorted(power["particles"], key=lambda r: (r.get("setting") or {}).get("ensemble") or 0)
    cost = {id(r): per * ((r.get("setting") or {}).get("ensemble") or 1) for r in rows}
    eps = power.get("epsilons") or []
    fig, ax = plt.subplots(figsize=(6.8, 4.3), layout="constrained")
    measured = []
    plot_smallest_eps(ax, rows, cost, power.get("keys") or [], eps, lambda r: r.get("detectable"), measured)
    flagged = [cost[id(r)] for r in rows if (r.get("unperturbed") or {}).get("disagreement") == "model"]
    if flagged:
        bottom = min(eps) / 1.6 if eps else 1e-3
        ax.scatter(flagged, [bottom] * len(flagged), marker="X", color="0.45", s=60,
                   label="the unperturbed hydro is itself flagged (model)")
    for r in rows:
        base = r.get("unperturbed") or {}
        members = (r.get("setting") or {}).get("ensemble")
        measured.append((f"unperturbed hydro against {members} members",
                         f"{base.get('disagreement')}, agreed until t = {fmt(base.get('agreed_until'), 4)}", None))
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("particle cost: N × ensemble (disks)")
    ax.set_ylabel("smallest detectable ε")
    ax.legend(fontsize=7, loc="best")
    hydro = power.get("hydro") or {}
    return Drawn(fig, measured, caption_values={
        "hydro": f"{hydro.get('model')} cells={hydro.get('cells')}",
        "sn": fmt(power.get("signal_to_noise"), 3), "per": per,
        "grid": f"{fmt(min(eps), 3)} to {fmt(max(eps), 3)}, {len(eps)} values" if eps else "empty"})


@figure(file="a6_comparison_power_transport.png", section="atlas", anchor="comparison_power_transport",
        title="Comparison power by the transport fit: the smallest coefficient error it catches",
        caption=("At each particle run of the reference engine the factor F on the {closure} closure's {coefficient} "
                 "is fitted to the members' k = 1 mode with its jackknife standard error σ, as granvv run fits it "
                 "(grey, right axis: F ± σ). A hydro with one coefficient multiplied by (1 + ε) (solid) or divided "
                 "by it (dashed) has the factor its {coefficient} is moved by; ε is caught when that factor is more "
                 "than {sigmas} σ from F while the unperturbed closure (F = 1) is not. A point is the smallest ε "
                 "from which every larger ε on the grid ({grid}) is caught; a triangle at the top, none up to the "
                 "largest; a grey cross at the bottom, a run against which the unperturbed closure is itself off "
                 "(nothing is caught there). Keys that do not move {coefficient} are not judged ({not_judged}). "
                 "The particle cost is N × ensemble ({per} disks per member); the table gives each run's wall "
                 "seconds (the fit's own hydro grid apart)."))
def fig_comparison_power_transport(run):
    power = run.atlas("comparison_power")
    fit = power.get("transport_fit") if isinstance(power, dict) else None
    if not isinstance(fit, dict) or not power.get("particles"):
        raise Skip("the scene measures no single transport coefficient (or the comparison power was skipped)")
    per = power.get("disks_per_member") or 1
    rows = sorted(power["particles"], key=lambda r: (r.get("setting") or {}).get("ensemble") or 0)
    cost = {id(r): per * ((r.get("setting") or {}).get("ensemble") or 1) for r in rows}
    eps = power.get("epsilons") or []
    top = max(eps) * 1.6 if eps else 1.0
    bottom = min(eps) / 1.6 if eps else 1e-3
    fig, ax = plt.subplots(figsize=(6.8, 4.3), layout="constrained")
    measured = []
    plot_smallest_eps(ax, rows, cost, fit.get("keys_judged") or [], eps,
                      lambda r: (r.get("transport_fit") or {}).get("detectable"), measured)
    off = [cost[id(r)] for r in rows if (r.get("transport_fit") or {}).get("unperturbed_off") is True]
    if off:
        ax.scatter(off, [bottom] * len(off), marker="X", color="0.45", s=60, label="the unperturbed closure is off")
    right = ax.twinx()
    fx, fy, fe = [], [], []
    for r in rows:
        rf = r.get("transport_fit") or {}
        members = (r.get("setting") or {}).get("ensemble")
        if isinstance(rf.get("factor"), (int, float)) and isinstance(rf.get("error"), (int, float)) and rf.get("failure") is None:
            fx.append(cost[id(r)])
            fy.append(rf["factor"])
            fe.append(rf["error"])
            edge = ", at the factor grid's edge" if rf.get("at_grid_edge") else ""
            measured.append((f"F against {members} members (fit {fmt(rf.get('wall_seconds'), 3)} s)",
                             f"{fmt(rf['factor'], 4)} ± {fmt(rf['error'], 2)}{edge}", None))
        else:
            measured.append((f"F against {members} members", f"no fit: {rf.get('failure')}", None))
    if fx:
        right.errorbar(fx, fy, yerr=fe, fmt="s", color="0.55", ms=4, capsize=2)
        right.axhline(1.0, color="0.75", lw=0.8)
    right.set_ylabel("fitted factor F ± σ", color="0.45")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_ylim(bottom / 1.3, top * 1.3)
    ax.set_xlabel("particle cost: N × ensemble (disks)")
    ax.set_ylabel("smallest ε caught by the fit")
    ax.legend(fontsize=7, loc="best")
    hydro = power.get("hydro") or {}
    judged = set(fit.get("keys_judged") or [])
    return Drawn(fig, measured, caption_values={
        "coefficient": fit.get("coefficient"), "closure": hydro.get("model"),
        "sigmas": fmt(run.atlas("sigmas"), 3), "per": per,
        "not_judged": ", ".join(k for k in power.get("keys") or [] if k not in judged) or "none",
        "grid": f"{fmt(min(eps), 3)} to {fmt(max(eps), 3)}, {len(eps)} values" if eps else "empty"})
