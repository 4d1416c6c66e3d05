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
                 "contact virial, against the {closure} closure's p(n, T) evaluated at the "
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
    closure = P["attrs"].get("closure", "hydro")
    fig, axes = plt.subplots(1, len(idx) + 1, figsize=(2.6 * (len(idx) + 1) + 1.0, 3.0),
                             layout="constrained")
    for ax, i in zip(axes[:-1], idx):
        ax.errorbar(x, md[i], yerr=err[i] if err is not None else None, fmt="o", ms=2.6, color=CMP_MD,
                    elinewidth=0.8, capsize=0, label="MD ± standard error")
        ax.plot(x, eos[i], color=CMP_HYDRO, lw=1.5, label=f"{closure}: p(n, T) of the MD's n, T")
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
        ax.plot(bt, beos, color=CMP_HYDRO, lw=1.5, ls="--", label=f"{closure}: p(n0, T(t))")
        ax.set_xlabel(MD_T_UNIT)
        ax.set_title("box", fontsize=9)
        ax.legend(fontsize=7, loc="best")
    measured = []
    z, ze, zf = (num(run.md_summary(k)) for k in ("compressibility", "compressibility_error",
                                                   "compressibility_enskog"))
    measured.append(("box P/(nT): particles ± error; Enskog 1 + (1 + r)φχ",
                     f"{fmt(z)} ± {fmt(ze)}; {fmt(zf)}", None))
    last = idx[-1]
    ratio = np.nanmean(md[last]) / np.nanmean(eos[last]) if np.isfinite(eos[last]).any() else None
    measured.append((f"mean over bins at t = {fmt(t[last], 3)}: MD / {closure} p(n, T)", fmt(num(ratio)), None))
    return Drawn(fig, measured, caption_values={"closure": f"\"{closure}\""})
