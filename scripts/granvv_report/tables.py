"""The page's tables: the run header, the side-by-side verdict with its metrics, Haff times and cost,
the numbers of summary.json, and the points, fit and settings of a sweep."""
import math

from markupsafe import Markup, escape

from .data import arr, cmp_box, cmp_vec, cmp_window, compared_fields, get, hydro_t0, md_value, num, sweep_points
from .formatting import CMP_FIELD_HTML, fmt, pct


def status_badge(status):
    """A run or engine status as a coloured badge, or — when absent."""
    return Markup(f'<span class="status {escape(str(status))}">{fmt(status)}</span>') if status else fmt(None)


def fired_at_parting(fired, validity):
    """The monitors that had crossed their thresholds by the parting, with their crossing times."""
    if fired is None:
        return fmt(None) if validity is None else Markup("no field parted")
    if not fired:
        return Markup("none")
    return Markup(", ".join(f"{escape(name)} (t = {fmt(num(((validity or {}).get(name) or {}).get('time')))})"
                            for name in fired))


def compare_section(run):
    """The verdict box and the tables of the side-by-side section, or None without /compare."""
    C = run.compare
    c = run.compare_summary() or {}
    if C is None and not c:
        return None
    attrs = C["attrs"] if C else {}

    def pick_value(key, summary_key=None):
        v = attrs.get(key)
        if v is None or (isinstance(v, float) and not math.isfinite(v)):
            v = c.get(summary_key or key)
        return v

    verdict_text = pick_value("verdict") or ""
    kind = pick_value("disagreement") or ""
    sn = num(pick_value("signal_to_noise"))
    sn_txt = fmt(sn, 3)
    plain = {
        "none": Markup("The fields agree within the particles' statistical error"
                       + (f" (signal/noise = {sn_txt}: the imposed flow is not well above the particles' noise, "
                          "so this agreement tests the hydro only weakly)." if sn is not None and sn < 3 else
                          f" (signal/noise = {sn_txt}).")),
        "noise": Markup(f"The particles' own fluctuations compete with the imposed signal (signal/noise = {sn_txt}): "
                        "the difference is noise-driven, not a failure of the hydro."),
        "model": Markup(f"The signal is clear of the noise (signal/noise = {sn_txt}): the difference is the hydro's."),
    }.get(kind, Markup(f"Disagreement kind: {escape(kind) or '—'} (signal/noise = {sn_txt})."))
    L = cmp_box(run)
    w, left, first = (cmp_window(C) if C else
                      (num(c.get("agreement_window")), num(c.get("left_at")), c.get("first_field_to_leave") or ""))
    t = arr(C, "t", 1) if C else None
    sig, frac = num(pick_value("sigmas")), num(pick_value("agreement_fraction"))

    def t_both(v):
        if v is None:
            return fmt(None)
        return Markup(f"t = {fmt(v)}" + (f" (t<sub>MD</sub> = {fmt(v * L)} σ(m/T<sub>0</sub>)<sup>1/2</sup>)" if L else ""))

    rows = [
        ("agreement window (every field within "
         + (f"{fmt(sig)}σ in at least {pct(frac, 3)} of the bins" if sig and frac else "the tolerance") + ")",
         Markup("up to ") + t_both(w) if w is not None else Markup("none: the fields differ from the first compared time")),
        ("first field to leave (time)", Markup(f"{Markup(CMP_FIELD_HTML.get(first, escape(first))) if first else fmt(None)}"
                                              + (f" at {t_both(left)}" if left is not None else ""))),
        ("signal-to-noise (imposed flow against the thermal velocity noise on the bin scale, docs/physics.md §8)", sn_txt),
        ("disagreement kind", fmt(kind or None)),
        ("hydro started from", fmt({"md": "the MD's coarse-grained t = 0 fields", "case": "the case's initial fields"}
                                   .get(pick_value("hydro_initial"), pick_value("hydro_initial")))),
        ("compared times", Markup(f"{t.size}, from t = {fmt(t[0])} to {fmt(t[-1])}") if t is not None else fmt(None)),
        ("the hydro's validity monitors (docs/physics.md §9) that had fired when the first field parted",
         fired_at_parting(c.get("monitors_fired_at_parting"), run.hydro_summary("validity"))),
    ]
    # metrics per field and time
    metrics = []
    if C and t is not None:
        for key in compared_fields(C):
            g = C["fields"][key]
            cols = {k: cmp_vec(g, k, t.size) for k in ("l1", "l2", "linf", "fraction_within", "worst_z")}
            agrees = run.compare_summary("fields", key, "agrees") or []   # the program's verdict per time
            trs = []
            for i in range(t.size):
                trs.append({"bad": i < len(agrees) and agrees[i] is False,
                            "cells": [fmt(num(t[i])), fmt(num(t[i] * L) if L else None)]
                            + [fmt(num(cols[k][i]) if cols[k] is not None else None, 3)
                               for k in ("l1", "l2", "linf", "fraction_within", "worst_z")]})
            metrics.append({"field": Markup(CMP_FIELD_HTML.get(key, key)), "source": fmt(g["attrs"].get("error_source")),
                            "rows": trs})
    # Haff: the particles' measured t0 against kinetic theory and the hydro's (its closure's)
    t0h_origin = escape(hydro_t0(run)[1])
    h = c.get("haff") if isinstance(c.get("haff"), dict) else {}
    t0m = num(h.get("t0_measured")) if h else None
    t0m = t0m if t0m is not None else md_value(run, "haff_t0_measured")
    t0e = num(h.get("t0_measured_error")) if h else None
    t0e = t0e if t0e is not None else md_value(run, "haff_t0_measured_error")
    t0c = num(h.get("t0_theory_enskog")) if h else None
    t0c = t0c if t0c is not None else md_value(run, "haff_t0_theory")
    t0d = num(h.get("t0_theory_dilute")) if h else None
    t0d = t0d if t0d is not None else md_value(run, "haff_t0_theory_dilute")
    t0h = num(h.get("t0_hydro")) if h else None
    # t0_measured / t0 - 1 and (t0_measured - t0) / its fit error, against each reference: the
    # comparison's haff block, else (no comparison block) the particle engine's own numbers
    if h:
        devs = [(h.get("deviation_enskog"), h.get("deviation_enskog_sigmas")),
                (h.get("deviation_dilute"), h.get("deviation_dilute_sigmas")),
                (h.get("measured_deviation_from_hydro"), h.get("deviation_hydro_sigmas"))]
    else:
        devs = [(run.md_summary("haff_t0_deviation"), run.md_summary("haff_t0_deviation_sigmas")),
                (run.md_summary("haff_t0_deviation_dilute"), None), (None, None)]

    unit = Markup(" σ(m/T<sub>0</sub>)<sup>1/2</sup>")
    haff = [("measured (fit of the MD's T(t))", Markup(f"{fmt(t0m)} ± {fmt(t0e, 2)}{unit}") if t0m is not None else fmt(None),
             fmt(None), fmt(None))]
    for (lab, ref), (d, sg) in zip((("kinetic theory, Enskog χ(φ)", t0c), ("kinetic theory, dilute (χ = 1)", t0d),
                                    (Markup(f"t<sub>0</sub> of the hydro's {t0h_origin} (in MD time)"), t0h)), devs):
        haff.append((lab, Markup(f"{fmt(ref)}{unit}") if ref is not None else fmt(None), pct(num(d)), fmt(num(sg), 3)))
    cost = get(c, "cost") or {}
    ch, cm = cost.get("hydro") or {}, cost.get("md") or {}
    cost_rows = [
        ("hydro: wall time", Markup(f"{fmt(num(ch.get('wall_seconds')), 3)} s") if num(ch.get("wall_seconds")) is not None else fmt(None)),
        ("hydro: cells, steps", Markup(f"{fmt(ch.get('cells'))}, {fmt(ch.get('steps'))}")),
        ("hydro: cell-steps, cell-steps/s", Markup(f"{fmt(num(ch.get('cell_steps')), 3)}, {fmt(num(ch.get('cell_steps_per_second')), 3)}")),
        ("MD: wall time", Markup(f"{fmt(num(cm.get('wall_seconds')), 3)} s") if num(cm.get("wall_seconds")) is not None else fmt(None)),
        ("MD: particles, ensemble members", Markup(f"{fmt(cm.get('particles'))}, {fmt(cm.get('ensemble'))}")),
        ("MD: atom-steps, atom-steps/s", Markup(f"{fmt(num(cm.get('atom_steps')), 3)}, {fmt(num(cm.get('atom_steps_per_second')), 3)}")),
        ("MD / hydro wall-time ratio", fmt(num(cost.get("md_to_hydro_wall_ratio")), 3)),
    ]
    notes = []
    if h.get("hydro_cools_differently"):
        notes.append(Markup(
            f"The hydro's Haff time t<sub>0</sub> = {fmt(t0h)} σ(m/T<sub>0</sub>)<sup>1/2</sup> (of its {t0h_origin}, with the "
            "K, q the hydro ran with, in MD time) "
            f"differs from the particles' measured t<sub>0</sub> = {fmt(t0m)} by {pct(num(h.get('deviation_hydro')))}: the hydro does "
            "not cool like this particle box (its K, q do not describe the box, e.g. when md.particles or the box "
            "is set directly). Differences in T then come from the cooling rate, whatever the signal-to-noise "
            "classification above says."))
    return {"verdict": verdict_text, "kind": kind, "plain": plain, "rows": rows, "metrics": metrics,
            "sigmas": fmt(sig), "haff": haff, "cost": cost_rows, "notes": notes}


def header_rows(run):
    """The rows of the run table at the top of the page."""
    h = run.hydro_summary() or {}
    ref = run.config_table("case", "reference") or run.config_table("reference") or run.attrs.get("case.reference")
    desc = (run.config_table("case", "description") or run.config_table("description")
            or run.attrs.get("case.description"))
    rows = [
        ("case", fmt(run.top_summary("case") or run.attrs.get("case"))),
        ("reference", fmt(ref)),
        ("description", fmt(desc)) if desc else None,
        ("status", status_badge(run.top_summary("status"))),
    ]
    if run.has_hydro():
        rows += [
            ("hydro status", fmt(h.get("status"))),
            ("stop reason", fmt(h.get("stop_reason"))),
            ("final time", fmt(num(h.get("t_final")))) if num(h.get("t_final")) is not None else None,
            ("wall time (hydro)", Markup(f"{fmt(num(h.get('wall_seconds')), 3)} s") if num(h.get("wall_seconds")) is not None else fmt(None)),
            ("cells", fmt(h.get("cells"))),
            ("steps", fmt(h.get("steps"))),
            ("cell-steps / s", fmt(num(h.get("cell_steps_per_second")), 3)),
        ]
    else:
        disabled = str(run.config("hydro.enabled")).lower() == "false"
        rows.append(("hydro", fmt("not run" + (" (hydro.enabled = false)" if disabled else ""))))
    md = run.md_summary()
    md_attrs = (run.md_group or {}).get("attrs") or {}
    if isinstance(md, dict) or md_attrs:
        rows += md_header_rows(md if isinstance(md, dict) else {}, md_attrs, run.config_table("md") or {})
    w = num(run.compare_summary("wall_seconds"))
    if w is not None:
        rows.append(("wall time (compare)", Markup(f"{fmt(w, 3)} s")))
    rows.append(("granvv version", fmt(run.top_summary("granvv_version") or run.attrs.get("granvv_version"))))
    return [r for r in rows if r]


def md_header_rows(md, attrs, cfg_md):
    """Header rows of the particle engine: status, and one line with the scene and its cost
    (summary.json first, then the /md attributes, then the configuration, e.g. after a failure)."""
    def v(key):
        for src in (md, attrs, cfg_md):
            x = num(src.get(key)) if isinstance(src, dict) else None
            if x is not None and not (src is cfg_md and key in ("particles", "restitution") and x == 0):
                return x   # (in the configuration, 0 disks or r = 0 means "derive from K, q")
        return None

    status = status_badge(md.get("status"))
    if md.get("error"):
        status += Markup(" — ") + escape(str(md["error"]))
    N, Lx, Ly = v("particles"), v("box_length"), v("box_width")
    r, rm = v("restitution"), v("restitution_measured")
    parts = []
    if N is not None:
        parts.append(f"{fmt(int(N))} disks")
    if Lx is not None and Ly is not None:
        parts.append(f"L<sub>x</sub> × L<sub>y</sub> = {fmt(Lx)} × {fmt(Ly)} σ")
    if v("area_fraction") is not None:
        parts.append(f"φ = {fmt(v('area_fraction'))}")
    if r is not None:
        parts.append(f"r = {fmt(r)} (measured {fmt(rm, 6)})" if rm is not None else f"r = {fmt(r)}")
    ens = md.get("ensemble") if md.get("ensemble") is not None else cfg_md.get("ensemble")
    seed = md.get("seed") if md.get("seed") is not None else cfg_md.get("seed")
    if ens is not None:
        e = int(num(ens)) if num(ens) is not None else None
        s0 = int(num(seed)) if num(seed) is not None else None
        seeds = ("" if s0 is None else f" (seed {s0})" if e == 1 else
                 f" (seeds {s0}–{s0 + e - 1})" if e else "")
        parts.append(f"ensemble of {fmt(ens)}{seeds}")
    if v("t_end") is not None:
        parts.append(f"to t = {fmt(v('t_end'))} σ(m/T<sub>0</sub>)<sup>1/2</sup>")
    if v("wall_seconds") is not None:
        parts.append(f"{fmt(v('wall_seconds'), 3)} s wall")
    if v("atom_steps_per_second") is not None:
        parts.append(f"{fmt(v('atom_steps_per_second'), 3)} atom-steps/s")
    return [("MD status", status),
            (particle_engine_label(md, cfg_md), Markup(", ".join(parts)) if parts else fmt(None))]


def particle_engine_label(md, cfg_md):
    """The row's name with the engine that ran, as the run wrote it (summary.json's md.engine,
    else the resolved md.engine key)."""
    name = md.get("engine") if isinstance(md, dict) else None
    if not isinstance(name, str) or not name:
        name = (cfg_md or {}).get("engine")
    return f"particle engine ({name})" if isinstance(name, str) and name else "particle engine"


def flatten(d, prefix=""):
    out = []
    for k, v in d.items():
        key = f"{prefix}{k}"
        if isinstance(v, dict):
            out += flatten(v, key + ".")
        elif isinstance(v, list):
            if not v:
                out.append((key, Markup("none")))
            elif all(not isinstance(x, (dict, list)) for x in v) and len(v) <= 12:
                out.append((key, Markup(", ".join(str(fmt(x)) for x in v))))
            else:
                out.append((key, Markup(f"[{len(v)} entries]")))
        else:
            out.append((key, fmt(v)))
    return out


def engine_tables(run):
    """One table per engine block of summary.json (without the snapshot list)."""
    return [{"name": eng, "rows": flatten({k: v for k, v in block.items() if k != "snapshots"})}
            for eng, block in run.engine_blocks()]


def snapshot_table(run):
    snaps = run.hydro_summary("snapshots")
    if not isinstance(snaps, list) or not snaps:
        return None
    order = ["t", "n_max", "T_min", "energy", "energy_thermal", "energy_kinetic", "energy_kinetic_y",
             "collapse_error", "collapse_within_tolerance"]
    seen = []
    for rec in snaps:
        for k in (rec or {}):
            if k not in seen:
                seen.append(k)
    cols = [k for k in order if k in seen] + [k for k in seen if k not in order]

    def cell(v):
        return fmt(v if isinstance(v, bool) or num(v) is None else num(v))

    return {"cols": cols, "rows": [[cell(get(r, c)) for c in cols] for r in snaps]}


def sweep_verdicts(run):
    """Plain sentences: the power fit, where the paper's small-q rate departs, kinetic theory's misses."""
    c = run.cooling() if isinstance(run.cooling(), dict) else None
    if c is None:
        err = run.sweep("cooling_error")
        return [Markup("No cooling analysis: no point measured a Haff time with an error"
                       + (f" ({escape(err)})" if err else "") + ".")]
    sig = num(c.get("sigmas"))
    out = []
    fit = c.get("power_of_one_minus_r2")
    if isinstance(fit, dict) and num(fit.get("power")) is not None:
        p, pe = num(fit.get("power")), num(fit.get("power_error"))
        z = num(fit.get("deviation_from_one_sigmas"))
        out.append(Markup(f"The measured cooling rate scales as (1 − r<sup>2</sup>)<sup>p</sup> with p = {fmt(p, 4)} ± "
                          f"{fmt(pe, 2)} over r ≥ {fmt(num(fit.get('r_min')))} ({fmt(fit.get('points'))} points"
                          + (f"; {fmt(abs(z), 2)}σ from kinetic theory's p = 1" if z is not None else "") + ")."))
    else:
        out.append(Markup("No power fit: fewer than two points in its range of r."))
    rs = [num(q.get("restitution")) for q in c.get("points") or [] if isinstance(q, dict)]
    rs = [v for v in rs if v is not None]
    dep = num(c.get("paper_departs_at_r"))
    if dep is None:
        out.append(Markup(f"The paper's small-q rate (8q/K, with χ(φ)) departs from the measured one by more than "
                          f"{fmt(sig)}σ nowhere in the sweep."))
    else:
        everywhere = rs and dep >= max(rs) - 1e-12 and all(q.get("paper_beyond_sigmas") for q in c.get("points") or [])
        out.append(Markup(f"The paper's small-q rate (8q/K, with χ(φ)) departs from the measured one by more than "
                          f"{fmt(sig)}σ for r ≤ {fmt(dep)}" + (" — at every r of the sweep." if everywhere else ".")))
    miss = [q for q in c.get("points") or [] if isinstance(q, dict) and q.get("enskog_beyond_sigmas")]
    if miss:
        out.append(Markup(f"Kinetic theory with χ(φ) itself misses the measured t<sub>0</sub> by more than {fmt(sig)}σ at r = "
                          + ", ".join(str(fmt(num(q.get("restitution")))) for q in miss)
                          + " (" + ", ".join(f"{pct(num(q.get('deviation_enskog')))}" for q in miss)
                          + "): there the statistical error understates the systematic one, and a departure of "
                          "the small-q rate means something only where it is larger than kinetic theory's own miss."))
    elif rs:
        out.append(Markup(f"Kinetic theory with χ(φ) agrees with every measured t<sub>0</sub> within {fmt(sig)}σ."))
    return out


def sweep_tables(run):
    pts = sweep_points(run)
    rows = []
    for p in pts:
        md, c = p["md"], p["cool"] or {}
        t0, t0e = num(md.get("haff_t0_measured")), num(md.get("haff_t0_measured_error"))
        th = num(md.get("haff_t0_theory"))
        dev = num(c.get("deviation_enskog")) if c else num(md.get("haff_t0_deviation"))
        sg = num(c.get("deviation_enskog_sigmas")) if c else num(md.get("haff_t0_deviation_sigmas"))
        st = p["status"]
        rows.append({
            "cells": [fmt(p["value"]),
                      Markup(f'<span class="status {escape(str(st))}">{fmt(st)}</span>') if st else
                      Markup(f"— (exit {fmt(p['exit_code'])})"),
                      fmt(num(md.get("restitution"))), fmt(num(md.get("restitution_measured")), 6),
                      Markup(f"{fmt(t0)} ± {fmt(t0e, 2)}") if t0 is not None else fmt(None),
                      fmt(th), fmt(num(md.get("haff_t0_theory_dilute"))), fmt(num(md.get("haff_t0_paper"))),
                      pct(dev), fmt(sg, 3),
                      Markup(f"{fmt(num(md.get('wall_seconds')), 3)} s") if num(md.get("wall_seconds")) is not None else fmt(None)],
            "link": p["link"], "dir": p["dir"],
            "bad": bool(c.get("enskog_beyond_sigmas"))})
    fit = run.cooling("power_of_one_minus_r2")
    fit_rows = None
    if isinstance(fit, dict):
        p, pe = num(fit.get("power")), num(fit.get("power_error"))
        fit_rows = [("power p of (1 − r<sup>2</sup>)", Markup(f"{fmt(p, 4)} ± {fmt(pe, 2)}")),
                    ("(p − 1)/δp", fmt(num(fit.get("deviation_from_one_sigmas")), 3)),
                    ("prefactor C (ζ = C (1 − r<sup>2</sup>)<sup>p</sup>, in (T<sub>0</sub>/m)<sup>1/2</sup>/σ)", fmt(num(fit.get("prefactor")), 4)),
                    ("χ<sup>2</sup> per degree of freedom", fmt(num(fit.get("chi2_per_dof")), 3)),
                    ("points in the fit, r ≥", Markup(f"{fmt(fit.get('points'))}, {fmt(num(fit.get('r_min')))}"))]
    settings = [
        ("case", fmt(run.sweep("case"))),
        ("swept key", Markup(f"<code>{escape(str(run.sweep('key')))}</code>")),
        ("values", Markup(", ".join(str(fmt(v)) for v in run.sweep("values") or [])) if run.sweep("values") else fmt(None)),
        ("fixed settings (every point)", Markup(", ".join(f"<code>{escape(str(v))}</code>" for v in run.sweep("fixed_sets") or []))
         if run.sweep("fixed_sets") else Markup("none (the case file as it is)")),
        ("status", status_badge(run.sweep("status"))),
        ("points finished", Markup(f"{len(pts)} of {len(run.sweep('values') or [])}")),
        ("wall time", Markup(f"{fmt(num(run.sweep('wall_seconds')), 3)} s") if num(run.sweep("wall_seconds")) is not None else fmt(None)),
        ("granvv version", fmt(run.sweep("granvv_version"))),
    ]
    seeds = {(p["md"].get("seed"), p["md"].get("ensemble")) for p in pts if p["md"]}
    if seeds:
        settings.insert(4, ("seeds, ensemble members", Markup("; ".join(
            f"seed {fmt(s)}, ensemble of {fmt(e)}" for s, e in sorted(seeds, key=str)))))
    return rows, fit_rows, settings


def _knobs_text(s):
    """The cost knobs of an atlas setting or run row, as text ("" for a model without knobs)."""
    if "cells" in s:
        return f"{s['cells']} cells, step factor {fmt(s['step_factor'], 3)}"
    if "max_overlap" in s:
        return (f"ensemble {s.get('ensemble')}, max_overlap {fmt(s['max_overlap'], 3)}, "
                f"{s.get('steps_per_contact')} steps per contact, adaptive stiffness "
                f"{'on' if s.get('adaptive_stiffness') else 'off'}")
    if "ensemble" in s:
        return f"ensemble {s['ensemble']}"
    return ""


def _setting_text(s):
    if not isinstance(s, dict):
        return "—"
    knobs = _knobs_text(s)
    return f"{s.get('model', '—')}, {knobs}" if knobs else s.get("model", "—")


def atlas_tables(run):
    """(recommendation rows, ladder rows, run rows, skipped rows) of an atlas page."""
    rec = run.atlas("recommendation") or {}
    rec_rows = [("tolerance (relative)", fmt(rec.get("tolerance")))]
    if rec.get("model"):
        rec_rows.append(("cheapest adequate model", _setting_text(rec.get("setting"))))
        cost = rec.get("cost") or {}
        rec_rows.append(("its cost", Markup("{} s, {} {}").format(fmt(cost.get('wall_seconds'), 3),
                                                                  fmt(cost.get('work'), 3), cost.get('work_unit', ''))))
        ref_err = rec.get("reference_statistical_error") or {}
        for k, v in sorted((rec.get("error") or {}).items()):
            rec_rows.append((f"its error: {k}", fmt(v, 3) if k not in ref_err else
                             Markup(f"{fmt(v, 3)} (reference's statistical error {fmt(ref_err[k], 2)})")))
        nxt = rec.get("next_rung")
        if isinstance(nxt, dict):
            rec_rows.append(("next rung up", _setting_text(nxt.get("setting")) + ("" if nxt.get("adequate")
                             else " (not adequate either)")))
            rec_rows.append(("its cost", f"{fmt((nxt.get('cost') or {}).get('wall_seconds'), 3)} s"))
        else:
            rec_rows.append(("next rung up", "none ran"))
    else:
        rec_rows.append(("cheapest adequate model", rec.get("reason", "none")))
    ladder = [(r.get("model"), "runs" if r.get("runs") else "skipped: " + str(r.get("reason")))
              for r in run.atlas("ladder") or []]
    names = run.atlas("observables") or []
    rows = []
    order = lambda r: (r.get("model", ""), r.get("cells") or 0, r.get("step_factor") or 0, r.get("ensemble") or 0,
                       r.get("max_overlap") or 0, r.get("steps_per_contact") or 0, bool(r.get("adaptive_stiffness")))
    for r in sorted(run.runs(), key=order):
        errs = r.get("model_error") or {}
        worst = max(errs.values()) if errs else None
        num = r.get("numerical_error") or {}
        rows.append([r.get("model"), _knobs_text(r) or "—",
                     r.get("status"), fmt(r.get("wall_seconds"), 3),
                     Markup("{} {}").format(fmt(r.get('work'), 3), r.get('work_unit', '')),
                     fmt(max(num.values()), 3) if num else "—", fmt(worst, 3) if worst is not None else "—",
                     f"{len(errs)}/{len(names)}", "yes" if r.get("over_resolved") else "",
                     ", ".join(r.get("pareto") or [])])
    skipped = [(_setting_text(s.get("setting")), s.get("reason")) for s in run.atlas("skipped") or []]
    return rec_rows, ladder, rows, skipped
