"""How a table cell reads (fusion.book.tables: cell_text, sci, tidy_table_html, use_book_tables): no NaN,
inf, True/False or e-notation in a published table, and one notation for powers of ten (1.5×10⁻⁷)."""

from __future__ import annotations

import re

import numpy as np
import pandas as pd
import pytest

from fusion.book.tables import cell_text, power_of_ten, sci, tidy_table_html, use_book_tables


@pytest.mark.parametrize("raw, shown", [
    ("NaN", "—"), ("nan", "—"), ("<NA>", "—"), ("None", "—"), (" NaN ", " — "),
    ("inf", "∞"), ("-inf", "-∞"), ("True", "yes"), ("False", "no"),
    ("1e-09", "10⁻⁹"), ("-2.952e+05", "-2.952×10⁵"), ("6.313e-05, 1.757", "6.313×10⁻⁵, 1.757"),
    ("1.5E-7", "1.5×10⁻⁷"),
    # left alone: words containing the tokens, plain numbers, identifiers with an e between digits
    ("Nantes", "Nantes"), ("True value", "True value"), ("0.000", "0.000"), ("2e", "2e"), ("x1e5", "x1e5"),
    ("Fig. 2e-3", "Fig. 2×10⁻³"),
])
def test_cell_text(raw, shown):
    assert cell_text(raw) == shown


@pytest.mark.parametrize("x, shown", [
    (1.5e-7, "1.5×10⁻⁷"), (-2.952e5, "-2.952×10⁵"), (1e-9, "10⁻⁹"), (0.1235, "0.1235"), (3, "3"),
    (np.int64(7), "7"), (float("nan"), "—"), (None, "—"), (float("inf"), "∞"), (-np.inf, "-∞"),
    (True, "yes"), (np.bool_(False), "no"), (0.0, "0"), (-0.0, "0"), (12345.678, "1.235×10⁴"),
])
def test_sci(x, shown):
    assert sci(x) == shown


def test_power_of_ten_and_bad_input():
    assert power_of_ten("1.5", -7) == "1.5×10⁻⁷"
    assert power_of_ten("-1", 3) == "-10³"
    with pytest.raises(TypeError):
        power_of_ten("1", 2.0)  # type: ignore[arg-type]
    with pytest.raises(TypeError):
        sci("1e-3")  # type: ignore[arg-type]
    with pytest.raises(TypeError):
        cell_text(1.0)  # type: ignore[arg-type]
    with pytest.raises(TypeError):
        tidy_table_html(None)  # type: ignore[arg-type]


def test_tidy_table_html_changes_cell_text_only():
    df = pd.DataFrame({"a": [np.nan, 1.5e-7], "ok": [True, False], "x": [np.inf, 2.0]},
                      index=pd.Index(["r1e5", "r2"], name="row"))
    html = df.style.format(precision=3, subset=["x"]).format("{:.4g}", subset=["a"]).set_uuid("t1e5").to_html()
    assert "nan" in html and "True" in html and "inf" in html           # pandas' own text
    tidy = tidy_table_html(html)
    text = " ".join(re.findall(r"<t[dh][^>]*>(.*?)</t[dh]>", tidy, re.S))
    assert "e-07" in html
    for raw in ("nan", "NaN", "True", "False", "inf", "e-07"):
        assert raw not in text
    for shown in ("—", "yes", "no", "∞", "1.5×10⁻⁷"):
        assert shown in text
    assert "T_t1e5" in tidy and "r1e5" in tidy                           # ids and labels untouched
    assert tidy_table_html(tidy) == tidy                                # idempotent


def test_use_book_tables_formats_dataframes_and_stylers_in_ipython():
    pytest.importorskip("IPython")
    from IPython.core.interactiveshell import InteractiveShell

    shell = InteractiveShell.instance()
    try:
        use_book_tables(shell)
        df = pd.DataFrame({"a": [np.nan, 1.0], "ok": [True, False]})
        for obj in (df, df.style.format(precision=2)):
            data, _ = shell.display_formatter.format(obj)
            assert "—" in data["text/html"] and "yes" in data["text/html"]
            assert ">NaN<" not in data["text/html"] and ">True<" not in data["text/html"]
    finally:
        InteractiveShell.clear_instance()


RAW = re.compile(r"^(NaN|nan|<NA>|&lt;NA&gt;|None|NaT|-?inf|True|False)$|(?<![\w.])\d+(\.\d+)?[eE][-+]?\d+(?![\w.])")


def raw_table_cells(html: str) -> list[str]:
    """Table cells of an HTML output that show a raw NaN, inf, True/False or an e-notation number."""
    cells = (re.sub(r"<[^>]*>", "", c).strip() for c in re.findall(r"<t[dh]\b[^>]*>(.*?)</t[dh]>", html, re.S))
    return [c for c in cells if RAW.search(c)]


def test_raw_table_cells_finds_what_it_should():
    html = "<table><tr><td>NaN</td><td>1.5e-07</td><td class='x'><b>True</b></td><td>Nantes</td><td>x1e5</td></tr></table>"
    assert raw_table_cells(html) == ["NaN", "1.5e-07", "True"]
    assert raw_table_cells(tidy_table_html(html)) == []


def test_stored_chapter_tables_print_no_raw_values():
    """No table in a chapter's stored outputs prints NaN, inf, True/False or e-notation (the book's
    notation: —, ∞, yes/no, 1.5×10⁻⁷), once the chapters run with use_book_style."""
    import json
    from pathlib import Path

    found = {}
    for nb in sorted((Path(__file__).resolve().parents[1] / "notebooks").glob("*.ipynb")):
        bad = []
        for cell in json.loads(nb.read_text(encoding="utf-8"))["cells"]:
            for out in cell.get("outputs", []):
                for mime, data in out.get("data", {}).items():
                    if mime.endswith("text/html"):
                        bad += raw_table_cells("".join(data) if isinstance(data, list) else data)
        if bad:
            found[nb.name] = f"{len(bad)} cells, e.g. {sorted(set(bad))[:6]}"
    assert not found, "\n".join(f"{k}: {v}" for k, v in found.items())


def test_a_table_with_a_repeated_column_is_refused_by_name() -> None:
    """fuzz 17: a repeated header made ``table[name]`` a frame and pandas raised an unnamed TypeError."""
    import pandas as pd
    import pytest

    from fusion.book.tables import mismatches

    t = pd.DataFrame([[1.0, 1.0, 1.0]], columns=["published x", "reproduced x", "published x"])
    with pytest.raises(ValueError, match=r"^table has repeated column names: \['published x'\]"):
        mismatches(t, 2)
