"""The particles' pressure against the equation of state of the comparison's hydro closure
(docs/physics.md §11): bin by bin at the compared times, and the box against time."""
import matplotlib.pyplot as plt
import numpy as np

from .data import Skip, arr, cmp_pressure, num
from .formatting import fmt
from .registry import Drawn, figure
from .style import CMP_HYDRO, CMP_MD, MD_T_UNIT, pick

PRESSURE_MAX_TIMES = 4


@figure(file="cmp_pressure.png", section="compare", anchor="cmp_pressure",
        title="The particles' pressure against the closure's equation of state",
        caption=("The particles' (P_xx + P_yy)/2, kinetic (about each bin's mean flow) plus the "
                 "contact virial, against {closure} p(n, T) evaluated at the "
                 "particles' own n and T (n T F_p with F_p = 1 + (1 + r) φ χ for \"enskog\", n T for "
                 "\"dilute\"): a direct test of the equation of state. Left: bin by bin at the "
                 "snapshot times; right: the whole box at every sample (MD units, T0/σ²)."))
def fig_cmp_pressure(run):
    """Particle pressure ± error against the closure's p(n, T), per bin and for the box."""
    P = cmp_pressure(run)
    t, x = arr(P, "t", 1), arr(P, "x", 1)
    md, err, eos = arr(P, "md", 1), arr(P, "md_error", 1), arr(P, "eos", 1)
    bt, bmd, berr, beos = (arr(P, k, 1) for k in ("box_t", "box_md", "box_md_error", "box_eos"))
    if t is None or x is None or md is None or eos is None or md.shape != (t.size, x.size):
        raise Skip("/compare/pressure has no [times x bins] pressure")
    idx = [i for i in pick(range(t.size), PRESSURE_MAX_TIMES) if np.isfinite(md[i]).any()]
    if not idx:
        raise Skip("no snapshot with a measured contact virial (t = 0 has none)")
    # One equation of state per closure of the comparison (compare.closures), the first one's
    # alone without the list.
    closures = {name: G["data"] for name, G in (P.get("closures") or {}).items() if G}
    order = [c for c in (run.compare_summary("closure_order") or []) if c in closures] or list(closures)
    if not order:
        closure = P["attrs"].get("closure", "hydro")
        order, closures = [closure], {closure: {"eos": P["data"].get("eos"), "box_eos": P["data"].get("box_eos")}}
    eos_of = {c: (arr({"data": closures[c]}, "eos", 1), arr({"data": closures[c]}, "box_eos", 1)) for c in order}
    styles = ["-", "--", ":", "-."]
    fig, axes = plt.subplots(1, len(idx) + 1, figsize=(2.6 * (len(idx) + 1) + 1.0, 3.0),
                             layout="constrained")
    for ax, i in zip(axes[:-1], idx):
        ax.errorbar(x, md[i], yerr=err[i] if err is not None else None, fmt="o", ms=2.6, color=CMP_MD,
                    elinewidth=0.8, capsize=0, label="MD ± standard error")
        for k, c in enumerate(order):
            e = eos_of[c][0]
            if e is not None and e.shape == md.shape:
                ax.plot(x, e[i], color=CMP_HYDRO if k == 0 else f"C{k}", lw=1.5, ls=styles[k % 4],
                        label=f"{c}: p(n, T) of the MD's n, T")
        ax.set_title(f"t = {fmt(t[i], 3)}", fontsize=9)
        ax.set_xlabel(r"$x$  [$\sigma$]")
    axes[0].set_ylabel(r"$P$  [$T_0/\sigma^2$]")
    axes[0].legend(fontsize=7, loc="best")
    ax = axes[-1]
    if bt is not None and bmd is not None and beos is not None:
        ok = np.isfinite(bmd)
        ax.plot(bt[ok], bmd[ok], color=CMP_MD, lw=1.0, label="MD box")
        if berr is not None and np.isfinite(berr[ok]).any():
            ax.fill_between(bt[ok], (bmd - berr)[ok], (bmd + berr)[ok], color=CMP_MD, alpha=0.25, lw=0)
        for k, c in enumerate(order):
            be = eos_of[c][1]
            if be is not None and be.size == bt.size:
                ax.plot(bt, be, color=CMP_HYDRO if k == 0 else f"C{k}", lw=1.5, ls=styles[(k + 1) % 4],
                        label=f"{c}: p(n0, T(t))")
        ax.set_xlabel(MD_T_UNIT)
        ax.set_title("box", fontsize=9)
        ax.legend(fontsize=7, loc="best")
    measured = []
    z, ze, zf = (num(run.md_summary(k)) for k in ("compressibility", "compressibility_error",
                                                   "compressibility_enskog"))
    measured.append(("box P/(nT): particles ± error; Enskog 1 + (1 + r)φχ",
                     f"{fmt(z)} ± {fmt(ze)}; {fmt(zf)}", None))
    last = idx[-1]
    for c in order:
        e = eos_of[c][0]
        if e is None or e.shape != md.shape or not np.isfinite(e[last]).any():
            continue
        ratio = np.nanmean(md[last]) / np.nanmean(e[last])
        measured.append((f"mean over bins at t = {fmt(t[last], 3)}: MD / {c} p(n, T)", fmt(num(ratio)), None))
    peak = arr(P, "peak_bin", 1)
    if peak is not None and peak.size == t.size:
        for i in idx:
            b = int(peak[i])
            eos_at = "; ".join(f"{c} {fmt(num(eos_of[c][0][i, b]))}" for c in order
                               if eos_of[c][0] is not None and eos_of[c][0].shape == md.shape)
            measured.append((f"densest bin (x = {fmt(x[b], 3)}) at t = {fmt(t[i], 3)}: MD ± error; p(n, T)",
                             f"{fmt(num(md[i, b]))} ± {fmt(num(err[i, b]) if err is not None else None)}; {eos_at}",
                             None))
    named = " and ".join(f"the \"{c}\" closure's" for c in order)
    return Drawn(fig, measured, caption_values={"closure": named})
