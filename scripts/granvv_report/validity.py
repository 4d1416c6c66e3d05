"""The hydro's validity monitors (summary.json hydro.validity, docs/physics.md §9): the one helper
that marks their first crossings on a time axis, shared by every hydro time plot."""
from .data import num

# Monitor key in summary.json -> short label on the plots.
MONITOR_LABELS = {
    "area_fraction": r"$\phi$",
    "knudsen_density": r"Kn$_n$",
    "knudsen_velocity": r"Kn$_v$",
    "knudsen_temperature": r"Kn$_T$",
    "collision_flow": r"$\tau_c|\partial_x v|$",
}
# Monitor key -> /hydro/timeseries column (hydro/validity_monitors.cpp names them).
MONITOR_COLUMNS = {
    "area_fraction": "phi_max",
    "knudsen_density": "knudsen_n_max",
    "knudsen_velocity": "knudsen_v_max",
    "knudsen_temperature": "knudsen_T_max",
    "collision_flow": "collision_flow_max",
}


def validity_crossings(validity):
    """[(key, label, time, value, threshold)] of the monitors that crossed, earliest first."""
    out = []
    for key, m in (validity or {}).items():
        if not isinstance(m, dict) or not m.get("crossed"):
            continue
        t = num(m.get("time"))
        if t is not None:
            out.append((key, MONITOR_LABELS.get(key, key), t, num(m.get("value")), num(m.get("threshold"))))
    return sorted(out, key=lambda c: c[2])


def mark_validity(ax, validity, x_of=lambda t: t):
    """A vertical line and a label at each monitor's first crossing, at x_of(t) of its scaled hydro
    time t, where that lies on the axis. Returns the number of lines drawn."""
    drawn = 0
    lo, hi = ax.get_xlim()
    for k, (key, label, t, _, _) in enumerate(validity_crossings(validity)):
        x = x_of(t)
        if not (min(lo, hi) <= x <= max(lo, hi)) or (ax.get_xscale() == "log" and x <= 0):
            continue
        ax.axvline(x, color="C5", lw=0.8, ls=(0, (2, 2)), alpha=0.8, zorder=1)
        ax.text(x, 0.98 - 0.07 * (k % 5), " " + label, transform=ax.get_xaxis_transform(), color="C5",
                fontsize=7.5, va="top", ha="left")
        drawn += 1
    return drawn
