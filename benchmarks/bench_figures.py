"""Issue 37, item 3: what publishing a figure costs, before and after the one-render ``glue_figure``.

Before: ``audit_figure`` drew the figure on Agg (a full render), then ``myst_nb.glue`` had IPython's PNG
formatter draw it twice (the layout pass of ``bbox_inches="tight"`` and the PNG). Now: one run of the
layout engine, the layout pass and the PNG, the audit made on the PNG's render. Both paths are timed
alternately on the same figures (IPython's inline PNG formatter registered as in a kernel; the display
itself replaced by a no-op), 9 repeats, median; the PNG bytes of both are compared.

Writes ``benchmarks/results/figures.json``. Run: ``.venv/bin/python benchmarks/bench_figures.py``
"""

from __future__ import annotations

import os
import statistics
import sys
import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import IPython.display  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import myst_nb.ext.glue as nbglue  # noqa: E402
import numpy as np  # noqa: E402
from IPython.core import pylabtools  # noqa: E402
from IPython.core.interactiveshell import InteractiveShell  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _results import write_results  # noqa: E402

from fusion.book import figures as book_figures  # noqa: E402
from fusion.book import style  # noqa: E402
from fusion.book.figures import audit_figure, glue_figure  # noqa: E402

REPEATS = 9


def figure(seed: int):
    """A two-panel figure in the book's style: two methods per panel, log axis, legend outside."""
    rng = np.random.default_rng(seed)
    fig, axes = style.new_figure(1, 2, figsize=(6.5, 3.0))
    for ax in axes:
        x = np.linspace(0.0, 10.0 ** rng.uniform(0, 3), 200)
        for key in ("mean", "optimal_fusion_set"):
            ax.plot(x, np.abs(np.cumsum(rng.normal(size=200))) * 10.0 ** rng.uniform(-3, 5) + 1e-3,
                    **style.method_style(key))
        ax.set_yscale("log")
        ax.set_xlabel("frame")
        ax.set_ylabel("error (m)")
    axes[1].legend(loc="upper left", bbox_to_anchor=(1.01, 1.0))
    return fig


def main() -> None:
    shell = InteractiveShell.instance()
    pylabtools.select_figure_formats(shell, {"png"}, bbox_inches="tight")
    shown: list = []
    keep = lambda obj, **kw: shown.append(obj)  # noqa: E731
    nbglue.ipy_display = keep
    IPython.display.display = keep
    style.use_book_style()

    def old(seed: int) -> None:
        fig = figure(seed)
        audit_figure(fig)
        nbglue.glue("k", fig, display=False)
        plt.close(fig)

    def new(seed: int) -> None:
        glue_figure("k", figure(seed))

    def one_layout(seed: int) -> None:
        book_figures.RELAYOUT_BEFORE_PNG = False
        try:
            glue_figure("k", figure(seed))
        finally:
            book_figures.RELAYOUT_BEFORE_PNG = True

    seeds = range(6)
    same, same_one = [], []
    for s in seeds:
        shown.clear()
        old(s)
        new(s)
        one_layout(s)
        same.append(shown[0] == shown[1])
        same_one.append(shown[0] == shown[2])
    times: dict[str, list[float]] = {"old": [], "new": [], "one_layout": []}
    fns = {"old": old, "new": new, "one_layout": one_layout}
    for r in range(REPEATS):
        names = list(fns) if r % 2 == 0 else list(fns)[::-1]
        for name in names:
            t0 = time.process_time()
            for s in seeds:
                fns[name](s)
            times[name].append((time.process_time() - t0) / len(seeds))
    mo, mn, m1 = (statistics.median(times[k]) for k in ("old", "new", "one_layout"))
    write_results("figures", [
        {"key": "figure_old_s", "what": "publish one figure: audit draw + glue (3 draws), CPU", "value": mo, "unit": "s"},
        {"key": "figure_new_s", "what": "publish one figure: layout run + one render audited (landed), CPU",
         "value": mn, "unit": "s"},
        {"key": "figure_speedup", "what": "old / new (landed)", "value": mo / mn, "unit": "x"},
        {"key": "figure_png_identical", "what": f"figures whose stored PNG and metadata are identical (of {len(same)})",
         "value": float(sum(same)), "unit": ""},
        {"key": "figure_one_layout_s", "what": "option RELAYOUT_BEFORE_PNG=False: one layout fewer, CPU",
         "value": m1, "unit": "s"},
        {"key": "figure_one_layout_speedup", "what": "old / option", "value": mo / m1, "unit": "x"},
        {"key": "figure_one_layout_png_identical", "what": f"option: figures whose PNG is identical (of {len(same)})",
         "value": float(sum(same_one)), "unit": ""},
    ], repeats=REPEATS, statistic="median of interleaved repeats (process CPU time)",
        load_average_at_end=os.getloadavg())


if __name__ == "__main__":
    main()
