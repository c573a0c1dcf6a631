"""Fuzz 32b (chapter layer, issue 35): text options used as their plain text, real keys within their meaning, the
glue-prefix rule of comparison_numbers, E2.6 of another setup refused by every reader.

Each test fails on the code before the fix. No chapter registry is imported: each test builds only what it needs
(the studies that would cost CPU are replaced by recorders).
"""

from __future__ import annotations

import enum
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st


def K(s: str) -> str:
    """A caller's ``(str, Enum)`` member of value ``s``: ``== s`` and hashes like it, but ``str()`` and an f-string
    give ``"K.M"`` (the usual string enum before Python 3.11's StrEnum)."""
    return enum.Enum("K", {"M": s}, type=str).M


class _Reached(Exception):
    """Raised by a recorder in place of a study: carries the arguments the study would have received."""


def _recorder(*args, **kwargs):
    raise _Reached(args, kwargs)


def _reached(call) -> tuple:
    with pytest.raises(_Reached) as exc:
        call()
    return exc.value.args[0]


def _wavelet_study(mp):
    from fusion.book.chapters.lecture_wavelets import records as m
    mp.setattr(m, "_study", _recorder)
    return _reached(lambda: m.study(K("m26"), runs=20))[0], "m26"


def _weighting_study(mp):
    from fusion.book.chapters.lecture_weighting import studies as m
    mp.setattr(m, "_study", _recorder)
    return _reached(lambda: m.study(K("s21"), runs=20))[0], "s21"


def _ofs_failure(mp):
    from fusion.book.chapters.ofs import records as m
    mp.setattr(m, "study", _recorder)
    return _reached(lambda: m.ev_fig4_unaffected({"failure": K("random size")}, seed=1, runs=100))[3], "random size"


def _chernoff_settings(mp):
    from fusion.book.chapters.chernoff.evidence import _settings
    return _settings({"reading": K("plain")}, {"reading": ("guard", "plain")}, {})["reading"], "plain"


def _ci_reading(mp):
    from fusion.book.chapters.ci import studies as m
    rid = next(iter(m._STOCHASTIC))
    alt = next(r.key for r in m.claim_file().record(rid).readings if r.key != "primary")  # a reading of the record's
    mp.setattr(m, "_record", lambda rid, seed, runs: {"primary": "P", alt: alt})  # claim file (checked before the study)
    return m.record_evidence(rid, {"reading": K(alt)}, seed=1, runs=100), alt


def _wavelet_label(mp):
    from fusion.book.chapters.lecture_wavelets.verdicts import sensor_conjunction
    rng = np.random.default_rng(1)
    c = sensor_conjunction(rng.random((100, 2)), rng.random((100, 2)), K("A"), "B", "MSE", seed=1, claim="less")
    return c.parts[0][1].a_name.removesuffix(" (sensor 1)"), "A"


def _ofs_glue_key(mp):
    from fusion.book.chapters.ofs.verdicts import comparison_numbers
    from fusion.book.ledger import Comparison
    rng = np.random.default_rng(1)
    c = Comparison(rng.random(100), rng.random(100), "A", "B", "less", "x", seed=1)
    return min(comparison_numbers(c, K("k"), fields=["a"])), "k_a"


#: Chapter sites that check a text argument and then use it (fuzz 32b C1): what reached the computation.
C1_SITES = {"lecture_wavelets.records.study": _wavelet_study, "lecture_weighting.studies.study": _weighting_study,
            "ofs.records settings['failure']": _ofs_failure, "chernoff.evidence._settings": _chernoff_settings,
            "ci.studies.record_evidence settings['reading']": _ci_reading,
            "lecture_wavelets.verdicts.sensor_conjunction a_name": _wavelet_label,
            "ofs.verdicts.comparison_numbers key": _ofs_glue_key}


@pytest.mark.parametrize("site", sorted(C1_SITES))
def test_a_str_enum_text_is_used_as_its_plain_text(site: str, monkeypatch: pytest.MonkeyPatch) -> None:
    """A checked text reaches the computation as the plain str the check returns (rule 19): ``K('m26')`` chose
    E2.6's study, ``K('s21')`` raised KeyError 'K.M', ``settings['failure']`` reached the study as 'K.M'."""
    got, want = C1_SITES[site](monkeypatch)
    assert type(got) is str and got == want, (site, got)


def test_ofs_vary_table1_given_as_a_str_enum_reads_table1(monkeypatch: pytest.MonkeyPatch) -> None:
    """``vary = K('table1')`` fell through to the scale sweep (a study of 500 runs) instead of Table 1's reading."""
    from fusion.book.chapters.ofs import records as m
    monkeypatch.setattr(m, "membership_study", _recorder)
    assert len(m.ev_membership_free({"vary": K("table1")}, seed=1, runs=100).parts) == 2
    with pytest.raises(ValueError, match=r"settings\['vary'\]"):
        m.ev_membership_free({"vary": "tables"}, seed=1, runs=100)


_BAD_PERIOD = st.one_of(st.sampled_from([math.nan, math.inf, -math.inf, 0.0, -0.0]),
                        st.floats(max_value=0.0, allow_nan=False, allow_infinity=False))


@settings(max_examples=15, deadline=None)
@given(bad=_BAD_PERIOD, field=st.sampled_from(["fig6_periods", "paired_fig6", "fuzzy_levels"]))
def test_real_keys_outside_their_meaning_are_refused_by_the_field(bad: float, field: str) -> None:
    """NaN, infinite, zero or negative periods, weights and levels were accepted as keys (fuzz 32b C2): a period of
    -1 s was glued as ``ci_fig6_d_1``, period 1 s's key. The chapter's own keys still pass."""
    from fusion._results import _check
    from fusion.book.chapters.ci.claim_inputs import _PAIRED_FIELDS, PeriodRuns
    from fusion.book.chapters.ci.constants import W_GRID, W_PUB

    v = PeriodRuns(seed=1, fruit_fly=np.ones(3), grid=np.ones(3)) if field == "fig6_periods" else np.ones(3)
    good = {"fig6_periods": (0.5, 0.2), "paired_fig6": (W_PUB, W_GRID), "fuzzy_levels": (0.001, 0.05)}[field]
    if field == "paired_fig6" and bad == 0.0:
        bad = 1.5  # a weight of 0 is a weight; above 1 is not
    spec = _PAIRED_FIELDS[field]
    assert set(_check(spec, dict.fromkeys(good, v), field, {})) == set(good)
    with pytest.raises(ValueError, match=f"{field}'s key"):
        _check(spec, {**dict.fromkeys(good, v), bad: v}, field, {})


@pytest.mark.parametrize("field, bad", [("ir_sens", -1.0), ("slip_weights", math.nan), ("slip_weights", 2.0)])
def test_ledger_real_keys_of_ir_and_slip_are_refused(field: str, bad: float) -> None:
    from fusion._results import _check
    from fusion.book.chapters.ci.claim_inputs import _LEDGER_FIELDS

    v = {"x": 1.0} if field == "ir_sens" else (1.0, 1.0)
    base = {0.5: v} if field == "ir_sens" else {0.0018: v, 0.0033: v, 0.5: v}  # the weights read (fuzz 34b B3)
    assert list(_check(_LEDGER_FIELDS[field], base, field, {})) == list(base)
    with pytest.raises(ValueError, match=f"{field}'s key"):
        _check(_LEDGER_FIELDS[field], {**base, bad: v}, field, {})


@pytest.mark.parametrize("bad", [math.nan, -1.0, 0.0, math.inf])
def test_path_period_table_refuses_a_row_of_a_bad_period(bad: float) -> None:
    from fusion.book.chapters.ci import path_period_table

    row = {"CI": 1.0}
    assert len(path_period_table({(0.1, "q"): row})) == 1
    with pytest.raises(ValueError, match=r"rows\[.*period"):
        path_period_table({(0.1, "q"): row, (bad, "q"): row})


@pytest.mark.parametrize("cls, field, good, bad", [
    ("fusion.book.chapters.ci.printed:PrintedWeightFacts", "trace", 0.0018, 1.5),
    ("fusion.book.chapters.time_registration_ledger.studies:RegistrationStudy", "sweep", 0.3, -1.0),
    ("fusion.book.chapters.time_registration_ledger.studies:RegistrationStudy", "s3_fair", 3.0, math.inf),
    ("fusion.book.chapters.lecture_correlated.ridge:PluginExact", "known", 1.0, 0.0),
    ("fusion.book.chapters.lecture_correlated.ridge:PluginExact", "theta_at", 0.5, math.nan),
    ("fusion.book.chapters.chernoff_snis:SnisBiasStudy", "delta", 0.7, -0.5)])
def test_frozen_results_check_real_keys_by_the_producers_rule(cls: str, field: str, good: float, bad: float) -> None:
    """D2 (decided: fixed): a record rebuilt with ``dataclasses.replace`` accepted NaN, infinite or negative keys
    (a weight, a noise level σ > 0, a tolerance c > 0, a finite x). The field's key rule alone is probed here (its
    entries are studies): the rule each dict spec runs on every key before its entries."""
    import importlib

    mod, name = cls.split(":")
    check_key = getattr(importlib.import_module(mod), name).__result_spec__.fields[field].args.get("check_key")
    assert check_key is not None, f"{name}.{field} checks no key"
    check_key(good, f"{name}.{field}'s key")
    with pytest.raises(ValueError, match=f"{name}.{field}'s key"):
        check_key(bad, f"{name}.{field}'s key")


@pytest.mark.parametrize("key", ["k\n", " ", "a-b", "x\u200b", "1"])
def test_comparison_numbers_keys_follow_the_glue_prefix_rule(key: str) -> None:
    """D1 (decided: fixed): ``comparison_numbers`` glued ``k\\n_a``; ``glue_seeds`` refuses such prefixes by name."""
    from fusion.book.chapters.ofs.verdicts import comparison_numbers
    from fusion.book.ledger import Comparison

    rng = np.random.default_rng(1)
    c = Comparison(rng.random(100), rng.random(100), "A", "B", "less", "x", seed=1)
    assert set(comparison_numbers(c, "ofs_k", fields=["a"])) == {"ofs_k_a"}
    with pytest.raises(ValueError, match="key"):
        comparison_numbers(c, key)


def _signal_study(gains: list[float], key: tuple, runs: int):
    """A SignalStudy holding one case and its setup, built without a simulation (what ``cell`` reads)."""
    from fusion.scenarios.wavelet_sensors import SignalStudy

    out = object.__new__(SignalStudy)
    for k, v in {"gains": np.array(gains), "sigma": np.array([0.1, 0.2]), "length": 64, "runs": runs, "seed": 1,
                 "cases": {key: {"raw": {"mse": np.ones(runs)}}}}.items():
        object.__setattr__(out, k, v)
    return out


def test_signal_readers_refuse_e26_of_another_setup() -> None:
    """D3 (decided: fixed): ``glue_signals``/``table_signals`` (through ``cell``) took E2.6's cell from a study of
    equal gains; ``glue_mechanism`` refused it. One rule for every reader of ``e26``; swapped roles still read."""
    from fusion.book.chapters.lecture_wavelets.verdicts import cell

    key = ("two tones", "hard", "max")
    sg, e26 = _signal_study([1.0, 1.5], key, 100), _signal_study([1.0, 1.5], key, 300)
    assert cell(sg, e26, key).runs == 300 and cell(e26, sg, key).runs == 100
    with pytest.raises(ValueError, match="e26 is a study of another setup than sg"):
        cell(sg, _signal_study([1.0, 1.0], key, 300), key)
