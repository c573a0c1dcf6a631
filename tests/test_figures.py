"""The figure audit (fusion.book.figures): each rule caught on a figure that breaks it, passed on one that does not."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt
import numpy as np
import pytest

from fusion.book import style
from fusion.book.figures import OKABE_ITO, FigureStyleError, allowed_colors, audit_figure


@pytest.fixture(autouse=True)
def _close():
    style.use_book_style()
    yield
    plt.close("all")


def _good():
    fig, ax = plt.subplots(figsize=(6.0, 3.0))
    x = np.linspace(0.0, 1.0, 50)
    ax.plot(x, x, color=style.color("mean"), label=style.METHOD_LABELS["mean"])
    ax.plot(x, x ** 2, color=style.color("optimal_fusion_set"), label=style.METHOD_LABELS["optimal_fusion_set"])
    ax.axhline(0.5, color="0.6", ls=":")
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0))
    return fig, ax


def test_a_figure_that_follows_the_rules_passes():
    fig, _ = _good()
    assert audit_figure(fig) == []


def test_registry_colours_are_in_the_palette():
    assert set(c.upper() for c in OKABE_ITO) <= allowed_colors()
    assert all(c.upper() in allowed_colors() for c in style.METHOD_COLORS.values())


def test_matplotlib_default_colour_is_rejected():
    fig, ax = _good()
    ax.plot([0, 1], [1, 0], color="C0")          # #1F77B4, not Okabe-Ito
    with pytest.raises(FigureStyleError, match="#1F77B4"):
        audit_figure(fig)


def test_a_method_in_another_colour_is_rejected():
    fig, ax = plt.subplots(figsize=(6.0, 3.0))
    ax.plot([0, 1], [0, 1], color=style.color("optimal_fusion_set"), label=style.METHOD_LABELS["mean"])
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0))
    with pytest.raises(FigureStyleError, match="registered colour"):
        audit_figure(fig)


def test_an_internal_key_as_label_is_rejected():
    fig, ax = plt.subplots(figsize=(6.0, 3.0))
    ax.plot([0, 1], [0, 1], color=style.color("optimal_fusion_set"), label="optimal_fusion_set")
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0))
    with pytest.raises(FigureStyleError, match="internal key"):
        audit_figure(fig)


def test_small_text_is_rejected():
    fig, ax = _good()
    ax.set_title("tiny", fontsize=7)
    with pytest.raises(FigureStyleError, match="7.0 pt"):
        audit_figure(fig)


def test_a_legend_over_the_data_is_rejected_and_outside_is_not():
    fig, ax = plt.subplots(figsize=(6.0, 3.0))
    x = np.linspace(0.0, 1.0, 200)
    ax.plot(x, np.full_like(x, 0.95), color=style.color("mean"), label=style.METHOD_LABELS["mean"])
    ax.set_ylim(0.0, 1.0)
    ax.legend(loc="upper right")
    with pytest.raises(FigureStyleError, match="legend covers data"):
        audit_figure(fig)
    ax.legend(loc="lower left")               # empty corner: passes
    assert audit_figure(fig) == []


def test_a_too_wide_figure_is_rejected():
    fig, ax = plt.subplots(figsize=(10.0, 3.0))
    ax.plot([0, 1], [0, 1], color="k")
    with pytest.raises(FigureStyleError, match="wide"):
        audit_figure(fig)


def test_colour_maps_viridis_passes_jet_fails():
    fig, ax = plt.subplots(figsize=(5.0, 3.0))
    z = np.add.outer(np.arange(5.0), np.arange(5.0))
    ax.contour(z, cmap="viridis")
    assert audit_figure(fig) == []
    ax.contour(z, cmap="jet")
    with pytest.raises(FigureStyleError, match="jet"):
        audit_figure(fig)


def test_every_breach_is_listed_at_once():
    fig, ax = plt.subplots(figsize=(9.0, 3.0))
    ax.plot([0, 1], [0, 1], color="C1")
    ax.set_xlabel("x", fontsize=6)
    with pytest.raises(FigureStyleError) as err:
        audit_figure(fig)
    text = str(err.value)
    assert "wide" in text and "#FF7F0E" in text and "6.0 pt" in text


def test_not_a_figure():
    with pytest.raises(TypeError, match="fig"):
        audit_figure("figure")


def test_method_style_gives_the_registered_colour_label_and_marker():
    kw = style.method_style("optimal_fusion_set", markers=True)
    assert kw["color"] == style.METHOD_COLORS["optimal_fusion_set"]
    assert kw["label"] == style.METHOD_LABELS["optimal_fusion_set"] and kw["marker"] == "o"
    assert "marker" not in style.method_style("optimal_fusion_set")
    with pytest.raises(ValueError, match="method"):
        style.method_style("no such method")


def test_registry_is_colour_blind_safe_and_consistent():
    for key, colour in style.METHOD_COLORS.items():
        h = colour.upper()
        grey = len({h[1:3], h[3:5], h[5:7]}) == 1
        assert h in OKABE_ITO or grey, f"{key}: {colour} is neither Okabe-Ito nor grey"
    assert set(style.METHOD_MARKERS) <= set(style.METHOD_COLORS)
    assert set(style.METHOD_LINESTYLES) <= set(style.METHOD_COLORS)


def test_errorbars_scatter_and_bands_are_audited_and_scatter_under_a_legend_is_caught():
    fig, ax = plt.subplots(figsize=(6.0, 3.0))
    ax.errorbar([0.2, 0.5], [0.2, 0.5], xerr=[0.05, 0.05], fmt="o", color=style.color("mean"), label="sensor 1")
    ax.fill_between([0.0, 1.0], [0.0, 0.1], [0.1, 0.2], color="0.85")
    ax.scatter([0.95], [0.95], color=style.color("mean"), label="sensor 2")
    ax.set(xlim=(0, 1), ylim=(0, 1))
    ax.legend(loc="lower right")
    assert audit_figure(fig) == []
    ax.legend(loc="upper right")
    with pytest.raises(FigureStyleError, match="legend covers data"):
        audit_figure(fig)


def test_registry_has_no_key_written_twice():
    """Chapters add their blocks to the registry; a key written twice would silently take the last colour."""
    import ast
    import collections
    from pathlib import Path

    tree = ast.parse(Path(style.__file__).read_text(encoding="utf-8"))
    seen = 0
    for node in ast.walk(tree):
        value = getattr(node, "value", None) if isinstance(node, ast.AnnAssign) else None
        if isinstance(value, ast.Call) and getattr(value.func, "id", "") == "constant" and value.args:
            value = value.args[0]   # a registry made read-only: constant({...})
        if isinstance(value, ast.Dict):
            seen += 1
            keys = [k.value for k in value.keys if isinstance(k, ast.Constant)]
            dups = [k for k, c in collections.Counter(keys).items() if c > 1]
            assert not dups, f"{node.target.id}: {dups}"
    assert seen >= 2, "no registry dict literal found in style.py: the check would pass without checking anything"


def test_a_label_outside_the_registry_is_rejected_and_registered_kinds_pass():
    fig, ax = _good()
    ax.plot([0, 1], [1, 0], color="0.5", label="my new method")
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0))
    with pytest.raises(FigureStyleError, match="'my new method' is not in the registry"):
        audit_figure(fig)
    plt.close(fig)
    fig, ax = _good()
    for lab in ("true path", "sensor 2", f"{style.METHOD_LABELS['median']} [causal]", "x = 0.5"):
        ax.plot([0, 1], [0.2, 0.3], color="0.5", label=lab)
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0))
    assert audit_figure(fig) == []


@pytest.mark.parametrize(("label", "ok"), [
    ("sensor 3", True), ("sensors 4 and 10 fail", True), ("sensor 1 (run 1)", True),
    ("median [look-ahead]", True), ("not a method [causal]", False),   # the suffix needs a registered method
    ("x = 10", True), ("x = ten", False), ("median, run 3", True), ("", False), ("published!", False),
])
def test_is_registered_label(label: str, ok: bool):
    assert style.is_registered_label(label) is ok


def test_every_registered_pattern_is_a_valid_regular_expression_and_label_sets_are_disjoint_from_keys():
    import re

    for pattern, meaning in style.LABEL_PATTERNS:
        re.compile(pattern)
        assert meaning
    internal = {k for k, lab in style.METHOD_LABELS.items() if k != lab}
    assert not internal & style.FIGURE_LABELS      # a non-method label never reads like an internal key
    with pytest.raises(TypeError, match="label"):
        style.is_registered_label(3)


@pytest.fixture
def png_kernel():
    """IPython's inline PNG formatter registered as in a notebook kernel (bbox_inches="tight"), removed after."""
    from IPython.core import pylabtools
    from IPython.core.interactiveshell import InteractiveShell
    from matplotlib.figure import Figure

    shell = InteractiveShell.instance()
    pylabtools.select_figure_formats(shell, {"png"}, bbox_inches="tight")
    yield shell
    shell.display_formatter.formatters["image/png"].pop(Figure, None)


def _figure(seed: int):
    rng = np.random.default_rng(seed)
    fig, axes = style.new_figure(1, 2, figsize=(6.5, 3.0))
    for ax in axes:
        x = np.linspace(0.0, 10.0 ** rng.uniform(0, 3), 200)
        for key in ("mean", "optimal_fusion_set"):
            ax.plot(x, np.cumsum(rng.normal(size=200)) * 10.0 ** rng.uniform(-3, 5), **style.method_style(key))
        ax.set_xlabel("frame")
        ax.set_ylabel("error (m)")
    axes[1].legend(loc="upper left", bbox_to_anchor=(1.01, 1.0))
    return fig


@pytest.mark.parametrize("seed", range(6))
def test_glue_figure_stores_the_bytes_of_audit_then_glue_and_renders_once(png_kernel, monkeypatch, seed: int) -> None:
    """The one-render glue_figure displays exactly what audit_figure + myst_nb.glue displayed (PNG bytes, metadata).

    Constrained layout moves on its second run: without the layout run that replaces the audit's draw,
    the PNG of every one of these six figures would differ (checked when this was written)."""
    import IPython.display
    import myst_nb.ext.glue as nbglue
    from matplotlib.figure import Figure

    from fusion.book.figures import glue_figure

    shown: list[tuple] = []
    record = lambda obj, **kw: shown.append((obj, kw))  # noqa: E731
    monkeypatch.setattr(nbglue, "ipy_display", record)
    monkeypatch.setattr(IPython.display, "display", record)
    fig = _figure(seed)
    audit_figure(fig)
    nbglue.glue("k", fig, display=False)  # the old path
    draws = []
    monkeypatch.setattr(Figure, "draw", lambda self, r, _d=Figure.draw: (draws.append(r), _d(self, r))[1])
    glue_figure("k", _figure(seed))
    (old, old_kw), (new, new_kw) = shown
    assert old == new and old_kw == new_kw
    assert any(k.endswith("image/png") for k in new)
    assert len(draws) == 2  # tight-bbox layout pass + the PNG (before: the audit's full draw as well)


def test_glue_figure_audits_the_png_render(png_kernel, monkeypatch) -> None:
    import IPython.display

    from fusion.book.figures import glue_figure

    monkeypatch.setattr(IPython.display, "display", lambda *a, **k: pytest.fail("a bad figure was glued"))
    fig, ax = _good()
    ax.plot([0, 1], [0, 1], color="#ff0000", label=style.METHOD_LABELS["mean"])
    with pytest.raises(FigureStyleError, match="not in the registry's palette"):
        glue_figure("k", fig)
    fig, ax = plt.subplots(figsize=(6.0, 3.0))
    x = np.linspace(0.0, 1.0, 50)
    ax.plot(x, x, color=style.color("mean"), label=style.METHOD_LABELS["mean"])
    ax.legend(loc="center")  # over the line
    with pytest.raises(FigureStyleError, match="legend covers data"):
        glue_figure("k", fig)
    fig, ax = plt.subplots(figsize=(9.0, 3.0))  # too wide: measured before the tight bbox shrinks the print
    ax.plot([0, 1], [0, 1], color=style.color("mean"))
    with pytest.raises(FigureStyleError, match="wide"):
        glue_figure("k", fig)


# --------------------------------------------------------------------------- alt text (issue 28)


def test_describe_figure_says_what_is_plotted():
    fig, ax = _good()
    ax.set_xlabel("time (s)")
    ax.set_ylabel(r"RMSE $\sigma_{\rm max}$ (m)")
    text = style.describe_figure(fig)
    assert text.startswith("Line chart of RMSE σ_max (m) against time (s)")
    assert style.METHOD_LABELS["mean"] in text and style.METHOD_LABELS["optimal_fusion_set"] in text
    fig2, axes = plt.subplots(1, 2, figsize=(6.0, 3.0))
    axes[0].scatter([0, 1], [1, 0], color=style.color("mean"))
    axes[1].bar([0, 1], [1, 2], color=style.color("mean"))
    axes[1].set_title("counts")
    text2 = style.describe_figure(fig2)
    assert text2.startswith("2 panels.") and "Scatter plot" in text2 and "Panel 2 (counts): Bar chart" in text2
    fig3, ax3 = plt.subplots(figsize=(6.0, 3.0))
    ax3.plot([0, 1], [0, 1], color=style.color("mean"))          # two points are a line
    ax3.axhline(0.5, color="0.6")                                 # a reference line alone is not
    ax3.set_xlabel("time (s)")
    assert style.describe_figure(fig3) == "Line chart against time (s)."
    fig4, ax4 = plt.subplots(figsize=(6.0, 3.0))
    ax4.axhline(0.5, color="0.6")
    assert style.describe_figure(fig4) == "Plot."
    with pytest.raises(TypeError):
        style.describe_figure("not a figure")  # type: ignore[arg-type]


def test_alt_text_set_on_a_figure_wins_and_paths_are_refused():
    fig, _ = _good()
    assert style.figure_alt(fig) == style.describe_figure(fig)
    style.set_figure_alt(fig, "The mean's error grows linearly; the optimal set's quadratically.")
    assert style.figure_alt(fig).startswith("The mean's error")
    style.set_figure_alt(fig, None)
    assert style.figure_alt(fig) == style.describe_figure(fig)
    for bad in ("", "   ", "../_images/abc.png", "figures/fig1.svg", "_images/x"):
        with pytest.raises(ValueError):
            style.set_figure_alt(fig, bad)


def test_notebook_png_carries_its_alt_text():
    """In IPython, use_book_style's PNG formatter writes the figure's alt text into the PNG, which
    book/_ext/fusion_figures.py reads back (png_description)."""
    import base64

    from IPython.core.interactiveshell import InteractiveShell

    shell = InteractiveShell.instance()
    try:
        style.use_book_style()                       # inside IPython now: retina PNG + descriptions
        fig, _ = _good()
        style.set_figure_alt(fig, "Two curves: σ of the mean against ω.")
        data, meta = shell.display_formatter.format(fig)
        png = data["image/png"]
        png = base64.b64decode(png) if isinstance(png, str) else png
        assert style.png_description(png) == "Two curves: σ of the mean against ω."
        import struct

        assert struct.unpack(">I", png[16:20])[0] // 2 == meta["image/png"]["width"]   # retina: 2× pixels
        style.set_figure_alt(fig, None)
        data, _ = shell.display_formatter.format(fig)
        png = data["image/png"]
        png = base64.b64decode(png) if isinstance(png, str) else png
        assert style.png_description(png) == style.describe_figure(fig)
    finally:
        InteractiveShell.clear_instance()


def test_png_description_reads_text_chunks_and_ignores_other_files(tmp_path):
    import io

    fig, _ = _good()
    for text in ("plain latin-1 text", "Unicode: σ², ω ∈ [0, 1]"):
        buf = io.BytesIO()
        fig.savefig(buf, format="png", metadata={"Description": text})
        assert style.png_description(buf.getvalue()) == text
    buf = io.BytesIO()
    fig.savefig(buf, format="png")
    assert style.png_description(buf.getvalue()) is None
    assert style.png_description(b"GIF89a...") is None


def test_glue_figure_attaches_the_registry_alt_text(monkeypatch):
    import IPython.display

    from fusion.book import figures

    seen = {}
    monkeypatch.setattr(IPython.display, "display", lambda *a, **k: None)
    monkeypatch.setattr(plt, "close", lambda fig: seen.update(alt=style.figure_alt(fig)))
    # the registry is read-only (a public constant): the test swaps in another one
    monkeypatch.setattr(style, "FIGURE_ALT", style.FIGURE_ALT | {"test_fig_key": "Registry text: what the figure shows."})
    fig, _ = _good()
    figures.glue_figure("test_fig_key", fig)
    assert seen["alt"] == "Registry text: what the figure shows."
    fig, _ = _good()
    figures.glue_figure("test_fig_key", fig, alt="Argument text: wins over the registry.")
    assert seen["alt"] == "Argument text: wins over the registry."
    fig, _ = _good()
    figures.glue_figure("other_key", fig)
    assert seen["alt"] == style.describe_figure(fig)
