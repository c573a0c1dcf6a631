"""Fuzz 21a, classes L, S, K, N, G, W, M and debatables D2-D4, D6, D8, D12, D13 (issue 35).

Each test is a reproducer of the fuzz report with the refusal or documented result the fix gives. The rules are
shared: a folder argument goes through ``fusion._paths.folder`` (class L and ``source_digest``, class S).
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from hypothesis import given, settings, strategies as st

from fusion.book import claims as C
from fusion.book import ledger as L
from fusion.book.study_cache import source_digest

ROOT = Path(__file__).resolve().parents[1]


def _ledger() -> L.Ledger:
    led = L.Ledger("lecture003")
    led.add(L.Claim("x-1", "lecture003", "§1", "a claim", "1.0", L.Proposition(True, "ok"), "https://example.org",
                    headline=True))
    return led


# ---------------------------------------------------------------- class L: folder arguments, one rule

def _folder_calls(tmp_path):
    """Every public function taking a folder, as (call, argument name); each call takes the folder value."""
    return [(lambda v: _ledger().write(v), "directory"), (L.ledger_dir, "start"), (C.claims_dir, "start"),
            (C.load_all, "directory"), (source_digest, "package")]


def test_l1_write_takes_a_str_folder(tmp_path):
    target = tmp_path / "new" / "ledger"
    digest = _ledger().write(str(target))
    assert digest == _ledger().write(target) and (target / _ledger().filename).is_file()


@pytest.mark.parametrize("bad", [5, None.__class__, b"/tmp", ["x"]])
def test_l2_wrong_type_is_a_type_error_naming_the_argument(tmp_path, bad):
    for call, name in _folder_calls(tmp_path):
        with pytest.raises(TypeError, match=f"^{name} must be a path"):
            call(bad)


def test_l3_a_file_where_a_folder_is_wanted(tmp_path):
    f = tmp_path / "afile"
    f.write_text("x")
    for call, name in _folder_calls(tmp_path):
        with pytest.raises(ValueError, match=f"^{name} must be a folder"):
            call(f)
        with pytest.raises(ValueError, match=f"^{name} must be a folder"):
            call(str(f))


@settings(max_examples=25, deadline=None)
@given(st.sampled_from(["long", "nul", "long-component"]), st.booleans())
def test_l4_l7_unusable_names_are_named_not_echoed(kind, as_str):
    base = str(ROOT / "tests")
    value = {"long": "/work/" + "a" * 5000, "nul": base + "/a\x00b", "long-component": base + "/" + "a" * 300}[kind]
    for call, name in _folder_calls(None):
        with pytest.raises(ValueError, match=f"^{name}") as err:
            call(value if as_str else Path(value))
        assert len(str(err.value)) < 200


def test_l_missing_folder_refused_except_where_it_is_made(tmp_path):
    missing = tmp_path / "missing"
    for call, name in _folder_calls(tmp_path)[1:]:
        with pytest.raises(ValueError, match=f"^{name} must be an existing folder"):
            call(missing)
    assert not missing.exists()
    _ledger().write(missing)
    assert missing.is_dir()


def test_l_valid_folders_keep_working():
    assert L.ledger_dir(ROOT / "tests") == L.ledger_dir(str(ROOT)) == ROOT / "book" / "ledger"
    assert C.claims_dir(str(ROOT / "tests")) == ROOT / "book" / "claims"
    assert set(C.load_all(str(ROOT / "book" / "claims"))) == set(C.load_all())


# ---------------------------------------------------------------- class S: source_digest resolves before caching

def test_s1_relative_name_is_resolved_before_the_cache(tmp_path, monkeypatch):
    for tree, body in (("one", "x = 1\n"), ("two", "x = 2\n")):
        (tmp_path / tree / "pkg").mkdir(parents=True)
        (tmp_path / tree / "pkg" / "a.py").write_text(body)
    monkeypatch.chdir(tmp_path / "one")
    first = source_digest("pkg")
    monkeypatch.chdir(tmp_path / "two")
    second = source_digest("pkg")
    assert first != second
    assert second == source_digest(tmp_path / "two" / "pkg")
    assert first == source_digest(os.fspath(tmp_path / "one" / "pkg"))
