"""A transport coefficient measured from the particles (docs/physics.md §14): the k = 1 amplitude of
the scene's field, the members' mean with its jackknife error, against the hydro's decay at the
closure's coefficient (F = 1) and at the fitted factor F."""
import matplotlib.pyplot as plt
import numpy as np

from .data import Skip, arr, num
from .formatting import fmt
from .registry import Drawn, figure
from .style import CMP_FIELD_TEX, CMP_HYDRO, CMP_MD, T_UNIT


@figure(file="cmp_transport.png", section="compare", anchor="cmp_transport",
        title="Transport coefficients from the decay of a mode",
        caption=("The k = 1 {phase} 2πx amplitude of {field} ({relative}): the mean over the "
                 "particle members with its jackknife error (delete-one, over members), against the "
                 "hydro's decay with the {closure} closure's coefficient (F = 1) and with it times the "
                 "fitted factor F, each from the start amplitude that fits best. F is fitted to "
                 "every snapshot at once, its error from refitting every leave-one-out ensemble "
                 "(docs/physics.md §14)."))
def fig_cmp_transport(run):
    """Mode amplitude ± jackknife error against the hydro at F = 1 and the fitted F."""
    groups = {name: G for name, G in (run.transport or {}).items() if G and not _is_flux_fit(G)}
    if not groups:
        raise Skip("no transport measurement matched to the hydro (compare.transport = \"none\" "
                   "or a flux fit, drawn on its own)")
    pairs = {name: G for name, G in groups.items() if G.get("signals")}
    if pairs:
        return _pair_figure(run, *next(iter(pairs.items())))
    fig, axes = plt.subplots(1, len(groups), figsize=(4.4 * len(groups), 3.2), layout="constrained",
                             squeeze=False)
    measured, fields, phases, closures = [], [], [], []
    for ax, (name, G) in zip(axes[0], groups.items()):
        t, a, e = arr(G, "t", 3), arr(G, "amplitude", 3), arr(G, "amplitude_error", 3)
        unit, fitted = arr(G, "hydro_unit_factor", 3), arr(G, "hydro_fitted", 3)
        if t is None or a is None or e is None:
            raise Skip(f"/transport/{name} has no amplitudes")
        attrs = G["attrs"]
        F, dF = num(attrs.get("factor")), num(attrs.get("factor_error"))
        closure, field = attrs.get("closure", "hydro"), attrs.get("field", "")
        ax.errorbar(t, a, yerr=e, fmt="o", ms=3, color=CMP_MD, elinewidth=0.8, capsize=0,
                    label="particles ± jackknife error")
        if unit is not None and unit.size == t.size:
            ax.plot(t, unit, color="0.4", lw=1.2, ls="--", label=f"{closure}, F = 1")
        if fitted is not None and fitted.size == t.size:
            ax.plot(t, fitted, color=CMP_HYDRO, lw=1.5, label=f"{closure}, F = {fmt(F, 3)} ± {fmt(dF, 2)}")
        ax.set_title(name.replace("_", " "), fontsize=9)
        ax.set_xlabel(T_UNIT)
        ax.set_ylabel(f"k = 1 amplitude of {CMP_FIELD_TEX.get(field, field)}")
        ax.legend(fontsize=7, loc="best")
        block = run.transport_summary(name) or {}
        measured.append((f"{name}: measured / elastic dilute value",
                         f"{fmt(num(block.get('measured')))} ± {fmt(num(block.get('error')))}", None))
        chi2, dof = num(attrs.get("chi2")), num(attrs.get("degrees_of_freedom"))
        measured.append((f"{name}: factor F on the {closure} closure's; χ² / degrees of freedom",
                         f"{fmt(F)} ± {fmt(dF)}; {fmt(chi2, 3)} / {fmt(dof)}", None))
        for other, value in (block.get("closures") or {}).items():
            measured.append((f"{name}: {other} closure / elastic dilute value", fmt(num(value)), None))
        fields.append(CMP_FIELD_TEX.get(field, field))
        phases.append(attrs.get("phase", ""))
        closures.append(closure)
    relative = "relative to its box mean" if any(f in ("$n$", "$T$") for f in fields) else "as it is"
    values = {"field": ", ".join(fields), "phase": "/".join(sorted(set(phases))),
              "closure": ", ".join(sorted(set(closures))), "relative": relative}
    return Drawn(fig, measured, caption_values=values)


def _pair_figure(run, name, G):
    """Two coefficients fitted jointly: every signal's amplitude ± jackknife error against the
    hydro at the fitted pair of factors."""
    t = arr(G, "t", 3)
    signals = G["signals"]
    fig, axes = plt.subplots(1, len(signals), figsize=(4.4 * len(signals), 3.2), layout="constrained",
                             squeeze=False)
    attrs = G["attrs"]
    closure = attrs.get("closure", "hydro")
    fields = []
    for ax, (signal, S) in zip(axes[0], signals.items()):
        a, e, fitted = arr(S, "amplitude", 3), arr(S, "amplitude_error", 3), arr(S, "hydro_fitted", 3)
        if t is None or a is None or e is None:
            raise Skip(f"/transport/{name}/{signal} has no amplitudes")
        field, _, phase = signal.partition(":")
        ax.errorbar(t, a, yerr=e, fmt="o", ms=3, color=CMP_MD, elinewidth=0.8, capsize=0,
                    label="particles ± jackknife error")
        if fitted is not None and fitted.size == t.size:
            ax.plot(t, fitted, color=CMP_HYDRO, lw=1.5, label=f"{closure}, fitted factors")
        ax.set_title(f"{name.replace('_', ' ')}: {signal}", fontsize=9)
        ax.set_xlabel(T_UNIT)
        ax.set_ylabel(f"k = 1 amplitude of {CMP_FIELD_TEX.get(field, field)} ({phase})")
        ax.legend(fontsize=7, loc="best")
        fields.append(CMP_FIELD_TEX.get(field, field))
    measured = _joint_fit_rows(run, attrs, "correlation of the two errors")
    values = {"field": ", ".join(fields), "phase": "sin/cos", "closure": closure,
              "relative": "relative to its box mean" if any(f in ("$n$", "$T$") for f in fields) else "as it is"}
    return Drawn(fig, measured, caption_values=values)


def _joint_fit_rows(run, attrs, correlation_label):
    """The table rows of coefficients fitted jointly: each one's measured value ± error and every
    closure's value (relative to the elastic dilute value), then the errors' correlation and χ²."""
    rows = []
    for c in [k[:-len("_measured")] for k in attrs if k.endswith("_measured")]:
        block = run.transport_summary(c) or {}
        rows.append((f"{c}: measured / elastic dilute value",
                     f"{fmt(num(block.get('measured')))} ± {fmt(num(block.get('error')))}", None))
        for other, value in (block.get("closures") or {}).items():
            rows.append((f"{c}: {other} closure / elastic dilute value", fmt(num(value)), None))
    rows.append((f"{correlation_label}; χ² / degrees of freedom",
                 f"{fmt(num(attrs.get('correlation')))}; {fmt(num(attrs.get('chi2')), 3)} / "
                 f"{fmt(num(attrs.get('degrees_of_freedom')))}", None))
    return rows


def _is_flux_fit(G):
    """A group of coefficients fitted to the particles' own flux (no hydro in the fit)."""
    return "response" in G["data"]


@figure(file="cmp_heat_flux.png", section="compare", anchor="cmp_heat_flux",
        title="The heat flux at its definition",
        caption=("The k = 1 sine part of the particles' heat flux (relative to the ensemble's "
                 "mean flow; kinetic, and the contacts' share where the engine measures it), "
                 "divided by k κ0 T: the mean over the members with its "
                 "jackknife error, against the fit −κ∂T/∂x − μ∂n/∂x + β∂²v/∂x² to every snapshot "
                 "with its Navier–Stokes part (κ and μ) and μ's part alone. No hydro enters the fit "
                 "(docs/physics.md §14)."))
def fig_cmp_heat_flux(run):
    """Heat-flux response ± jackknife error against the fit and its Navier-Stokes part."""
    fits = {name: G for name, G in (run.transport or {}).items() if G and _is_flux_fit(G)}
    if not fits:
        raise Skip("no coefficient measured from the particles' heat flux")
    name, G = next(iter(fits.items()))
    t, y, e = arr(G, "t", 3), arr(G, "response", 3), arr(G, "response_error", 3)
    fitted, ns, mu_part = arr(G, "fitted", 3), arr(G, "navier_stokes", 3), arr(G, "density_part", 3)
    if t is None or y is None or e is None:
        raise Skip(f"/transport/{name} has no response")
    fig, ax = plt.subplots(figsize=(6.0, 3.4), layout="constrained")
    ax.errorbar(t, y, yerr=e, fmt="o", ms=3, color=CMP_MD, elinewidth=0.8, capsize=0,
                label="particles ± jackknife error")
    if fitted is not None and fitted.size == t.size:
        ax.plot(t, fitted, color=CMP_HYDRO, lw=1.5, label="fit: κ, μ and the Burnett term")
    if ns is not None and ns.size == t.size:
        ax.plot(t, ns, color="0.4", lw=1.2, ls="--", label="its Navier–Stokes part (κ, μ)")
    if mu_part is not None and mu_part.size == t.size:
        ax.plot(t, mu_part, color="0.4", lw=1.0, ls=":", label="μ's part, −μ∂n/∂x")
    ax.axhline(0.0, color="0.8", lw=0.8)
    ax.set_xlabel(T_UNIT)
    ax.set_ylabel("q / (k κ0 T), k = 1 sine part")
    ax.legend(fontsize=7, loc="best")
    return Drawn(fig, _joint_fit_rows(run, G["attrs"], "correlation of the errors of κ and μ"))
