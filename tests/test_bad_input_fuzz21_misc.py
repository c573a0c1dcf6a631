"""Fuzz 21a, classes L, S, K, N, G, W, M and debatables D2-D4, D6, D8, D12, D13 (issue 35).

Each test is a reproducer of the fuzz report with the refusal or documented result the fix gives. The rules are
shared: a folder argument goes through ``fusion._paths.folder`` (class L and ``source_digest``, class S).
"""

from __future__ import annotations

import dataclasses
import importlib
import inspect
import io
import math
import os
import pkgutil
import struct
import time
import zlib
from collections.abc import Mapping
from decimal import Decimal
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings, strategies as st

from fusion._frozen import ReadOnlyMapping, constant
from fusion.book import claims as C
from fusion.book import ledger as L
from fusion.book.figures import glue_figure
from fusion.book.glue import glue_all
from fusion.book.style import new_figure, png_description
from fusion.book.tables import side_by_side
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
        (tmp_path / tree / "pkg" / "__init__.py").write_text("")
    monkeypatch.chdir(tmp_path / "one")
    first = source_digest("pkg")
    monkeypatch.chdir(tmp_path / "two")
    second = source_digest("pkg")
    assert first != second
    assert second == source_digest(tmp_path / "two" / "pkg")
    assert first == source_digest(os.fspath(tmp_path / "one" / "pkg"))


# ---------------------------------------------------------------- class G / D6: glue_all's finiteness rule

@pytest.mark.parametrize("bad", [Decimal("sNaN"), Decimal("NaN"), Decimal("-Infinity"), pd.NA, pd.NaT,
                                 np.datetime64("NaT"), complex(math.nan, 0.0), complex(1.0, math.inf),
                                 np.complex128(complex(0, math.nan)), np.array([1.0, math.nan]),
                                 np.array(math.inf), np.array(["NaT"], dtype="datetime64[s]")])
def test_g1_d6_non_finite_or_missing_values_are_refused_by_key(bad):
    with pytest.raises(ValueError, match=r"^values\['a'\] must be finite"):
        glue_all({"ok": 1.0, "a": bad})


@pytest.mark.parametrize("good", [Decimal("1.5"), complex(1, 2), np.array([1.0, 2.0]), "NaN", 3, None, True,
                                  np.datetime64("2024-01-01")])
def test_g_finite_values_pass_the_check(good, monkeypatch):
    import myst_nb
    seen = {}
    monkeypatch.setattr(myst_nb, "glue", lambda k, v, display: seen.__setitem__(k, v))
    glue_all({"a": good})
    assert "a" in seen


# ---------------------------------------------------------------- class W: glue_figure's key type

@pytest.mark.parametrize("key", [5, None, b"k", ["k"]])
def test_w1_glue_figure_key_of_a_wrong_type(key):
    fig, _ = new_figure()
    try:
        with pytest.raises(TypeError, match="^key must be a str"):
            glue_figure(key, fig)
    finally:
        plt.close(fig)
    fig, _ = new_figure()
    try:
        with pytest.raises(ValueError, match="^key must be a non-empty"):
            glue_figure("", fig)
    finally:
        plt.close(fig)


# ---------------------------------------------------------------- class N: png_description of malformed PNGs

_SIG = b"\x89PNG\r\n\x1a\n"


def _chunk(kind: bytes, body: bytes) -> bytes:
    return struct.pack(">I4s", len(body), kind) + body + b"\0\0\0\0"


@pytest.mark.parametrize("body", [
    (b"iTXt", b"Description\0"), (b"iTXt", b"Description\0\0"), (b"zTXt", b"Description\0\0notzlib"),
    (b"zTXt", b"Description\0"), (b"zTXt", b"Description\0\0" + zlib.compress(b"abc")[:-3]),
    (b"iTXt", b"Description\0\0\0en\0\0\xff\xfe"), (b"iTXt", b"Description\0\1\0\0\0notzlib"),
    (b"zTXt", b"Description\0\1" + zlib.compress(b"abc"))])
def test_n1_n3_malformed_description_is_none(body):
    assert png_description(_SIG + _chunk(*body)) is None


@settings(max_examples=200, deadline=None)
@given(st.sampled_from([b"tEXt", b"zTXt", b"iTXt"]), st.binary(max_size=60))
def test_n_any_description_chunk_gives_text_none_or_a_named_refusal(kind, rest):
    try:
        out = png_description(_SIG + _chunk(kind, b"Description\0" + rest))
    except ValueError as exc:
        assert str(exc).startswith("data")
    else:
        assert out is None or isinstance(out, str)


def test_n4_inflation_is_bounded():
    bomb = _SIG + _chunk(b"zTXt", b"Description\0\0" + zlib.compress(b"\0" * 50_000_000, 9))
    t0 = time.process_time()
    with pytest.raises(ValueError, match="^data: the PNG's Description chunk inflates beyond"):
        png_description(bomb)
    assert time.process_time() - t0 < 1.0
    itxt = _SIG + _chunk(b"iTXt", b"Description\0\1\0\0\0" + zlib.compress(b"a" * 200_000))
    with pytest.raises(ValueError, match="^data"):
        png_description(itxt)
    with pytest.raises(ValueError, match="^data"):
        png_description(_SIG + _chunk(b"tEXt", b"Description\0" + b"a" * 200_000))


def test_n_valid_descriptions_still_read():
    assert png_description(_SIG + _chunk(b"tEXt", b"Description\0caf\xe9")) == "café"
    assert png_description(_SIG + _chunk(b"zTXt", b"Description\0\0" + zlib.compress(b"a plot"))) == "a plot"
    itxt = b"Description\0\1\0en\0\0" + zlib.compress("θ rises".encode())
    assert png_description(_SIG + _chunk(b"iTXt", itxt)) == "θ rises"
    for alt in ("Error against the number of sensors: it falls.", "σ against n: it falls (θ = 0.5)."):
        fig, _ = new_figure()
        buf = io.BytesIO()
        fig.savefig(buf, format="png", metadata={"Description": alt})   # as the notebooks' PNG formatter writes
        plt.close(fig)
        assert png_description(buf.getvalue()) == alt


# ---------------------------------------------------------------- class K: public constants are read-only

def _public_modules():
    """Every module of the package that has an ``__all__`` (main package, book layer, chapter layer)."""
    import fusion
    names = [m.name for m in pkgutil.walk_packages(fusion.__path__, "fusion.")]
    mods = [importlib.import_module("fusion")]
    for name in names:
        mod = importlib.import_module(name)
        if hasattr(mod, "__all__"):
            mods.append(mod)
    return mods


def _mutable(value, path, seen=frozenset()):
    """The path of the first mutable part of ``value`` (dict, list, set, writable array, frame), or None."""
    if id(value) in seen:
        return None
    seen = seen | {id(value)}
    if isinstance(value, (dict, list, set, bytearray, pd.DataFrame, pd.Series, pd.Index)):
        return f"{path} ({type(value).__name__})"
    if isinstance(value, np.ndarray):
        return f"{path} (writable array)" if value.flags.writeable or value.dtype == object else None
    if isinstance(value, (tuple, frozenset)):
        return next((m for i, x in enumerate(value) if (m := _mutable(x, f"{path}[{i}]", seen))), None)
    if isinstance(value, Mapping):
        return next((m for k, x in value.items() if (m := _mutable(x, f"{path}[{k!r}]", seen))), None)
    if dataclasses.is_dataclass(value) and not isinstance(value, type):   # a published table, a source record
        return next((m for f in dataclasses.fields(value)
                     if (m := _mutable(getattr(value, f.name), f"{path}.{f.name}", seen))), None)
    return None


def test_k_every_public_constant_is_read_only():
    mutable, n = [], 0
    for mod in _public_modules():
        for name in mod.__all__:
            value = getattr(mod, name)
            if inspect.isclass(value) or inspect.ismodule(value) or callable(value):
                continue
            n += 1
            if (m := _mutable(value, f"{mod.__name__}.{name}")):
                mutable.append(m)
    assert n > 150 and not mutable, mutable


def test_k_the_check_sees_a_mutable_constant():
    assert _mutable({"a": 1}, "x") and _mutable((ReadOnlyMapping({"a": [1]}),), "x") and _mutable(np.zeros(2), "x")
    assert _mutable(constant({"a": [1], "b": {2}, "c": np.zeros(2), "d": ({"e": 1},)}), "x") is None


def test_k1_k4_the_reported_constants_cannot_be_changed():
    from fusion import data
    from fusion.scenarios import thermocouples as TC, wavelet_sensors as W
    with pytest.raises(ValueError, match="read-only"):
        TC.DEFAULT_SIGMAS[:] = 50.0
    with pytest.raises(TypeError):
        data.YANG2012_FAILURE["biases"] = (400.0, 800.0)
    with pytest.raises(TypeError):
        W.CONFIGS[0]["level"] = 1
    with pytest.raises(TypeError):
        C.SCHEMA["required"] = []
    with pytest.raises(AttributeError):
        C.SCHEMA["required"].append("x")   # a tuple


def test_k_read_only_constants_still_serve_their_callers():
    import jsonschema
    import yaml
    doc = yaml.safe_load((ROOT / "book" / "claims" / "yang2012optimal.yaml").read_text(encoding="utf-8"))
    assert not list(jsonschema.Draft202012Validator(C.SCHEMA).iter_errors(doc))
    doc["records"][0]["test"] = "not-a-test"
    assert list(jsonschema.Draft202012Validator(C.SCHEMA).iter_errors(doc))
    from fusion import data
    from fusion.scenarios import thermocouples as TC
    z = TC.inject_failure(TC.simulate(np.random.default_rng(0), 80), **data.YANG2012_FAILURE)
    assert z.shape == (80, 10)
    merged = ReadOnlyMapping({"a": 1}) | {"b": 2}
    assert merged == {"a": 1, "b": 2} and type(merged) is dict and ({"b": 2} | ReadOnlyMapping({"a": 1})) == merged
    assert type(ReadOnlyMapping({"a": 1}).copy()) is dict


# ---------------------------------------------------------------- class M: side_by_side row labels

def test_m1_tuple_labels_index_the_table():
    labels = [(1, "a"), (1, "b"), (2, "a")]
    for index in (labels, pd.MultiIndex.from_tuples(labels)):
        df = side_by_side([1.0, 2.0, 3.0], [1.0, 2.5, 3.0], index)
        assert list(df.index) == labels and df.index.name == "observation" and df.index.nlevels == 1
        assert df.loc[[(1, "b")], "difference"].iloc[0] == 0.5


@pytest.mark.parametrize("nan", [math.nan, np.nan, np.float32("nan"), complex(math.nan, 0)])
def test_m2_two_nan_labels_are_a_repeated_label(nan):
    with pytest.raises(ValueError, match=r"^index must not repeat an entry: index\[0\] and index\[2\]"):
        side_by_side([1.0, 2.0, 3.0], [1.0, 2.0, 3.0], [float("nan"), 2.0, nan])
    assert side_by_side([1.0, 2.0], [1.0, 2.0], [nan, 2.0]).shape == (2, 3)   # one NaN label is a label


@settings(max_examples=50, deadline=None)
@given(st.lists(st.one_of(st.integers(-3, 3), st.floats(allow_infinity=False), st.text(max_size=2),
                          st.tuples(st.integers(0, 2), st.text(max_size=1))), min_size=1, max_size=6))
def test_m_labels_are_refused_exactly_when_a_lookup_would_be_ambiguous(labels):
    n = len(labels)
    keys = [("NaN",) if isinstance(v, float) and v != v else v for v in labels]
    try:
        df = side_by_side(np.ones(n), np.ones(n), labels)
    except ValueError as exc:
        assert str(exc).startswith("index must not repeat") and len(set(keys)) < n
    else:
        assert len(set(keys)) == n and df.shape == (n, 3)


# ---------------------------------------------------------------- D2-D4: study_cache / process_cache keys

@pytest.mark.filterwarnings("ignore::PendingDeprecationWarning")   # np.asmatrix
def test_d2_keys_determine_longdouble_masked_and_matrix_arguments():
    from fusion.book.study_cache import study_key

    def key(v):
        return study_key("m.f", {"x": v}, digest="0")
    one = np.longdouble(1)
    assert key(one + np.longdouble(1e-19)) != key(one) and key(one) == key(np.longdouble(1))
    data = np.arange(3.0)
    masked = np.ma.masked_array(data, mask=[False, True, False])
    assert len({key(data), key(masked), key(np.ma.masked_array(data)), key(np.asmatrix(data))}) == 4
    assert key(masked) == key(np.ma.masked_array(data.copy(), mask=[False, True, False]))
    # a masked entry's hidden value does not matter
    assert key(masked) == key(np.ma.masked_array([0.0, 99.0, 2.0], mask=[False, True, False]))


def test_d3_a_cached_masked_result_keeps_its_mask():
    from fusion.book.study_cache import study_cache

    @study_cache(maxsize=2)
    def f(n: int):
        return np.ma.masked_array(np.arange(float(n)), mask=[False] * n)
    first = f(3)
    assert isinstance(first, np.ma.MaskedArray) and not first.mask.any()
    first.mask[0] = True                 # an array subclass is the caller's own copy (fuzz 37a C1): its edit stays there
    first[1] = np.ma.masked
    assert not f(3).mask.any() and f(3).tolist() == [0.0, 1.0, 2.0]


def test_d4_process_cache_is_equality_keyed_as_documented():
    from fusion.book.study_cache import process_cache

    @process_cache(maxsize=4)
    def sign(x):
        return math.copysign(1.0, x[0] if isinstance(x, tuple) else x)
    assert sign(0.0) == 1.0 and sign(-0.0) == 1.0   # documented: equal arguments share a result
    assert sign.cache_info().hits == 1


# ---------------------------------------------------------------- D8: parameters_matching's option name

@pytest.mark.parametrize("option", ["threshold", "include_self"])
def test_d8_a_non_numeric_option_is_refused_as_name(option):
    from fusion.book.audit import parameters_matching
    with pytest.raises(ValueError, match=f"^name must be a numeric option of method 'optimal_fusion_set', "
                                         f"one of \\('scale',\\), got '{option}'"):
        parameters_matching(np.array([1.0, 2.0, 3.5]), 2.0, "optimal_fusion_set", option, 0.01, 100.0)


def test_d8_degenerate_every_grid_point_is_a_root_hi_included():
    from fusion.book.audit import parameters_matching
    roots = parameters_matching(np.array([2.0]), 2.0, "support_degree", "alpha", 0.1, 10.0, n_grid=5)
    assert np.allclose(roots, np.geomspace(0.1, 10.0, 5))
    assert parameters_matching(np.array([2.0]), 3.0, "support_degree", "alpha", 0.1, 10.0, n_grid=5).size == 0


# ---------------------------------------------------------------- D12: pd.NA in an object column is missing

def test_d12_pd_na_is_missing_in_an_object_column_as_in_a_nullable_one():
    from fusion.book.tables import mismatches
    obj = pd.DataFrame({"published": pd.Series([1.0, pd.NA, 3.0], dtype=object),
                        "reproduced": pd.Series([1.0, 2.0, pd.NA], dtype=object)})
    nullable = obj.astype("Float64")
    assert mismatches(obj).equals(mismatches(nullable))
    assert list(mismatches(obj)["reproduced"]) == [False, False, True]
    with pytest.raises(TypeError, match=r"^table\['published'\] must hold numbers"):
        mismatches(obj.assign(published=pd.Series(["1.0", pd.NA, 3.0], dtype=object)))


# ---------------------------------------------------------------- D13: result containers check nothing (documented)

def test_d13_result_containers_are_documented_as_unchecked_and_their_producers_check():
    from fusion.book.audit import SubsetMatch, matching_subsets
    from fusion.book.benchmarks import BenchmarkResult
    from fusion.data import Published
    for cls in (BenchmarkResult, Published):
        assert "the constructor checks nothing" in cls.__doc__
    # SubsetMatch checks its fields since fuzz 29a C1 (it stores the plain numbers it read)
    with pytest.raises(TypeError, match="members"):
        SubsetMatch("x", 1.0)
    with pytest.raises(ValueError, match="value"):
        SubsetMatch((0,), math.nan)
    found = matching_subsets(np.array([1.0, 2.0, 4.0]), 1.5, 0.05, np.mean)
    assert found and all(isinstance(m, SubsetMatch) and all(isinstance(i, int) for i in m.members)
                         and math.isfinite(m.value) for m in found)
