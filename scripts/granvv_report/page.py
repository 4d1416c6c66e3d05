"""Page assembly: draws the figures of a page through the registry, fills the tables and renders the
jinja2 templates beside this package (scripts/report_template.html, sweep_template.html, with
report_style.html and report_figure.html) into DIR/report.html, written to a temporary file and
renamed, so a failed run never leaves a half-written page."""
import datetime
import json
import os
import tempfile
from pathlib import Path

import jinja2
from markupsafe import Markup

from . import figures_atlas, figures_compare, figures_hydro, figures_inertia, figures_md, figures_particles, figures_pressure, figures_sweep, figures_transport  # noqa: F401 - importing registers
from .data import AtlasRun, ReportError, Run, SweepRun, is_atlas_folder, is_sweep_folder
from .registry import draw_figures
from .formatting import fmt
from .tables import (atlas_tables, compare_section, engine_tables, header_rows, snapshot_table, sweep_tables,
                     sweep_verdicts)

TEMPLATES = Path(__file__).resolve().parent.parent
RUN_TEMPLATE = "report_template.html"
SWEEP_TEMPLATE = "sweep_template.html"
ATLAS_TEMPLATE = "atlas_template.html"
PAPER = "Efrati, Livne &amp; Meerson, PRL 94, 088001 (2005)"


def figure_folder(outdir):
    """DIR/figures, created, with DIR and it writable (else ReportError)."""
    figdir = outdir / "figures"
    try:
        figdir.mkdir(exist_ok=True)
    except OSError as e:
        raise ReportError(f"cannot create {figdir}: {e.strerror or e}")
    if not os.access(outdir, os.W_OK) or not os.access(figdir, os.W_OK):
        raise ReportError(f"{outdir} or {figdir} is not writable")
    return figdir


def write_page(outdir, template, page_name="report.html", **fields):
    """Render template into DIR/page_name: a temporary file, renamed."""
    env = jinja2.Environment(loader=jinja2.FileSystemLoader(TEMPLATES),
                             autoescape=jinja2.select_autoescape(["html"]), undefined=jinja2.StrictUndefined)
    html = env.get_template(template).render(**fields)
    fd, tmp = tempfile.mkstemp(prefix=".report.", suffix=".html.tmp", dir=outdir)
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as fh:
            fh.write(html)
        os.chmod(tmp, 0o644)
        os.replace(tmp, outdir / page_name)
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)


def generated_at():
    return datetime.datetime.now().astimezone().strftime("%Y-%m-%d %H:%M %Z")


def build_sweep(outdir, strict=False):
    run = SweepRun(outdir)
    run.figdir = figure_folder(run.outdir)
    figures, skipped, failed = draw_figures("sweep", run, run.figdir, strict)
    warn = []
    status = run.sweep("status")
    if status not in ("ok", None):
        warn.append(f"sweep status is '{status}': "
                    + ("it is still running or was stopped; the page shows the points finished so far."
                       if status == "running" else "at least one point failed (see its exit code)."))
    rows, fit_rows, settings = sweep_tables(run)
    write_page(
        run.outdir, SWEEP_TEMPLATE,
        case=run.sweep("case") or run.outdir.name, key=run.sweep("key") or "", status=status,
        run=settings, verdicts=sweep_verdicts(run), points=rows, fit=fit_rows,
        figures=figures, skipped=skipped, failed=failed, warnings=warn,
        raw=json.dumps(run.without_points(), indent=2),
        generated=generated_at(), source=str(run.sweep_path),
    )
    return figures, skipped, failed


def build_atlas(outdir, strict=False):
    run = AtlasRun(outdir)
    run.figdir = figure_folder(run.outdir)
    figures, skipped, failed = draw_figures("atlas", run, run.figdir, strict)
    rec, ladder, rows, skipped_runs = atlas_tables(run)
    raw = {k: v for k, v in run.at.items() if k not in ("runs", "stability", "timeline", "dem_map", "comparison_power")}
    write_page(
        run.outdir, ATLAS_TEMPLATE, page_name="atlas.html",
        case=run.atlas("case") or run.outdir.name, status=run.atlas("status"),
        recommendation=rec, ladder=ladder, runs=rows, skipped_runs=skipped_runs,
        observables=run.atlas("observables") or [], times=[fmt(t) for t in run.atlas("times") or []],
        sigmas=run.atlas("sigmas"), figures=figures, skipped=skipped, failed=failed, raw=json.dumps(raw, indent=2),
        generated=generated_at(), source=str(run.atlas_path),
    )
    return figures, skipped, failed


def build(outdir, strict=False):
    """Write DIR/report.html and DIR/figures/*.png: a sweep page for a sweep folder, an atlas page
    (DIR/atlas.html) for an atlas folder, else a run page."""
    if is_sweep_folder(outdir):
        return build_sweep(outdir, strict)
    if is_atlas_folder(outdir):
        return build_atlas(outdir, strict)
    run = Run(outdir)
    run.figdir = figure_folder(run.outdir)
    ran = {"hydro": run.has_hydro(), "md": run.has_md(), "compare": run.has_compare()}
    # a model that did not run (no hydro, no particles, no comparison) lists no entries at all
    figures, skipped, failed = draw_figures(
        "run", run, run.figdir, strict, list_skip=lambda spec: ran[spec.section])

    if isinstance(run.config_text, str) and run.config_text.strip():
        config_block = run.config_text.rstrip()
    else:
        config_block = "\n".join(f"{k} = {v}" for k, v in sorted(run.attrs.items())
                                 if k not in ("config_toml",)) or "(no configuration stored in results.h5)"

    write_page(
        run.outdir, RUN_TEMPLATE,
        case=run.top_summary("case") or run.attrs.get("case") or run.outdir.name,
        status=run.top_summary("status"),
        header=header_rows(run),
        figures=[f for f in figures if f["section"] != "compare"],
        cmp_figures=[f for f in figures if f["section"] == "compare"],
        compare=compare_section(run),
        skipped=skipped, failed=failed, warnings=run.warnings,
        engines=engine_tables(run), snapshots=snapshot_table(run),
        md_units=any(f["section"] == "md" for f in figures),
        config=config_block, groups=run.groups, paper=Markup(PAPER),
        generated=generated_at(), source=str(run.results_path),
    )
    return figures, skipped, failed
