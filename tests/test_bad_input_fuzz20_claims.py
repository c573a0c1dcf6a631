"""Fuzz 20's cases of claim files and the ledger's pairs (issue 35), by class.

* B: a malformed claim file (a sequence or another non-text as a mapping key, nesting thousands deep, an integer
  too long to read) is a :class:`fusion.book.claims.ClaimsFileError` naming the file, never a TypeError,
  RecursionError or Python's digit-limit ValueError; every mapping key of a claim file is a text (the loader).
* G: a :class:`~fusion.book.claims.ClaimSpec` stores ``margin`` and ``baseline`` read-only and checks ``baseline``
  in ``__post_init__`` (so ``dataclasses.replace`` is checked); a :class:`~fusion.book.claims.ClaimsFile` checks
  its fields.
* F1/F2: a numpy real scalar (float32, int64) is a valid margin, as for the shared scalar reader.
* Q1/Q2: a list pair is a pair for ``Comparison``'s ``conditions`` and ``Conjunction``'s parts.
"""

from __future__ import annotations

import copy
import dataclasses
import pickle

import numpy as np
import pytest

from fusion.book import claims as C
from fusion.book import ledger as L

YANG = "yang2012optimal.yaml"


@pytest.fixture(scope="module")
def base_text() -> str:
    return (C.claims_dir() / YANG).read_text(encoding="utf-8")


@pytest.fixture(scope="module")
def cf() -> C.ClaimsFile:
    return C.load(C.claims_dir() / YANG)


def _load(tmp_path, text: str, name: str = "bad.yaml") -> C.ClaimsFile:
    p = tmp_path / name
    p.write_text(text, encoding="utf-8")
    return C.load(p)


# --- B: malformed claim files --------------------------------------------------------------------------------

def test_sequence_key_is_a_claims_file_error(tmp_path, base_text):
    text = base_text.replace("quantities:\n", "quantities:\n  ? [x]\n  : 1\n", 1)
    with pytest.raises(C.ClaimsFileError, match=r"bad\.yaml.*key must be a text"):
        _load(tmp_path, text)


@pytest.mark.parametrize("key", ["null", "5", "yes", ".nan"])
def test_quantity_key_not_a_text_is_refused(tmp_path, base_text, key):
    text = base_text.replace("quantities:\n", f"quantities:\n  {key}: {{label: x, margin: {{relative: 0.05}}, why: y}}\n", 1)
    with pytest.raises(C.ClaimsFileError, match=r"bad\.yaml.*key must be a text"):
        _load(tmp_path, text)


@pytest.mark.parametrize("text", ["source: " + "[" * 5000 + "]" * 5000 + "\n",
                                  "source: " + "{a: " * 3000 + "1" + "}" * 3000 + "\n",
                                  "source: " + "[" * 100 + "]" * 100 + "\n"])
def test_deep_nesting_is_a_claims_file_error(tmp_path, text):
    with pytest.raises(C.ClaimsFileError, match=r"bad\.yaml.*nested more than"):
        _load(tmp_path, text)


def test_overlong_integer_is_a_claims_file_error(tmp_path, base_text):
    text = base_text.replace("source: yang2012optimal", "source: " + "9" * 5000, 1)
    with pytest.raises(C.ClaimsFileError, match=r"bad\.yaml.*integer too long"):
        _load(tmp_path, text)


def test_every_claim_file_still_loads():
    assert C.load_all()  # the loader's new rules (text keys, depth, integers) refuse no file of the book


# --- G: ClaimSpec and ClaimsFile ----------------------------------------------------------------------------------

def _comparing(cf):
    """The first record whose test takes a margin (a published test compares nothing: fuzz 21 R, load's rule)."""
    return next(r for r in cf.records if r.test in ("paired", "equivalence", "exact"))


def test_margin_and_baseline_are_read_only(cf):
    spec = dataclasses.replace(_comparing(cf), baseline={"name": "m", "defined": False, "reason": "r"})
    spec = dataclasses.replace(spec, margin={"relative": 0.05})
    for field in ("margin", "baseline"):
        value = getattr(spec, field)
        with pytest.raises(TypeError):
            value[next(iter(value))] = -1.0
        for other in (copy.deepcopy(spec), pickle.loads(pickle.dumps(spec))):
            with pytest.raises(TypeError):
                getattr(other, field)["x"] = 1
    assert spec.margin == {"relative": 0.05}  # compares equal to the dict it was given


def test_a_loaded_quantity_margin_is_read_only(cf):
    with pytest.raises(TypeError):
        next(iter(cf.quantities.values()))["margin"]["relative"] = -1.0


@pytest.mark.parametrize(("baseline", "exc", "field"), [
    ({"zz": 1}, ValueError, "baseline"),
    ({"name": "m"}, ValueError, "baseline"),
    ({"name": "m", "defined": True, "extra": "x"}, ValueError, "baseline"),
    ({"name": 5, "defined": True}, TypeError, "baseline.name"),
    ({"name": "m", "defined": 1}, TypeError, "baseline.defined"),
    ({"name": "m", "defined": False, "reason": None}, TypeError, "baseline.reason"),
])
def test_replace_checks_baseline(cf, baseline, exc, field):
    with pytest.raises(exc, match=field.replace(".", r"\.")):
        dataclasses.replace(cf.records[0], baseline=baseline)


def test_replace_keeps_a_valid_baseline(cf):
    b = {"name": "m", "defined": False, "reason": "r", "stand_in": "s"}
    assert dataclasses.replace(cf.records[0], baseline=b).baseline == b


@pytest.mark.parametrize(("field", "value", "name"), [
    ("records", [1], "records"), ("records", (1,), "records"), ("records", "x", "records"),
    ("quantities", [1], "quantities"), ("source", 5, "source"), ("path", "x.yaml", "path")])
def test_claims_file_checks_its_fields(cf, field, value, name):
    with pytest.raises(TypeError, match=name):
        dataclasses.replace(cf, **{field: value})


def test_claims_file_stores_a_list_of_records_as_a_tuple(cf):
    again = dataclasses.replace(cf, records=list(cf.records))
    assert again.records == cf.records and isinstance(again.records, tuple)


# --- F1/F2: numpy scalars are numbers -------------------------------------------------------------------------

@pytest.mark.parametrize("margin", [{"relative": np.float32(0.05)}, {"absolute": np.int64(1)},
                                    {"absolute": np.uint8(2)}, {"relative": np.float64(0.1)}])
def test_numpy_scalar_margin_is_valid(cf, margin):
    assert dataclasses.replace(_comparing(cf), margin=margin).margin == margin


@pytest.mark.parametrize("margin", [{"relative": np.bool_(True)}, {"relative": True}, {"relative": np.float32("nan")},
                                    {"absolute": np.int64(-1)}, {"relative": "0.05"}])
def test_non_numbers_and_bad_numbers_stay_refused(cf, margin):
    with pytest.raises(ValueError, match="margin"):
        dataclasses.replace(_comparing(cf), margin=margin)


# --- Q1/Q2: list pairs ------------------------------------------------------------------------------------------

def _runs():
    rng = np.random.default_rng(0)
    a = 1 + rng.random(120)
    return a, a + 0.5 + 0.01 * rng.random(120)


def test_comparison_takes_a_list_pair_of_conditions():
    a, b = _runs()
    c = L.Comparison(a, b, "A", "B", "less", "m", conditions=["x", "x"])
    assert c.conditions == ("x", "x")
    with pytest.raises(ValueError, match="conditions"):  # R6 still refuses different conditions
        L.Comparison(a, b, "A", "B", "less", "m", conditions=["x", "y"])
    with pytest.raises(TypeError, match="conditions"):
        L.Comparison(a, b, "A", "B", "less", "m", conditions=["x", "x", "x"])


def test_conjunction_takes_list_pairs():
    p, q = L.Proposition(True, "x"), L.Proposition(True, "y")
    c = L.Conjunction([["p", p], ["q", q]])
    assert c.parts == (("p", p), ("q", q))
    with pytest.raises(TypeError, match="parts"):
        L.Conjunction([["p", p, 1], ["q", q]])
