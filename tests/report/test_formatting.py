"""scripts/granvv_report/formatting.py: the numbers of the page (HTML) and of figure labels (TeX)
at known values, absent and non-finite ones included."""
import math
import unittest

import numpy as np
from markupsafe import Markup

import report_fixtures  # noqa: F401 - puts the package on the path
from granvv_report.formatting import fmt, pct, tex_num, verdict, within_tolerance

MINUS, THIN = "\u2212", "\u2009"


class Fmt(unittest.TestCase):
    def test_absent_booleans_and_text(self):
        self.assertEqual(fmt(None), "—")
        self.assertEqual(fmt(True), "yes")
        self.assertEqual(fmt(False), "no")
        self.assertEqual(fmt("a<b & c"), "a&lt;b &amp; c")  # escaped: the page inserts it as is

    def test_integers_are_grouped_by_thin_spaces_and_never_rounded(self):
        self.assertEqual(fmt(1234567), f"1{THIN}234{THIN}567")
        self.assertEqual(fmt(np.int64(10**9)), f"1{THIN}000{THIN}000{THIN}000")

    def test_plain_range_with_significant_digits_and_a_true_minus(self):
        self.assertEqual(fmt(0), "0")
        self.assertEqual(fmt(0.0), "0")
        self.assertEqual(fmt(3.14159265), "3.142")
        self.assertEqual(fmt(3.14159265, digits=6), "3.14159")
        self.assertEqual(fmt(-2.5), f"{MINUS}2.5")
        self.assertEqual(fmt(1e-3), "0.001")  # the lower end is plain
        self.assertEqual(fmt(np.float64(12.5)), "12.5")
    def test_scientific_outside_1e_minus_3_to_1e5(self):
        self.assertEqual(fmt(1.2e-15), "1.20 × 10⁻¹⁵")
        self.assertEqual(fmt(-9.99e-4), f"{MINUS}9.99 × 10⁻⁴")
        self.assertEqual(fmt(123456.0), "1.23 × 10⁵")
        # 99999.5 rounds to 1e+05 at four digits: written as a power, not as "1e+05".
        self.assertEqual(fmt(99999.5), "1.00 × 10⁵")
        self.assertEqual(fmt(6.02e23, digits=2), "6.0 × 10²³")  # at least one decimal

    def test_non_finite_floats_are_nan_and_other_objects_their_escaped_text(self):
        self.assertEqual(fmt(float("nan")), "NaN")
        self.assertEqual(fmt(math.inf), "NaN")
        self.assertEqual(fmt(np.float64("nan")), "NaN")
        self.assertEqual(fmt(["<x>"]), "[&#39;&lt;x&gt;&#39;]")

    def test_results_are_markup(self):
        for x in (None, True, 3, "s", 2.5, 1e-9, float("nan")):
            self.assertIsInstance(fmt(x), Markup, x)


class Pct(unittest.TestCase):
    def test_fractions_as_percent(self):
        self.assertEqual(pct(0.0123), "1.23 %")
        self.assertEqual(pct(-0.5), f"{MINUS}50 %")
        self.assertEqual(pct(0.123456, digits=5), "12.346 %")
        self.assertEqual(pct("0.25"), "25 %")

    def test_absent_and_non_finite_are_a_dash(self):
        for x in (None, float("nan"), math.inf, "n/a"):
            self.assertEqual(pct(x), "—", x)


class Verdicts(unittest.TestCase):
    def test_badges(self):
        self.assertIsNone(verdict(None))
        self.assertEqual(verdict(True), ("pass", "within paper bound"))
        self.assertEqual(verdict(False), ("fail", "outside paper bound"))
        self.assertEqual(verdict(False, "agrees", "disagrees"), ("fail", "disagrees"))
        self.assertEqual(within_tolerance(True), ("pass", "within tolerance"))
        self.assertEqual(within_tolerance(False), ("fail", "outside tolerance"))
        self.assertIsNone(within_tolerance(None))


class TexNum(unittest.TestCase):
    def test_plain_and_powers_of_ten(self):
        self.assertEqual(tex_num(0), "0")
        self.assertEqual(tex_num(3.14159), "3.14")
        self.assertEqual(tex_num(87.349, 4), "87.35")
        self.assertEqual(tex_num(1.5e-5), r"1.50\times10^{-5}")
        self.assertEqual(tex_num(-2e6), r"-2.00\times10^{6}")
        self.assertEqual(tex_num(0.0125, 2), "0.013")

    def test_absent_and_non_finite(self):
        self.assertEqual(tex_num(None), "?")
        self.assertEqual(tex_num(float("nan")), "?")
        self.assertEqual(tex_num(math.inf), r"\infty")  # K/4q at q = 0
        self.assertEqual(tex_num(-math.inf), r"-\infty")


if __name__ == "__main__":
    unittest.main()
