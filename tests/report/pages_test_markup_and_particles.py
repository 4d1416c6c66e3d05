"""Pages and figures made by the real CLI from folders the real binary writes: no HTML markup shown
as text (escaped tags on the page, tags in a matplotlib label), the particle engine named as the run
wrote it, the strips of the disks in the report of a run with frames (and a note without them), and
`granvv movie` writing the animation of those frames."""
import re
import subprocess
import unittest

import matplotlib.pyplot as plt
from markupsafe import escape
from PIL import Image

from report_fixtures import BINARY, TINY_MD, copy_of, granvv_run, scratch
from granvv_report import data, page  # noqa: F401 - page imports the figure modules, registering them
from granvv_report.registry import figures_of
from granvv_report.tables import particle_engine_label

ESCAPED_TAG = re.compile(r"&lt;/?(sub|sup|b|i|code|br)\b")
HTML_TAG = re.compile(r"</?(sub|sup|b|i|code|br)\b")
FRAMES = ["--set", "md.snapshot_interval=1"]   # TINY_MD runs to t = 5: six frames, t = 0 … 5


def granvv(*args, timeout=600):
    return subprocess.run([str(BINARY), *map(str, args)], capture_output=True, text=True, timeout=timeout)


def figure_texts(fig):
    """Every string a figure shows: titles, labels, tick labels, legend entries, annotations."""
    return [t.get_text() for t in fig.findobj(lambda a: hasattr(a, "get_text"))]


class ParticleRunReport(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.run_dir = granvv_run("md_haff", *TINY_MD, *FRAMES)

    def test_page_shows_no_markup_as_text_names_the_engine_and_draws_the_strips(self):
        out = copy_of(self.run_dir, self)
        done = granvv("report", out)
        self.assertEqual(done.returncode, 0, done.stderr)
        html = (out / "report.html").read_text()
        self.assertIsNone(ESCAPED_TAG.search(html), ESCAPED_TAG.search(html) and
                          html[ESCAPED_TAG.search(html).start() - 80:ESCAPED_TAG.search(html).end() + 40])
        self.assertIn("particle engine (event_driven)", html)
        self.assertNotIn("LAMMPS)", html.split("particle engine (")[1][:40])
        self.assertIn('src="figures/particles_strips.png"', html)
        with Image.open(out / "figures" / "particles_strips.png") as im:
            self.assertEqual(im.format, "PNG")

    def test_no_figure_label_holds_an_html_tag(self):
        # Every figure of a run page drawn on this run (the pressure at t = 5 among them): matplotlib
        # shows text as it is, so a tag in a title or legend would be printed raw.
        run = data.Run(self.run_dir)
        drawn = 0
        for spec in figures_of("run"):
            try:
                d = spec.draw(run)
            except data.Skip:
                continue
            drawn += 1
            for text in figure_texts(d.fig):
                self.assertIsNone(HTML_TAG.search(text), f"{spec.file}: {text!r}")
            plt.close(d.fig)
        self.assertGreaterEqual(drawn, 5)

    def test_movie_animates_every_frame(self):
        out = copy_of(self.run_dir, self)
        done = granvv("movie", out)
        self.assertEqual(done.returncode, 0, done.stderr)
        with Image.open(out / "movie.gif") as im:
            self.assertEqual(im.format, "GIF")
            self.assertEqual(im.n_frames, 6)
        elsewhere = scratch(self) / "m.gif"
        self.assertEqual(granvv("movie", out, "--out", elsewhere).returncode, 0)
        self.assertTrue(elsewhere.is_file())
        bad = granvv("movie", out, "--out", scratch(self) / "m.mp4")
        self.assertEqual(bad.returncode, 2)
        self.assertEqual(len(bad.stderr.strip().splitlines()), 1, bad.stderr)
        self.assertIn(".gif", bad.stderr)


class RunWithoutFrames(unittest.TestCase):
    def test_strips_are_skipped_with_a_note_and_movie_refuses_in_one_line(self):
        out = copy_of(granvv_run("md_haff", *TINY_MD), self)
        self.assertEqual(granvv("report", out).returncode, 0)
        html = (out / "report.html").read_text()
        self.assertNotIn('src="figures/particles_strips.png"', html)
        self.assertTrue(re.search(r"particles_strips\.png</code>: [^<]*md\.snapshot_interval", html),
                        "the strips are listed as skipped, with the key that makes frames")
        done = granvv("movie", out)
        self.assertEqual(done.returncode, 2)
        self.assertEqual(len(done.stderr.strip().splitlines()), 1, done.stderr)
        self.assertIn("md.snapshot_interval", done.stderr)


class EngineLabel(unittest.TestCase):
    def test_the_label_is_the_engine_the_summary_names(self):
        for engine in ("lammps", "event_driven"):
            run = data.Run(granvv_run("md_haff", "--set", f"md.engine={engine}", "--set", "md.particles=400",
                                      "--set", "md.box_width=40", "--set", "md.t_end=2",
                                      "--set", "md.output_times=[0, 2]", "--set", "md.ensemble=1",
                                      "--set", "md.sample_interval=1", "--set", "compare.enabled=false"))
            self.assertEqual(particle_engine_label(run.md_summary(), run.config_table("md")),
                             f"particle engine ({engine})")


class AtlasPage(unittest.TestCase):
    def test_recommendation_and_runs_table_show_powers_of_ten_not_tags(self):
        out = scratch(self) / "atlas"
        done = granvv("atlas", "haff", "--budget", "5", "--quiet", "--out", out)
        self.assertEqual(done.returncode, 0, done.stderr)
        html = (out / "atlas.html").read_text()
        self.assertIsNone(ESCAPED_TAG.search(html))
        # haff's hydro runs take 10³–10⁴ cell-steps: written with a power of ten in the runs table
        self.assertRegex(html, r"\d × 10[⁰¹²³⁴⁵⁶⁷⁸⁹]+ cell_steps")


class NumbersInsideText(unittest.TestCase):
    def test_a_power_of_ten_survives_an_f_string_and_escaping(self):
        from granvv_report.formatting import fmt
        self.assertEqual(str(escape(f"{fmt(3.3e4, 2)} cell-steps")), "3.3 × 10⁴ cell-steps")
        self.assertEqual(f"t = {fmt(5.3e4, 2)}", "t = 5.3 × 10⁴")


if __name__ == "__main__":
    unittest.main()
