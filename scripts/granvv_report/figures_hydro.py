"""Figures of the hydro (/hydro): the paper's Figs. 1-4 (profiles, energy, flow-by-inertia collapse,
approach to the singularity), Haff's law, the linear theory of the homogeneous cooling state and
self-convergence. Efrati, Livne & Meerson, PRL 94, 088001 (2005); docs/physics.md §1-§3."""
import math

import matplotlib.pyplot as plt
import numpy as np
from markupsafe import Markup, escape

from .data import Skip, arr, find_snapshot_summary, get, hydro_t0, num, same_time, snapshot_labels
from .formatting import fmt, pct, tex_num, verdict, within_tolerance
from .registry import Drawn, figure
from .validity import MONITOR_COLUMNS, MONITOR_LABELS, mark_validity
from .style import (N_UNIT, T_FIELD, T_UNIT, V_UNIT, X_UNIT, marker_every, pick, power_scale,
                    sorted_periodic, thin, time_colors, tlabel, wrap)


def unstable_modes_sentence(run):
    """For a caption: this run's number of linearly unstable clustering modes (summary.json), with
    its K, q and closure."""
    n = run.hydro_summary("unstable_modes")
    if n is None:
        return ""
    K, q, closure = num(run.config("physics.K")), num(run.config("physics.q")), run.hydro_summary("closure")
    at = f" (K = {fmt(K)}, q = {fmt(q)})" if K is not None and q is not None else ""
    below = f", below the cut-off of its {escape(closure)} closure" if closure else ""
    return f" This run{at} has {fmt(n)} linearly unstable clustering modes{below}."


@figure(file="fig1_profiles.png", section="hydro", anchor="profiles",
        title='Density and velocity profiles (paper Fig. 1)',
        caption=('Fig. 1: with K = 4·10<sup>−4</sup>, q = 10<sup>−2</sup> the gas develops high, '
                 'narrow density peaks with steepening velocity gradients; with 2000 Lagrangian mesh '
                 'points the major peak holds more than 50 mesh points above n = 10<sup>2</sup> '
                 'shortly before it becomes singular. The inset shows the earlier density history '
                 'around the major peak.{unstable_modes}'))
def fig_profiles(run):
    """Paper Fig. 1: density (log) and velocity (and temperature) profiles at the output times."""
    F = run.hydro_fields
    if F is None:
        raise Skip("no /hydro/fields in results.h5")
    t, x, n = arr(F, "t"), arr(F, "x", 2), arr(F, "n", 2)
    vx, vy, T = arr(F, "v_x", 2), arr(F, "v_y", 2), arr(F, "T", 2)
    if t is None or x is None or n is None or x.ndim != 2 or n.shape != x.shape or x.shape[0] != t.size:
        raise Skip("/hydro/fields lacks t, x, n of matching shapes")
    ns = t.size
    labels = snapshot_labels(F, ns)
    dn = max(np.nanmax(np.abs(n[i] / np.nanmean(n[i]) - 1)) for i in range(ns))
    dv = max(np.nanmax(np.abs(vx[i])) for i in range(ns)) if vx is not None else 0.0
    if dn < 1e-8 and dv < 1e-8:
        raise Skip("the profiles stay uniform (homogeneous cooling state): nothing to draw")
    idx = pick(range(ns))
    cols = time_colors(t[idx])
    last = idx[-1]
    clustered = np.nanmax(n[last]) > 5
    has_T = T is not None and T.shape == n.shape
    has_vy = vy is not None and vy.shape == n.shape and np.nanmax(np.abs(vy)) > 0
    rows = 2 + int(has_T)
    fig = plt.figure(figsize=(10.5 if clustered else 7.5, 2.6 * rows + 0.4), layout="constrained")
    gs = fig.add_gridspec(rows, 2 if clustered else 1, width_ratios=[2.1, 1] if clustered else None)
    ax_n = fig.add_subplot(gs[0, 0])
    ax_v = fig.add_subplot(gs[1, 0], sharex=ax_n)
    ax_T = fig.add_subplot(gs[2, 0], sharex=ax_n) if has_T else None
    # density axis: log for clusters, linear for mild contrast, n - 1 for linear perturbations
    n_mode = "delta" if dn < 1e-2 else ("log" if np.nanmax(n[idx]) / np.nanmin(n[idx]) > 3 else "lin")
    n_f, n_suffix = power_scale(n[idx] - 1.0) if n_mode == "delta" else (1.0, "")
    v_f, v_suffix = power_scale(*(a[idx] for a in (vx, vy if has_vy else None) if a is not None))
    for c, i in zip(cols, idx):
        xs, ni, *rest = sorted_periodic(x[i], n[i], *(a[i] for a in (vx, vy, T) if a is not None))
        lw = 1.8 if i == last else 1.1
        ax_n.plot(xs, (ni - 1.0) * n_f if n_mode == "delta" else ni, color=c, lw=lw, label=tlabel(t[i], labels[i]))
        k = 0
        if vx is not None:
            ax_v.plot(xs, rest[k] * v_f, color=c, lw=lw)
            k += 1
        if vy is not None:
            if has_vy:
                ax_v.plot(xs, rest[k] * v_f, color=c, lw=0.9, ls="--")
            k += 1
        if ax_T is not None:
            ax_T.plot(xs, rest[k], color=c, lw=lw)
    if n_mode == "log":
        ax_n.set_yscale("log")
        ax_n.set_ylabel(N_UNIT)
    elif n_mode == "delta":
        ax_n.set_ylabel(r"$n - 1$  [$n_0$]" + n_suffix)
        ax_n.axhline(0, color="0.5", lw=0.6)
    else:
        ax_n.set_ylabel(N_UNIT)
    ax_n.set_title("(a) density" + (" perturbation" if n_mode == "delta" else ""))
    ax_n.legend(loc="best", ncol=2 if len(idx) > 4 else 1)
    ax_v.set_ylabel(r"$v$  [$\sqrt{T_0/m}$]" + v_suffix)
    ax_v.set_title("(b) velocity" + ("  (solid $v_x$, dashed $v_y$)" if has_vy else ""))
    ax_v.axhline(0, color="0.5", lw=0.6)
    if ax_T is not None:
        ax_T.set_yscale("log")
        ax_T.set_ylabel(T_FIELD)
        ax_T.set_title("(c) granular temperature")
    (ax_T or ax_v).set_xlabel(X_UNIT)
    ax_n.set_xlim(-0.5, 0.5)
    for a in (ax_n, ax_v) + ((ax_T,) if ax_T else ()):
        if a is not (ax_T or ax_v):
            plt.setp(a.get_xticklabels(), visible=False)

    zoom_text = ""
    if clustered:
        ip = int(np.nanargmax(n[last]))
        xp = float(x[last, ip])
        xp_label = round(xp, 4) + 0.0   # + 0.0: no "-0.0000" in the label
        d = wrap(x[last] - xp)
        # half-width: 1.5 x the extent where the final peak exceeds 3 x the median density
        thr = 3.0 * max(1.0, float(np.nanmedian(n[last])))
        inside = np.abs(d[n[last] > thr])
        w = float(np.clip(1.5 * inside.max() if inside.size else 0.02, 5.0 / n.shape[1], 0.25))
        ax_z = fig.add_subplot(gs[:, 1])
        # paper's inset: earlier density history around the major peak
        zidx = [i for i in idx]
        for c, i in zip(cols, zidx):
            di = wrap(x[i] - xp)
            sel = np.abs(di) <= w
            o = np.argsort(di[sel])
            ax_z.plot(di[sel][o], n[i][sel][o], color=c, lw=1.8 if i == last else 1.1,
                      marker="." if i == last else None, ms=2.5)
        ax_z.set_yscale("log")
        ax_z.set_xlim(-w, w)
        ax_z.set_xlabel(rf"$x - x_{{\rm peak}}$  [$L_x$],  $x_{{\rm peak}} = {xp_label:.4f}$")
        ax_z.set_ylabel(N_UNIT)
        ax_z.set_title("(d) history around the major peak")
        zoom_text = "Panel (d) plays the role of the paper's inset, in a fixed window around the final peak."
    measured = [
        ("linearly unstable clustering modes", fmt(run.hydro_summary("unstable_modes")), None),
        ("cells", fmt(run.hydro_summary("cells") or n.shape[1]), None),
        (f"peak density at t = {fmt(t[last])} (last plotted snapshot)", fmt(float(np.nanmax(n[last]))), None),
        (f"cells with n &gt; 10<sup>2</sup> at t = {fmt(t[last])} (counted in the plotted snapshot)",
         fmt(int(np.sum(n[last] > 100))), None),
    ]
    return Drawn(fig, measured,
                 note=Markup(zoom_text + " Profiles are drawn at cell centres, sorted in x on the periodic domain."),
                 caption_values=dict(unstable_modes=unstable_modes_sentence(run)))


@figure(file="fig2_energy.png", section="hydro", anchor="energy",
        title='Energy: total, thermal, kinetic (paper Fig. 2)',
        caption=("Fig. 2: E(t) follows Haff's law at early times and deviates later. Thermal and "
                 'macroscopic kinetic energy both decay at first, the thermal one faster; at late '
                 'times the kinetic energy approaches a constant (flow by inertia), so E is dominated '
                 'by thermal energy early and by kinetic energy late. The thermal energy keeps '
                 "following Haff's law until the singularity. Panel (b) is not in the paper: it "
                 'checks that the scheme conserves E + E<sub>cooled</sub> and momentum to round-off.'))
def fig_energy(run):
    """Paper Fig. 2: energy split on log-log axes with Haff's law, and the energy balance."""
    ts = run.hydro_ts
    t, E = arr(ts, "t", 3), arr(ts, "energy", 3)
    if t is None or E is None or E.size != t.size:
        raise Skip("no energy time series")
    Eth, Ek = arr(ts, "energy_thermal"), arr(ts, "energy_kinetic")
    Eky, Ec, haff = arr(ts, "energy_kinetic_y"), arr(ts, "energy_cooled"), arr(ts, "haff_T")
    P = arr(ts, "momentum")
    ok = lambda a: a is not None and a.size == t.size  # noqa: E731
    pos = t > 0
    if pos.sum() < 2:
        raise Skip("energy time series has fewer than two positive times")
    t0 = hydro_t0(run)[0]
    has_balance = ok(Ec)
    fig, axes = plt.subplots(1, 2 if has_balance else 1, figsize=(11 if has_balance else 6.2, 4.3),
                             layout="constrained", squeeze=False)
    ax = axes[0, 0]
    tt = t[pos]
    me = marker_every(tt, 16)
    ax.plot(tt, E[pos], color="k", lw=2.6, label=r"total $E$ (Eq. 3)")
    if ok(Eth):
        ax.plot(tt, Eth[pos], color="C3", ls="none", marker="o", mfc="none", ms=5, markevery=me,
                label=r"thermal $\int nT\,dx$")
        ax.plot(tt, Eth[pos], color="C3", lw=0.7, alpha=0.6)
    if ok(Ek) and np.nanmax(Ek[pos]) > 0:
        ax.plot(tt, Ek[pos], color="C0", ls="none", marker="s", mfc="none", ms=5, markevery=me,
                label=r"kinetic $\int n v_x^2/2\,dx$")
        ax.plot(tt, Ek[pos], color="C0", lw=0.7, alpha=0.6)
    if ok(Eky) and np.nanmax(Eky[pos]) > 0:
        ax.plot(tt, Eky[pos], color="C2", ls="none", marker="^", mfc="none", ms=5, markevery=me,
                label=r"transverse kinetic $\int n v_y^2/2\,dx$")
        ax.plot(tt, Eky[pos], color="C2", lw=0.7, alpha=0.6)
    if ok(haff):
        ref = Eth[0] if ok(Eth) else E[0]
        ax.plot(tt, ref * haff[pos], color="0.35", lw=0.9,
                label=r"Haff: $E_{\rm th}(0)\,(1+t/t_0)^{-2}$")
    ax.set_xscale("log")
    ax.set_yscale("log")
    lo = tt.min()
    if t0:
        lo = max(lo, 0.1 * t0)
        if lo < t0 < tt.max():
            ax.axvline(t0, color="0.6", lw=0.7, ls=":")
            ax.text(t0, 0.5, r" $t_0$", transform=ax.get_xaxis_transform(), color="0.4", fontsize=8)
    ax.set_xlim(lo, tt.max() * 1.15)
    mark_validity(ax, run.hydro_summary("validity"))
    ax.set_xlabel(T_UNIT)
    ax.set_ylabel(r"energy  [$N T_0$]")
    ax.set_title("(a) energy split")
    ax.legend(loc="best")
    if has_balance:
        ax2 = axes[0, 1]
        E0 = E[0]
        bal = (E + Ec - E0) / E0
        pm = (P - P[0]) / math.sqrt(2 * E0) if ok(P) else None
        f, suffix = power_scale(bal, pm)
        tb, bal_t = thin(t, bal * f)
        ax2.plot(tb, bal_t, color="k", lw=0.9, label=r"$(E + E_{\rm cooled} - E(0))\,/\,E(0)$")
        if pm is not None:
            tb, pm_t = thin(t, pm * f)
            ax2.plot(tb, pm_t, color="C1", lw=0.9, label=r"$(P - P(0))\,/\,\sqrt{2E(0)}$")
        ax2.axhline(0, color="0.5", lw=0.6)
        ax2.set_xlabel(T_UNIT)
        ax2.set_ylabel("relative drift" + suffix)
        ax2.set_title("(b) conservation: energy balance and momentum")
        ax2.legend(loc="best")
        mark_validity(ax2, run.hydro_summary("validity"))
    measured = [
        ("energy balance drift |E + E<sub>cooled</sub> − E(0)| / E(0)", fmt(run.hydro_summary("energy_drift")), None),
        ("momentum drift", fmt(run.hydro_summary("momentum_drift")), None),
    ]
    if ok(Eth) and ok(Ek):
        measured.append((f"at the last time t = {fmt(t[-1])}: E<sub>kin</sub>/E, E<sub>th</sub>/E "
                         "(read off the time series)",
                         Markup(f"{fmt(Ek[-1] / E[-1], 3)}, {fmt(Eth[-1] / E[-1], 3)}"), None))
        if ok(haff):
            measured.append(("E<sub>th</sub>(t<sub>end</sub>) / [E<sub>th</sub>(0)(1+t<sub>end</sub>/t<sub>0</sub>)<sup>−2</sup>] "
                             "(read off the time series)", fmt(Eth[-1] / (Eth[0] * haff[-1]), 3), None))
    return Drawn(fig, measured)


@figure(file="fig3_inertia_collapse.png", section="hydro", anchor="collapse",
        title='Flow by inertia: velocity collapse (paper Fig. 3)',
        caption=('Fig. 3: the velocity plotted against ξ = x − v t at times 1, 2 and 3.225 collapses '
                 'onto a single curve, the initial profile v<sub>0</sub> = a sin 2πx (a = −0.05); all '
                 'curves coincide within 1.5 %. Panel (c) shows that difference directly, in per cent '
                 'of the amplitude, with the tolerance band (analysis.collapse_tolerance, by default '
                 "the paper's 1.5 %)."))
def fig_collapse(run):
    """Paper Fig. 3: v vs x, v vs xi = x - t v with the initial profile, and the collapse error."""
    L, F = run.hydro_lagrangian, run.hydro_fields
    if L is None:
        raise Skip("no /hydro/lagrangian in results.h5")
    X, V, XI, V0 = (arr(L, k, 2) for k in ("node_x", "node_v_x", "xi", "inertia_v0"))
    t = arr(F, "t") if F else None
    if any(a is None for a in (X, V, XI, V0, t)) or not (X.shape == V.shape == XI.shape == V0.shape) \
            or X.ndim != 2 or X.shape[0] != t.size:
        raise Skip("/hydro/lagrangian lacks node_x, node_v_x, xi, inertia_v0 matching /hydro/fields/t")
    amp = float(np.nanmax(np.abs(V0)))
    if not amp > 0:
        raise Skip("initial velocity profile is zero: no flow by inertia to test")
    tau_in = num(run.hydro_theory["attrs"].get("inertia_tau")) if run.hydro_theory else None
    collapse = [num(get(r, "collapse_error")) for r in run.hydro_summary("snapshots") or []]
    if tau_in is None and all(c is None for c in collapse):
        raise Skip("the program makes no flow-by-inertia prediction for this initial condition "
                   "(inertia_tau absent/NaN, no collapse_error in summary.json)")
    labels = snapshot_labels(F, t.size)
    later = [i for i in range(t.size) if t[i] > 0]
    if not later:
        raise Skip("no snapshot after t = 0")
    idx = pick(later, 6)
    cols = time_colors(t[idx])
    i0 = next((i for i in range(t.size) if t[i] == 0), None)
    fig = plt.figure(figsize=(10.5, 7.4), layout="constrained")
    gs = fig.add_gridspec(2, 2, height_ratios=[1.25, 1])
    ax_a = fig.add_subplot(gs[0, 0])
    ax_b = fig.add_subplot(gs[0, 1], sharey=ax_a)
    ax_c = fig.add_subplot(gs[1, :])
    if i0 is not None:
        xs, vs = sorted_periodic(X[i0], V[i0])
        ax_a.plot(xs, vs, color="0.6", lw=1.0, ls="--", label="$t=0$")
    # v0 as a smooth reference over the full period
    ref_i = idx[-1]
    xr, v0r = sorted_periodic(XI[ref_i], V0[ref_i])
    ax_b.plot(xr, v0r, color="k", lw=3.2, alpha=0.25, label=r"initial profile $v_0(\xi)$", zorder=1)
    for c, i in zip(cols, idx):
        xs, vs = sorted_periodic(X[i], V[i])
        ax_a.plot(xs, vs, color=c, label=tlabel(t[i], labels[i]))
        xis, vis, v0s = sorted_periodic(XI[i], V[i], V0[i])
        ax_b.plot(xis, vis, color=c, lw=1.1, label=tlabel(t[i], labels[i]), zorder=2)
        rec = find_snapshot_summary(run, float(t[i]))
        ce = num(get(rec, "collapse_error"))
        lab = tlabel(t[i]) + (f"  (summary: {100 * ce:.2f} %)" if ce is not None else "")
        ax_c.plot(xis, 100 * (vis - v0s) / amp, color=c, lw=1.1, label=lab)
    ax_a.set_xlim(-0.5, 0.5)
    ax_b.set_xlim(-0.5, 0.5)
    ax_a.set_xlabel(X_UNIT)
    ax_a.set_ylabel(V_UNIT)
    ax_a.set_title("(a) velocity vs Eulerian $x$")
    ax_a.legend(loc="best", fontsize=7.5)
    ax_b.set_xlabel(r"$\xi = x - t\,v$  [$L_x$]")
    ax_b.set_title(r"(b) velocity vs $\xi$: collapse onto $v_0$")
    ax_b.legend(loc="best", fontsize=7.5)
    plt.setp(ax_b.get_yticklabels(), visible=False)
    tol = num(run.hydro_summary("collapse_tolerance"))   # analysis.collapse_tolerance
    if tol is not None:
        ax_c.axhspan(-100 * tol, 100 * tol, color="C2", alpha=0.12, label=f"tolerance: ±{100 * tol:g} %")
        for s in (-1, 1):
            ax_c.axhline(s * 100 * tol, color="C2", lw=0.8, ls="--")
    ax_c.axhline(0, color="0.5", lw=0.6)
    ax_c.set_xlim(-0.5, 0.5)
    ax_c.set_xlabel(r"$\xi$  [$L_x$]")
    ax_c.set_ylabel(r"$(v - v_0(\xi))\,/\,|a|$  [%]")
    ax_c.set_title(rf"(c) deviation from the initial profile, $|a| = \max|v_0| = {amp:.4g}$")
    ymax = max(2.5 * 100 * (tol or 0.0), 1.1 * float(np.nanmax(np.abs(ax_c.dataLim.intervaly))))
    ax_c.set_ylim(-ymax, ymax)
    ax_c.legend(loc="center left", bbox_to_anchor=(1.01, 0.5), fontsize=7.5)
    measured = []
    for r in run.hydro_summary("snapshots") or []:
        tt, e = num(get(r, "t")), num(get(r, "collapse_error"))
        if tt is not None and e is not None:
            measured.append((f"collapse error at t = {fmt(tt)}", pct(e), within_tolerance(get(r, "collapse_within_tolerance"))))
    worst = num(run.hydro_summary("collapse_error_max"))
    if worst is not None:
        measured.insert(0, ("largest collapse error over the snapshots", pct(worst),
                            within_tolerance(run.hydro_summary("collapse_within_tolerance"))))
    measured.append(("collapse tolerance (analysis.collapse_tolerance)", pct(tol), None))
    return Drawn(fig, measured,
                 note=Markup("Collapse error = max over nodes of |v − v<sub>0</sub>(ξ)| / |a|, as computed by the "
                             "C++ code (summary.json); the legend of (c) repeats it."))


@figure(file="fig4a_singularity.png", section="hydro", anchor="singularity",
        title='Approach to the singularity (paper Fig. 4a)',
        caption=('Fig. 4a: |∂v/∂x| and n at x = 0 grow without bound; their inverses (inset) decrease '
                 'linearly in time — the linear dependence sets in already at early times — and '
                 'vanish at the singularity. Flow by inertia from v<sub>0</sub> = a sin 2πx predicts '
                 'τ = 1/(2π|a|) ≃ 3.18, which agrees with the simulation within 2 %. In flow by '
                 'inertia 1/|∂v/∂x| = τ − t exactly and n = n<sub>0</sub>(0)(1 − t/τ)<sup>−1</sup> at '
                 'the peak; panel (c), not in the paper, shows this power law against the time left.'))
def fig_singularity(run):
    """Paper Fig. 4a: n and |dv/dx| at the peak vs t, and their inverses with the fitted line to tau."""
    ts = run.hydro_ts
    t, nmax, g = arr(ts, "t", 3), arr(ts, "n_max", 3), arr(ts, "dvdx_peak", 3)
    if t is None or nmax is None or nmax.size != t.size:
        raise Skip("no n_max time series")
    if np.nanmax(nmax) < 3 * max(nmax[0], 1e-300):
        raise Skip(f"peak density grows only to {np.nanmax(nmax):.3g}: no singularity to follow")
    g = np.abs(g) if g is not None and g.size == t.size else None
    tau = num(run.hydro_summary("singularity_time"))
    tau_in = num(run.hydro_summary("inertia_singularity_time"))
    if tau_in is None and run.hydro_theory:
        tau_in = num(run.hydro_theory["attrs"].get("inertia_tau"))
    win = run.hydro_summary("tau_fit_window") or {}
    tw0, tw1 = num(win.get("t_min")), num(win.get("t_max"))
    with np.errstate(divide="ignore", invalid="ignore"):
        inv_n = 1.0 / nmax
        inv_g = np.where(g > 0, 1.0 / g, np.nan) if g is not None else None
    # markers evenly spaced in t, plus log-spaced in the time left to the end (dt shrinks there)
    rem = t[-1] - t
    me = [int(np.argmin(np.abs(t - v))) for v in np.linspace(t[0], t[-1], 22)]
    if rem[0] > 0 and np.any(rem > 0):
        small = rem[rem > 0].min()
        me += [int(np.argmin(np.abs(rem - v))) for v in np.geomspace(max(small, 1e-6 * rem[0]), 0.1 * rem[0], 12)]
    me = sorted(set(me))
    ncol = 3 if tau is not None else 2
    fig, axes = plt.subplots(1, ncol, figsize=(4.4 * ncol, 4.4), layout="constrained")
    ax, ax2 = axes[0], axes[1]
    sty_n = dict(color="C0", lw=0.8, marker="o", mfc="white", ms=4.5, markevery=me)
    sty_g = dict(color="C3", lw=0.8, marker="s", ms=3.8, markevery=me)
    ax.plot(t, nmax, label=r"$n$ at the peak, $n_{\max}$", **sty_n)
    if g is not None:
        ax.plot(t, g, label=r"$|\partial v/\partial x|$ at the peak", **sty_g)
    ax.set_yscale("log")
    for a in (ax, ax2):
        if tau is not None:
            a.axvline(tau, color="k", lw=1.0, label=rf"$\tau$ fitted $= {tau:.4f}$")
        if tau_in is not None:
            a.axvline(tau_in, color="C2", lw=1.0, ls="--",
                      label=rf"$\tau = 1/(2\pi|a|) = {tau_in:.4f}$ (inertia)")
        if tw0 is not None and tw1 is not None:
            a.axvspan(tw0, tw1, color="C1", alpha=0.12, lw=0, label="fit window" if a is ax2 else None)
    ax.set_xlabel(T_UNIT)
    ax.set_ylabel(r"$n_{\max}$ [$n_0$],  $|\partial v/\partial x|$ [$\sqrt{T_0/m}/L_x$]")
    ax.set_title("(a) peak density and velocity gradient")
    ax.legend(loc="upper left")
    # inverses: linear in t, both vanish at tau (paper's inset)
    ax2.plot(t, inv_n, label=r"$1/n_{\max}$", **sty_n)
    if inv_g is not None:
        ax2.plot(t, inv_g, label=r"$1/|\partial v/\partial x|$", **sty_g)
    if tau is not None:
        # straight line through (tau, 0); slope: least squares inside the fit window (drawing aid only)
        sel = (t >= (tw0 if tw0 is not None else -np.inf)) & (t <= (tw1 if tw1 is not None else np.inf)) & (t < tau)
        tl = np.linspace(t[0], tau, 60)
        for y, col in ((inv_n, "#0b3c66"), (inv_g, "#6b1010")):
            if y is None:
                continue
            m = sel & np.isfinite(y)
            if m.sum() < 2:
                continue
            A = np.sum(y[m] * (tau - t[m])) / np.sum((tau - t[m]) ** 2)
            ax2.plot(tl, A * (tau - tl), color=col, lw=1.0, ls="--", zorder=4)
        ax2.plot([], [], color="0.2", lw=1.0, ls="--", label=r"fit $\propto(\tau - t)$ in the window")
    # robust top: an isolated spike of 1/|dv/dx| (the peak cell hopping early on) must not flatten the rest
    tops = [float(np.nanmax(inv_n))]
    if inv_g is not None and np.isfinite(inv_g).any():
        tops.append(float(np.nanpercentile(inv_g, 98)))
    ax2.set_ylim(0, 1.12 * max(tops))
    ax2.set_xlabel(T_UNIT)
    ax2.set_ylabel(r"$1/n_{\max}$ [$1/n_0$],  $1/|\partial v/\partial x|$ [$L_x/\sqrt{T_0/m}$]")
    ax2.set_title("(b) inverses (paper's inset)")
    ax2.legend(loc="upper right")
    for a in (ax, ax2):
        mark_validity(a, run.hydro_summary("validity"))
    # Panel (c) counts time from the blow-up (extrapolated from the last samples of 1/n_max), the
    # time n_max really diverges; pressure in the peak bends 1/n_max, so the window fit comes earlier.
    tau_c = num(run.hydro_summary("blowup_time")) or tau
    if tau is not None:
        ax3 = axes[2]
        before = t < tau_c
        dtau = tau_c - t[before]
        me3 = [int(i) for i in np.unique([np.argmin(np.abs(np.log(dtau) - v))
                                          for v in np.linspace(np.log(dtau.min()), np.log(dtau.max()), 25)])]
        ax3.plot(dtau, nmax[before], **{**sty_n, "markevery": me3}, label=r"$n_{\max}$")
        if g is not None:
            ax3.plot(dtau, g[before], **{**sty_g, "markevery": me3}, label=r"$|\partial v/\partial x|$")
        ref = np.geomspace(dtau.min(), dtau.max(), 10)
        ax3.plot(ref, 1.0 / ref, color="k", lw=1.0, ls=":", label=r"$(\tau - t)^{-1}$")
        ax3.set_xscale("log")
        ax3.set_yscale("log")
        ax3.invert_xaxis()
        ax3.set_xlabel(rf"$\tau_b - t$  [$L_x/\sqrt{{T_0/m}}$],  blow-up $\tau_b = {tau_c:.5f}$")
        ax3.set_title("(c) divergence as $(\\tau - t)^{-1}$")
        ax3.legend(loc="upper left")
        after = ~before
        if after.any():
            ax3.text(0.98, 0.03, f"not shown: {int(after.sum())} samples with $t \\geq \\tau_b$,\n"
                     f"reaching $n_{{\\max}} = {tex_num(float(np.nanmax(nmax[after])))}$ at $t = {t[after][-1]:.4f}$",
                     transform=ax3.transAxes, ha="right", va="bottom", fontsize=7.5,
                     bbox=dict(boxstyle="round,pad=0.3", fc="white", ec="0.8"))
    dev = num(run.hydro_summary("singularity_time_deviation"))
    measured = [
        ("singularity time τ (fit of 1/n<sub>max</sub> in the window)", fmt(tau), None),
        ("fit window", Markup(f"n ∈ [{fmt(num(win.get('n_min')))}, {fmt(num(win.get('n_max')))}], "
                              f"t ∈ [{fmt(tw0)}, {fmt(tw1)}]") if win else fmt(None), None),
        ("blow-up time τ<sub>b</sub> (1/n<sub>max</sub> extrapolated from the last two samples)",
         fmt(num(run.hydro_summary("blowup_time"))), None),
        ("relative deviation τ<sub>b</sub>/τ<sub>inertia</sub> − 1",
         pct(num(run.hydro_summary("blowup_time_deviation"))), None),
        ("flow-by-inertia prediction τ = 1/(2π|a|)", fmt(tau_in), None),
        ("relative deviation τ/τ<sub>inertia</sub> − 1", pct(dev),
         verdict(run.hydro_summary("singularity_time_within_tolerance"))),
    ]
    pdt = run.hydro_summary("peak_density_times")
    if isinstance(pdt, dict) and pdt:
        measured.append(("time the peak density first reaches " +
                         ", ".join(escape(k) for k in pdt), Markup(", ".join(str(fmt(num(v))) for v in pdt.values())),
                         None))
    return Drawn(fig, measured,
                 note=Markup("The dashed straight lines in (b) pass through (τ, 0) with τ from summary.json; their "
                             "slopes are least-squares fits inside the shaded window, drawn only to guide the eye."))


@figure(file="fig4b_density_profile.png", section="hydro", anchor="density_profile",
        title='Density profile near the singularity (paper Fig. 4b)',
        caption=('Fig. 4b (t = 3.209 and 3.225): very close to x = 0 the density grows as '
                 'n<sub>0</sub>(0)(1 − t/τ)<sup>−1</sup>; outside that core, but still close to x = '
                 '0, n(x, t) approaches the universal profile n ∝ |x|<sup>−2/3</sup> (straight line, '
                 'for reference).'))
def fig_density_profile(run):
    """Paper Fig. 4b: n vs |x - x_peak| on log-log axes near the singularity, x^{-2/3} reference."""
    F = run.hydro_fields
    if F is None:
        raise Skip("no /hydro/fields in results.h5")
    t, x, n = arr(F, "t"), arr(F, "x", 2), arr(F, "n", 2)
    if t is None or x is None or n is None or n.shape != x.shape or x.shape[0] != t.size:
        raise Skip("/hydro/fields lacks t, x, n of matching shapes")
    ps = run.hydro_summary("profile_slope") or {}
    t_fit = num(ps.get("t"))
    cand = [i for i in range(t.size) if t[i] > 0 and np.nanmax(n[i]) > 10]
    if not cand:
        raise Skip("no snapshot with a density peak above 10 n0")
    idx = cand[-3:]
    i_fit = None
    if t_fit is not None:
        i_fit = int(np.argmin(np.abs(t - t_fit)))
        if not same_time(t[i_fit], t_fit):
            i_fit = None
        elif i_fit not in idx:
            idx = sorted(set(idx[-2:] + [i_fit]))
    labels = snapshot_labels(F, t.size)
    cols = time_colors(t[idx])
    fig, ax = plt.subplots(figsize=(7.4, 5.0), layout="constrained")
    dmin = np.inf
    for c, i in zip(cols, idx):
        ip = int(np.nanargmax(n[i]))
        d = wrap(x[i] - x[i, ip])
        for side, ls, mk in ((d > 0, "-", None), (d < 0, "none", "o")):
            o = np.argsort(np.abs(d[side]))
            dd, nn = np.abs(d[side])[o], n[i][side][o]
            if dd.size:
                dmin = min(dmin, dd.min())
            ax.plot(dd, nn, color=c, ls=ls, marker=mk, ms=2.2, mfc="none", mew=0.6,
                    lw=1.6 if i == i_fit else 1.1,
                    label=tlabel(t[i], labels[i]) + (" — fitted" if i == i_fit else "") if side is not None and ls == "-" else None)
    ax.set_xscale("log")
    ax.set_yscale("log")
    xlo = max(dmin * 0.7, 1e-7)
    ax.set_xlim(xlo, 0.5)
    vis = [n[i][np.abs(wrap(x[i] - x[i, int(np.nanargmax(n[i]))])) >= xlo] for i in idx]
    top = max((float(np.nanmax(v)) for v in vis if v.size), default=None)
    if top:
        ax.set_ylim(top=3 * top)
    slope = num(ps.get("slope"))
    x0, x1 = num(ps.get("x_min")), num(ps.get("x_max"))
    ref_i = i_fit if i_fit is not None else idx[-1]
    ipr = int(np.nanargmax(n[ref_i]))
    dref = np.abs(wrap(x[ref_i] - x[ref_i, ipr]))
    xa, xb = (x0, x1) if x0 and x1 and 0 < x0 < x1 else (1e-3, 2e-2)
    xm = math.sqrt(xa * xb)
    sel = (dref >= xa) & (dref <= xb) & (n[ref_i] > 0)

    def anchor(p):
        """n at xm of the power law with exponent p that best matches the data in the window (log space)."""
        if not sel.any():
            return float(np.nanmedian(n[ref_i]))
        return float(np.exp(np.mean(np.log(n[ref_i][sel]) - p * np.log(dref[sel] / xm))))

    if x0 and x1:
        ax.axvspan(x0, x1, color="C1", alpha=0.10, lw=0, label="fit window")
    if slope is not None:
        xx = np.geomspace(xa, xb, 20)
        ax.plot(xx, anchor(slope) * (xx / xm) ** slope, color="k", lw=1.3, ls="--", zorder=5,
                label=rf"fitted slope ${slope:.3f}$ (summary)")
    xx = np.geomspace(xa / 4, min(xb * 6, 0.5), 20)
    ax.plot(xx, 2.5 * anchor(-2 / 3) * (xx / xm) ** (-2 / 3), color="C3", lw=2.0, alpha=0.8,
            label=r"reference $\propto |x - x_{\rm peak}|^{-2/3}$ (shifted)")
    ax.plot([], [], color="0.4", ls="-", label=r"$x > x_{\rm peak}$ (lines)")
    ax.plot([], [], color="0.4", ls="none", marker="o", mfc="none", ms=3, label=r"$x < x_{\rm peak}$ (circles)")
    ax.set_xlabel(r"$|x - x_{\rm peak}|$  [$L_x$]")
    ax.set_ylabel(N_UNIT)
    ax.set_title("Density profile near the singularity")
    ax.legend(loc="lower left", fontsize=8)
    measured = [
        (f"fitted log-log slope of n(|x|) at t = {fmt(t_fit)}", fmt(slope), None),
        ("paper", Markup("−2/3 ≈ −0.667"), None),
        ("difference slope − (−2/3)", fmt(slope + 2 / 3 if slope is not None else None, 2), None),
        ("fit range |x − x<sub>peak</sub>|", Markup(f"[{fmt(x0)}, {fmt(x1)}]"), None),
    ]
    return Drawn(fig, measured)


@figure(file="fig5_haff.png", section="hydro", anchor="haff",
        title="Haff's cooling law",
        caption=("The homogeneous cooling state obeys Haff's law T = (1 + "
                 't/t<sub>0</sub>)<sup>−2</sup>, t<sub>0</sub> = K/(4q): a straight line of slope −2 '
                 'against 1 + t/t<sub>0</sub> on log-log axes. A uniform run must follow it to '
                 'round-off; in a clustering run the mean temperature departs from it once the '
                 'density is no longer uniform.'))
def fig_haff(run):
    """Haff's law: mass-weighted T vs t on log-log axes, and the relative deviation."""
    ts = run.hydro_ts
    t, Tm, haff = arr(ts, "t", 2), arr(ts, "T_mean", 2), arr(ts, "haff_T", 2)
    if t is None or Tm is None or haff is None or not (t.size == Tm.size == haff.size):
        raise Skip("no T_mean / haff_T time series")
    Tmin = arr(ts, "T_min")
    t0, t0_origin = hydro_t0(run)
    if t0 and t0 > 0:
        X = 1 + t / t0
        xlabel = r"$1 + t/t_0$" + rf"   ($t_0 = {tex_num(t0)}$ of the {t0_origin})"
        keep = np.ones_like(t, dtype=bool)
    else:
        X, xlabel, keep = t, T_UNIT, t > 0
    fig, (ax, ax2) = plt.subplots(2, 1, figsize=(7.4, 6.2), sharex=True, layout="constrained",
                                  gridspec_kw={"height_ratios": [2, 1]})
    Xk, Tk, Hk = thin(X[keep], Tm[keep], haff[keep])
    ax.plot(Xk, Hk, color="0.3", lw=3.0, alpha=0.35, label=r"Haff: $(1 + t/t_0)^{-2}$")
    ax.plot(Xk, Tk, color="C3", lw=1.3, label=r"$\langle T\rangle$ (mass-weighted)")
    if Tmin is not None and Tmin.size == t.size:
        Xk2, Tmk = thin(X[keep], Tmin[keep])
        ax.plot(Xk2, Tmk, color="C0", lw=1.0, ls=":", label=r"$T_{\min}$")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_ylabel(T_FIELD)
    ax.set_title("(a) cooling of the granular temperature")
    ax.legend(loc="lower left")
    with np.errstate(divide="ignore", invalid="ignore"):
        dev = Tm / haff - 1
    f, suffix = power_scale(dev[keep])
    Xd, dd = thin(X[keep], dev[keep] * f)
    ax2.plot(Xd, dd, color="C3", lw=1.2)
    ax2.axhline(0, color="0.5", lw=0.6)
    ax2.set_xlabel(xlabel)
    ax2.set_ylabel(r"$\langle T\rangle/T_{\rm Haff} - 1$" + suffix)
    ax2.set_title("(b) relative deviation from Haff's law")
    for a in (ax, ax2):
        mark_validity(a, run.hydro_summary("validity"),
                      (lambda v: 1 + v / t0) if t0 and t0 > 0 else (lambda v: v))
    measured = [
        ("max |⟨T⟩/T<sub>Haff</sub> − 1| (summary)", fmt(run.hydro_summary("haff_max_relative_error")), None),
        ("t<sub>0</sub> written by the code", fmt(t0), None),
    ]
    return Drawn(fig, measured)


@figure(file="fig6_linear_theory.png", section="hydro", anchor="linear",
        title='Linear theory: clustering and shear modes',
        caption=('Linearising around the homogeneous cooling state gives a clustering mode and a '
                 'shear mode. Mode k (k<sub>x</sub> = 2πk) is clustering-unstable if πkK &lt; √q (the '
                 'dilute closure; another closure has its own cut-off).{unstable_modes} Growth is '
                 'algebraic in t, i.e. exponential in the collision clock used on the vertical axis.'))
def fig_linear_theory(run):
    """Growth rates of the clustering and shear modes of the HCS vs mode number, with thresholds."""
    th = run.hydro_theory
    k = arr(th, "mode_k", 2)
    cr, sr = arr(th, "clustering_rate", 2), arr(th, "shear_rate", 2)
    if k is None or ((cr is None or cr.size != k.size) and (sr is None or sr.size != k.size)):
        raise Skip("no growth rates in /hydro/theory")
    nu = th["attrs"].get("unstable_modes")
    nsu = th["attrs"].get("shear_unstable_modes")
    fig, ax = plt.subplots(figsize=(7.8, 4.6), layout="constrained")
    pos_max = 0.0
    curves = []
    if cr is not None and cr.size == k.size:
        curves.append((cr, "C3", "clustering (thermal) mode", "o"))
    if sr is not None and sr.size == k.size:
        curves.append((sr, "C0", "shear mode", "s"))
    few = k.max() <= 40
    for y, c, lab, mk in curves:
        ax.plot(k, y, color=c, lw=1.2 if few else 1.5, label=lab, marker=mk if few else None, ms=4)
        pos_max = max(pos_max, float(np.nanmax(y)))
    ax.axhline(0, color="0.3", lw=0.8)
    if not few:
        ax.set_xscale("log")
    if pos_max > 0:
        ax.set_ylim(-1.6 * pos_max, 1.25 * pos_max)
    kc = num(run.hydro_summary("clustering_cutoff_mode"))   # sqrt(q) / (pi K)
    if kc:
        ax.axvline(kc, color="C3", ls="--", lw=1.0,
                   label=rf"paper: $\pi k K = \sqrt{{q}}$, $k = {kc:.1f}$")
    for count, c, lab in ((nu, "C3", "clustering"), (nsu, "C0", "shear")):
        if count is not None and num(count) is not None and num(count) >= 1:
            if lab == "clustering":
                ax.axvspan(0.1 if not few else k.min() - 0.5, num(count) + 0.5, color=c, alpha=0.06, lw=0)
            ax.plot([num(count)], [0], marker="v", color=c, ms=8, ls="none",
                    label=f"last unstable {lab} mode (code): $k = {int(num(count))}$")
    # a linear-mode run: measured growth of one seeded mode against the theory curve
    lm = run.hydro_summary("linear_mode")
    lm_note = None
    if isinstance(lm, dict):
        km, th_r, me_r = num(lm.get("k")), lm.get("rate_theory"), lm.get("rate_measured")
        th_re = num(th_r[0] if isinstance(th_r, list) and th_r else th_r)
        me_re = num(me_r[0] if isinstance(me_r, list) and me_r else me_r)
        on_curve = None
        if km is not None and cr is not None and th_re is not None:
            j = np.flatnonzero(k == km)
            if j.size and abs(cr[j[0]] - th_re) <= 1e-3 * max(1.0, abs(th_re)):
                on_curve = True
        if on_curve and me_re is not None:
            ax.plot([km], [me_re], marker="*", color="k", ms=13, ls="none", zorder=6,
                    label=rf"measured, seeded mode $k = {int(km)}$")
        elif km is not None:
            lm_note = ("The seeded-mode rate refers to a branch other than the plotted curve; "
                       "see the table.")
    ax.set_xlim((k.min() - 0.5, k.max() + 0.5) if few else (max(0.8, k.min() * 0.8), k.max() * 1.25))
    ax.set_xlabel(r"mode number $k$  ($k_x = 2\pi k$)")
    ax.set_ylabel("largest real growth rate  [collision-clock units]")
    ax.set_title("Linear stability of the homogeneous cooling state")
    ax.legend(loc="best")
    got = run.hydro_summary("unstable_modes")
    if got is None:
        got = nu
    measured = [
        ("unstable clustering modes: the k ≥ 1 with πkK &lt; √q", fmt(got), None),
        ("cutoff k<sub>c</sub> = √q/(πK)", fmt(kc), None),
        ("unstable shear modes (code)", fmt(run.hydro_summary("shear_unstable_modes") or nsu), None),
    ]
    if isinstance(lm, dict):
        def cplx(v):
            if isinstance(v, list) and len(v) == 2 and all(num(c) is not None for c in v):
                return Markup(f"{fmt(num(v[0]))} {'+' if num(v[1]) >= 0 else '−'} {fmt(abs(num(v[1])))} i")
            return fmt(num(v))
        measured += [
            (f"seeded mode k = {fmt(lm.get('k'))}, branch {fmt(lm.get('branch'))}: rate, theory", cplx(lm.get("rate_theory")), None),
            ("… rate, measured from the run", cplx(lm.get("rate_measured")), None),
            ("… relative error", pct(num(lm.get("relative_error"))), None),
        ]
    return Drawn(fig, measured,
                 note=Markup(escape(lm_note)) if lm_note else None,
                 caption_values=dict(unstable_modes=unstable_modes_sentence(run)))


@figure(file="fig7_convergence.png", section="hydro", anchor="convergence",
        title='Self-convergence of the Lagrangian scheme',
        caption=('The paper uses a Lagrangian scheme (Richtmyer–Morton) that resolves steep gradients '
                 'and high peaks until close to the singularity; a second-order scheme shows '
                 'differences between successive refinements falling as N<sup>−2</sup> (dashed line).'))
def fig_convergence(run):
    """Self-convergence: successive-refinement differences vs cells, slope-2 reference."""
    C = run.hydro_convergence
    cells = arr(C, "cells", 2)
    if cells is None:
        raise Skip("no /hydro/convergence study in results.h5")
    orders_s = run.hydro_summary("convergence") or {}
    fig, ax = plt.subplots(figsize=(6.8, 4.8), layout="constrained")
    drawn = []
    style = {"x": ("C0", "o", "position $x$"), "v": ("C3", "s", "velocity $v$"),
             "T": ("C1", "^", "temperature $T$"), "n": ("C2", "D", "density $n$")}
    words = {"x": "node position x", "v": "velocity v", "T": "temperature T", "n": "density n"}
    size = {"x": 10, "v": 5.5, "T": 6, "n": 6}   # x and v errors often coincide: nest the markers
    for key, (c, mk, lab) in style.items():
        e = arr(C, "error_" + key)
        if e is None or e.size != cells.size - 1:
            continue
        order = num(orders_s.get("order_" + key))
        if order is None:
            order = num(C["attrs"].get("order_" + key))
        ok = e > 0
        ax.plot(cells[:-1][ok], e[ok], color=c, marker=mk, ms=size[key], mfc="none", lw=1.2,
                label=f"{lab}: order {order:.2f}" if order is not None else lab)
        drawn.append((key, e, order))
    if not drawn:
        raise Skip("/hydro/convergence has cells but no error_* of length cells−1")
    top = max(float(np.nanmax(e)) for _, e, _ in drawn)
    xr = cells[:-1]
    ax.plot(xr, 1.8 * top * (xr / xr[0]) ** -2.0, color="k", ls="--", lw=1.0, label=r"reference $\propto N^{-2}$")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel(r"cells $N$  (difference between $N$ and the next refinement)")
    ax.set_ylabel("self-convergence difference")
    tconv = num(orders_s.get("t")) or num(C["attrs"].get("t"))
    ax.set_title("Self-convergence" + (f" at $t = {tconv:.4g}$" if tconv is not None else ""))
    ax.legend(loc="lower left")
    ax.set_xticks(xr)
    ax.set_xticklabels([str(int(v)) for v in xr])
    ax.minorticks_off()
    measured = [(f"observed order, {words[k]}", fmt(o, 3), None) for k, _, o in drawn]
    measured.append(("cells", Markup(", ".join(str(int(c)) for c in cells)), None))
    return Drawn(fig, measured)


@figure(file="fig8_validity.png", section="hydro", anchor="validity",
        title="Validity monitors: where the hydro's own assumptions stop holding",
        caption=("The largest local area fraction φ<sub>0</sub>n, the Knudsen numbers of density, "
                 "velocity and temperature (mean free path over gradient length) and the collision time "
                 "over the flow time |∂v/∂x|<sup>−1</sup>, each against its threshold (dashed, same colour; "
                 "docs/physics.md §9). The dotted vertical lines, drawn on every time plot of the hydro, "
                 "mark the first crossing of each."))
def fig_validity(run):
    """The validity monitors' time series (/hydro/timeseries) against their thresholds."""
    ts = run.hydro_ts
    t = arr(ts, "t", 2)
    validity = run.hydro_summary("validity") or {}
    if t is None or not validity:
        raise Skip("no validity monitors in this run (results.h5 and summary.json before they existed)")
    fig, ax = plt.subplots(figsize=(7.4, 4.3), layout="constrained")
    measured = []
    for k, (key, column) in enumerate(MONITOR_COLUMNS.items()):
        m = validity.get(key) or {}
        y = arr(ts, column)
        label = MONITOR_LABELS[key]
        if y is not None and y.size == t.size:
            tk, yk = thin(t, np.where(y > 0, y, np.nan))
            ax.plot(tk, yk, color=f"C{k}", lw=1.2, label=label)
            th = num(m.get("threshold"))
            if th:
                ax.axhline(th, color=f"C{k}", lw=0.7, ls="--")
        if m.get("crossed"):
            value = Markup(f"t = {fmt(num(m.get('time')))} at x = {fmt(num(m.get('place')), 3)} "
                           f"(value {fmt(num(m.get('value')), 3)}, threshold {fmt(num(m.get('threshold')))})")
        elif m.get("applies") is False:
            value = Markup("not applicable (no φ<sub>0</sub>: physics.area_fraction not given)")
        else:
            value = Markup(f"never (largest {fmt(num(m.get('largest')), 3)}, threshold {fmt(num(m.get('threshold')))})")
        measured.append((Markup(f"first crossing of {escape(key)}"), value, None))
    ax.set_yscale("log")
    ax.set_xlabel(T_UNIT)
    ax.set_ylabel("largest local value")
    mark_validity(ax, validity)
    ax.legend(loc="best", fontsize=8)
    return Drawn(fig, measured)
