"""Figures of the particle engine (/md, LAMMPS), in particle units (sigma = m = T0 = 1): Haff's law
against kinetic theory, the energy split with the transverse (shear) flow, the coarse-grained fields,
and the contact model (adaptive stiffness). docs/physics.md §4-§8."""
import math

import matplotlib
import matplotlib.pyplot as plt
import matplotlib.ticker
import numpy as np
from markupsafe import Markup, escape

from .data import (HYDRODYNAMIC_FIELDS, Skip, arr, compare_hydro_T, get, haff_temperature, hydro_t0,
                   md_config, md_members, md_series, md_timeseries, md_value, nanmean_rows, num)
from .formatting import fmt, pct, tex_num, verdict
from .registry import Drawn, figure
from .style import (MD_E_UNIT, MD_MAX_MEMBERS, MD_N_UNIT, MD_T_UNIT, MD_V_UNIT, MD_X_UNIT, band,
                    legend_on_top, pick, plain_log_ticks, power_scale, time_colors)


@figure(file="md1_haff.png", section="md", anchor="md_haff",
        title="MD: Haff's cooling law for inelastic disks",
        caption=("Haff's law: a homogeneous granular gas cools as T = T<sub>0</sub>(1 + "
                 't/t<sub>0</sub>)<sup>−2</sup>, a straight line of slope −2 against 1 + '
                 't/t<sub>0</sub> on log-log axes. For 2D smooth disks the cooling rate is ζ = √π (1 '
                 '− r<sup>2</sup>) χ n σ (T/m)<sup>1/2</sup>, so t<sub>0</sub> = 2/ζ(T<sub>0</sub>); '
                 "with χ = 1 and 1 − r<sup>2</sup> ≈ 4q it is the paper's t<sub>0</sub> = K/(4q). At "
                 'finite density the Enskog factor χ(φ) = (1 − 7φ/16)/(1 − φ)<sup>2</sup> (Henderson) '
                 'shortens t<sub>0</sub>{chi_shortening}{restitution}. Acceptance: the fitted '
                 't<sub>0</sub> lies within {tolerance} of the χ(φ) theory (green band). All three Haff '
                 'curves use the fitted T<sub>0</sub>, so panel (b) compares t<sub>0</sub> alone.'))
def fig_md_haff(run):
    """MD Haff: ensemble T(t) against Haff's law with the fitted, Enskog and dilute t0."""
    G, t = md_timeseries(run, at_least_two=True)
    S = t.size
    Tmem = md_members(G, "T", S)
    Tm = md_series(G, "T_mean", S)
    if Tm is None:
        if Tmem is None:
            raise Skip("/md/timeseries has neither T_mean nor T")
        Tm = nanmean_rows(Tmem)
    Ts = md_series(G, "T_stderr", S)
    M = Tmem.shape[0] if Tmem is not None else int(md_value(run, "ensemble") or 1)
    fit, chi, dil = (md_series(G, k, S) for k in ("haff_fit", "haff_theory", "haff_theory_dilute"))
    t0m, t0e = md_value(run, "haff_t0_measured"), md_value(run, "haff_t0_measured_error")
    T0m = md_value(run, "haff_T0_measured")
    t0c, t0d, t0p = (md_value(run, k) for k in ("haff_t0_theory", "haff_t0_theory_dilute", "haff_t0_paper"))
    T0 = T0m if T0m is not None else float(Tm[0])
    if chi is None and t0c:
        chi = haff_temperature(t, t0c, T0)
    if t0c and t0c > 0:
        X = 1 + t / t0c
        keep = np.ones(S, dtype=bool)
        xlabel = rf"$1 + t/t_0^{{\chi}}$,   $t_0^{{\chi}} = {t0c:.4g}\ \sigma\sqrt{{m/T_0}}$ (Enskog $\chi(\phi)$ theory)"
    else:
        X, keep, xlabel = t, t > 0, MD_T_UNIT
    if keep.sum() < 2:
        raise Skip("fewer than two samples at positive time")
    Xk = X[keep]
    fig, (ax, ax2) = plt.subplots(2, 1, figsize=(7.8, 7.0), sharex=True, layout="constrained",
                                  gridspec_kw={"height_ratios": [1.6, 1]})
    win = run.md_summary("haff_fit_window")
    w0, w1 = (num(win[0]), num(win[1])) if isinstance(win, list) and len(win) == 2 else (None, None)
    if w0 is not None and w1 is not None and w1 > w0:
        xw = (1 + w0 / t0c, 1 + w1 / t0c) if t0c and t0c > 0 else (w0, w1)
        for a in (ax, ax2):
            for j, xv in enumerate(xw):
                if Xk.min() <= xv <= Xk.max() and (xv > Xk.min() or j == 1):
                    a.axvline(xv, color="C1", lw=1.0, ls=(0, (4, 3)),
                              label="fit window limits" if a is ax and j == 1 else None)
    # acceptance: t0 within the program's tolerance of the chi(phi) theory, shown as the band of Haff
    # curves it allows
    tol = md_value(run, "haff_t0_tolerance")
    if t0c and t0c > 0 and tol is not None:
        lo_c = haff_temperature(t, t0c * (1 - tol), T0)
        hi_c = haff_temperature(t, t0c * (1 + tol), T0)
        ax.fill_between(Xk, lo_c[keep], hi_c[keep], color="C2", alpha=0.16, lw=0,
                        label=rf"acceptance: $t_0$ within $\pm{100 * tol:.0f}$ % of $t_0^{{\chi}}$")
    if Tmem is not None and Tmem.shape[0] > 1:
        for j, row in enumerate(Tmem[:MD_MAX_MEMBERS]):
            ax.plot(Xk, row[keep], color="C3", lw=0.6, alpha=0.35,
                    label=f"{Tmem.shape[0]} ensemble members" if j == 0 else None)
    has_err = band(ax, Xk, Tm[keep], Ts[keep] if Ts is not None else None, "C3", label="± standard error")
    ax.plot(Xk, Tm[keep], color="C3", lw=1.4, marker="o", ms=2.8,
            label=r"$T$ ensemble mean" if M > 1 else r"$T$ (one run)")
    if chi is not None:
        ax.plot(Xk, chi[keep], color="k", lw=1.1,
                label=rf"Haff, Enskog $\chi(\phi)$: $t_0 = {tex_num(t0c, 4)}$")
    if dil is not None:
        ax.plot(Xk, dil[keep], color="C0", lw=1.1, ls="--", label=rf"Haff, dilute $\chi = 1$: $t_0 = {tex_num(t0d, 4)}$")
    if fit is not None:
        lab = rf"fit: $t_0 = {tex_num(t0m, 4)}" + (rf" \pm {tex_num(t0e, 2)}$" if t0e is not None else "$")
        ax.plot(Xk, fit[keep], color="C4", lw=1.1, ls="-.", label=lab)
    # the hydro of a side-by-side run (same K, q): its mass-weighted <T>, in MD time
    hyd = compare_hydro_T(run)
    hyd_note = None
    t0_hyd = num(run.compare_summary("haff", "t0_hydro"))   # the hydro's t0, in MD time
    t0_hyd_origin = hydro_t0(run)[1]
    if hyd is not None:
        th, Th = hyd
        sel = th <= t[-1] * (1 + 1e-9)
        th, Th = th[sel], Th[sel]
        Xh = 1 + th / t0c if t0c and t0c > 0 else th
        ok = (Xh > 0) & (Th > 0)
        if ok.sum() >= 2:
            ax.plot(Xh[ok], Th[ok], color="C5", lw=1.6, ls=(0, (6, 2)), zorder=5,
                    label=r"hydro $\langle T\rangle$ (same $K$, $q$)"
                    + (rf", {t0_hyd_origin}: $t_0 = {tex_num(t0_hyd, 4)}$" if t0_hyd else ""))
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_ylabel(r"$T$  [$T_0$]")
    ax.set_title(r"(a) granular temperature against Haff's law $T_0(1 + t/t_0)^{-2}$")
    ax.legend(loc="lower left", fontsize=8)
    ylo = float(np.nanmin([np.nanmin(Tm[keep])] + ([np.nanmin(chi[keep])] if chi is not None else [])))
    yhi = float(np.nanmax([np.nanmax(Tm[keep])] + ([np.nanmax(chi[keep])] if chi is not None else [])))
    if Tmem is not None:
        ylo, yhi = min(ylo, float(np.nanmin(Tmem[:, keep]))), max(yhi, float(np.nanmax(Tmem[:, keep])))
    ax.set_ylim(ylo / 1.04, yhi * 1.03)
    plain_log_ticks(ax.yaxis, ylo / 1.04, yhi * 1.03)
    if hyd is not None and ok.any():
        Tlast = float(Th[ok][-1])
        if Tlast < ylo / 1.04 or Tlast > yhi * 1.03 or np.nanmin(Th[ok]) < ylo / 1.04:
            hyd_note = (f"the hydro's ⟨T⟩ leaves the panel: {Tlast:.3g} T0 at t = {th[ok][-1]:.4g} "
                        f"(the t0 of its {t0_hyd_origin} is not the particles' kinetic-theory t0)")
            ax.text(0.98, 0.97, "hydro leaves the panel:\n" + rf"$\langle T\rangle = {tex_num(Tlast)}$ at "
                    rf"$t = {th[ok][-1]:.4g}$", transform=ax.transAxes, ha="right", va="top", fontsize=8,
                    color="C5", bbox=dict(boxstyle="round,pad=0.3", fc="white", ec="C5", alpha=0.9))
    # (b) relative deviation, in per cent, from the two theories (both with the fitted T0)
    for ref, c, lab in ((chi, "k", r"$T/T_{\rm Haff}^{\chi} - 1$  (Enskog)"),
                        (dil, "C0", r"$T/T_{\rm Haff}^{\rm dilute} - 1$")):
        if ref is None:
            continue
        with np.errstate(divide="ignore", invalid="ignore"):
            d = 100 * (Tm / ref - 1)
            e = 100 * Ts / ref if Ts is not None else None
        band(ax2, Xk, d[keep], e[keep] if e is not None else None, c, alpha=0.13)
        ax2.plot(Xk, d[keep], color=c, lw=1.2, marker="o", ms=2.5, ls="-" if c == "k" else "--", label=lab)
    if hyd is not None and chi is not None and t0c and t0c > 0 and ok.sum() >= 2:
        ref_h = haff_temperature(th[ok], t0c, T0)
        dh = 100 * (Th[ok] / ref_h - 1)
        if np.nanmax(np.abs(dh)) <= 30:   # a hydro far off (wrong t0) would flatten the particles' curves
            ax2.plot(Xh[ok], dh, color="C5", lw=1.4, ls=(0, (6, 2)), label=r"hydro $\langle T\rangle/T_{\rm Haff}^{\chi} - 1$")
    if t0c and t0c > 0 and tol is not None:
        dev_band = [100 * (haff_temperature(t, t0c * (1 + s * tol)) / haff_temperature(t, t0c) - 1)
                    for s in (-1, 1)]
        ax2.fill_between(Xk, dev_band[0][keep], dev_band[1][keep], color="C2", alpha=0.16, lw=0, zorder=0,
                         label=rf"$t_0 = t_0^{{\chi}}(1 \pm {tol:g})$")
    ax2.axhline(0, color="0.5", lw=0.6)
    ax2.set_xlabel(xlabel)
    ax2.set_ylabel(r"$T/T_{\rm Haff} - 1$  [%]")
    ax2.set_title("(b) relative deviation from the two theories" + (" (bands: ± standard error)" if has_err else ""))
    ax2.legend(loc="best", fontsize=8)
    if t0c and t0c > 0:
        plain_log_ticks(ax2.xaxis, float(Xk.min()), float(Xk.max()))
        # top axis in t (a twin with fixed ticks: secondary_xaxis on a log parent mislabels here)
        top = ax.twiny()
        top.set_xscale("log")
        top.set_xlim(ax.get_xlim())
        tt = matplotlib.ticker.MaxNLocator(nbins=8, steps=[1, 2, 2.5, 5, 10]).tick_values(0, float(t[keep].max()))
        tt = [v for v in tt if 0 <= v <= t[keep].max() * (1 + 1e-9)]
        top.xaxis.set_major_locator(matplotlib.ticker.FixedLocator([1 + v / t0c for v in tt]))
        top.xaxis.set_major_formatter(matplotlib.ticker.FixedFormatter([f"{v:g}" for v in tt]))
        top.xaxis.set_minor_locator(matplotlib.ticker.NullLocator())
        top.grid(False)
        top.set_xlabel(MD_T_UNIT, fontsize=9)

    dev_c = num(run.md_summary("haff_t0_deviation"))
    dev_d = num(run.md_summary("haff_t0_deviation_dilute"))
    tol_text = pct(tol, 2)
    unit = Markup(" σ(m/T<sub>0</sub>)<sup>1/2</sup>")
    measured = [
        ("t<sub>0</sub> fitted, T = T<sub>0</sub>(1 + t/t<sub>0</sub>)<sup>−2</sup> to the ensemble mean"
         + (f" in t ∈ [{fmt(w0)}, {fmt(w1)}]" if w0 is not None and w1 is not None else ""),
         Markup(f"{fmt(t0m)} ± {fmt(t0e, 2)}{unit}") if t0m is not None else fmt(None), None),
        ("T<sub>0</sub> fitted", fmt(T0m), None),
        ("t<sub>0</sub> kinetic theory with Enskog χ(φ) = (1 − 7φ/16)/(1 − φ)<sup>2</sup>",
         Markup(f"{fmt(t0c)}{unit}") if t0c is not None else fmt(None), None),
        (f"… deviation t<sub>0</sub>/t<sub>0</sub><sup>χ</sup> − 1 (acceptance: within ±{tol_text})", pct(dev_c),
         verdict(run.md_summary("haff_t0_within_tolerance"), f"within {tol_text}", f"outside {tol_text}")),
        ("… in units of the fit error, (t<sub>0</sub> − t<sub>0</sub><sup>χ</sup>)/δt<sub>0</sub>",
         fmt(md_value(run, "haff_t0_deviation_sigmas"), 3), None),
        ("t<sub>0</sub> dilute kinetic theory (χ = 1)", Markup(f"{fmt(t0d)}{unit}") if t0d is not None else fmt(None), None),
        ("… deviation t<sub>0</sub>/t<sub>0</sub><sup>dilute</sup> − 1", pct(dev_d), None),
        ("paper's t<sub>0</sub> = K/(4q) in MD units (1 − r<sup>2</sup> replaced by 4q, χ = 1)",
         Markup(f"{fmt(t0p)}{unit}") if t0p is not None else fmt(None), None),
        ("… deviation t<sub>0</sub>/t<sub>0</sub><sup>paper</sup> − 1",
         pct(md_value(run, "haff_t0_deviation_paper")), None),
        ("ensemble members (seeds)", fmt(M), None),
    ]
    if hyd is not None:
        measured.append((f"hydro of the comparison: t<sub>0</sub> of its {escape(t0_hyd_origin)} in MD time (the K, q the hydro ran with)",
                         Markup(f"{fmt(t0_hyd)}{unit}") if t0_hyd else fmt(None), None))
        measured.append(("… deviation t<sub>0</sub><sup>hydro</sup>/t<sub>0</sub> − 1 from the fitted t<sub>0</sub>",
                         pct(num(run.compare_summary("haff", "deviation_hydro"))), None))
        if hyd_note:
            measured.append(("note", escape(hyd_note), None))
    phi, r = md_value(run, "area_fraction"), md_value(run, "restitution")
    return Drawn(fig, measured,
                 note=Markup("Times in σ(m/T<sub>0</sub>)<sup>1/2</sup> (top axis). T removes the local mean flow "
                             "(v<sub>x</sub> and v<sub>y</sub>) in each coarse-graining bin."
                             + ("" if M > 1 else " One run: no ensemble error band.")),
                 caption_values=dict(chi_shortening=f" by {fmt(100 * (1 - t0c / t0d), 2)} % at φ = {fmt(phi)}" if t0c and t0d and phi else "",
                                 restitution=f", r = {fmt(r)}" if r is not None else "",
                              tolerance=tol_text))


@figure(file="md2_energy.png", section="md", anchor="md_energy",
        title='MD: energy split and transverse flow',
        caption=('Not in the paper, whose 1D model has no transverse velocity (docs/physics.md §6): in a '
                 'periodic box the shear mode (flow along y, wave vector along x) can go unstable '
                 'before the clustering mode, so the macroscopic kinetic energy of a particle run '
                 'holds transverse flow. The granular temperature removes the full local mean '
                 "velocity (v<sub>x</sub> and v<sub>y</sub>) of each bin, and each component's flow "
                 'energy is counted on its own. In the homogeneous cooling state both stay at the '
                 'sampling-noise level (about T/2 per bin and component, dotted) while E<sub>th</sub> '
                 "≈ E follows Haff's law. Pair forces conserve momentum: its drift is round-off."))
def fig_md_energy(run):
    """MD energies: thermal and macroscopic kinetic (x, and y = shear), total; momentum drift."""
    G, t = md_timeseries(run, at_least_two=True)
    S = t.size
    keys = ("energy_total", "energy_thermal", "energy_kinetic_x", "energy_kinetic_y")
    E = {k: md_members(G, k, S) for k in keys}
    if all(v is None for v in E.values()):
        raise Skip("/md/timeseries has no energies")
    P = md_members(G, "momentum_x", S)
    Tm = md_series(G, "T_mean", S)
    Tmem = md_members(G, "T", S)
    if Tm is None and Tmem is not None:
        Tm = nanmean_rows(Tmem)
    N = md_value(run, "particles")
    has_p = P is not None and E["energy_total"] is not None and N
    fig, axes = plt.subplots(1, 2 if has_p else 1, figsize=(11.2 if has_p else 6.6, 4.5),
                             layout="constrained", squeeze=False,
                             gridspec_kw={"width_ratios": [1.45, 1]} if has_p else None)
    ax = axes[0, 0]
    style = {
        "energy_total": dict(color="k", lw=2.4, label=r"total kinetic $\Sigma_p\, m|c_p|^2/2$"),
        "energy_thermal": dict(color="C3", marker="o", label=r"thermal $\Sigma_b\, N_b T_b$"),
        "energy_kinetic_x": dict(color="C0", marker="s", label=r"flow along $x$: $\Sigma_b\, M_b v_{x,b}^2/2$"),
        "energy_kinetic_y": dict(color="C2", marker="^", label=r"transverse (shear) flow: $\Sigma_b\, M_b v_{y,b}^2/2$"),
    }
    me = max(1, S // 18)
    last = {}
    for k in keys:
        a = E[k]
        if a is None:
            continue
        st = dict(style[k])
        mean = nanmean_rows(a)
        last[k] = float(mean[-1])
        if a.shape[0] > 1:
            for row in a[:MD_MAX_MEMBERS]:
                ax.plot(t, row, color=st["color"], lw=0.5, alpha=0.3)
        mk = st.pop("marker", None)
        lab = st.pop("label") + (" (mean)" if a.shape[0] > 1 else "")
        ax.plot(t, mean, **{"lw": 1.2, **st}, marker=mk, ms=4, mfc="none", markevery=me, label=lab)
    bins = num(md_config(run, "bins"))
    kernel = md_config(run, "kernel")
    floor = None
    if Tm is not None and bins and kernel == "bin" and (E["energy_kinetic_x"] is not None or E["energy_kinetic_y"] is not None):
        floor = 0.5 * bins * Tm
        ax.plot(t, floor, color="0.45", lw=1.0, ls=":",
                label=rf"sampling-noise level per component $\approx B\,T/2$ ($B = {int(bins)}$ bins)")
    ax.set_yscale("log")
    ax.set_xlabel(MD_T_UNIT)
    ax.set_ylabel(MD_E_UNIT)
    ax.set_title("(a) energy split")
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.15), fontsize=7.8, ncol=2)
    drift = None
    if has_p:
        ax2 = axes[0, 1]
        E0 = E["energy_total"][:, :1]
        with np.errstate(divide="ignore", invalid="ignore"):
            pm = (P - P[:, :1]) / np.sqrt(2 * N * E0)
        drift = float(np.nanmax(np.abs(pm))) if np.isfinite(pm).any() else None
        f, suffix = power_scale(pm)
        for j, row in enumerate(pm[:MD_MAX_MEMBERS]):
            ax2.plot(t, row * f, lw=0.9, color=plt.get_cmap("tab10")(j % 10),
                     label=f"member {j + 1}" if 1 < pm.shape[0] <= 6 else None)
        ax2.axhline(0, color="0.5", lw=0.6)
        ax2.set_xlabel(MD_T_UNIT)
        ax2.set_ylabel(r"$(P_x - P_x(0))\,/\,\sqrt{2 N m E(0)}$" + suffix)
        ax2.set_title("(b) momentum drift")
        if 1 < pm.shape[0] <= 6:
            ax2.legend(loc="best", fontsize=7.8)
    measured = [
        ("linearly unstable clustering modes in this box (πkK &lt; √q)", fmt(run.md_summary("unstable_modes")), None),
        ("linearly unstable shear modes in this box", fmt(run.md_summary("shear_unstable_modes")), None),
    ]
    Eth = last.get("energy_thermal")
    if Eth:
        for k, lab in (("energy_kinetic_x", "x"), ("energy_kinetic_y", "y")):
            if k in last:
                row = (f"at t = {fmt(t[-1])}: E<sub>kin,{lab}</sub>/E<sub>th</sub> (read off the time series)",
                       fmt(last[k] / Eth, 3), None)
                measured.append(row)
                if floor is not None and floor[-1] > 0:
                    measured.append((f"… E<sub>kin,{lab}</sub> / sampling-noise level B T/2 "
                                     "(≈ 1: no flow above noise; computed here)", fmt(last[k] / floor[-1], 3), None))
    if drift is not None:
        measured.append(("max |P<sub>x</sub> − P<sub>x</sub>(0)| / (2NmE(0))<sup>1/2</sup> over members (computed here)",
                         fmt(drift, 2), None))
    return Drawn(fig, measured,
                 note=Markup("Energies are whole-box sums in T<sub>0</sub> (m = 1). The thermal energy uses the unbiased bin "
                             "temperatures, so E<sub>th</sub> + E<sub>kin,x</sub> + E<sub>kin,y</sub> exceeds the total by the "
                             "noise energy of the bin means."))


@figure(file="md3_fields.png", section="md", anchor="md_fields",
        title='MD: coarse-grained fields',
        caption=('A homogeneous cooling state has n = n<sub>0</sub>, v = 0 and a uniform T that '
                 "follows Haff's law, as long as no mode is linearly unstable (clustering: πkK &lt; "
                 '√q; docs/physics.md §2). In a particle run the fields carry thermal noise: on a '
                 'scale ℓ the velocity noise is about (n<sub>0</sub>L<sub>y</sub>ℓ)<sup>−1/2</sup> '
                 '(docs/physics.md §8), i.e. (T/N<sub>b</sub>)<sup>1/2</sup> per bin (dotted lines), '
                 'reduced by √M with M seeds.'))
def fig_md_fields(run):
    """MD coarse-grained profiles n, v_x, v_y, T at the snapshot times, with ensemble error bands."""
    F = run.md_fields
    t = arr(F, "t", 1)
    x = arr(F, "x", 1)   # [snapshots x bins]: the bins do not move, so the first row serves all
    x = x[0] if x is not None and x.ndim == 2 else None
    if t is None or x is None:
        if F is None:
            md_timeseries(run)   # Skip naming the failure, or the absence of a particle run
            raise Skip("no /md/fields in results.h5")
        raise Skip("no snapshots in /md/fields (md.output_times is empty)")
    ns, nb = t.size, x.size
    Q = {}
    for k in HYDRODYNAMIC_FIELDS:
        a = arr(F, k)
        if a is not None and a.shape == (ns, nb):
            e = arr(F, k + "_stderr")
            Q[k] = (a, e if e is not None and e.shape == (ns, nb) and np.isfinite(e).any() else None)
    if "n" not in Q:
        raise Skip("/md/fields lacks n of shape [snapshots x bins]")
    N, Lx, Ly = md_value(run, "particles"), md_value(run, "box_length"), md_value(run, "box_width")
    n0 = N / (Lx * Ly) if N and Lx and Ly else None
    M = int(md_value(run, "ensemble") or 1)
    t0c, T0m = md_value(run, "haff_t0_theory"), md_value(run, "haff_T0_measured")
    idx = pick(range(ns))
    cols = time_colors(t[idx])
    few = nb <= 60
    panels = [("n", "(a) number density", MD_N_UNIT), ("T", "(b) granular temperature", r"$T$  [$T_0$]"),
              ("v_x", "(c) longitudinal velocity $v_x$", r"$v_x$  " + MD_V_UNIT),
              ("v_y", "(d) transverse (shear) velocity $v_y$", r"$v_y$  " + MD_V_UNIT)]
    panels = [p for p in panels if p[0] in Q]
    ncols = 2 if len(panels) > 1 else 1
    nrows = math.ceil(len(panels) / ncols)
    fig, axes = plt.subplots(nrows, ncols, figsize=(11 if ncols == 2 else 6.8, 3.4 * nrows + 0.5),
                             sharex=True, layout="constrained", squeeze=False)
    any_err = False
    Nb = n0 * Lx * Ly / nb if n0 else None
    for (key, title, ylabel), ax in zip(panels, axes.flat):
        a, e = Q[key]
        entries = 0
        for c, i in zip(cols, idx):
            any_err |= band(ax, x, a[i], e[i] if e is not None else None, c, alpha=0.18)
            ax.plot(x, a[i], color=c, lw=1.3, marker="o" if few else None, ms=3,
                    label=(f"$t = {t[i]:.4g}$" if key == "n" else None))
            entries += key == "n"
            if key == "T" and t0c and t0c > 0 and T0m:
                ax.axhline(haff_temperature(t[i], t0c, T0m), color=c, lw=0.9, ls="--")
        if key in ("n", "T"):
            pos = a[idx][np.isfinite(a[idx]) & (a[idx] > 0)]
            if pos.size and pos.max() / pos.min() > 5:     # clusters: a log axis, as for the hydro
                ax.set_yscale("log")
        if key == "n" and n0:
            ax.axhline(n0, color="0.3", lw=0.9, ls="--", label=rf"$n_0 = N/(L_xL_y) = {n0:.4g}$")
            entries += 1
        if key == "T" and t0c and T0m:
            ax.plot([], [], color="0.3", lw=0.9, ls="--", label=r"Haff, Enskog $\chi(\phi)$, at each $t$")
            entries += 1
        if key in ("v_x", "v_y"):
            ax.axhline(0, color="0.5", lw=0.6)
            if "T" in Q and Nb and md_config(run, "kernel") in (None, "bin"):   # N_b is a bin's count
                Tl = float(np.nanmean(Q["T"][0][idx[-1]]))
                s = math.sqrt(Tl / (Nb * M)) if Tl > 0 else None
                if s:
                    for sgn in (-1, 1):
                        ax.axhline(sgn * s, color="0.35", lw=0.8, ls=":",
                                   label=(rf"$\pm\sqrt{{T/(N_b{' M' if M > 1 else ''})}}$ at the last $t$: "
                                          "bin sampling noise") if sgn > 0 else None)
                    entries += 1
        legend_on_top(ax, entries, min(entries, 4))
        ax.set_title(title)
        ax.set_ylabel(ylabel)
    for ax in axes.flat[len(panels):]:
        ax.set_visible(False)
    for ax in axes[-1, :]:
        ax.set_xlabel(MD_X_UNIT + "  (bin centres, box centred at 0)")
    if Lx:
        axes[0, 0].set_xlim(-Lx / 2, Lx / 2)
    il = idx[-1]
    measured = [
        ("snapshots (times)", Markup(", ".join(str(fmt(v)) for v in t)) if ns <= 12 else fmt(ns), None),
        ("bins, width", Markup(f"{nb}, {fmt(Lx / nb if Lx else None)} σ"), None),
        ("mean particles per bin N<sub>b</sub> = N/B", fmt(Nb, 4), None),
        ("ensemble members", fmt(M), None),
        ("unstable clustering modes in this box (πkK &lt; √q)", fmt(run.md_summary("unstable_modes")), None),
    ]
    if n0:
        n_last = Q["n"][0][il]
        measured.append((f"rms of n/n<sub>0</sub> − 1 over bins at t = {fmt(t[il])} (computed here)",
                         fmt(float(np.sqrt(np.nanmean((n_last / n0 - 1) ** 2))), 3), None))
        if Nb:
            measured.append(("… ideal-gas (Poisson) level 1/(N<sub>b</sub>M)<sup>1/2</sup>", fmt(1 / math.sqrt(Nb * M), 3), None))
    for k in ("v_x", "v_y"):
        if k in Q:
            measured.append((f"max |{k.replace('_', '<sub>')}</sub>| over bins at t = {fmt(t[il])} (computed here)",
                             fmt(float(np.nanmax(np.abs(Q[k][0][il]))), 3), None))
    return Drawn(fig, measured,
                 note=Markup(("Shaded: ± standard error of the ensemble mean over seeds. " if any_err else
                              "No error bands: one run (the standard error needs at least two seeds). ")
                             + "The density noise is not Poisson in general (static structure factor of the gas); "
                               "only an ensemble measures it."))


@figure(file="md4_contact.png", section="md", anchor="md_contact",
        title='MD: contact model and adaptive stiffness',
        caption=('docs/physics.md §5: linear spring–dashpot (LAMMPS gran/hooke, friction off), '
                 'm<sub>eff</sub> = m/2, γ<sub>n</sub> = −2 ln r '
                 '(k<sub>n</sub>/m<sub>eff</sub>)<sup>1/2</sup>/(π<sup>2</sup> + ln<sup>2</sup> '
                 'r)<sup>1/2</sup>, contact time t<sub>c</sub> = π/(k<sub>n</sub>/m<sub>eff</sub> − '
                 'γ<sub>n</sub><sup>2</sup>/4)<sup>1/2</sup>. Hard disks are approached by keeping '
                 'the overlap at the fastest relative speed below {overlap}, so k<sub>n</sub> ∝ '
                 'v<sub>max</sub><sup>2</sup>; as the gas cools k<sub>n</sub> is lowered and Δt = '
                 't<sub>c</sub>/n<sub>c</sub> raised at the same restitution (dotted: the continuous '
                 'scaling k<sub>n</sub> ∝ T, Δt ∝ T<sup>−1/2</sup>). r is checked by a binary '
                 'collision inside LAMMPS.'))
def fig_md_contact(run):
    """Contact model: kn and dt vs t (adaptive stiffness), with the hard-disk scaling."""
    G, t = md_timeseries(run)
    S = t.size
    kn, dt = md_members(G, "kn", S), md_members(G, "dt", S)
    if kn is None and dt is None:
        raise Skip("/md/timeseries has no kn or dt")
    Tm = md_series(G, "T_mean", S)
    Tmem = md_members(G, "T", S)
    changes = run.md_summary("stiffness_changes")
    rows = [(k, a) for k, a in (("kn", kn), ("dt", dt)) if a is not None]
    fig, axes = plt.subplots(len(rows), 1, figsize=(7.6, 2.9 * len(rows) + 0.4), sharex=True,
                             layout="constrained", squeeze=False)
    for (key, a), ax in zip(rows, axes[:, 0]):
        for j, row in enumerate(a[:MD_MAX_MEMBERS]):
            # sample i records the contact of the segment that ended at t[i]; it changes after a sample
            ax.plot(t, row, drawstyle="steps-pre", lw=1.3, color=plt.get_cmap("tab10")(j % 10),
                    label=f"member {j + 1}" if 1 < a.shape[0] <= 6 else
                    ("the run" if a.shape[0] == 1 else "each member" if j == 0 else None))
        Tref = Tmem[0] if Tmem is not None else Tm
        if Tref is not None and np.isfinite(Tref[0]) and Tref[0] > 0:
            p = 1.0 if key == "kn" else -0.5
            ax.plot(t, a[0, 0] * (Tref / Tref[0]) ** p, color="0.35", lw=0.9, ls=":",
                    label=(r"$k_n(0)\,T/T(0)$: hard-disk scaling $k_n \propto v^2$" if key == "kn" else
                           r"$\Delta t(0)\,(T/T(0))^{-1/2}$"))
        ax.set_yscale("log")
        lo, hi = float(np.nanmin(a)), float(np.nanmax(a))
        if Tref is not None and np.isfinite(Tref).all() and Tref[0] > 0:
            r_ = a[0, 0] * (Tref / Tref[0]) ** (1.0 if key == "kn" else -0.5)
            lo, hi = min(lo, float(np.nanmin(r_))), max(hi, float(np.nanmax(r_)))
        ax.set_ylim(lo / 1.25, hi * 1.25)
        if key == "kn":
            ax.set_ylabel(r"$k_n$  [$T_0/\sigma^2$]")
            ch = f"{int(num(changes))} stiffness change" + ("s" if num(changes) != 1 else "") if num(changes) is not None else ""
            ax.set_title(r"(a) normal stiffness $k_n$" + (f" — {ch} (all members)" if ch else ""))
        else:
            ax.set_ylabel(r"$\Delta t$  [$\sigma\sqrt{m/T_0}$]")
            ax.set_title(r"(b) time step $\Delta t = t_c/n_c$")
        ax.legend(loc="best", fontsize=7.8)
    axes[-1, 0].set_xlabel(MD_T_UNIT)
    ci, cf = run.md_summary("contact_initial") or {}, run.md_summary("contact_final") or {}
    nc = num(md_config(run, "steps_per_contact"))

    def trio(c):
        return Markup(f"{fmt(num(get(c, 'kn')))}, {fmt(num(get(c, 'gamma_n')))}, {fmt(num(get(c, 'dt')))}")

    r, rm = md_value(run, "restitution"), md_value(run, "restitution_measured")
    measured = [
        ("restitution r: target / measured (binary collision in LAMMPS)", Markup(f"{fmt(r)} / {fmt(rm, 6)}"), None),
        ("… difference r<sub>measured</sub> − r", fmt(rm - r if rm is not None and r is not None else None, 2), None),
        ("initial k<sub>n</sub>, γ<sub>n</sub>, Δt (member 1)", trio(ci), None),
        ("final k<sub>n</sub>, γ<sub>n</sub>, Δt (member 1)", trio(cf), None),
        ("stiffness changes (all members)", fmt(changes), None),
    ]
    tci, tcf = num(get(ci, "contact_time")), num(get(cf, "contact_time"))
    if tci:
        measured.append(("contact time t<sub>c</sub> = π/(k<sub>n</sub>/m<sub>eff</sub> − γ<sub>n</sub><sup>2</sup>/4)<sup>1/2</sup>: "
                         f"initial, final (member 1; Δt = t<sub>c</sub>/n<sub>c</sub>, md.steps_per_contact = "
                         f"{fmt(int(nc)) if nc else '—'})",
                         Markup(f"{fmt(tci)}, {fmt(tcf)}"), None))
    measured += [
        ("steps (all members), atom-steps", Markup(f"{fmt(run.md_summary('steps'))}, "
                                                   f"{fmt(md_value(run, 'atom_steps'), 3)}"), None),
        ("atom-steps / s", fmt(md_value(run, "atom_steps_per_second"), 3), None),
    ]
    ov = num(md_config(run, "max_overlap"))
    return Drawn(fig, measured,
                 note=Markup("Each member sets its own k<sub>n</sub> from the fastest speed of its own sample"
                             + ("; with md.adaptive_stiffness the stiffness is lowered whenever the fastest relative "
                                "speed has fallen below half its value at the last change."
                                if str(md_config(run, "adaptive_stiffness")).lower() != "false" else
                                "; md.adaptive_stiffness is off, so k<sub>n</sub> and Δt stay fixed.")),
                 caption_values=dict(overlap=f"{fmt(ov)} σ" if ov else "md.max_overlap"))
