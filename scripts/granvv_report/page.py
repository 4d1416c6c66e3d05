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

from . import figures_compare, figures_hydro, figures_md, figures_sweep  # noqa: F401 - importing registers
from .data import ReportError, Run, SweepRun, is_sweep_folder
from .registry import draw_figures
from .tables import (compare_section, engine_tables, header_rows, snapshot_table, sweep_tables,
                     sweep_verdicts)

TEMPLATES = Path(__file__).resolve().parent.parent
RUN_TEMPLATE = "report_template.html"
SWEEP_TEMPLATE = "sweep_template.html"
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


def write_page(outdir, template, **fields):
    """Render template into DIR/report.html: a temporary file, renamed."""
    env = jinja2.Environment(loader=jinja2.FileSystemLoader(TEMPLATES),
                             autoescape=jinja2.select_autoescape(["html"]), undefined=jinja2.StrictUndefined)
    html = env.get_template(template).render(**fields)
    fd, tmp = tempfile.mkstemp(prefix=".report.", suffix=".html.tmp", dir=outdir)
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as fh:
            fh.write(html)
        os.chmod(tmp, 0o644)
        os.replace(tmp, outdir / "report.html")
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)


def generated_at():
    return datetime.datetime.now().astimezone().strftime("%Y-%m-%d %H:%M %Z")


def build_sweep(outdir, strict=False):
    ctx = SweepRun(outdir)
    ctx.figdir = figure_folder(ctx.outdir)
    figures, skipped, failed = draw_figures("sweep", ctx, ctx.figdir, strict)
    warn = []
    status = ctx.sweep("status")
    if status not in ("ok", None):
        warn.append(f"sweep status is '{status}': "
                    + ("it is still running or was stopped; the page shows the points finished so far."
                       if status == "running" else "at least one point failed (see its exit code)."))
    rows, fit_rows, run = sweep_tables(ctx)
    write_page(
        ctx.outdir, SWEEP_TEMPLATE,
        case=ctx.sweep("case") or ctx.outdir.name, key=ctx.sweep("key") or "", status=status,
        run=run, verdicts=sweep_verdicts(ctx), points=rows, fit=fit_rows,
        figures=figures, skipped=skipped, failed=failed, warnings=warn,
        raw=json.dumps(ctx.without_points(), indent=2),
        generated=generated_at(), source=str(ctx.sweep_path),
    )
    return figures, skipped, failed


def build(outdir, strict=False):
    """Write DIR/report.html and DIR/figures/*.png: a sweep page for a sweep folder, else a run page."""
    if is_sweep_folder(outdir):
        return build_sweep(outdir, strict)
    ctx = Run(outdir)
    ctx.figdir = figure_folder(ctx.outdir)
    has_md, has_cmp = ctx.has_md(), ctx.has_compare()
    # no particle run: no MD entries at all; no comparison: no side-by-side entries
    figures, skipped, failed = draw_figures(
        "run", ctx, ctx.figdir, strict,
        list_skip=lambda spec: not ((spec.section == "md" and not has_md)
                                    or (spec.section == "compare" and not has_cmp)))

    if isinstance(ctx.config_text, str) and ctx.config_text.strip():
        config_block = ctx.config_text.rstrip()
    else:
        config_block = "\n".join(f"{k} = {v}" for k, v in sorted(ctx.attrs.items())
                                 if k not in ("config_toml",)) or "(no configuration stored in results.h5)"

    write_page(
        ctx.outdir, RUN_TEMPLATE,
        case=ctx.top_summary("case") or ctx.attrs.get("case") or ctx.outdir.name,
        status=ctx.top_summary("status"),
        header=header_rows(ctx),
        figures=[f for f in figures if f["section"] != "compare"],
        cmp_figures=[f for f in figures if f["section"] == "compare"],
        compare=compare_section(ctx),
        skipped=skipped, failed=failed, warnings=ctx.warnings,
        engines=engine_tables(ctx), snapshots=snapshot_table(ctx),
        md_units=any(f["section"] == "md" for f in figures),
        config=config_block, groups=ctx.groups, paper=Markup(PAPER),
        generated=generated_at(), source=str(ctx.results_path),
    )
    return figures, skipped, failed
