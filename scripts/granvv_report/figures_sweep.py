"""Figures of a sweep (sweep.json of `granvv sweep`, the cooling analysis of compare/cooling_sweep.hpp):
s1 t0(r), s2 zeta against 1 - r^2 with the fitted power, s3 theory against the measured rate, s4 cost
per point, s5 the transport coefficients measured from the particles against every closure's. Times in sigma sqrt(m/T0), cooling rates zeta = 2/t0 in sqrt(T0/m)/sigma."""
import matplotlib
import matplotlib.pyplot as plt
import matplotlib.ticker
import numpy as np
from markupsafe import Markup, escape

from .data import Skip, get, num, sweep_cooling, sweep_points, sweep_transport
from .formatting import fmt, pct, tex_num, verdict
from .registry import Drawn, figure
from .style import SWEEP_T_UNIT, SWEEP_Z_UNIT, plain_log_ticks, positive, power_scale


def theory_constant(y, r, power_of):
    """C with y = C / f(r) at every point (f = 1 - r^2 or 1 - r), or None when the points disagree
    (the sweep also changed something else, e.g. the area fraction)."""
    c = y * power_of(r)
    c = c[np.isfinite(c)]
    if c.size == 0:
        return None
    m = float(np.median(c))
    return m if np.all(np.abs(c / m - 1) < 1e-3) else None


def sweep_r_axis(run, d):
    """(x values, label, smooth) — r when it varies, else the swept value labelled by its key."""
    r = d["restitution"]
    if np.isfinite(r).sum() >= 2 and np.nanmax(r) > np.nanmin(r):
        return r, "restitution coefficient $r$", True
    return d["value"], run.sweep("key") or "swept value", False


@figure(file="s1_t0.png", section="sweep", anchor="sweep_t0",
        title='Haff time against r',
        caption=('Kinetic theory of smooth inelastic disks: ζ = √π (1 − r<sup>2</sup>) χ(φ) n σ '
                 '(T<sub>0</sub>/m)<sup>1/2</sup>, t<sub>0</sub> = 2/ζ, so t<sub>0</sub> ∝ 1/(1 − '
                 'r<sup>2</sup>); the Enskog factor χ(φ) = (1 − 7φ/16)/(1 − φ)<sup>2</sup> shortens '
                 "it at finite density{chi_at_phi}. The paper's hydro keeps the small-q form 8q/K, "
                 'i.e. 1 − r<sup>2</sup> ≈ 4q = 2(1 − r) and χ = 1: t<sub>0</sub> = K/4q ∝ 1/(1 − r), '
                 'too short by the factor (1 + r)/2 away from r = 1.'))
def fig_sweep_t0(run):
    """s1: measured Haff time against r with kinetic theory (chi, dilute) and the paper's small-q t0."""
    d = sweep_cooling(run)
    x, xlabel, smooth = sweep_r_axis(run, d)
    r = d["restitution"]
    fig, ax = plt.subplots(figsize=(7.6, 5.0), layout="constrained")
    ax.errorbar(x, d["t0"], yerr=d["t0_error"], fmt="o", color="C3", ms=6, capsize=3, lw=1.2, zorder=5,
                label=r"measured $t_0$ ± standard error (fit of $T(t)$)")
    chi = d["haff_t0_theory_dilute"] / d["haff_t0_theory"]
    curves = [("haff_t0_theory", lambda rr: 1 - rr ** 2, "k", "-", r"kinetic theory, Enskog $\chi(\phi)$: $\propto 1/(1-r^2)$"),
              ("haff_t0_theory_dilute", lambda rr: 1 - rr ** 2, "C0", "--", r"kinetic theory, dilute $\chi = 1$"),
              ("haff_t0_paper", lambda rr: 1 - rr, "C2", "-.", r"paper's small-$q$ hydro $K/4q$: $\propto 1/(1-r)$")]
    rr = None
    if smooth:
        lo, hi = float(np.nanmin(r)), float(np.nanmax(r))
        rr = np.linspace(max(0.0, lo - 0.05), min(0.998, hi + 0.5 * (1 - hi)), 300)
    for key, f, c, ls, lab in curves:
        y = d[key]
        C = theory_constant(y, r, f) if smooth else None
        if C is not None:
            ax.plot(rr, C / f(rr), color=c, ls=ls, lw=1.2, label=lab)
        elif np.isfinite(y).any():
            ax.plot(x, y, color=c, ls=ls, lw=1.0, marker="x", ms=6, label=lab.split(":")[0] + " (per point)")
    # the paper's rate with chi(phi) put in: t0_paper / chi
    Cp = theory_constant(d["haff_t0_paper"] / chi, r, lambda q: 1 - q) if smooth else None
    if Cp is not None:
        ax.plot(rr, Cp / (1 - rr), color="C2", ls=":", lw=1.2, label=r"paper's small-$q$ hydro with $\chi(\phi)$")
    ax.set_yscale("log")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(r"Haff time $t_0$  " + SWEEP_T_UNIT)
    ax.set_title(r"Haff time $t_0$ against the restitution coefficient")
    ax.legend(loc="upper left", fontsize=8)
    measured = []
    for p in d["points"]:
        c = p["cool"]
        measured.append((f"r = {fmt(num(c.get('restitution')))}: t<sub>0</sub> measured, Enskog theory, dilute",
                         Markup(f"{fmt(num(c.get('t0')))} ± {fmt(num(c.get('t0_error')), 2)}, "
                                f"{fmt(num(p['md'].get('haff_t0_theory')))}, {fmt(num(p['md'].get('haff_t0_theory_dilute')))}"),
                         None))
    phi = d["area_fraction"]
    return Drawn(fig, measured,
                 note=Markup("The theory curves are each point's own theory value carried along r by its r-dependence "
                             "(they coincide when the sweep changes nothing but r)." if smooth else
                             "The sweep does not vary r: the theory is drawn per point."),
                 caption_values=dict(chi_at_phi=f" (φ = {fmt(float(np.nanmedian(phi)))}: χ = {fmt(float(np.nanmedian(chi)), 4)})"
                                 if np.isfinite(phi).any() and np.isfinite(chi).any() else ""))


@figure(file="s2_zeta.png", section="sweep", anchor="sweep_zeta",
        title='Cooling rate against 1 − r²',
        caption=('Kinetic theory predicts ζ ∝ (1 − r<sup>2</sup>)<sup>1</sup> at fixed density and '
                 "T<sub>0</sub>; the paper's hydro uses 8q/K ∝ 1 − r, which agrees with it only as r "
                 '→ 1.'))
def fig_sweep_zeta(run):
    """s2: cooling rate against 1 - r^2 (log-log) with the fitted power law and kinetic theory."""
    d = sweep_cooling(run)
    r = d["restitution"]
    _x, _lab, smooth = sweep_r_axis(run, d)
    if not smooth:
        raise Skip("the sweep does not vary the restitution coefficient: no power of (1 − r²) to fit")
    u = 1 - r ** 2
    fit = run.cooling("power_of_one_minus_r2")
    sig = num(run.cooling("sigmas"))
    rmin = num(get(fit, "r_min")) if isinstance(fit, dict) else None
    used = r >= rmin - 1e-12 if rmin is not None else np.ones_like(r, dtype=bool)
    fig, ax = plt.subplots(figsize=(7.6, 5.0), layout="constrained")
    ax.errorbar(u[used], d["zeta"][used], yerr=d["zeta_error"][used], fmt="o", color="C3", ms=6, capsize=3,
                zorder=5, label=r"measured $\zeta = 2/t_0$" + (f" (fitted, $r \\geq {rmin:g}$)" if rmin is not None else ""))
    if (~used).any():
        ax.errorbar(u[~used], d["zeta"][~used], yerr=d["zeta_error"][~used], fmt="o", mfc="white", color="C3",
                    ms=6, capsize=3, zorder=5, label=r"measured, outside the fit range")
    uu = np.geomspace(float(np.nanmin(u)) / 1.5, min(1.0, float(np.nanmax(u)) * 1.15), 200)
    rr = np.sqrt(1 - uu)
    Ce = theory_constant(d["zeta_enskog"], r, lambda q: 1 / (1 - q ** 2))
    Cd = theory_constant(d["zeta_dilute"], r, lambda q: 1 / (1 - q ** 2))
    Cp = theory_constant(d["zeta_paper_enskog"], r, lambda q: 1 / (1 - q))
    if Ce is not None:
        ax.plot(uu, Ce * uu, color="k", lw=1.2, label=r"kinetic theory, Enskog $\chi(\phi)$: $\propto (1-r^2)^1$")
    if Cd is not None:
        ax.plot(uu, Cd * uu, color="C0", lw=1.1, ls="--", label=r"kinetic theory, dilute")
    if Cp is not None:
        ax.plot(uu, Cp * (1 - rr), color="C2", lw=1.2, ls=":", label=r"paper's small-$q$ $8q/K$ with $\chi(\phi)$: $\propto 1 - r$")
    p, pe = (num(get(fit, "power")), num(get(fit, "power_error"))) if isinstance(fit, dict) else (None, None)
    A = num(get(fit, "prefactor")) if isinstance(fit, dict) else None
    if p is not None and A is not None:
        uf = u[used]
        inside = np.geomspace(float(np.nanmin(uf)), float(np.nanmax(uf)), 100)
        ax.plot(inside, A * inside ** p, color="C3", lw=2.2, alpha=0.7,
                label=rf"fit $\zeta = C(1-r^2)^p$: $p = {p:.4g} \pm {tex_num(pe, 2)}$")
        ax.plot(uu, A * uu ** p, color="C3", lw=0.8, ls="--", alpha=0.6)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel(r"$1 - r^2$")
    ax.set_ylabel(r"cooling rate $\zeta = 2/t_0$  " + SWEEP_Z_UNIT)
    ax.set_title(r"Cooling rate against $1 - r^2$")
    ax.legend(loc="upper left", fontsize=8)
    # top axis: r itself
    top = ax.secondary_xaxis("top", functions=(lambda v: np.sqrt(np.clip(1 - v, 0, 1)),
                                               lambda v: 1 - np.asarray(v) ** 2))
    top.set_xlabel("$r$", fontsize=9)
    top.xaxis.set_major_locator(matplotlib.ticker.FixedLocator([0.0, 0.3, 0.5, 0.6, 0.7, 0.8, 0.9, 0.95, 0.98, 0.99,
                                                                0.995, 0.998, 0.999]))
    top.xaxis.set_major_formatter(matplotlib.ticker.FuncFormatter(lambda v, _: f"{v:g}"))
    top.xaxis.set_minor_locator(matplotlib.ticker.NullLocator())
    plain_log_ticks(ax.xaxis, *ax.get_xlim())
    plain_log_ticks(ax.yaxis, *ax.get_ylim())
    measured = [
        ("fitted power p of (1 − r<sup>2</sup>)", Markup(f"{fmt(p, 4)} ± {fmt(pe, 2)}") if p is not None else fmt(None),
         verdict(get(fit, "consistent_with_one"), f"p = 1 within {fmt(sig)}σ", f"p ≠ 1 beyond {fmt(sig)}σ")),
        ("… (p − 1)/δp", fmt(num(get(fit, "deviation_from_one_sigmas")), 3), None),
        ("… prefactor C, χ<sup>2</sup> per degree of freedom, points, r ≥",
         Markup(f"{fmt(A, 4)}, {fmt(num(get(fit, 'chi2_per_dof')), 3)}, {fmt(get(fit, 'points'))}, {fmt(rmin)}")
         if isinstance(fit, dict) else fmt(None), None),
        ("kinetic theory", Markup("p = 1"), None),
    ]
    return Drawn(fig, measured,
                 note=Markup("The fit (thick line, dashed outside its range) is the program's own (sweep.json)."
                             if p is not None else "No power fit: fewer than two points in the fit range."))


@figure(file="s3_deviation.png", section="sweep", anchor="sweep_deviation",
        title='Deviation of theory from the measured rate',
        caption=("The paper's small-q cooling 8q/K (with χ(φ) put in) overestimates the rate of "
                 'kinetic theory by 2/(1 + r): 5 % at r = 0.9, 18 % at r = 0.7, 33 % at r = 0.5. '
                 "Where it leaves the grey band (the measurement's own error) the particles can tell "
                 'the difference.'))
def fig_sweep_deviation(run):
    """s3: relative deviation of kinetic theory (chi) and of the paper's small-q rate from the measured rate."""
    d = sweep_cooling(run)
    x, xlabel, smooth = sweep_r_axis(run, d)
    sig = num(run.cooling("sigmas"))
    with np.errstate(divide="ignore", invalid="ignore"):
        rel = d["zeta_error"] / d["zeta"]
    fig, ax = plt.subplots(figsize=(7.6, 4.8), layout="constrained")
    o = np.argsort(x)
    ax.fill_between(x[o], -100 * sig * rel[o], 100 * sig * rel[o], color="0.5", alpha=0.18, lw=0,
                    label=rf"$\pm{sig:g}\sigma$ of the measured rate")
    ax.axhline(0, color="0.4", lw=0.7)
    for key, c, mk, lab in (("deviation_enskog", "k", "o", r"kinetic theory, Enskog $\chi(\phi)$: $\zeta^{\chi}/\zeta - 1$"),
                            ("paper_deviation", "C2", "s", r"paper's small-$q$ $8q/K$ with $\chi$: $\zeta^{\rm paper}/\zeta - 1$")):
        y = d[key]
        if not np.isfinite(y).any():
            continue
        ax.errorbar(x[o], 100 * y[o], yerr=100 * (1 + y[o]) * rel[o], fmt=mk + "-", color=c, ms=5.5, capsize=3,
                    lw=1.1, label=lab)
    dep = num(run.cooling("paper_departs_at_r"))
    if dep is not None and smooth:
        ax.axvline(dep, color="C2", lw=1.0, ls="--")
        ax.text(dep, 0.97, rf"  departs for $r \leq {dep:g}$  ", transform=ax.get_xaxis_transform(), color="C2",
                ha="right" if dep >= float(np.nanmax(x)) - 1e-9 else "left", va="top", fontsize=8)
    ax.set_xlabel(xlabel)
    ax.set_ylabel("relative deviation from the measured rate  [%]")
    ax.set_title("Theory against the measured cooling rate")
    ax.legend(loc="best", fontsize=8)
    measured = []
    for p in d["points"]:
        c = p["cool"]
        measured.append((f"r = {fmt(num(c.get('restitution')))}: Enskog theory, paper's small-q (with χ) — "
                         "relative deviation (in σ)",
                         Markup(f"{pct(num(c.get('deviation_enskog')))} ({fmt(num(c.get('deviation_enskog_sigmas')), 3)}σ), "
                                f"{pct(num(c.get('paper_deviation')))} ({fmt(num(c.get('paper_deviation_sigmas')), 3)}σ)"),
                         None))
    return Drawn(fig, measured,
                 note=Markup("Error bars: the measured rate's standard error carried into the ratio. Both deviations are "
                             "theory/measured − 1, as written by the program (sweep.json)."))


@figure(file="s4_cost.png", section="sweep", anchor="sweep_cost",
        title='Cost per point',
        caption=('Each point runs to the same cooling depth when md.time_unit = "haff" '
                 '(t<sub>end</sub> in units of the kinetic-theory t<sub>0</sub> ∝ 1/(1 − '
                 'r<sup>2</sup>)), so the particle work grows as r → 1 while the rate per atom-step '
                 'stays that of LAMMPS.'))
def fig_sweep_cost(run):
    """s4: cost per point: wall seconds of MD and hydro, atom-steps and their rate."""
    pts = sweep_points(run)
    x = np.array([p["value"] if p["value"] is not None else np.nan for p in pts])
    mdw = np.array([num(p["md"].get("wall_seconds")) or np.nan for p in pts])
    hw = np.array([p["hydro_wall"] if p["hydro_wall"] is not None else np.nan for p in pts])
    ast = np.array([num(p["md"].get("atom_steps")) or np.nan for p in pts])
    asr = np.array([num(p["md"].get("atom_steps_per_second")) or np.nan for p in pts])
    if not (np.isfinite(mdw).any() or np.isfinite(hw).any()):
        raise Skip("no point recorded a wall time")
    key = run.sweep("key") or "swept value"
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(11, 4.2), layout="constrained")
    if np.isfinite(mdw).any():
        ax.plot(x, positive(mdw), color="C3", marker="o", lw=1.2, label="MD (all members)")
    if np.isfinite(hw).any():
        ax.plot(x, positive(hw), color="C0", marker="s", lw=1.2, label="hydro")
    ax.set_yscale("log")
    ax.set_xlabel(key)
    ax.set_ylabel("wall time  [s]")
    ax.set_title("(a) wall time per point")
    ax.legend(loc="best", fontsize=8)
    if np.isfinite(ast).any():
        f1, suf1 = power_scale(ast)
        ax2.plot(x, ast * f1, color="C3", marker="o", lw=1.2, label="atom-steps")
        ax2.set_ylabel("atom-steps (all members)" + suf1)
        ax2.set_ylim(0, float(np.nanmax(ast)) * f1 * 1.15)
    ax2.set_xlabel(key)
    ax2.set_title("(b) particle work per point")
    if np.isfinite(asr).any():
        tw = ax2.twinx()
        f2, suf2 = power_scale(asr)
        tw.plot(x, asr * f2, color="C1", marker="^", lw=1.0, ls="--", label="atom-steps / s")
        tw.set_ylabel("atom-steps / s" + suf2, color="C1")
        tw.set_ylim(0, float(np.nanmax(asr)) * f2 * 1.15)
        tw.grid(False)
        h1, l1 = ax2.get_legend_handles_labels()
        h2, l2 = tw.get_legend_handles_labels()
        ax2.legend(h1 + h2, l1 + l2, loc="lower left", fontsize=8)
    total = np.nansum(mdw) + np.nansum(hw)
    measured = [
        ("sweep wall time (sweep.json), sum over points of MD + hydro",
         Markup(f"{fmt(num(run.sweep('wall_seconds')), 3)} s, {fmt(total, 3)} s"), None),
        ("atom-steps / s: lowest, highest", Markup(f"{fmt(num(np.nanmin(asr)) if np.isfinite(asr).any() else None, 3)}, "
                                                   f"{fmt(num(np.nanmax(asr)) if np.isfinite(asr).any() else None, 3)}"), None),
    ]
    return Drawn(fig, measured)


# Each coefficient's axis label, over its elastic dilute hard-disk value (docs/outputs.md, transport).
TRANSPORT_LABELS = {"shear_viscosity": r"$\eta/\eta_0$",
                    "effective_conductivity": r"$(\kappa - \mu n/T)/\kappa_0$",
                    "conductivity": r"$\kappa/\kappa_0$",
                    "mu": r"$\mu/\mu_0$"}
TRANSPORT_TITLES = {"shear_viscosity": "shear viscosity",
                    "effective_conductivity": "conductivity a pressure-balanced mode sees",
                    "conductivity": "heat conductivity", "mu": "inelastic heat-flux coefficient"}
TRANSPORT_NAMES = {"shear_viscosity": "η/η<sub>0</sub>", "effective_conductivity": "(κ − μn/T)/κ<sub>0</sub>",
                   "conductivity": "κ/κ<sub>0</sub>", "mu": "μ/μ<sub>0</sub>"}


@figure(file="s5_transport.png", section="sweep", anchor="sweep_transport",
        title="Transport coefficients against r: particles and closures",
        caption=("Each coefficient measured from the particles (the decay of the scene's k = 1 mode matched "
                 "to the hydro's, with the standard error from the members' scatter), divided by the elastic "
                 "dilute hard-disk value η<sub>0</sub> = √(mT/π)/(2σ), κ<sub>0</sub> = 4η<sub>0</sub>/m, "
                 "μ<sub>0</sub> = Tκ<sub>0</sub>/n, beside every closure's value at the same point. Inelastic "
                 "kinetic theory (Brey, Dufty, Kim &amp; Santos 1998; Garzó &amp; Dufty 1999) gives a second "
                 "heat-flux coefficient μ that grows from 0 as r falls, so that a pressure-balanced mode "
                 "sees κ − μn/T, below κ."))
def fig_sweep_transport(run):
    """s5: each measured coefficient (error bars) against r, with each closure's curve."""
    d = sweep_transport(run)
    x, xlabel, smooth = sweep_r_axis(run, d)
    at = "r" if smooth else (run.sweep("key") or "value")
    coefficients = d["coefficients"]
    names = sorted({n for c in coefficients.values() for n in c["closures"]})
    colour = {n: f"C{i % 10}" for i, n in enumerate(names)}
    fig, axes = plt.subplots(1, len(coefficients), figsize=(5.4 * len(coefficients), 4.6), layout="constrained",
                             squeeze=False, sharex=True)
    measured = []
    for ax, (key, c) in zip(axes[0], coefficients.items()):
        ax.axhline(1.0, color="0.5", lw=0.8, ls=":", label="elastic dilute value")
        for n in names:
            y = c["closures"].get(n)
            if y is not None and np.isfinite(y).any():
                ax.plot(x, y, color=colour[n], marker="s", ms=4, lw=1.3, label=f"closure {n}")
        ok = np.isfinite(c["measured"])
        ax.errorbar(x[ok], c["measured"][ok], yerr=np.nan_to_num(c["error"][ok]), fmt="o", color="k", ms=6,
                    capsize=3, lw=1.2, zorder=5, label="particles ± standard error")
        ax.set_xlabel(xlabel)
        ax.set_ylabel(TRANSPORT_LABELS.get(key, key))
        ax.set_title(TRANSPORT_TITLES.get(key, key))
        ax.legend(loc="best", fontsize=8)
        for i, p in enumerate(d["points"]):
            m, e = num(c["measured"][i]), num(c["error"][i])
            sides = []
            for n in names:
                v = num(c["closures"][n][i])
                sigmas = (v - m) / e if None not in (v, m, e) and e > 0 else None
                sides.append(f"{escape(n)} {fmt(v, 4)}" + (f" ({fmt(sigmas, 2)}σ)" if sigmas is not None else ""))
            measured.append((f"{at} = {fmt(num(x[i]))}: {TRANSPORT_NAMES.get(key, key)} measured; each closure "
                             "(its distance in σ)",
                             Markup(f"{fmt(m, 4)} ± {fmt(e, 2)}; " + ", ".join(sides)), None))
    return Drawn(fig, measured,
                 note=Markup("The values are the points' own (summary.json transport blocks, copied into "
                             "sweep.json); a closure's distance in σ is (closure − measured)/error."))

