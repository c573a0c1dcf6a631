"""Fuzz 21b's classes H and J and its debatable case d6 in the lecture chapters (issue 35).

* H: :func:`fusion.book.chapters.lecture.reading_of`, through which chapters 04 and 07 pick a record's reading,
  returned a non-Evidence ``ev`` (``5``, ``None``, ``{"primary": 5}``) as the evidence; it is now a TypeError
  naming ``ev`` (and the reading key).
* J: ``lecture_weighting.learning_settling``'s ``tol`` was unchecked (NaN read every epoch as settled, a negative
  tolerance accepted, a str a numpy error); it is a finite number > 0, named. The answer ``epochs + 1`` when the
  variances never settle within the study is documented and tested.
* d6: ``lecture_wavelets.typical_run`` of a comparison whose runs all tie is "contradicted". Decided by the
  rulebook's tie rule (R3's share of runs won: a tie is never a win): kept and documented; the sign tests
  (``typical_run``, ``sign_conjunction``) now share the rulebook's own tie test (a round-off difference is a tie),
  where they compared exactly.
"""

from __future__ import annotations

import re
import types
from functools import cache
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from fusion.book import rulebook
from fusion.book.chapters.lecture import reading_of
from fusion.book.chapters.lecture_wavelets import appendix as wa, verdicts
from fusion.book.chapters.lecture_weighting import learning
from fusion.book.ledger import Comparison, Conjunction, Proposition
from fusion.scenarios.lecture_weighting.learning import learning_study


def _names(msg: str, arg: str) -> bool:
    return re.search(rf"(?<![A-Za-z0-9_]){re.escape(arg)}(?![A-Za-z0-9_])", msg) is not None


def _comparison(shift: float = 1.0) -> Comparison:
    a = np.arange(100.0) + 1
    return Comparison(a, a + shift, "A", "B", "less", "m")


# --- H: reading_of refuses a non-Evidence ---------------------------------------------------------------------

_NOT_EVIDENCE = [5, None, "text", 1.5, [_comparison()], (_comparison(),), np.ones(3), object()]


@pytest.mark.parametrize("ev", _NOT_EVIDENCE + [{"primary": x} for x in _NOT_EVIDENCE]
                         + [{"primary": _comparison(), "other": None}, {1: _comparison()}],
                         ids=lambda ev: type(ev).__name__ if not isinstance(ev, dict) else f"dict-{list(ev.values())[-1]!r:.20}")
def test_reading_of_refuses_non_evidence(ev: Any) -> None:
    with pytest.raises(TypeError) as exc:
        reading_of("lec-x", ev, None)
    assert _names(str(exc.value), "ev"), str(exc.value)


@settings(max_examples=60, deadline=None)
@given(st.one_of(st.none(), st.integers(), st.floats(), st.text(), st.binary(), st.lists(st.integers()),
                 st.dictionaries(st.text(max_size=5), st.integers(), max_size=3)),
       st.sampled_from([None, {"reading": "primary"}]))
def test_reading_of_refuses_any_non_evidence(ev: Any, settings_: Any) -> None:
    """Whatever the object, a non-Evidence (or a mapping to one) is refused by type, naming ``ev``."""
    with pytest.raises(TypeError) as exc:
        reading_of("lec-x", ev if ev != {} else {"primary": 5}, settings_)
    assert _names(str(exc.value), "ev"), str(exc.value)


def test_reading_of_valid_evidence() -> None:
    """Documented input keeps working: one Evidence for the primary, a mapping (any Mapping) of readings."""
    c, d, p = _comparison(), _comparison(2.0), Proposition(True, "x")
    assert reading_of("lec-x", c, None) is c
    assert reading_of("lec-x", p, {"reading": "primary"}) is p
    conj = Conjunction((("s1", c), ("s2", d)))
    assert reading_of("lec-x", conj, None) is conj
    readings = {"primary": c, "other": d, "exact": p}
    assert reading_of("lec-x", readings, {"reading": "other"}) is d
    assert reading_of("lec-x", types.MappingProxyType(readings), {"reading": "exact"}) is p
    with pytest.raises(ValueError, match="settings"):  # a missing reading stays a refusal of the settings
        reading_of("lec-x", readings, {"reading": "absent"})


# --- J: learning_settling's tol -------------------------------------------------------------------------------

@cache
def _s22() -> Any:
    return learning_study(epochs=60, runs=3, last=10)


@pytest.mark.parametrize("tol", [float("nan"), float("inf"), -float("inf"), -0.1, 0.0, -0.0, -1e300, 1e-320])
def test_learning_settling_tol_value(tol: float) -> None:
    with pytest.raises(ValueError) as exc:
        learning.learning_settling(_s22(), tol)
    assert _names(str(exc.value), "tol"), str(exc.value)


@pytest.mark.parametrize("tol", ["0.05", None, True, 1j, [0.05], np.array([0.05, 0.1])])
def test_learning_settling_tol_type(tol: Any) -> None:
    with pytest.raises(TypeError) as exc:
        learning.learning_settling(_s22(), tol)
    assert _names(str(exc.value), "tol"), str(exc.value)


def test_learning_settling_never_settled_is_epochs_plus_one() -> None:
    """The documented degenerate answer: ``epochs + 1`` when the variances are still outside ``tol`` at the last
    epoch; 1 when they are within it from the first."""
    s = _s22()
    epochs = {int(n): Rh.shape[0] for n, (_, Rh) in s.learned.items()}
    assert learning.learning_settling(s, 1e-12) == {n: e + 1 for n, e in epochs.items()}
    assert learning.learning_settling(s, 1e6) == {n: 1 for n in epochs}


@settings(max_examples=30, deadline=None)
@given(st.floats(1e-6, 10.0), st.floats(1e-6, 10.0))
def test_learning_settling_valid_tol_monotone(t1: float, t2: float) -> None:
    """Every finite tol > 0 is accepted (int and numpy scalars too), and a larger tolerance settles no later."""
    lo, hi = sorted((t1, t2))
    a, b = learning.learning_settling(_s22(), lo), learning.learning_settling(_s22(), np.float64(hi))
    assert a.keys() == b.keys()
    assert all(1 <= b[n] <= a[n] for n in a)
    assert learning.learning_settling(_s22(), 1) == learning.learning_settling(_s22(), 1.0)


# --- d6: ties in the sign tests, by the rulebook's tie rule ---------------------------------------------------

def test_typical_run_all_ties_contradicted() -> None:
    """Decided (d6): a tie is never a win (the rulebook's share of runs won), so runs that all tie contradict
    "A beats B in more than half of the runs", for either claim, while the mean reads them not distinguishable."""
    a = np.random.default_rng(1).normal(1, 0.1, 200)
    for claim in ("less", "greater"):
        ev = Comparison(a, a.copy(), "A", "B", claim, "m", seed=1)
        t = wa.typical_run(ev)
        assert np.all(np.asarray(t.a) == 0.0)
        assert t.status() == "contradicted"
        assert ev.status() == "not distinguishable"


def test_sign_tests_round_off_is_a_tie() -> None:
    """A difference within round-off is a tie, as the rulebook counts it, not a win (they compared exactly)."""
    a = np.random.default_rng(2).normal(1, 0.1, 200)
    b = a * (1 + 1e-12)  # A below B by round-off in every run
    t = wa.typical_run(Comparison(a, b, "A", "B", "less", "m", seed=1))
    assert float(np.mean(t.a)) == 0.0
    assert rulebook.judge_paired(a, b, "less", 0.0).share == 0.0
    conj = verdicts.sign_conjunction(np.column_stack([a, a]), np.column_stack([b, b + 1.0]), "A", "B", 1)
    shares = [float(np.mean(p.a)) for _, p in conj.parts]
    assert shares == [0.0, 1.0]


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 2**32 - 1), st.floats(0.0, 1.0), st.sampled_from(["less", "greater"]))
def test_typical_run_share_is_the_rulebook_share(seed: int, tie_share: float, claim: str) -> None:
    """One tie rule: the sign test's fraction of runs won equals the rulebook's share of runs won, exact and
    round-off ties included."""
    rng = np.random.default_rng(seed)
    a = rng.normal(1, 0.1, 120)
    b = rng.normal(1, 0.1, 120)
    tied = rng.random(120) < tie_share
    b = np.where(tied, a * (1 + rng.choice([0.0, 1e-13, -1e-13], 120)), b)
    t = wa.typical_run(Comparison(a, b, "A", "B", claim, "m", seed=1))
    assert float(np.mean(t.a)) == pytest.approx(rulebook.judge_paired(a, b, claim, 0.0).share, abs=1e-15)
