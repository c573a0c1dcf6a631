"""Fuzz 52 C7 and D2: one rule for the ``settings`` of every chapter's record readers.

C7: chapter 01's readers silently ignored a misspelt key (``ev_weights_stability({'sensor': (1, 10)})`` gave the
halves comparison), chapters 04 and 07 checked the settings only after their studies, and a non-mapping was a
ValueError in chapters 02-04, 06 and 07 but a TypeError in chapter 05. Now ``fusion.book._reader_settings``:
a TypeError for a non-mapping, a ValueError naming ``settings`` and the unknown key, before any study; every
reading of every claim file still passes. D2: ``{'alpha': 0.25}``, the records' own α, was refused by chapter 01's
``_pair`` readers; it now gives the default's evidence.
"""

from __future__ import annotations

import importlib
import time

import pytest

from fusion.book._reader_settings import reads, settings_first
from fusion.book.chapters import ci, lecture_correlated as lc, lecture_wavelets as wv, lecture_weighting as lw, ofs
from fusion.book.chapters import chernoff as chc
from fusion.book.chapters.lecture import reading_key, reading_of
from fusion.book.chapters.time_registration_ledger import evidence as tre
from fusion.book.claims import claims_dir, load


def test_settings_first_rule() -> None:
    assert settings_first(None, ("a",)) == {}
    given = {"a": 1}
    assert settings_first(given, ("a", "b")) is given
    for bad in (["a"], "a", 5, ("a", 1)):
        with pytest.raises(TypeError, match=r"^settings must be a mapping"):
            settings_first(bad, ("a",))
    with pytest.raises(ValueError, match=r"^settings: unknown \['c'\] \(this record's reader takes only \['a', 'b'\]\)"):
        settings_first({"a": 1, "c": 2}, ("b", "a"))
    with pytest.raises(ValueError, match=r"^settings: unknown \[5\]"):
        settings_first({5: 1}, ("a",))
    with pytest.raises(ValueError, match=r"takes no settings"):
        settings_first({"a": 1}, ())

    @reads("x")
    def reader(settings, *, seed=0):
        """Doc."""
        return dict(settings), seed

    assert reader({"x": 1}, seed=2) == ({"x": 1}, 2) and reader(None) == ({}, 0)
    assert reader.settings_keys == frozenset({"x"}) and reader.__doc__ == "Doc."
    with pytest.raises(ValueError, match=r"unknown \['y'\]"):
        reader({"y": 1})


#: One reader of every chapter with settings, called as the claim file's evaluate calls it (a small run count where
#: the reader accepts one; the refusals come before any study).
_READERS = [
    ("ch01 weights_stability", lambda s: ofs.ev_weights_stability(s)),
    ("ch01 fig2_vs_support", lambda s: ofs.ev_fig2_vs_support(s)),
    ("ch01 weights_reasonable", lambda s: ofs.ev_weights_reasonable(s)),
    ("ch01 eq9_defined", lambda s: ofs.ev_eq9_defined(s)),
    ("ch02 awf_estimated", lambda s: lw.ev_awf_estimated(s)),
    ("ch03 wavelet_accurate", lambda s: wv.ev_wavelet_accurate(s)),
    ("ch04 correlation_matters", lambda s: lc.ev_correlation_matters(s, seed=7, runs=300)),
    ("ch04 ldl_cheaper", lambda s: lc.ev_ldl_cheaper(s, seed=7, runs=300)),
    ("ch05 fig6_foa_vs_grid", lambda s: ci.ev_fig6_foa_vs_grid(s)),
    ("ch05 record_evidence", lambda s: ci.record_evidence("ci-fig6-foa-vs-grid", s)),
    ("ch06 pso", lambda s: chc.ev_pso(s, seed=1, runs=3)),
    ("ch06 gaussian_ci", lambda s: chc.ev_gaussian_ci(s, seed=1, runs=3)),
    ("ch07 improved", lambda s: tre.ev_improved(s, seed=1, runs=120)),
    ("ch07 samples", lambda s: tre.ev_samples(s, seed=1, runs=120)),
]


@pytest.mark.parametrize("reader", [r[1] for r in _READERS], ids=[r[0] for r in _READERS])
def test_a_misspelt_setting_is_refused_before_any_study(reader) -> None:
    """C7: chapter 01 computed another reading's evidence; chapters 04 and 07 refused after their studies."""
    t = time.process_time()
    with pytest.raises(ValueError, match=r"^settings: unknown \['readin'\] \(this record's reader takes"):
        reader({"readin": "x"})
    assert time.process_time() - t < 1.0


@pytest.mark.parametrize("reader", [r[1] for r in _READERS], ids=[r[0] for r in _READERS])
@pytest.mark.parametrize("bad", [["reading"], "primary"], ids=["list", "str"])
def test_settings_not_a_mapping_is_one_type_error(reader, bad) -> None:
    """One rule: chapters 02-04, 06 and 07 raised a ValueError, chapter 05 a TypeError."""
    t = time.process_time()
    with pytest.raises(TypeError, match=r"^settings must be a mapping"):
        reader(bad)
    assert time.process_time() - t < 1.0


def test_fuzz52_c7_examples() -> None:
    with pytest.raises(ValueError, match=r"^settings: unknown \['sensor'\]"):
        ofs.ev_weights_stability({"sensor": (1, 10)})
    with pytest.raises(ValueError, match=r"^settings: unknown \['alph'\]"):
        ofs.ev_fig2_vs_support({"alph": 2.0})
    with pytest.raises(ValueError, match=r"^settings: unknown \['swep'\]"):
        ofs.ev_weights_reasonable({"swep": "noise spread σ_max/σ_min", "value": 16})
    with pytest.raises(ValueError, match=r"^settings: unknown \['alpha'\]"):  # only the support-degree readers
        ofs.ev_fig2_vs_mean({"alpha": 0.5})
    with pytest.raises(ValueError, match=r"^settings: unknown \['runs'\]"):
        reading_key({"runs": 3})


@pytest.mark.parametrize("call, exc, name", [
    (lambda: ofs.ev_fig2_vs_support({"alpha": 0.5, "noise": "equal"}), ValueError, "'alpha' 0.5 reads the α study"),
    (lambda: ofs.ev_fig4_vs_support({"alpha": 2.0, "failure": "random size"}), ValueError, "'alpha' 2 reads"),
    (lambda: ofs.ev_weights_reasonable({"value": 16}), ValueError, "a 'value' needs its 'sweep'"),
    (lambda: ofs.ev_weights_reasonable({"case": "failure", "sweep": "noise spread σ_max/σ_min", "value": 16}),
     ValueError, "'case' .* and 'sweep'"),
    (lambda: ofs.ev_weights_stability({"include_self": "no"}), TypeError, r"settings\['include_self'\]"),
    (lambda: ofs.ev_fig2_vs_mean({"include_self": 0}), TypeError, r"settings\['include_self'\]"),
    (lambda: ofs.ev_table2_ofs({"explanation": "yes"}), TypeError, r"settings\['explanation'\]"),
    (lambda: ofs.ev_table2_mean({"data": "corected"}), ValueError, r"settings\['data'\]"),
    (lambda: ofs.ev_table3_support({"data": "corrected"}), ValueError, "need its 'kernel'"),
    (lambda: ofs.ev_totals_ranking_mean({"guard": "men"}), ValueError, r"settings\['guard'\]"),
    (lambda: ofs.ev_totals_ranking_support({"total": "printd"}), ValueError, r"settings\['total'\]"),
    (lambda: ofs.ev_totals_ranking_support({"alpha": "0.5"}), TypeError, r"settings\['alpha'\]"),
    (lambda: ofs.ev_totals_ranking_support({"alpha": -1.0}), ValueError, r"settings\['alpha'\]"),
    (lambda: ofs.ev_obs_closer({"values": "recomputd"}), ValueError, r"settings\['values'\]"),
    (lambda: ofs.ev_obs_closer({"against": "bth"}), ValueError, r"settings\['against'\]"),
    (lambda: ofs.ev_eq3_5_rejects({"rule": "sum"}), ValueError, r"settings\['rule'\]"),
], ids=["alpha+noise", "alpha+failure", "value alone", "case+sweep", "include_self str", "include_self int",
        "explanation str", "data misspelt", "data without kernel", "guard", "total", "alpha str", "alpha negative",
        "values", "against", "rule"])
def test_chapter01_setting_values_are_never_read_as_the_default(call, exc, name) -> None:
    """C7's class in the values: ``{'data': 'corected'}`` read the printed table, ``bool('no')`` was true, ``alpha``
    with a noise read the α study of the primary noise."""
    t = time.process_time()
    with pytest.raises(exc, match=name):
        call()
    assert time.process_time() - t < 1.0


def test_d2_the_records_alpha_given_is_the_default() -> None:
    """D2: ``{'alpha': 0.25}`` (the records' own α, not in the α study's) was refused; it is the default's reading."""
    for fn in (ofs.ev_fig2_vs_support, ofs.ev_fig4_vs_support):
        a, b = fn({}, runs=100), fn({"alpha": 0.25}, runs=100)
        assert a == b and (a.a, a.b, a.a_name, a.b_name) == (b.a, b.b, b.a_name, b.b_name)
    with pytest.raises(ValueError, match=r"settings\['alpha'\] must be one of .* or the records' 0.25, got 0.3"):
        ofs.ev_fig2_vs_support({"alpha": 0.3})


def test_reading_of_refuses_a_non_mapping_by_type() -> None:
    with pytest.raises(TypeError, match="settings"):
        reading_of("r", {}, ["reading"])  # type: ignore[arg-type]


def test_every_claim_reading_passes_its_readers_checks(monkeypatch) -> None:
    """Every reading of every claim file: its keys are among its reader's declared keys (no study); chapter 01's
    readers, whose settings hold more than a reading key, run to their first study (stopped there)."""
    checked = 0
    for f in sorted(claims_dir().glob("*.yaml")):
        for spec in load(f).records:
            if not spec.evidence:
                continue
            mod, name = spec.evidence.split(":")
            keys = getattr(getattr(importlib.import_module(mod), name), "settings_keys", None)
            for r in spec.readings:
                if keys is not None:
                    settings_first(dict(r.settings), keys)
                    checked += 1
    assert checked >= 500

    class Reached(Exception):
        pass

    def stop(*args, **kwargs):
        raise Reached

    from fusion.book.chapters.ofs import records as rec
    for study in ("study", "alpha_study", "membership_study", "fair_weights", "weight_study", "faulty_member_share",
                  "not_neighbourhood_share", "tables", "corrected_table1", "_explained", "table1_totals"):
        monkeypatch.setattr(rec, study, stop)
    spec_file = load(claims_dir() / "yang2012optimal.yaml")
    n = 0
    for spec in spec_file.records:
        fn = getattr(rec, spec.evidence.split(":")[1])
        for r in spec.readings:
            try:
                fn(dict(r.settings), runs=100)
            except Reached:
                pass
            n += 1
    assert n >= 100


def test_fuzz54a_d1_a_key_equal_to_everything_is_compared_by_its_text() -> None:
    """Fuzz 54a D1: ``k in keys`` trusted a str subclass's ``__eq__``; one equal to everything passed as known."""

    class Anything(str):
        def __eq__(self, other: object) -> bool:
            return True

        __hash__ = str.__hash__

    with pytest.raises(ValueError, match="settings: unknown"):
        settings_first({Anything("nois"): 1}, ("noise",))
    assert settings_first({Anything("noise"): 1}, ("noise",))   # its text is a key the reader reads
