"""The flow by inertia seen through noise (summary.json compare.flow_by_inertia, written by
app/compare_output.cpp; docs/physics.md §8): what of the imposed single mode still agrees when the
particles' thermal noise seeds clusters everywhere, and what does not. Every number is the C++
program's; this module only draws them."""
import matplotlib.pyplot as plt
import numpy as np
from markupsafe import Markup

from .data import Skip, cmp_box, num
from .formatting import fmt
from .registry import Drawn, figure
from .style import CMP_HYDRO, CMP_INERTIA, CMP_MD, T_UNIT, md_time_axis, positive

# (key in compare.flow_by_inertia, panel title, y label, log axis)
PANELS = [
    ("v_mode", r"(a) imposed velocity mode: $b_1 = 2\langle v \sin 2\pi x\rangle$",
     r"$b_1(v)$  [$\sqrt{T_0/m}$]", False),
    ("n_mode", r"(b) density mode it drives: $a_1 = 2\langle n \cos 2\pi x\rangle$", r"$a_1(n)$  [$n_0$]", False),
    ("window_mass", r"(c) mass within the central window $|x| < w$", r"mass fraction", False),
    ("n_centre", r"(d) density at $x = 0$ (one bin)", r"$n(0)$  [$n_0$]", True),
]


def series(block, key):
    """(md, md_error, hydro, inertia) of one measure as float arrays (None -> NaN), or None."""
    g = block.get(key) if isinstance(block, dict) else None
    if not isinstance(g, dict):
        return None
    out = [np.array([np.nan if v is None else float(v) for v in (g.get(k) or [])])
           for k in ("md", "md_error", "hydro", "inertia")]
    return out if out[0].size and np.isfinite(out[0]).any() else None


@figure(file="cmp6_inertia.png", section="compare", anchor="cmp_inertia",
        title="Flow by inertia through the noise: the imposed mode, the central mass, the peak",
        caption=("The flow by inertia (paper Eqs. 4–6, dashed: the exact pressureless solution on the bins) "
                 "carries every fluid element at its initial speed, so the imposed mode gathers mass into "
                 "x = 0. Measures that average over many bins follow it even where the particles' noise "
                 "seeds clusters everywhere: (a) the velocity mode, (b) the density mode it drives, (c) the "
                 "mass within |x| &lt; {window}. The density at x = 0 itself (d) is one bin, and there "
                 "noise-born clusters, which saturate near close packing, decide it. Initial signal/noise: "
                 "of the velocity gradient on the shortest unstable wavelength {sn_gradient}, of the mode "
                 "amplitude {sn_mode}, on the bins {sn_bin} (docs/physics.md §8)."))
def fig_cmp_inertia(run):
    block = run.compare_summary("flow_by_inertia")
    if not isinstance(block, dict):
        raise Skip("summary.json has no compare.flow_by_inertia (no comparison)")
    if series(block, "v_mode") is None:
        raise Skip("compare.flow_by_inertia holds no particle values")
    inertia = series(block, "v_mode")[3]
    if not np.isfinite(inertia).any():
        raise Skip("the scene's initial velocity has no flow-by-inertia reference")
    t = np.array([float(v) for v in run.compare_summary("times") or []])
    w = num(block.get("central_window"))
    L = cmp_box(run)
    fig, axes = plt.subplots(2, 2, figsize=(11.2, 8.2), layout="constrained")
    measured = []
    last = {}
    for ax, (key, title, ylabel, log) in zip(axes.flat, PANELS):
        s = series(block, key)
        if s is None or s[0].size != t.size:
            ax.set_visible(False)
            continue
        md, err, hydro, exact = s
        tr = positive if log else (lambda a: a)
        ax.plot(t, tr(hydro), color=CMP_HYDRO, marker="o", ms=4, lw=1.4, label="hydro (binned)")
        ax.errorbar(t, tr(md), yerr=np.where(np.isfinite(err), err, 0.0), fmt="s", ms=4.5, color=CMP_MD,
                    capsize=2.5, lw=1.0,
                    label="MD, mean of seeds ± s.e." if np.isfinite(err).any() else "MD (one seed)")
        ax.plot(t, tr(exact), color=CMP_INERTIA, lw=1.1, ls="--", marker="^", ms=3.5,
                label="flow by inertia (exact, binned)")
        if log:
            ax.set_yscale("log")
        ax.set_title(title, fontsize=9.5)
        ax.set_xlabel(T_UNIT)
        ax.set_ylabel(ylabel)
        ax.legend(loc="best", fontsize=7.8)
        md_time_axis(ax, L)
        k = int(np.flatnonzero(np.isfinite(exact))[-1]) if np.isfinite(exact).any() else t.size - 1
        last[key] = (k, md, err, hydro, exact)
    for key, label in (("v_mode", "b<sub>1</sub>(v)"), ("n_mode", "a<sub>1</sub>(n)"),
                       ("window_mass", f"mass within |x| &lt; {fmt(w, 3)}"), ("n_centre", "n(x = 0)")):
        if key not in last:
            continue
        k, md, err, hydro, exact = last[key]
        measured.append((Markup(f"{label} at t = {fmt(t[k])}: MD ± s.e., hydro, flow by inertia"),
                         Markup(f"{fmt(md[k])} ± {fmt(num(err[k]), 2)}, {fmt(num(hydro[k]))}, "
                                f"{fmt(num(exact[k]))}"), None))
    if "n_centre" in last:
        _, md, err, hydro, _ = last["n_centre"]
        measured.append((Markup(f"n(x = 0) at the last time t = {fmt(t[-1])}: MD ± s.e., hydro"),
                         Markup(f"{fmt(md[-1])} ± {fmt(num(err[-1]), 2)}, {fmt(num(hydro[-1]))}"), None))
    sn = {k: fmt(num(run.md_summary(k)), 3) for k in
          ("signal_to_noise_gradient_initial", "signal_to_noise_mode_initial", "signal_to_noise_initial")}
    measured.append(("initial signal/noise: velocity gradient, mode amplitude, bins",
                     Markup(f"{sn['signal_to_noise_gradient_initial']}, {sn['signal_to_noise_mode_initial']}, "
                            f"{sn['signal_to_noise_initial']}"), None))
    return Drawn(fig, measured,
                 note=Markup("The last flow-by-inertia point is the last compared time before its singularity "
                             "τ = 1/(2π|a|); the hydro's pressure delays its own singularity past it."),
                 caption_values={"window": fmt(w, 3),
                                 "sn_gradient": sn["signal_to_noise_gradient_initial"],
                                 "sn_mode": sn["signal_to_noise_mode_initial"],
                                 "sn_bin": sn["signal_to_noise_initial"]})
