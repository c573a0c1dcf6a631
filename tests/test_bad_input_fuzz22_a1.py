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

from fusion.book import claims as C

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
