"""The figure registry: each figure is declared once, by the decorator on the function that draws it,
with its file name, page section, anchor, title and caption template.

    @figure(file="fig2_energy.png", section="hydro", anchor="energy",
            title="Energy: total, thermal, kinetic (paper Fig. 2)",
            caption="Fig. 2: E(t) follows Haff's law ...")
    def fig_energy(run):
        ...                                  # raise Skip("why") when the data are absent
        return Drawn(fig, measured, note=...)

The function returns the matplotlib figure, the "Measured" rows [(label, value, badge or None)], an
optional note, and the values of the caption's {placeholders} (str.format). The page draws the figures
section by section (the order of SECTIONS), each section in declaration order.
"""
import multiprocessing
import os
import sys
import traceback
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass, field

import matplotlib.pyplot as plt
from markupsafe import Markup

from . import PROG
from .data import Skip
from .style import save

# The page sections and the page each belongs to.
SECTIONS = {"hydro": "run", "md": "run", "compare": "run", "sweep": "sweep", "atlas": "atlas"}


@dataclass
class Drawn:
    fig: object
    measured: list
    note: object = None
    caption_values: dict = field(default_factory=dict)


@dataclass
class Figure:
    file: str
    section: str
    anchor: str
    title: str
    caption: str
    draw: object


FIGURES = []


def figure(file, section, anchor, title, caption):
    """Register the decorated function as a figure of the page (see the module docstring)."""
    if section not in SECTIONS:
        raise ValueError(f"unknown report section {section!r}")

    def register(fn):
        if any(f.file == file or f.anchor == anchor for f in FIGURES):
            raise ValueError(f"figure {file} ({anchor}) is declared twice")
        FIGURES.append(Figure(file, section, anchor, title, caption, fn))
        return fn

    return register


def figures_of(page):
    """The figures of a page, section by section in the order of SECTIONS, each in declaration order."""
    order = list(SECTIONS)
    return sorted((f for f in FIGURES if SECTIONS[f.section] == page), key=lambda f: order.index(f.section))


def _draw(spec, run, figdir, strict):
    """One figure drawn and saved: ("figure", dict for the templates), ("skip", why) or ("failed", why).
    A skipped or failed figure's stale PNG of an earlier run is removed."""
    try:
        d = spec.draw(run)
        img = save(d.fig, figdir, spec.file)
        return "figure", {"id": spec.anchor, "title": spec.title, "img": img, "section": spec.section,
                          "paper": Markup(spec.caption.format(**d.caption_values)),
                          "measured": d.measured, "note": d.note}
    except Skip as e:
        outcome = "skip", str(e)
    except Exception as e:  # noqa: BLE001 - one broken figure must not sink the page
        plt.close("all")
        outcome = "failed", f"{type(e).__name__}: {e}"
        print(f"{PROG}: warning: {spec.file} failed: {type(e).__name__}: {e}", file=sys.stderr)
        if strict:
            traceback.print_exc()
    if (figdir / spec.file).exists():
        (figdir / spec.file).unlink()   # a stale figure of an earlier run must not linger
    return outcome


# The job of the worker processes, inherited through fork: (specs, run, figdir, strict).
_JOB = None


def _draw_in_worker(index):
    specs, run, figdir, strict = _JOB
    return _draw(specs[index], run, figdir, strict)


def _workers(count):
    """How many processes draw: one per core this process may use, at most one per figure."""
    return max(1, min(count, len(os.sched_getaffinity(0))))


def draw_figures(page, run, figdir, strict, list_skip=lambda spec: True):
    """Each figure of the page drawn: (figures, skipped, failed). A figure is a dict for the templates
    (id, title, img, paper, measured, note, section). list_skip(spec) says whether a skip is worth
    listing on the page. The figures are independent, so they are drawn in parallel by forked worker
    processes (one per core; the Agg backend gives the same PNG bytes as drawing them in turn), and
    collected in page order."""
    global _JOB
    specs = figures_of(page)
    workers = _workers(len(specs))
    if workers == 1:
        outcomes = [_draw(spec, run, figdir, strict) for spec in specs]
    else:
        _JOB = (specs, run, figdir, strict)
        try:
            with ProcessPoolExecutor(workers, mp_context=multiprocessing.get_context("fork")) as pool:
                outcomes = list(pool.map(_draw_in_worker, range(len(specs))))
        finally:
            _JOB = None
    figures, skipped, failed = [], [], []
    for spec, (kind, value) in zip(specs, outcomes):
        if kind == "figure":
            figures.append(value)
        elif kind == "skip":
            if list_skip(spec):
                skipped.append((spec.file, value))
        else:
            failed.append((spec.file, value))
    return figures, skipped, failed
