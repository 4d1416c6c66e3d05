"""Numbers and verdict badges for the page (HTML-safe) and for matplotlib labels."""
import math

import numpy as np
from markupsafe import Markup, escape

from .data import num

# The compared fields as the page writes them.
CMP_FIELD_HTML = {"n": "n", "v_x": "v<sub>x</sub>", "v_y": "v<sub>y</sub>", "T": "T"}


# Powers of ten as Unicode superscripts, not <sup> tags: a number then reads the same in HTML
# (escaped or not, inside an f-string or not) and in a matplotlib title or legend.
_SUPERSCRIPT = str.maketrans("0123456789-", "⁰¹²³⁴⁵⁶⁷⁸⁹⁻")


def power_of_ten(e):
    """10 to the integer e as text: 10⁴, 10⁻¹⁵."""
    return "10" + str(int(e)).translate(_SUPERSCRIPT)


def fmt(x, digits=4):
    """HTML-safe number that is also plain text: 3.183, 1.2 × 10⁻¹⁵, — for absent."""
    if x is None:
        return Markup("—")
    if isinstance(x, bool):
        return Markup("yes" if x else "no")
    if isinstance(x, (int, np.integer)):
        return Markup(f"{int(x):,}".replace(",", "\u2009"))
    if isinstance(x, str):
        return escape(x)
    v = num(x)
    if v is None:
        return Markup("NaN") if isinstance(x, float) else escape(str(x))
    if v == 0:
        return Markup("0")
    if 1e-3 <= abs(v) < 1e5 and "e" not in f"{v:.{digits}g}":
        return Markup(f"{v:.{digits}g}".replace("-", "−"))
    m, e = f"{v:.{max(digits - 2, 1)}e}".split("e")
    return Markup(f"{m.replace('-', '−')} × {power_of_ten(e)}")


def pct(x, digits=3):
    v = num(x)
    return Markup("—") if v is None else Markup(f"{100 * v:.{digits}g} %".replace("-", "−"))


def verdict(ok, yes="within paper bound", no="outside paper bound"):
    """Badge for the page: (css class, text), or None when there is nothing to judge."""
    if ok is None:
        return None
    return ("pass", yes) if ok else ("fail", no)


def within_tolerance(ok):
    """Badge of a verdict the program wrote against a tolerance (True, False, or None: nothing to judge)."""
    return verdict(ok, "within tolerance", "outside tolerance")


def tex_num(v, digits=3):
    """Number for a matplotlib label ("?" when absent or NaN)."""
    if v is None or math.isnan(v):
        return "?"
    if math.isinf(v):
        return r"\infty" if v > 0 else r"-\infty"
    if v != 0 and not 1e-3 <= abs(v) < 1e5:
        m, e = f"{v:.{digits - 1}e}".split("e")
        return rf"{m}\times10^{{{int(e)}}}"
    return f"{v:.{digits}g}"
