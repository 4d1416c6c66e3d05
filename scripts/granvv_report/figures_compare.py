"""Figures of the side-by-side run (/compare, written by app/compare_output.cpp), in the hydro's
scaled units: fields at the compared times, peak, gradient and energies against time, agreement
metrics, and the density modes against linear theory. docs/physics.md §7-§8."""
import math
import warnings

import matplotlib.pyplot as plt
import numpy as np
from markupsafe import Markup, escape

from .data import (Skip, arr, cmp_box, cmp_data, cmp_rows, cmp_vec, cmp_window, compared_fields,
                   haff_temperature, hydro_t0, md_members, md_value, nanmean_rows, num)
from .formatting import CMP_FIELD_HTML, fmt, tex_num, verdict
from .registry import Drawn, figure
from .validity import mark_validity
from .style import (CMP_FIELD_STYLE, CMP_FIELD_TEX, CMP_HYDRO, CMP_INERTIA, CMP_MAX_TIMES, CMP_MD, T_UNIT,
                    X_UNIT, band, md_time_axis, pick, positive)


def cmp_fields(C, t, x):
    """[(key, title, ylabel, colour, hydro, md, md_error or None)] for the compared fields."""
    out = []
    for key in compared_fields(C):
        g = C["fields"][key]
        title, ylabel, colour = CMP_FIELD_STYLE[key]
        h, m = cmp_rows(g, "hydro", (t.size, x.size)), cmp_rows(g, "md", (t.size, x.size))
        if h is None or m is None:
            continue
        e = cmp_rows(g, "md_error", (t.size, x.size))
        out.append((key, title, ylabel, colour, h, m, e if e is not None and np.isfinite(e).any() else None))
    return out


def mark_window(ax, C, t, label=True):
    """Shade the agreement window [t_first, window] and mark where the first field leaves it."""
    w, left, first = cmp_window(C)
    sig = num(C["attrs"].get("sigmas"))
    drawn = False
    if w is not None:
        if w > t[0]:
            ax.axvspan(t[0], w, color="C2", alpha=0.10, lw=0, zorder=0)
        ax.axvline(w, color="C2", lw=1.1, ls="-", zorder=1,
                   label=(rf"agreement window: all fields within {sig:g}$\sigma$ to $t = {w:.4g}$"
                          if sig else rf"agreement window to $t = {w:.4g}$") if label else None)
        drawn = True
    if left is not None:
        ax.axvline(left, color="C3", lw=1.0, ls=":", zorder=1,
                   label=(rf"first to leave: {CMP_FIELD_TEX.get(first, first)} at $t = {left:.4g}$" if first else
                          rf"a field leaves at $t = {left:.4g}$") if label else None)
        drawn = True
    return drawn


def centred_slope_at_peak(n, v):
    """|dv/dx| at the bin of the largest n (centred difference on equal bins of the unit period),
    as the C++ comparison does for hydro and MD; NaN when the row is not finite."""
    if n is None or v is None or not (np.isfinite(n).all() and np.isfinite(v).all()):
        return np.nan
    b = int(np.argmax(n))
    nb = n.size
    return abs((v[(b + 1) % nb] - v[(b - 1) % nb]) * nb / 2.0)


@figure(file="cmp1_profiles.png", section="compare", anchor="cmp_profiles",
        title='Side by side: fields at the compared times',
        caption=('The hydro (Eqs. 1–2, same K and q) against the particles coarse-grained into the '
                 'same n, v, T. The hydro is binned exactly like the particles, so the two are '
                 'compared bin by bin. {inertia}A bin agrees when |hydro − MD| is below the chosen '
                 'number of standard errors of the MD mean.'))
def fig_cmp_profiles(run):
    """Side by side: n, v_x, (v_y), T of hydro and MD (± error) on the bins at up to 6 times."""
    C, t, x = cmp_data(run)
    rows = cmp_fields(C, t, x)
    if not rows:
        raise Skip("/compare/fields holds no hydro and md rows of [times x bins]")
    L = cmp_box(run)
    I = C.get("inertia")
    inertia = {"n": cmp_rows(I, "n", (t.size, x.size)), "v_x": cmp_rows(I, "v", (t.size, x.size))}
    idx = pick(range(t.size), CMP_MAX_TIMES)
    nr, nc = len(rows), len(idx)
    width = max(2.3 * nc + 1.3, 7.5)
    leg_cols = max(1, min(3, int(width // 3.0)))
    leg_rows = math.ceil(3 / leg_cols)
    fig = plt.figure(figsize=(width, 2.05 * nr + 1.0 + 0.25 * leg_rows), layout="constrained")
    gs = fig.add_gridspec(nr + 1, nc, height_ratios=[0.13 * leg_rows + 0.07] + [1.0] * nr)
    axes = np.empty((nr, nc), dtype=object)
    for r in range(nr):
        for c in range(nc):
            axes[r, c] = fig.add_subplot(gs[r + 1, c], sharex=axes[0, 0] if (r or c) else None)
    few = x.size <= 60
    has_inertia = False
    for r, (key, title, ylabel, colour, h, m, e) in enumerate(rows):
        lo, hi = np.inf, -np.inf
        for c, i in enumerate(idx):
            ax = axes[r, c]
            ax.plot(x, h[i], color=CMP_HYDRO, lw=1.5, zorder=3, label="hydro (binned like the particles)")
            ei = e[i] if e is not None else None
            if few:
                ax.errorbar(x, m[i], yerr=ei, fmt="o", ms=2.6, color=CMP_MD, elinewidth=0.8, capsize=0,
                            zorder=2, label="MD mean ± standard error" if e is not None else "MD mean")
            else:
                band(ax, x, m[i], ei, CMP_MD, alpha=0.22, zorder=1)
                ax.plot(x, m[i], color=CMP_MD, lw=0.9, zorder=2,
                        label="MD mean ± standard error" if e is not None else "MD mean")
            inr = inertia.get(key)
            if inr is not None and np.isfinite(inr[i]).any():
                ax.plot(x, inr[i], color=CMP_INERTIA, lw=1.1, ls="--", zorder=4,
                        label="flow by inertia (paper Eqs. 5–6)")
                has_inertia = True
            vals = [h[i], m[i]] + ([m[i] - ei, m[i] + ei] if ei is not None else []) \
                + ([inr[i]] if inr is not None else [])
            fin = np.concatenate([np.asarray(v)[np.isfinite(v)] for v in vals])
            if fin.size:
                lo, hi = min(lo, float(fin.min())), max(hi, float(fin.max()))
            if key in ("v_x", "v_y"):
                ax.axhline(0, color="0.5", lw=0.6)
            if key == "n":
                ax.axhline(1, color="0.5", lw=0.6)
            if r == 0:
                ax.set_title(f"$t = {t[i]:.4g}$" + (rf"  ($t_{{\rm MD}} = {t[i] * L:.4g}$)" if L else ""),
                             fontsize=8.8, loc="center")
            if c == 0:
                ax.set_ylabel(ylabel)
            else:
                ax.tick_params(labelleft=key == "T")
            if r == nr - 1:
                ax.set_xlabel(X_UNIT)
            else:
                plt.setp(ax.get_xticklabels(), visible=False)
        # a common scale along a row shows the evolution; T cools, so each time gets its own
        if key != "T" and np.isfinite(lo) and hi > lo:
            pad = 0.06 * (hi - lo)
            for c in range(nc):
                axes[r, c].set_ylim(lo - pad, hi + pad)
    axes[0, 0].set_xlim(-0.5, 0.5)
    handles, labels = [], []
    for ax in axes.flat:
        for hd, lb in zip(*ax.get_legend_handles_labels()):
            if lb not in labels:
                handles.append(hd)
                labels.append(lb)
    lax = fig.add_subplot(gs[0, :])
    lax.axis("off")
    lax.legend(handles, labels, loc="center", ncol=min(len(labels), leg_cols), fontsize=8.5, frameon=False)
    nb = x.size
    measured = [
        ("compared times t (scaled), all", Markup(", ".join(str(fmt(v)) for v in t)) if t.size <= 14 else fmt(t.size), None),
        ("… in MD time (σ(m/T<sub>0</sub>)<sup>1/2</sup>), shown", Markup(", ".join(str(fmt(v * L)) for v in t[idx])) if L else fmt(None), None),
        ("bins (the particles' coarse-graining), width", Markup(f"{nb}, {fmt(1.0 / nb)} L<sub>x</sub>"
                                                              + (f" = {fmt(L / nb)} σ" if L else "")), None),
        ("hydro started from", fmt({"md": "the MD's coarse-grained t = 0 fields (ensemble mean)",
                                    "case": "the case's initial fields"}.get(C["attrs"].get("hydro_initial"),
                                                                            C["attrs"].get("hydro_initial"))), None),
    ]
    for key, *_rest in rows:
        src = C["fields"][key]["attrs"].get("error_source")
        measured.append((f"MD error of {CMP_FIELD_HTML.get(key, key)}", fmt(src), None))
    return Drawn(fig, measured,
                 note=Markup("Rows: fields; columns: up to six compared times (first and last always). n and v share one "
                             "scale along a row; T has its own per time (it cools). Error bars: ± one standard error of the "
                             "MD mean (its source is listed above)."),
                 caption_values=dict(inertia="Flow by inertia (dashed), the paper's Eqs. (5)–(6), is the pressureless limit the single mode "
                                 "approaches before its singularity. " if has_inertia else ""))


@figure(file="cmp2_time.png", section="compare", anchor="cmp_time",
        title='Side by side: peak, gradient and energies against time',
        caption=('Fig. 4a: the density and |∂v/∂x| at the peak grow towards the singularity; flow by '
                 "inertia (dashed) predicts both. Fig. 2: the thermal energy follows Haff's law while "
                 "the flow's kinetic energy decays slowly and takes over. Here both engines are "
                 "measured on the particles' bins; the lines in (c) are the full time series of each "
                 "engine (the MD's flow energy with the sampling noise of the bin means removed, so "
                 'it can dip below zero in a noise-only gas).'))
def fig_cmp_time(run):
    """Side by side against time: peak density, |dv/dx| at the peak, E_th and E_kin per particle."""
    C, t, x = cmp_data(run)
    P, E = C.get("peak"), C.get("energy")
    K = t.size
    L = cmp_box(run)
    hn, mn, mne = (cmp_vec(P, k, K) for k in ("hydro_n", "md_n", "md_n_error"))
    hg, mg, inn = (cmp_vec(P, k, K) for k in ("hydro_dvdx", "md_dvdx", "inertia_n"))
    I = C.get("inertia")
    In, Iv = cmp_rows(I, "n", (K, x.size)), cmp_rows(I, "v", (K, x.size))
    ig = None
    if In is not None and Iv is not None:
        ig = np.array([centred_slope_at_peak(In[i], Iv[i]) for i in range(K)])
        if not np.isfinite(ig).any():
            ig = None
    if hn is None and mn is None and hg is None and E is None:
        raise Skip("/compare has neither peak nor energy data")
    fig = plt.figure(figsize=(11.2, 8.6), layout="constrained")
    gs = fig.add_gridspec(2, 2, height_ratios=[1, 1.15])
    ax_a, ax_b, ax_c = fig.add_subplot(gs[0, 0]), fig.add_subplot(gs[0, 1]), fig.add_subplot(gs[1, :])
    # (a) peak density
    if hn is not None:
        ax_a.plot(t, hn, color=CMP_HYDRO, marker="o", ms=4, lw=1.4, label="hydro (binned)")
    if mn is not None:
        ax_a.errorbar(t, mn, yerr=mne, fmt="s", ms=4.5, color=CMP_MD, capsize=2.5, lw=1.0,
                      label="MD ± standard error" if mne is not None else "MD")
    if inn is not None:
        ax_a.plot(t, inn, color=CMP_INERTIA, lw=1.1, ls="--", marker="^", ms=3.5, label="flow by inertia (binned)")
    ax_a.set_ylabel(r"peak density $n_{\max}$  [$n_0$] (on the bins)")
    ax_a.set_title("(a) peak density")
    # (b) |dv/dx| at the peak
    if hg is not None:
        ax_b.plot(t, hg, color=CMP_HYDRO, marker="o", ms=4, lw=1.4, label="hydro (binned)")
    if mg is not None:
        ax_b.plot(t, mg, color=CMP_MD, marker="s", ms=4.5, lw=1.0, ls="-", label="MD (no error estimate)")
    if ig is not None:
        ax_b.plot(t, ig, color=CMP_INERTIA, lw=1.1, ls="--", marker="^", ms=3.5, label="flow by inertia (binned)")
    ax_b.set_ylabel(r"$|\partial v_x/\partial x|$ at the peak  [$\sqrt{T_0/m}/L_x$]")
    ax_b.set_title(r"(b) velocity gradient at the density peak")
    for a in (ax_a, ax_b):
        mark_window(a, C, t, label=False)
        a.set_xlabel(T_UNIT)
        a.legend(loc="best", fontsize=7.8)
        md_time_axis(a, L)
        mark_validity(a, run.hydro_summary("validity"))
    # (c) energies per particle: the full time series of both engines, and the binned values
    ts = run.hydro_ts
    th = arr(ts, "t", 2)
    drawn = 0
    t0h, t0h_origin = hydro_t0(run)
    if th is not None:
        eth, ek, eky = arr(ts, "energy_thermal"), arr(ts, "energy_kinetic"), arr(ts, "energy_kinetic_y")
        if eth is not None and eth.size == th.size:
            ax_c.plot(th, positive(eth), color="C3", lw=1.8, label=r"hydro $E_{\rm th}$")
            drawn += 1
            if t0h:
                ax_c.plot(th, haff_temperature(th, t0h, eth[0]), color="0.3", lw=1.0, ls=":",
                          label=rf"Haff $E_{{\rm th}}(0)(1+t/t_0)^{{-2}}$, $t_0 = {tex_num(t0h)}$ of the hydro's {t0h_origin}")
        if ek is not None and ek.size == th.size:
            tot = ek + (eky if eky is not None and eky.size == th.size else 0.0)
            ax_c.plot(th, positive(tot), color="C0", lw=1.8, label=r"hydro $E_{\rm kin}$ (flow)")
            drawn += 1
    G = run.md_ts
    tm = arr(G, "t", 2)
    N = num(C["attrs"].get("particles")) or md_value(run, "particles")
    if tm is not None and L and N:
        S = tm.size
        ets = md_members(G, "energy_thermal", S)
        kx, ky = md_members(G, "energy_kinetic_x", S), md_members(G, "energy_kinetic_y", S)
        nx, ny = md_members(G, "kinetic_noise_x", S), md_members(G, "kinetic_noise_y", S)
        tt = tm / L
        series = []
        if ets is not None:
            series.append((ets / N, "#8c1010", r"MD $E_{\rm th}$"))
        if kx is not None:
            flow = kx + (ky if ky is not None else 0.0) - (nx if nx is not None else 0.0) - (ny if ny is not None else 0.0)
            series.append((flow / N, "#0b2e59", r"MD $E_{\rm kin}$ (flow, bin noise removed)"))
        for a, col, lab in series:
            M = a.shape[0]
            mean = nanmean_rows(a)
            if M > 1:
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore", RuntimeWarning)
                    se = np.nanstd(a, axis=0, ddof=1) / math.sqrt(M)
                # log axis: shade only where the whole band is positive (a noise-only flow energy is ~0 ± se)
                se = np.where(np.isfinite(se) & (mean - se > 0), se, np.nan)
                band(ax_c, tt, mean, se, col, alpha=0.2, label=None)
            ax_c.plot(tt, positive(mean), color=col, lw=1.3, ls=(0, (4, 2)), zorder=4,
                      label=lab + (f" (mean of {M} ± s.e.)" if M > 1 else ""))
            drawn += 1
    if E is not None:
        for k, col, mk, lab in (("hydro_thermal", "C3", "o", r"$E_{\rm th}$ hydro binned"),
                                ("md_thermal", "C3", "s", r"$E_{\rm th}$ MD binned"),
                                ("hydro_kinetic", "C0", "o", r"$E_{\rm kin}$ hydro binned"),
                                ("md_kinetic", "C0", "s", r"$E_{\rm kin}$ MD binned")):
            v = cmp_vec(E, k, K)
            if v is None:
                continue
            filled = k.startswith("md")
            ax_c.plot(t, positive(v), ls="none", marker=mk, ms=6 if filled else 8, color=col,
                      mfc=col if filled else "none", mew=1.2, label=lab + " (compared times)")
            drawn += 1
    if not drawn:
        ax_c.set_visible(False)
    else:
        ax_c.set_yscale("log")
        mark_window(ax_c, C, t, label=True)
        ax_c.set_xlabel(T_UNIT)
        ax_c.set_ylabel(r"energy per particle  [$T_0$]")
        ax_c.set_title("(c) thermal and flow kinetic energy per particle")
        ax_c.legend(loc="center left", bbox_to_anchor=(1.01, 0.5), fontsize=7.8)
        md_time_axis(ax_c, L)
        tmax = max(float(t[-1]), float(th[-1]) if th is not None else 0.0)
        ax_c.set_xlim(0, tmax * 1.02 if tmax > 0 else 1)
    last = K - 1
    measured = [
        (f"peak density at the last compared time t = {fmt(t[last])}: hydro, MD ± error, flow by inertia",
         Markup(f"{fmt(hn[last] if hn is not None else None)}, {fmt(mn[last] if mn is not None else None)} ± "
                f"{fmt(mne[last] if mne is not None else None, 2)}, {fmt(num(inn[last]) if inn is not None else None)}"), None),
        ("… |dv/dx| at the peak: hydro, MD",
         Markup(f"{fmt(hg[last] if hg is not None else None, 3)}, {fmt(mg[last] if mg is not None else None, 3)}"), None),
    ]
    if E is not None:
        vals = {k: cmp_vec(E, k, K) for k in ("hydro_thermal", "md_thermal", "hydro_kinetic", "md_kinetic")}
        if vals["hydro_thermal"] is not None and vals["md_thermal"] is not None:
            measured.append(("… E<sub>th</sub> per particle: hydro, MD (binned)",
                             Markup(f"{fmt(vals['hydro_thermal'][last])}, {fmt(vals['md_thermal'][last])}"), None))
        if vals["hydro_kinetic"] is not None and vals["md_kinetic"] is not None:
            measured.append(("… E<sub>kin</sub> per particle: hydro, MD (binned, noise removed)",
                             Markup(f"{fmt(vals['hydro_kinetic'][last])}, {fmt(vals['md_kinetic'][last])}"), None))
    measured.append((f"hydro's Haff time t<sub>0</sub>, of its {escape(t0h_origin)} (scaled; MD units)",
                     Markup(f"{fmt(t0h)}; {fmt(num(run.compare_summary('haff', 't0_hydro')))}"), None))
    return Drawn(fig, measured,
                 note=Markup("Green: the agreement window (every field within the chosen σ at every compared time up to "
                             "the green line); red dotted: where the first field leaves. Top axes: MD time "
                             "t<sub>MD</sub> = t L<sub>x</sub> in σ(m/T<sub>0</sub>)<sup>1/2</sup>. In (c) the markers are "
                             "the energies of the compared (ensemble-mean) bins; the dashed MD lines are the mean over "
                             "members of each member's own energies, so with several members the MD line keeps flows of "
                             "random phase (noise-born modes, shear) that the ensemble mean averages out."))


@figure(file="cmp3_metrics.png", section="compare", anchor="cmp_metrics",
        title='Side by side: agreement metrics against time',
        caption=('How far the hydro is from the particles, field by field: (a) the fraction of bins '
                 'where |hydro − MD| is within the chosen number of standard errors of the MD mean '
                 '(for pure Gaussian noise about 99.7 % at 3σ); a field agrees at a time when this '
                 'fraction reaches the required one (dashed). (b) The worst bin in standard errors. '
                 "(c) The size of the difference relative to the field's natural scale: n<sub>0</sub> "
                 'for n, the thermal speed (mean T)<sup>1/2</sup> for v, the mean T for T.'))
def fig_cmp_metrics(run):
    """Per field against time: fraction of bins within sigmas, worst z, normalised L2 and L-infinity."""
    C, t, x = cmp_data(run)
    K = t.size
    frac_req, sig = num(C["attrs"].get("agreement_fraction")), num(C["attrs"].get("sigmas"))
    tracks = []
    for key in compared_fields(C):
        g = C["fields"][key]
        colour = CMP_FIELD_STYLE[key][2]
        d = {k: cmp_vec(g, k, K) for k in ("fraction_within", "worst_z", "l1", "l2", "linf")}
        if all(v is None for v in d.values()):
            continue
        tracks.append((key, colour, d))
    if not tracks:
        raise Skip("/compare/fields holds no metrics")
    L = cmp_box(run)
    fig, axes = plt.subplots(1, 3, figsize=(13.5, 4.4), layout="constrained")
    ax_f, ax_z, ax_n = axes
    lab = CMP_FIELD_TEX
    ymin = 1.0
    for key, col, d in tracks:
        if d["fraction_within"] is not None:
            ax_f.plot(t, d["fraction_within"], color=col, marker="o", ms=4, lw=1.2, label=lab[key])
            ymin = min(ymin, float(np.nanmin(d["fraction_within"])))
        if d["worst_z"] is not None:
            ax_z.plot(t, positive(d["worst_z"]), color=col, marker="o", ms=4, lw=1.2, label=lab[key])
        if d["l2"] is not None:
            ax_n.plot(t, positive(d["l2"]), color=col, marker="o", ms=4, lw=1.3, label=lab[key] + r"  $L_2$")
        if d["linf"] is not None:
            ax_n.plot(t, positive(d["linf"]), color=col, marker="^", ms=3.5, lw=1.0, ls="--",
                      label=lab[key] + r"  $L_\infty$")
    if frac_req is not None:
        ax_f.axhline(frac_req, color="k", lw=1.0, ls="--", label=f"required fraction {frac_req:g}")
        ymin = min(ymin, frac_req)
    ax_f.set_ylim(max(-0.02, ymin - 0.08 * (1.02 - ymin) - 0.02), 1.02)
    ax_f.set_ylabel(rf"fraction of bins with $|d| < {sig:g}\,\sigma_{{\rm MD}}$" if sig else "fraction of bins within")
    ax_f.set_title("(a) bins that agree")
    if sig is not None:
        ax_z.axhline(sig, color="k", lw=1.0, ls="--", label=rf"{sig:g}$\sigma$")
    ax_z.set_yscale("log")
    ax_z.set_ylabel(r"worst $|{\rm hydro} - {\rm MD}|\,/\,\sigma_{\rm MD}$ over the bins")
    ax_z.set_title("(b) worst bin, in standard errors")
    ax_n.set_yscale("log")
    ax_n.set_ylabel(r"$\|{\rm hydro} - {\rm MD}\|\,/\,$scale")
    ax_n.set_title(r"(c) normalised $L_2$ (solid), $L_\infty$ (dashed)")
    for a in axes:
        mark_window(a, C, t, label=a is ax_f)
        a.set_xlabel(T_UNIT)
        md_time_axis(a, L)
        mark_validity(a, run.hydro_summary("validity"))
    ax_f.legend(loc="upper center", bbox_to_anchor=(0.5, -0.2), fontsize=7.8, ncol=2)
    ax_z.legend(loc="best", fontsize=7.8)
    ax_n.legend(loc="best", fontsize=7.2, ncol=2)
    measured = []
    for key, _col, d in tracks:
        fw = d["fraction_within"]
        worst = d["worst_z"]
        i_min = int(np.nanargmin(fw)) if fw is not None and np.isfinite(fw).any() else None
        measured.append((f"{CMP_FIELD_HTML.get(key, key)}: lowest fraction within (at t), largest worst z",
                         Markup(f"{fmt(fw[i_min], 3) if i_min is not None else fmt(None)} "
                                f"(t = {fmt(t[i_min]) if i_min is not None else fmt(None)}), "
                                f"{fmt(num(np.nanmax(worst)) if worst is not None else None, 3)}"),
                         verdict(run.compare_summary("fields", key, "agrees_throughout"), "agrees throughout", "leaves")))
    return Drawn(fig, measured)


@figure(file="cmp4_modes.png", section="compare", anchor="cmp_modes",
        title='Side by side: density Fourier modes against linear theory',
        caption=('Linearised around the homogeneous cooling state, the equations have constant '
                 'coefficients in the collision clock s = t<sub>0</sub> ln(1 + t/t<sub>0</sub>): each '
                 'mode grows or decays as exp(λ s), and mode k is clustering-unstable when πkK &lt; '
                 "√q. The theory (dashed) evolves each member's own t = 0 perturbation (n, v, T of "
                 "that k) and takes the rms over members; the MD's |n<sub>k</sub>| is the rms over "
                 'members too (the phases of noise-born modes differ between seeds).'))
def fig_cmp_modes(run):
    """Density Fourier modes |n_k| / |n_k(0)| against the collision clock: MD, hydro, linear theory."""
    C, t, x = cmp_data(run)
    Mo = C.get("modes")
    if Mo is None:
        raise Skip("no /compare/modes (compare.density_modes = 0)")
    k = arr(Mo, "k", 1)
    s = arr(C, "collision_clock", 1)
    if k is None or s is None or s.size != t.size:
        raise Skip("/compare/modes lacks k, or /compare lacks the collision clock")
    M, K = k.size, t.size
    hyd, md, mde, th = (cmp_rows(Mo, n, (K, M)) for n in ("hydro", "md", "md_error", "theory"))
    rate = cmp_vec(Mo, "theory_rate", M)
    if md is None and hyd is None:
        raise Skip("/compare/modes has no hydro or md amplitudes")

    def norm(a):
        if a is None:
            return None
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(a[:1] > 0, a / a[:1], np.nan)

    def slope(a):
        """Least-squares slope of ln a against s (all compared times with a > 0)."""
        out = np.full(M, np.nan)
        if a is None:
            return out
        for j in range(M):
            ok = np.isfinite(a[:, j]) & (a[:, j] > 0)
            if ok.sum() >= 2 and np.ptp(s[ok]) > 0:
                out[j] = np.polyfit(s[ok], np.log(a[ok, j]), 1)[0]
        return out

    hn, mn, tn = norm(hyd), norm(md), norm(th)
    me = mde / md[:1] if mde is not None and md is not None else None
    ncol = M + 1 if M + 1 <= 3 else min(4, math.ceil(math.sqrt(M + 1)))
    nrow = math.ceil((M + 1) / ncol)
    fig, axes = plt.subplots(nrow, ncol, figsize=(3.3 * ncol + 0.6, 2.9 * nrow + 0.6), layout="constrained",
                             squeeze=False)
    flat = list(axes.flat)
    for j in range(M):
        ax = flat[j]
        if mn is not None:
            ax.errorbar(s, positive(mn[:, j]), yerr=me[:, j] if me is not None and np.isfinite(me[:, j]).any() else None,
                        fmt="s", ms=4, color=CMP_MD, capsize=2, lw=0.9,
                        label="MD (rms over members)" + (" ± s.e." if me is not None and np.isfinite(me).any() else ""))
        if hn is not None:
            ax.plot(s, positive(hn[:, j]), color=CMP_HYDRO, marker="o", ms=3.5, lw=1.3, label="hydro")
        if tn is not None:
            ax.plot(s, positive(tn[:, j]), color="k", lw=1.1, ls="--", label="linear theory")
        if rate is not None and np.isfinite(rate[j]):
            ax.plot(s, np.exp(rate[j] * (s - s[0])), color="0.55", lw=0.8, ls=":",
                    label=r"$e^{\lambda_k s}$ (fastest branch)")
        ax.set_yscale("log")
        ax.set_title(rf"$k = {int(k[j])}$" + (rf",  $\lambda_k = {rate[j]:.3g}$" if rate is not None else ""),
                     fontsize=9)
        ax.set_xlabel(r"collision clock $s = t_0\ln(1+t/t_0)$  [$L_x/\sqrt{T_0/m}$]", fontsize=8.2)
        ax.set_ylabel(r"$|n_k(t)|\,/\,|n_k(0)|$")
        if j == 0:
            ax.legend(loc="best", fontsize=7.2)
    ax = flat[M]
    kk = k.astype(int)
    if rate is not None:
        ax.plot(kk, rate, color="k", marker="o", ms=5, lw=1.2, label=r"theory $\lambda_k$ (fastest branch)")
    gm, gh = slope(md), slope(hyd)
    # keep the theory readable: a mode born from almost nothing at t = 0 has a huge fitted exponent;
    # such points sit on the panel's edge as arrows with their value
    ref = rate[np.isfinite(rate)] if rate is not None else np.array([])
    allv = np.concatenate([ref, gm[np.isfinite(gm)], gh[np.isfinite(gh)]])
    if ref.size and allv.size:
        span = max(float(ref.max()) - min(0.0, float(ref.min())), 1e-12)
        lo_lim = min(0.0, float(ref.min())) - 0.6 * span
        hi_lim = float(ref.max()) + 0.6 * span
        lo = max(lo_lim, float(allv.min()) - 0.08 * span)
        hi = min(hi_lim, float(allv.max()) + 0.08 * span)
    else:
        lo = hi = None
    for g, col, mk, mfc, lab in ((gm, CMP_MD, "s", CMP_MD, "MD: fitted exponent"),
                                 (gh, CMP_HYDRO, "D", "none", "hydro: fitted exponent")):
        if not np.isfinite(g).any():
            continue
        inside = np.isfinite(g) if lo is None else np.isfinite(g) & (g >= lo) & (g <= hi)
        ax.plot(kk[inside], g[inside], color=col, marker=mk, ms=5, mfc=mfc, ls="none", label=lab)
        if lo is not None:
            for j in np.flatnonzero(np.isfinite(g) & ~inside):
                up = g[j] > hi
                ax.plot([kk[j]], [hi if up else lo], color=col, marker="^" if up else "v", ms=7, mfc=mfc,
                        ls="none", clip_on=False)
                ax.annotate(f"{g[j]:.3g}", (kk[j], hi if up else lo), textcoords="offset points",
                            xytext=(6 if col == CMP_MD else -6, -10 if up else 4),
                            ha="left" if col == CMP_MD else "right", fontsize=7, color=col)
    if lo is not None and hi > lo:
        ax.set_ylim(lo, hi)
    ax.axhline(0, color="0.5", lw=0.7)
    ax.set_xticks(kk)
    ax.set_xlabel("mode number $k$")
    ax.set_ylabel(r"growth exponent in $s$")
    ax.set_title("growth exponents")
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.2), fontsize=7.2, ncol=2)
    for a in flat[M + 1:]:
        a.set_visible(False)
    measured = []
    for j in range(M):
        measured.append((f"k = {int(k[j])}: exponent in s — theory, MD fit, hydro fit (fits computed here)",
                         Markup(f"{fmt(num(rate[j]) if rate is not None else None, 3)}, {fmt(num(gm[j]), 3)}, "
                                f"{fmt(num(gh[j]), 3)}"), None))
    return Drawn(fig, measured,
                 note=Markup("Each curve is divided by its own t = 0 value. The fitted exponents are least-squares slopes of "
                             "ln|n<sub>k</sub>| against s over all compared times, nonlinear growth included — a guide, not "
                             "a measurement of λ<sub>k</sub>."))


@figure(file="cmp5_closures.png", section="compare", anchor="cmp_closures",
        title="One particle ensemble, several hydro closures (compare.closures)",
        caption=("Each hydro closure (docs/physics.md §9) run against the same particles and compared on "
                 "its own: the density on the bins at the last time each closure was compared, and the "
                 "peak density over time, against the particles' ensemble mean (± standard error). The "
                 "rows below give each closure's agreement window, first field to part, verdict and the "
                 "validity monitors that had fired by then."))
def fig_cmp_closures(run):
    """Density profiles and peak density of each closure's hydro over the same particles."""
    C = run.compare
    closures = (C or {}).get("closures") or {}
    order = run.compare_summary("closure_order") or list(closures)
    order = [name for name in order if closures.get(name)]
    if len(order) < 2:
        raise Skip("a single hydro closure (compare.closures lists one)")
    L = cmp_box(run)
    fig, (ax_a, ax_b) = plt.subplots(1, 2, figsize=(11, 4.2), layout="constrained")
    styles = ["-", "--", ":", "-."]
    measured = []
    md_drawn = False
    for k, name in enumerate(order):
        G = closures[name]
        t, x = arr(G, "t", 1), arr(G, "x", 2)
        g = G["fields"].get("n")
        if t is None or x is None or g is None:
            continue
        h = cmp_rows(g, "hydro", (t.size, x.size))
        m, e = cmp_rows(g, "md", (t.size, x.size)), cmp_rows(g, "md_error", (t.size, x.size))
        if h is None or m is None:
            continue
        i = t.size - 1
        if not md_drawn:
            ax_a.errorbar(x, m[i], yerr=e[i] if e is not None else None, fmt="o", ms=2.6, color=CMP_MD,
                          elinewidth=0.8, capsize=0, label=rf"MD mean, $t = {t[i]:.4g}$")
            pk = G.get("peak") or {}
            mn, mne = arr(pk, "md_n"), arr(pk, "md_n_error")
            if mn is not None and mn.size == t.size:
                ax_b.errorbar(t, mn, yerr=mne if mne is not None and mne.size == t.size else None, fmt="s",
                              ms=4, color=CMP_MD, capsize=2.5, lw=1.0, label="MD (± standard error)")
            md_drawn = True
        ax_a.plot(x, h[i], color=f"C{k}", lw=1.5, ls=styles[k % 4], label=rf"hydro {name}, $t = {t[i]:.4g}$")
        hn = arr(G.get("peak") or {}, "hydro_n")
        if hn is not None and hn.size == t.size:
            ax_b.plot(t, hn, color=f"C{k}", lw=1.4, ls=styles[k % 4], marker="o", ms=3.5, label=f"hydro {name}")
        c = run.compare_summary("closures", name) or {}
        w, left, first = num(c.get("agreement_window")), num(c.get("left_at")), c.get("first_field_to_leave")
        fired = c.get("monitors_fired_at_parting")
        md_t = (lambda v: f" (t<sub>MD</sub> = {fmt(v * L)})" if L and v is not None else "")
        value = Markup(
            f"window to t = {fmt(w)}{md_t(w)}; "
            + (f"first to part: {escape(first)} at t = {fmt(left)}{md_t(left)}; " if first else "every field agrees; ")
            + f"verdict: {escape(c.get('disagreement') or '—')}; "
            + ("monitors fired by then: " + (escape(", ".join(fired)) if fired else "none") if fired is not None else ""))
        measured.append((Markup(f"closure <b>{escape(name)}</b>"), value, None))
        if w is not None:
            ax_b.axvline(w, color=f"C{k}", lw=0.8, ls=styles[k % 4], alpha=0.6)
    if not md_drawn:
        raise Skip("/compare/closures holds no density rows")
    ax_a.set_xlabel(r"$x$  [$L_x$]")
    ax_a.set_ylabel(r"$n$  [$n_0$] (on the bins)")
    ax_a.set_title("(a) density at the last compared time")
    ax_a.legend(loc="best", fontsize=7.8)
    ax_b.set_xlabel(T_UNIT)
    ax_b.set_ylabel(r"peak density $n_{\max}$  [$n_0$] (on the bins)")
    ax_b.set_title("(b) peak density (lines: agreement windows)")
    ax_b.legend(loc="best", fontsize=7.8)
    md_time_axis(ax_b, L)
    return Drawn(fig, measured)
