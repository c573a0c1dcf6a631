"""Fuzz 22a, classes K, N, M, A, H, P, W, T and debatables D7, D8 (issue 35).

Each test is a reproducer of the fuzz report with the refusal or documented result the fix gives.
"""

from __future__ import annotations

import json
from pathlib import Path

import jsonschema
import pytest
import yaml
from hypothesis import given, settings, strategies as st

from fusion.book import claims as C, style

ROOT = Path(__file__).resolve().parents[1]


# K: the claim schema stays read-only for callers, and load validates against a plain copy jsonschema can read
def test_k_schema_is_a_json_schema_and_read_only():
    plain = json.loads(json.dumps(C.SCHEMA, default=dict))   # the documented way to a plain schema
    jsonschema.Draft202012Validator.check_schema(plain)
    with pytest.raises(TypeError):
        C.SCHEMA["required"] = []


@pytest.mark.parametrize("entry", [
    {"label": "x", "margin": {"relative": 0.05}, "zzz": 1},   # an extra field
    {"margin": {"relative": 0.05}},                          # no label
    {"label": "x", "margin": {"relative": -1}},              # a negative margin
    3.0,                                                      # not an object
])
def test_k_load_reports_a_quantities_subschema_error(tmp_path, entry):
    doc = yaml.safe_load((ROOT / "book" / "claims" / "lecture003.yaml").read_text(encoding="utf-8"))
    doc["quantities"]["mse"] = entry
    p = tmp_path / "lecture003.yaml"
    p.write_text(yaml.safe_dump(doc, allow_unicode=True), encoding="utf-8")
    with pytest.raises(C.ClaimsFileError, match=r"quantities"):
        C.load(p)
    # the schema load runs (not only load's own Python checks) reports it
    assert list(jsonschema.Draft202012Validator(C._PLAIN_SCHEMA).iter_errors(doc))


# N: one bound on an alt text, in characters, shared by set_figure_alt and png_description
def _png_of(fig):
    import io
    from fusion.book import style as S
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=10, metadata={"Description": S.figure_alt(fig)})
    return buf.getvalue()


@pytest.mark.parametrize("char", ["a", "é", "→"])   # tEXt (Latin-1) and iTXt (UTF-8, up to 3 bytes a character)
def test_n_alt_bound_is_characters_and_shared(char):
    import matplotlib.pyplot as plt
    from fusion.book import style as S
    fig, _ = S.new_figure()
    try:
        longest = char * S._MAX_DESCRIPTION
        S.set_figure_alt(fig, longest)          # at the bound: accepted, and read back whole
        assert S.png_description(_png_of(fig)) == longest
        with pytest.raises(ValueError, match="^alt must be at most 100,000 characters"):
            S.set_figure_alt(fig, longest + char)
        assert S.figure_alt(fig) == longest      # the refused alt left the figure's alt as it was
    finally:
        plt.close(fig)


def test_n_png_description_refuses_beyond_the_bound_in_characters():
    import struct
    import zlib
    from fusion.book import style as S

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))
    head = b"\x89PNG\r\n\x1a\n"
    text = ("→" * (S._MAX_DESCRIPTION + 1)).encode("utf-8")
    png = head + chunk(b"iTXt", b"Description\0\0\0\0\0" + text) + chunk(b"IEND", b"")
    with pytest.raises(ValueError, match="100,001 characters, beyond 100,000"):
        S.png_description(png)


# M: describe_figure keeps to MAX_ALT_CHARS, " …" included
@pytest.mark.parametrize("title", ["t" * 800, "word " * 200, "w" * 697 + " " + "x" * 50])
def test_m_describe_figure_at_most_max_alt_chars(title):
    import matplotlib.pyplot as plt
    from fusion.book import style as S
    fig, ax = S.new_figure()
    try:
        ax.set_title(title)
        out = S.describe_figure(fig)
        assert len(out) <= S.MAX_ALT_CHARS and out.endswith(" …")
    finally:
        plt.close(fig)


# P: power_of_ten's mantissa is the digits of a finite number
@pytest.mark.parametrize("m", ["", "nan", "abc", "1.5×10²", "inf", "1.", ".5", "1e3", " 1", "١"])
def test_p_power_of_ten_refuses_a_mantissa_that_is_not_digits(m):
    from fusion.book import tables as T
    with pytest.raises(ValueError, match="^mantissa must be the digits of a finite number"):
        T.power_of_ten(m, 3)


@given(st.decimals(allow_nan=False, allow_infinity=False, places=3), st.integers(-400, 400))
@settings(max_examples=100, deadline=None)
def test_p_power_of_ten_takes_every_finite_number_s_digits(d, e):
    from fusion.book import tables as T
    m = f"{d:f}"
    out = T.power_of_ten(m, e)
    assert out.endswith(str(e).translate(T._SUPERSCRIPT))


# H: highlight_mismatches' uuid is an HTML/CSS identifier
def _table():
    from fusion.book import tables as T
    return T.side_by_side([1.0, 2.0], [1.0, 2.1], ["a", "b"], decimals=1)


@pytest.mark.parametrize("uuid", ["", "a b", 'x"><img src=q>', "1abc", "-x", "a.b", "a#b", "é"])
def test_h_highlight_mismatches_refuses_a_uuid_that_is_not_an_identifier(uuid):
    from fusion.book import tables as T
    with pytest.raises(ValueError, match="^uuid must be an HTML id prefix"):
        T.highlight_mismatches(_table(), 1, uuid=uuid)


@given(st.from_regex(r"[A-Za-z][A-Za-z0-9_-]{0,20}", fullmatch=True))
@settings(max_examples=30, deadline=None)
def test_h_highlight_mismatches_takes_an_identifier_and_the_highlight_reaches_its_cell(uuid):
    from fusion.book import tables as T
    html = T.highlight_mismatches(_table(), 1, uuid=uuid).to_html()
    assert f"#T_{uuid}_row1_col1" in html and f'id="T_{uuid}_row1_col1"' in html


# T: a wrong type is a TypeError naming the argument; the caller's argument is the one named
@pytest.mark.parametrize("chapter", [2, Path("notebooks/02_b"), b"notebooks/02_b", 2.0])
def test_t_ledger_file_refuses_a_chapter_that_is_not_a_str(chapter):
    from fusion.book.ledger import Source
    s = Source("k", "s", "t", "notebooks/01_a", 1, ("notebooks/01_a", "notebooks/02_b"))
    with pytest.raises(TypeError, match="^chapter must be"):
        s.ledger_file(chapter)
    assert s.ledger_file("notebooks/02_b") == "k-02.json" and s.ledger_file() == "k-01.json"


def test_t_stochastic_readings_names_root(tmp_path):
    from fusion.book import stability as S
    f = tmp_path / "README.md"
    f.write_text("x")
    for root in (f, tmp_path / "missing"):
        with pytest.raises(ValueError, match="^root must be"):
            S.stochastic_readings(root)
    with pytest.raises(TypeError, match="^root must be"):
        S.stochastic_readings(3)


# W: a folder or a dangling symlink under a ledger file's name, in a valid folder
def _make(p, kind):
    import os
    if kind == "dir":
        p.mkdir()
    else:
        os.symlink(p.parent / "nonexistent-target", p)


def _ledger():
    from fusion.book.ledger import Claim, Ledger, Proposition
    L = Ledger("lecture003", "notebooks/02_lecture_weighting")
    L.add(Claim("lec-x-1", "lecture003", "§1", "a claim", "1.0", Proposition(True, "ok"), "https://example.org",
                headline=True))
    return L


@pytest.mark.parametrize("kind", ["dir", "link"])
def test_w_ledger_write_refuses_a_non_file_under_the_file_s_name(tmp_path, kind):
    L = _ledger()
    _make(tmp_path / L.filename, kind)
    with pytest.raises(ValueError, match=rf"^directory holds {L.filename}, which is"):
        L.write(tmp_path)


def test_w_ledger_write_overwrites_a_file_and_follows_a_link_to_one(tmp_path):
    L = _ledger()
    target = tmp_path / "elsewhere.json"
    target.write_text("not json")
    (tmp_path / L.filename).symlink_to(target)
    L.write(tmp_path)
    assert json.loads(target.read_text(encoding="utf-8"))["source"] == "lecture003"


@pytest.mark.parametrize("kind", ["dir", "link"])
def test_w_stochastic_readings_refuses_a_non_file_ledger_entry_naming_it(tmp_path, kind):
    import shutil
    from fusion.book import stability as S
    (tmp_path / "_toc.yml").write_text("format: jb-book\nroot: index\n")
    shutil.copytree(ROOT / "book" / "claims", tmp_path / "book" / "claims")
    shutil.copytree(ROOT / "book" / "ledger", tmp_path / "book" / "ledger")
    assert S.stochastic_readings(tmp_path)          # the copy reads
    _make(tmp_path / "book" / "ledger" / "zz.json", kind)
    with pytest.raises(ValueError, match=r"^ledger file .*zz\.json: not a readable file"):
        S.stochastic_readings(tmp_path)


# A: new_figure's dpi and figsize checked by name before any figure is made; audit_figure checks the size first
@pytest.mark.parametrize("kw,name,kind", [
    (dict(dpi=1e4), "dpi", ValueError), (dict(dpi=float("nan")), "dpi", ValueError), (dict(dpi=0), "dpi", ValueError),
    (dict(dpi=-5), "dpi", ValueError), (dict(dpi="100"), "dpi", TypeError),
    (dict(figsize=(1e6, 1e6)), "figsize", ValueError), (dict(figsize=(7.5, 1e5)), "figsize", ValueError),
    (dict(figsize=(float("nan"), 3)), "figsize", ValueError), (dict(figsize=(1e-6, 1e-6)), "figsize", ValueError),
    (dict(figsize=7.5), "figsize", TypeError), (dict(figsize=(7.5, 3, 1)), "figsize", TypeError),
])
def test_a_new_figure_refuses_a_size_or_dpi_outside_the_book_s_range(kw, name, kind):
    import matplotlib.pyplot as plt
    from fusion.book import style as S
    before = plt.get_fignums()
    with pytest.raises(kind, match=f"^{name} must be"):
        S.new_figure(1, 1, **kw)
    assert plt.get_fignums() == before      # refused before any figure was made


@given(st.floats(*style.FIGURE_SIDE_RANGE_IN), st.floats(*style.FIGURE_SIDE_RANGE_IN),
       st.sampled_from([72, 100, 150.0]))
@settings(max_examples=15, deadline=None)
def test_a_new_figure_takes_sizes_within_the_range(w, h, dpi):
    import matplotlib.pyplot as plt
    from fusion.book import style as S
    fig, _ = S.new_figure(1, 1, figsize=(w, h), dpi=dpi)
    try:
        assert tuple(fig.get_size_inches()) == pytest.approx((w, h)) and fig.get_dpi() == pytest.approx(dpi)
    finally:
        plt.close(fig)


@pytest.mark.parametrize("size,dpi,wide", [((1e6, 1e6), 100, True), ((7.5, 1e5), 100, False),
                                           ((7.0, 3.0), 1e4, False), ((30.0, 3.0), 100, True)])
def test_a_audit_figure_reports_the_size_before_drawing(monkeypatch, size, dpi, wide):
    import matplotlib.pyplot as plt
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from fusion.book import figures as F
    fig = plt.figure(figsize=(7.0, 3.0))
    try:
        fig.set_size_inches(*size)
        fig.set_dpi(dpi)
        monkeypatch.setattr(FigureCanvasAgg, "draw", lambda self: pytest.fail("drew the figure"))
        with pytest.raises(F.FigureStyleError, match="figure not drawn: its (figsize|dpi) must be") as e:
            F.audit_figure(fig)
        assert ("in wide (> 7.5 in)" in str(e.value)) == wide
    finally:
        plt.close(fig)


# D7 (decided: documented): plain_math drops every brace, balanced or not, and never raises on malformed TeX
@given(st.text(alphabet="${}\\^_ abfrcsigma0123", max_size=40))
@settings(max_examples=100, deadline=None)
def test_d7_plain_math_gives_plain_text_for_any_formula(tex):
    from fusion.book import style as S
    out = S.plain_math(tex)
    assert not set(out) & set("${}\\") and out == " ".join(out.split())


def test_d7_plain_math_documented_examples():
    from fusion.book import style as S
    assert S.plain_math("$\\frac{a}{b}$") == "fracab" and S.plain_math("$\\frac{a}{") == "fraca"


# D8 (decided: documented): side_by_side refuses a NaN or infinite value; a table built otherwise skips it
@pytest.mark.parametrize("bad", [float("nan"), float("inf")])
def test_d8_side_by_side_refuses_a_missing_value_naming_it(bad):
    from fusion.book import tables as T
    with pytest.raises(ValueError, match="^published"):
        T.side_by_side([1.0, bad], [1.0, 2.0], ["a", "b"])
    with pytest.raises(ValueError, match="^reproduced"):
        T.side_by_side([1.0, 2.0], [1.0, bad], ["a", "b"])


def test_d8_mismatches_skips_a_missing_published_value_in_a_table_built_otherwise():
    import numpy as np
    from fusion.book import tables as T
    tab = T.side_by_side([1.0, 2.0], [1.0, 2.5], ["a", "b"], decimals=1)
    tab.iloc[1, 0] = np.nan
    assert not T.mismatches(tab, 1).to_numpy().any()
    assert "—" in T.highlight_mismatches(tab, 1, uuid="d8").to_html()
