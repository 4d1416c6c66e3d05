"""The disks themselves: the particle frame at each compared time as a strip of the box, coloured by
the local density, drawn above the hydro's and the particles' density profiles on the same x axis."""
import matplotlib.pyplot as plt
import numpy as np

from .data import Skip
from .formatting import fmt
from .frames import compared_density, local_density, read_frames
from .registry import Drawn, figure
from .style import CMP_HYDRO, CMP_MD, pick

STRIP_MAX_TIMES = 4
STRIP_MAX_DISKS = 200_000     # more are drawn as a random subset of this many (the colours stay exact)
STRIP_BINS = 32               # bins of the colour without a comparison (with one: the comparison's bins)
FIG_WIDTH_IN = 7.6


def disk_marker_size(Lx, axes_width_in):
    """Scatter size (points²) of a disk of diameter σ on an axis spanning Lx σ, at least a dot."""
    d_points = 72.0 * axes_width_in / Lx
    return max(d_points ** 2, 1.5)


def strip_times(frames, profiles):
    """[(frame index, scaled t or None, row of the profiles or None)] to draw: the compared times that
    have a frame, else (no comparison) frames spread over the run."""
    if profiles is not None:
        rows = []
        for i in range(profiles.t.size):
            k = frames.nearest(profiles.t[i] * profiles.box_length)
            if k is not None:
                rows.append((k, profiles.t[i], i))
        if not rows:
            raise Skip("no particle frame at the compared times (frames at t_MD = "
                       f"{', '.join(str(fmt(v, 3)) for v in frames.times[:6])}{' …' if frames.times.size > 6 else ''}; "
                       "set md.snapshot_interval to a divisor of the output times' spacing)")
        return pick(rows, STRIP_MAX_TIMES)
    return [(k, None, None) for k in pick(list(range(frames.times.size)), STRIP_MAX_TIMES)]


@figure(file="particles_strips.png", section="md", anchor="particles_strips",
        title="The particles: the box at the compared times, above the density profiles",
        caption=("Each strip is the whole box of one member ({member}) at one time, {Lx} σ long and {Ly} σ wide "
                 "(stretched across: x is scaled by L<sub>x</sub>), every disk a dot of its diameter where it "
                 "resolves and coloured by the density n/n<sub>0</sub> of its bin. Below each strip, on the "
                 "same x axis: the particles' coarse-grained density (ensemble mean ± standard error) and the "
                 "hydro's, averaged over the same bins (the comparison's profiles). Clusters in the strip are "
                 "where the particles' density peaks."))
def fig_particle_strips(run):
    """Strips of the disks at the compared times, aligned above n(x) of the hydro and the particles."""
    frames = read_frames(run.outdir)
    profiles = compared_density(run)
    rows = strip_times(frames, profiles)
    Lx, Ly = frames.box
    bins = profiles.x.size if profiles is not None else STRIP_BINS
    fig = plt.figure(figsize=(FIG_WIDTH_IN, 2.3 * len(rows) + 0.6), layout="constrained")
    grid = fig.add_gridspec(2 * len(rows), 1, height_ratios=[1.0, 1.3] * len(rows))
    measured, first = [], None
    rng = np.random.default_rng(0)
    size = disk_marker_size(Lx, FIG_WIDTH_IN * 0.85)
    for j, (k, t_scaled, i) in enumerate(rows):
        pos = frames.positions(k)
        ok = np.isfinite(pos).all(axis=1)
        pos = pos[ok]
        colour, centres, n_bins = local_density(pos[:, 0], Lx, bins)
        shown = np.arange(pos.shape[0])
        if shown.size > STRIP_MAX_DISKS:
            shown = np.sort(rng.choice(shown, STRIP_MAX_DISKS, replace=False))
        ax_s = fig.add_subplot(grid[2 * j])
        ax_p = fig.add_subplot(grid[2 * j + 1], sharex=ax_s)
        first = first or ax_s
        sc = ax_s.scatter(pos[shown, 0] / Lx, pos[shown, 1], c=colour[shown], s=size, cmap="viridis",
                          vmin=0.0, vmax=max(2.0, float(np.nanmax(colour))), linewidths=0, rasterized=True)
        ax_s.set_ylim(-Ly / 2, Ly / 2)
        ax_s.set_yticks([])
        ax_s.set_ylabel(f"{fmt(Ly, 3)} σ", fontsize=8)
        t_md = frames.times[k]
        ax_s.set_title(r"$t_\mathrm{MD}$" + f" = {fmt(t_md, 4)}" + (f" (scaled t = {fmt(t_scaled, 3)})" if t_scaled is not None else ""),
                       fontsize=9)
        plt.setp(ax_s.get_xticklabels(), visible=False)
        fig.colorbar(sc, ax=ax_s, label=r"$n/n_0$", aspect=8, pad=0.01)
        if profiles is not None:
            md, err = profiles.md[i], profiles.md_error[i] if profiles.md_error is not None else None
            ax_p.plot(profiles.x, profiles.hydro[i], color=CMP_HYDRO, lw=1.5, label="hydro (binned)")
            if err is not None:
                ax_p.errorbar(profiles.x, md, yerr=err, fmt="o", ms=3, color=CMP_MD, capsize=2,
                              label="particles (ensemble mean)")
            else:
                ax_p.plot(profiles.x, md, "o", ms=3, color=CMP_MD, label="particles (ensemble mean)")
        ax_p.step(centres, n_bins, where="mid", color="0.45", lw=0.9, label="this member's frame")
        ax_p.set_ylabel(r"$n$  [$n_0$]")
        ax_p.set_xlim(-0.5, 0.5)
        ax_p.legend(loc="upper right", fontsize=7)
        label = f"t<sub>MD</sub> = {fmt(t_md, 4)}: disks drawn, densest bin n/n<sub>0</sub> of the frame"
        value = f"{fmt(int(shown.size))} of {fmt(int(pos.shape[0]))}, {fmt(float(np.max(n_bins)), 3)}"
        if profiles is not None:
            value += f" (ensemble mean's densest bin {fmt(float(np.nanmax(profiles.md[i])), 3)})"
        measured.append((label, value, None))
    ax_p.set_xlabel(r"$x$  [$L_x$]")
    member = frames.path.name
    return Drawn(fig, measured,
                 note=None if profiles is not None else
                 "No comparison in this run: the profile is the frame's own binned density.",
                 caption_values={"member": member, "Lx": fmt(Lx, 4), "Ly": fmt(Ly, 3)})
